//! The temporal path (`render --scale S --temporal`), checked by pictures
//! against high's of the same moment: as sharp, sharp only through its
//! history, and without trails behind what moves.
//!
//! These draw off-screen on whatever adapter exists (lavapipe in CI).

use glam::{Vec2, Vec3};
use image::RgbaImage;
use rolypoly_core::frames::{FrameOptions, Frames};
use rolypoly_core::scene::{SHIPPED_SCENES, Scene, load_scene, parse_scene};
use rolypoly_core::simulation::Simulation;
use rolypoly_core::steps_for;
use rolypoly_physics::World;
use rolypoly_reference::ssim;
use rolypoly_render::{Quality, QualityChoice};

fn simulation(scene: &Scene, seed: u64) -> Simulation {
    let world = World::new(scene.world.clone(), seed).expect("the scene builds");
    Simulation::new(world, scene.effects.clone(), seed)
}

fn high() -> FrameOptions {
    FrameOptions {
        quality: Some(QualityChoice::Fixed(Quality::High)),
        ..FrameOptions::default()
    }
}

fn low() -> FrameOptions {
    FrameOptions {
        quality: Some(QualityChoice::Fixed(Quality::Low)),
        ..FrameOptions::default()
    }
}

/// Lit at half the width and height, resolved over time.
fn temporal() -> FrameOptions {
    FrameOptions {
        scale: Some(0.5),
        temporal: true,
        ..high()
    }
}

/// The frame of `scene` run from `seed` to `seconds`, drawn as `options`
/// say, with its history where they ask for the temporal path; and the
/// run at that moment.
fn frame(
    scene: &Scene,
    seed: u64,
    seconds: f64,
    options: &FrameOptions,
    size: (u32, u32),
) -> (RgbaImage, Simulation) {
    let mut sim = simulation(scene, seed);
    let mut frames = Frames::new(&scene.world, scene.quality, options, size)
        .unwrap_or_else(|e| panic!("cannot draw: {e:#}"));
    let steps = steps_for(seconds, scene.world.solver.dt);
    let image = frames
        .draw_at(&mut sim, steps, &scene.light)
        .unwrap_or_else(|e| panic!("cannot draw: {e:#}"));
    (image, sim)
}

const SIZE: (u32, u32) = (1280, 720);

/// Lit at half the size, the temporal frame is as sharp as high's: its
/// history fills in what a frame lit at that size leaves out.
#[test]
fn the_temporal_frame_at_half_size_is_as_sharp_as_high() {
    let scene = load_scene(None).expect("the built-in scene");
    for seed in [1, 2] {
        let (reference, _) = frame(&scene, seed, 10.0, &high(), SIZE);
        let (upsampled, _) = frame(&scene, seed, 10.0, &temporal(), SIZE);
        let (coarse, _) = frame(&scene, seed, 10.0, &low(), SIZE);
        let (sharp, plain) = (ssim(&reference, &upsampled), ssim(&reference, &coarse));
        println!("seed {seed}: SSIM against high: temporal {sharp:.4}, low {plain:.4}");
        assert!(sharp >= 0.98, "seed {seed}: temporal SSIM {sharp:.4}");
        assert!(sharp > plain + 0.03, "seed {seed}: low {plain:.4}");
    }
}

/// What lifts it is the history: one frame of the temporal path with none
/// before it is the frame lit at half the size spread over the output. Its
/// samples lie nearer the output's pixel centres than plain upscaling's, a
/// better start, but it stays far from high's until the frames before it
/// are folded in.
#[test]
fn without_its_history_the_temporal_frame_is_a_plain_upscale() {
    let scene = load_scene(None).expect("the built-in scene");
    let seed = 3;
    let mut sim = simulation(&scene, seed);
    sim.ticks(steps_for(10.0, scene.world.solver.dt));
    let draw = |options: &FrameOptions, sim: &Simulation| {
        Frames::new(&scene.world, scene.quality, options, SIZE)
            .and_then(|mut frames| frames.draw(sim, &scene.light))
            .unwrap_or_else(|e| panic!("cannot draw: {e:#}"))
    };
    let reference = draw(&high(), &sim);
    let first = ssim(&reference, &draw(&temporal(), &sim));
    let coarse = ssim(&reference, &draw(&low(), &sim));
    let (resolved, _) = frame(&scene, seed, 10.0, &temporal(), SIZE);
    let full = ssim(&reference, &resolved);
    println!(
        "SSIM against high: low {coarse:.4}, a first temporal frame {first:.4}, with its history {full:.4}"
    );
    assert!(first < 0.97, "first {first:.4}");
    assert!(
        full >= first + 0.02,
        "first {first:.4}, with history {full:.4}"
    );
}

/// Where a ball is on screen in a frame of `size` seen by `view_proj`.
fn pixel_of(view_proj: glam::Mat4, point: Vec3, size: Vec2) -> Vec2 {
    let ndc = view_proj.project_point3(point);
    Vec2::new((ndc.x + 1.0) * 0.5 * size.x, (1.0 - ndc.y) * 0.5 * size.y)
}

