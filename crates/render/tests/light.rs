//! Each of the light's effects checked by the picture (L1-L4): the frame
//! with the effect differs from the frame without it where it should, and
//! not where it should not. Every other effect is off in both frames, so
//! that each test sees its own effect alone.

use glam::Vec3;
use image::RgbaImage;
use rolypoly_fx::FireballLook;
use rolypoly_physics::{World, WorldConfig};
use rolypoly_render::{BallView, Camera, Light, PointLight, RenderSettings, SceneView, Snapshot};

mod common;
use common::pixel_of;

const SIZE: (u32, u32) = (480, 270);

/// The default room with nothing in it, and every effect off.
fn empty_room() -> (WorldConfig, SceneView) {
    let mut config = WorldConfig::default();
    config.balls.count = 0;
    config.tumblers.placements.clear();
    let world = World::new(config.clone(), 1).expect("scene builds");
    let mut view = SceneView::from_world(&world, None);
    view.light = Light {
        bloom: None,
        fireball_light: false,
        indirect: false,
        occlusion: false,
        ..view.light
    };
    (config, view)
}

/// The frames of `without` and of `with` (the same view with one effect
/// switched on).
fn frames(
    config: &WorldConfig,
    without: &SceneView,
    with: &SceneView,
    camera: &Camera,
) -> (RgbaImage, RgbaImage) {
    let mut snap = Snapshot::new(config, RenderSettings::default(), SIZE.0, SIZE.1, None)
        .unwrap_or_else(|e| panic!("cannot render: {e}"));
    let off = snap.capture(without, camera).expect("frame");
    let on = snap.capture(with, camera).expect("frame");
    (off, on)
}

/// Mean linear-ish colour (0..1 per channel) of the pixels within `r`
/// pixels of `centre`.
fn mean_around(img: &RgbaImage, (cx, cy): (u32, u32), r: i32) -> Vec3 {
    let mut sum = Vec3::ZERO;
    let mut n = 0.0;
    for dy in -r..=r {
        for dx in -r..=r {
            let (x, y) = (cx as i32 + dx, cy as i32 + dy);
            if x < 0 || y < 0 || x >= img.width() as i32 || y >= img.height() as i32 {
                continue;
            }
            let p = img.get_pixel(x as u32, y as u32).0;
            sum += Vec3::new(p[0] as f32, p[1] as f32, p[2] as f32) / 255.0;
            n += 1.0;
        }
    }
    sum / n
}

fn brightness(c: Vec3) -> f32 {
    c.dot(Vec3::new(0.2126, 0.7152, 0.0722))
}

#[test]
fn bloom_glows_around_the_bulb_and_leaves_lit_walls_alone() {
    let (config, without) = empty_room();
    let with = SceneView {
        light: Light {
            bloom: Some(rolypoly_render::Bloom {
                strength: 1.0,
                threshold: 2.0,
            }),
            ..without.light
        },
        ..without.clone()
    };
    let camera = Camera::overview(without.room_size);
    let (off, on) = frames(&config, &without, &with, &camera);
    let (w, h) = SIZE;
    let bulb = pixel_of(&camera, without.light.position, w, h);
    // Just beside the bulb (a few pixels across here), below it on the
    // ceiling.
    let beside = (bulb.0 + 8, bulb.1 + 6);
    let glow = brightness(mean_around(&on, beside, 2)) - brightness(mean_around(&off, beside, 2));
    assert!(glow > 0.03, "no glow beside the bulb: {glow}");
    // Lit walls and floor, away from the bulb, are below the threshold.
    let size = without.room_size;
    for p in [
        Vec3::new(-0.3 * size.x, 0.3 * size.y, -0.5 * size.z),
        Vec3::new(-0.5 * size.x, 0.4 * size.y, 0.0),
        Vec3::new(0.2 * size.x, 0.0, 0.1 * size.z),
    ] {
        let at = pixel_of(&camera, p, w, h);
        let change = (mean_around(&on, at, 3) - mean_around(&off, at, 3))
            .abs()
            .max_element();
        assert!(change < 0.015, "a lit surface at {p} halos: {change}");
    }
}

