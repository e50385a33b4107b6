//! The path tracer against light worked out by hand: a furnace whose
//! bounces sum to a geometric series, the inverse square and the cosine,
//! the umbra and penumbra of a sphere's shadow, and noise that falls as
//! one over the square root of the samples.

use glam::Vec3;
use rolypoly_reference::{Material, Radiance, Ray, Sampler, Scene, SphereLight, radiance, render};
use rolypoly_render::{Camera, room_surfaces};
use std::f32::consts::PI;

/// The mean radiance along `ray` over `paths` paths.
fn mean_along(scene: &Scene, ray: Ray, paths: u64, seed: u64) -> f32 {
    let mut sum = 0.0f64;
    for i in 0..paths {
        let mut rng = Sampler::new(seed, i, 0);
        sum += f64::from(radiance(scene, ray, &mut rng).x);
    }
    (sum / paths as f64) as f32
}

fn mean(picture: &Radiance) -> f64 {
    picture.pixels.iter().map(|p| f64::from(p.x)).sum::<f64>() / picture.pixels.len() as f64
}

fn room(size: Vec3, material: Material) -> Scene {
    let mut scene = Scene::new();
    for s in room_surfaces(size) {
        scene.add_rectangle(s.corner, s.u, s.v, material);
    }
    scene
}

#[test]
fn a_white_furnace_sums_its_bounces() {
    // Every surface of a closed room glows with radiance 1 and reflects
    // `albedo` of what falls on it: everywhere inside, the light is
    // 1 + a + a^2 + ... = 1 / (1 - a). 32 x 32 pixels at 64 samples.
    for (albedo, size) in [
        (0.5, Vec3::new(2.0, 2.0, 2.0)),
        (0.8, Vec3::new(6.0, 3.0, 4.0)),
    ] {
        let mut scene = room(
            size,
            Material {
                emission: Vec3::ONE,
                ..Material::matte(Vec3::splat(albedo))
            },
        );
        scene.finish();
        let camera = Camera {
            eye: Vec3::new(0.1, 0.45 * size.y, 0.2),
            target: Vec3::new(-0.3, 0.6 * size.y, -1.0),
            fov_y_deg: 90.0,
        };
        let picture = render(&scene, &camera, (32, 32), 64, 11, &|| {});
        let expected = 1.0 / (1.0 - f64::from(albedo));
        let got = mean(&picture);
        assert!(
            (got / expected - 1.0).abs() < 0.01,
            "albedo {albedo}: {got} against {expected}"
        );
    }
}

#[test]
fn a_point_light_falls_off_as_cosine_over_distance_squared() {
    // A light of intensity I a height h over a matte plane of albedo a:
    // at distance x along the plane the radiance is a / pi * I cos / r^2,
    // with r^2 = h^2 + x^2 and cos = h / r.
    let (albedo, intensity) = (0.6, 5.0);
    for height in [1.0f32, 2.5] {
        let mut scene = Scene::new();
        scene.add_rectangle(
            Vec3::new(-100.0, 0.0, 100.0),
            Vec3::X * 200.0,
            Vec3::NEG_Z * 200.0,
            Material::matte(Vec3::splat(albedo)),
        );
        scene.add_light(SphereLight::of_intensity(
            Vec3::new(0.0, height, 0.0),
            1e-3,
            Vec3::splat(intensity),
        ));
        scene.finish();
        for x in [0.0f32, 0.7, 2.0, 4.0] {
            let ray = Ray {
                origin: Vec3::new(x, 0.05, 0.0),
                dir: Vec3::NEG_Y,
            };
            let r2 = height * height + x * x;
            let expected = albedo / PI * intensity * (height / r2.sqrt()) / r2;
            let got = mean_along(&scene, ray, 4000, 2);
            assert!(
                (got / expected - 1.0).abs() < 0.01,
                "h {height} x {x}: {got} against {expected}"
            );
        }
    }
}

/// Where the lines that touch both circles (radii `big` at height `top`
/// and `small` at `low`, on one axis) cross the ground: on the same side
/// of both (the umbra's edge) or crossing between them (the penumbra's).
fn tangent_at_ground(top: f32, big: f32, low: f32, small: f32, crossing: bool) -> f32 {
    let sin = if crossing { big + small } else { big - small } / (top - low);
    let cos = (1.0 - sin * sin).sqrt();
    let offset = if crossing {
        low * sin + small
    } else {
        low * sin - small
    };
    (offset / cos).abs()
}