/// The largest difference of a channel between the two pictures at
/// `at`, of 1 (none outside them).
fn difference_at(a: &RgbaImage, b: &RgbaImage, at: Vec2) -> Option<f32> {
    let (x, y) = (at.x.floor() as i64, at.y.floor() as i64);
    if x < 0 || y < 0 || x >= a.width() as i64 || y >= a.height() as i64 {
        return None;
    }
    let (p, q) = (
        a.get_pixel(x as u32, y as u32),
        b.get_pixel(x as u32, y as u32),
    );
    (0..3)
        .map(|c| (p[c] as f32 - q[c] as f32).abs() / 255.0)
        .reduce(f32::max)
}

/// How far, in pixels past its outline, a ball's trail runs behind it: the
/// run of pixels along its motion, backwards from its outline, where the
/// temporal frame differs from high's by more than `STEP`.
fn trail_behind(
    high: &RgbaImage,
    temporal: &RgbaImage,
    centre: Vec2,
    radius: f32,
    back: Vec2,
) -> f32 {
    const STEP: f32 = 10.0 / 255.0;
    let mut past = 1.0;
    while past < 4.0 * radius {
        match difference_at(high, temporal, centre + back * (radius + past)) {
            Some(d) if d > STEP => past += 1.0,
            _ => break,
        }
    }
    past - 1.0
}

/// Whether the sphere at `centre` is the first that the ray from `eye`
/// through it meets among `spheres`: the ball shows at its centre's pixel.
fn first_seen(eye: Vec3, centre: Vec3, spheres: &[(Vec3, f32)]) -> bool {
    let direction = (centre - eye).normalize();
    let own = (centre - eye).length();
    let hit = |(c, r): &(Vec3, f32)| {
        let along = (*c - eye).dot(direction);
        let across2 = (*c - eye).length_squared() - along * along;
        (across2 <= r * r).then(|| along - (r * r - across2).sqrt())
    };
    let own_hit = own
        - spheres
            .iter()
            .find(|(c, _)| *c == centre)
            .map_or(0.0, |(_, r)| *r);
    !spheres
        .iter()
        .filter(|(c, _)| *c != centre)
        .filter_map(hit)
        .any(|t| t > 0.0 && t < own_hit)
}

/// The 10k pit falling, seen from a still camera: behind each ball that
/// falls across the picture, the temporal frame departs from high's for no
/// longer than the ball's radius (a history that followed no motion would
/// leave each ball's past places drawn behind it).
#[test]
fn falling_balls_leave_no_trail_longer_than_their_radius() {
    let pit = SHIPPED_SCENES
        .iter()
        .find(|s| s.name == "ballpit-10k.toml")
        .expect("the 10k pit ships");
    let scene = parse_scene(pit.text, pit.name).expect("the pit loads");
    let size = (640, 360);
    for (seed, seconds) in [(1, 0.15), (2, 0.25)] {
        let (reference, sim) = frame(&scene, seed, seconds, &high(), size);
        let (upsampled, _) = frame(&scene, seed, seconds, &temporal(), size);
        let frames = Frames::new(&scene.world, scene.quality, &high(), size).expect("frames");
        let camera = frames.camera();
        let screen = Vec2::new(size.0 as f32, size.1 as f32);
        let view_proj = camera.view_projection(screen.x / screen.y);
        let balls = sim.world.balls();
        let spheres: Vec<(Vec3, f32)> = (0..balls.len())
            .filter(|&i| balls.alive()[i])
            .map(|i| (balls.positions()[i].as_vec3(), balls.radii()[i] as f32))
            .collect();
        let mut trails = Vec::new();
        for i in (0..balls.len()).filter(|&i| balls.alive()[i]) {
            let position = balls.positions()[i].as_vec3();
            let velocity = balls.velocities()[i].as_vec3();
            let radius = balls.radii()[i] as f32;
            let centre = pixel_of(view_proj, position, screen);
            let across = (position - camera.eye).cross(Vec3::Y).normalize();
            let radius_px =
                (pixel_of(view_proj, position + across * radius, screen) - centre).length();
            // A frame's motion at the history's rate, in pixels.
            let motion = pixel_of(view_proj, position + velocity / 60.0, screen) - centre;
            let inside = centre.cmpge(Vec2::ZERO).all() && centre.cmplt(screen).all();
            if !inside
                || radius_px < 3.0
                || motion.length() < 0.25 * radius_px
                || !first_seen(camera.eye, position, &spheres)
            {
                continue;
            }
            let back = -motion.normalize();
            trails.push((
                trail_behind(&reference, &upsampled, centre, radius_px, back),
                radius_px,
            ));
        }
        assert!(
            trails.len() >= 30,
            "seed {seed}: {} balls cross the picture",
            trails.len()
        );
        // Balls in front of and behind one another overlap, and a ball's
        // trail may run into another's outline: a tenth of them may.
        let mut beyond: Vec<f32> = trails
            .iter()
            .map(|(trail, radius)| trail / radius)
            .collect();
        beyond.sort_by(f32::total_cmp);
        let ninetieth = beyond[beyond.len() * 9 / 10];
        let median = beyond[beyond.len() / 2];
        println!(
            "seed {seed}: {} falling balls, trails in radii: median {median:.2}, 90th percentile {ninetieth:.2}",
            trails.len()
        );
        assert!(
            ninetieth <= 1.0,
            "seed {seed}: 90th percentile {ninetieth:.2} radii"
        );
    }
}