#[test]
fn indirect_light_tints_the_floor_by_the_red_wall_red_and_by_the_green_wall_green() {
    let (config, without) = empty_room();
    let with = SceneView {
        light: Light {
            indirect: true,
            ..without.light
        },
        ..without.clone()
    };
    let camera = Camera::overview(without.room_size);
    let (off, on) = frames(&config, &without, &with, &camera);
    let (w, h) = SIZE;
    let half = 0.5 * without.room_size.x;
    let redness = |c: Vec3| c.x / c.y;
    // The floor a hand's width from each side wall.
    let by_red = pixel_of(&camera, Vec3::new(-half + 0.15, 0.0, 0.0), w, h);
    let by_green = pixel_of(&camera, Vec3::new(half - 0.15, 0.0, 0.0), w, h);
    // The bounce brightens the whole floor, which the tone mapping's
    // curve desaturates; what it tints shows beside the other wall: the
    // floor by the red wall is redder than by the green one, by more with
    // the bounce than without.
    let tint = |frame: &RgbaImage| {
        redness(mean_around(frame, by_red, 2)) / redness(mean_around(frame, by_green, 2))
    };
    let (tint_off, tint_on) = (tint(&off), tint(&on));
    assert!(
        tint_on > tint_off * 1.03,
        "red over green by the walls: {tint_off} without, {tint_on} with"
    );
}

#[test]
fn occlusion_darkens_the_floor_beside_a_resting_ball_and_not_far_from_it() {
    let (config, mut without) = empty_room();
    let radius = 0.12;
    without.balls.push(BallView {
        position: Vec3::new(0.0, radius, 0.0),
        radius,
        color: Vec3::splat(0.9),
    });
    let with = SceneView {
        light: Light {
            occlusion: true,
            ..without.light
        },
        ..without.clone()
    };
    let camera = Camera {
        eye: Vec3::new(0.0, 0.7, 1.0),
        target: Vec3::new(0.0, 0.05, 0.0),
        fov_y_deg: 50.0,
    };
    let (off, on) = frames(&config, &without, &with, &camera);
    let (w, h) = SIZE;
    // Beside the ball, out of the shadow the light above casts under it.
    for side in [-1.0, 1.0] {
        let beside = pixel_of(&camera, Vec3::new(side * 1.25 * radius, 0.0, 0.0), w, h);
        let darker =
            brightness(mean_around(&off, beside, 1)) - brightness(mean_around(&on, beside, 1));
        assert!(
            darker > 0.03,
            "the floor beside the ball is not darker: {darker}"
        );
    }
    let far = pixel_of(&camera, Vec3::new(0.6, 0.0, -0.3), w, h);
    let change =
        (brightness(mean_around(&off, far, 2)) - brightness(mean_around(&on, far, 2))).abs();
    assert!(change < 0.01, "open floor changed: {change}");
}

#[test]
fn the_fireball_lights_the_floor_under_it_and_not_across_the_room() {
    let (config, mut without) = empty_room();
    let look = FireballLook::at(Vec3::new(0.0, 0.4, 0.0), 0.2, 0.0);
    without.fireball = Some(look);
    without.fireball_light = PointLight::of_fireball(Some(&look), None);
    let with = SceneView {
        light: Light {
            fireball_light: true,
            ..without.light
        },
        ..without.clone()
    };
    let camera = Camera::overview(without.room_size);
    let (off, on) = frames(&config, &without, &with, &camera);
    let (w, h) = SIZE;
    let under = pixel_of(&camera, Vec3::new(0.45, 0.0, 0.2), w, h);
    let lit = brightness(mean_around(&on, under, 2)) - brightness(mean_around(&off, under, 2));
    assert!(lit > 0.02, "the floor under the fireball is not lit: {lit}");
    let across = pixel_of(&camera, Vec3::new(-3.0, 0.0, -3.0), w, h);
    let change =
        (brightness(mean_around(&on, across, 2)) - brightness(mean_around(&off, across, 2))).abs();
    assert!(change < 0.02, "the far corner changed: {change}");
}