#[test]
fn a_spheres_shadow_has_the_umbra_and_penumbra_of_the_lights_size() {
    // A sphere light of radius R at height H over a black ball of radius
    // b at height h: on the ground, dark within the umbra, fully lit
    // beyond the penumbra, partly between.
    for (light_radius, ball_radius, ball_height) in [(0.2f32, 0.3f32, 1.0f32), (0.35, 0.25, 1.4)] {
        let light_height = 3.0;
        let albedo = 0.5;
        let mut scene = Scene::new();
        scene.add_rectangle(
            Vec3::new(-50.0, 0.0, 50.0),
            Vec3::X * 100.0,
            Vec3::NEG_Z * 100.0,
            Material::matte(Vec3::splat(albedo)),
        );
        scene.add_sphere(
            Vec3::new(0.0, ball_height, 0.0),
            ball_radius,
            Material::matte(Vec3::ZERO),
        );
        let intensity = 4.0;
        scene.add_light(SphereLight::of_intensity(
            Vec3::new(0.0, light_height, 0.0),
            light_radius,
            Vec3::splat(intensity),
        ));
        scene.finish();
        let umbra = tangent_at_ground(light_height, light_radius, ball_height, ball_radius, false);
        let penumbra =
            tangent_at_ground(light_height, light_radius, ball_height, ball_radius, true);
        assert!(umbra < penumbra);
        let lit = |x: f32| {
            let r2 = light_height * light_height + x * x;
            albedo / PI * intensity * (light_height / r2.sqrt()) / r2
        };
        let share = |x: f32| {
            let ray = Ray {
                origin: Vec3::new(x, 0.01, 0.0),
                dir: Vec3::NEG_Y,
            };
            mean_along(&scene, ray, 3000, 4) / lit(x)
        };
        let margin = 0.02;
        assert!(
            share(umbra - margin) < 0.01,
            "inside the umbra {umbra}: {}",
            share(umbra - margin)
        );
        assert!(share(0.0) < 0.01);
        assert!(
            (share(penumbra + margin) - 1.0).abs() < 0.01,
            "beyond the penumbra {penumbra}: {}",
            share(penumbra + margin)
        );
        let steps: Vec<f32> = (0..=4)
            .map(|k| share(umbra + (penumbra - umbra) * (0.1 + 0.2 * k as f32)))
            .collect();
        assert!(steps[0] > 0.0 && steps[4] < 1.0, "{steps:?}");
        assert!(
            steps.windows(2).all(|w| w[1] > w[0]),
            "the penumbra brightens outwards: {steps:?}"
        );
    }
}

/// A small lit room with a ball and a box of light in it.
fn lit_room() -> (Scene, Camera) {
    let size = Vec3::new(4.0, 3.0, 4.0);
    let mut scene = room(size, Material::matte(Vec3::new(0.7, 0.6, 0.5)));
    scene.add_sphere(
        Vec3::new(0.3, 0.5, -0.4),
        0.5,
        Material::matte(Vec3::new(0.2, 0.5, 0.8)),
    );
    scene.add_light(SphereLight::of_intensity(
        Vec3::new(0.0, 2.6, 0.0),
        0.1,
        Vec3::splat(6.0),
    ));
    scene.finish();
    let camera = Camera {
        eye: Vec3::new(0.0, 1.4, 1.9),
        target: Vec3::new(0.0, 0.8, -2.0),
        fov_y_deg: 70.0,
    };
    (scene, camera)
}

/// The root mean square of the difference of two pictures.
fn rms_difference(a: &Radiance, b: &Radiance) -> f64 {
    let sum: f64 = a
        .pixels
        .iter()
        .zip(&b.pixels)
        .map(|(p, q)| f64::from((*p - *q).length_squared()))
        .sum();
    (sum / a.pixels.len() as f64).sqrt()
}

#[test]
fn noise_falls_as_one_over_the_square_root_of_the_samples() {
    // Two pictures of different seeds differ by their noise alone: at four
    // times the samples, by half as much.
    let (scene, camera) = lit_room();
    let size = (40, 30);
    let noise = |spp| {
        let a = render(&scene, &camera, size, spp, 1, &|| {});
        let b = render(&scene, &camera, size, spp, 2, &|| {});
        rms_difference(&a, &b)
    };
    for spp in [4, 16] {
        let ratio = noise(spp) / noise(4 * spp);
        assert!(
            (ratio - 2.0).abs() < 0.25,
            "{spp} spp: noise falls by {ratio} at 4x"
        );
    }
}

#[test]
fn the_same_samples_give_the_same_picture_on_any_thread_count() {
    let (scene, camera) = lit_room();
    let on = |threads| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| render(&scene, &camera, (24, 18), 8, 5, &|| {}))
    };
    let one = on(1);
    assert_eq!(one, on(2));
    assert_eq!(one, on(3));
    // And another seed, another picture.
    assert_ne!(one, render(&scene, &camera, (24, 18), 8, 6, &|| {}));
}
