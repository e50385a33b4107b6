//! Golden frames of the fireball and its effects (X1-X4): in flight with
//! its trail, spreading in a wall it hit, and collapsing a ball it caught.
//! Compared as in `common/mod.rs`; `ROLYPOLY_BLESS=1` re-writes the goldens.

use glam::{DVec3, Vec3};
use image::RgbaImage;
use rolypoly_fx::{Effects, EffectsConfig};
use rolypoly_physics::{World, WorldConfig};
use rolypoly_render::{Camera, RenderSettings, SceneView, Snapshot};

mod common;
use common::check_golden;

/// Runs `world` with its effects for `seconds`, then draws it.
fn frame(mut world: World, seconds: f64, camera: Camera) -> RgbaImage {
    let config = world.config().clone();
    let mut fx = Effects::new(EffectsConfig::default(), 1);
    let mut events = Vec::new();
    for _ in 0..(seconds / config.solver.dt).round() as usize {
        // The program's tick: the physics step, then the effects of its events.
        world.step();
        world.take_events(&mut events);
        fx.consume(&events, &world);
        fx.update(config.solver.dt, world.fireball());
    }
    let mut snap = Snapshot::new(&config, RenderSettings::default(), 480, 270, None)
        .unwrap_or_else(|e| panic!("cannot render: {e}"));
    let view = SceneView::from_world(&world, None).with_effects(&fx, &world);
    snap.capture(&view, &camera).expect("frame")
}

#[test]
fn fireball_in_flight_with_its_trail() {
    let mut world = World::new(WorldConfig::default(), 1).expect("scene");
    world.launch_fireball(None);
    let camera = Camera {
        eye: Vec3::new(-1.5, 1.8, 3.6),
        target: Vec3::new(0.6, 1.2, 1.0),
        fov_y_deg: 60.0,
    };
    check_golden("fireball-flight", &frame(world, 0.35, camera));
}

#[test]
fn fireball_hitting_a_wall() {
    let mut config = WorldConfig::default();
    config.balls.count = 0;
    let mut world = World::new(config, 1).expect("scene");
    world.launch_fireball(Some((DVec3::new(0.0, 1.5, 0.0), DVec3::NEG_Z)));
    let camera = Camera {
        eye: Vec3::new(0.6, 1.7, -1.2),
        target: Vec3::new(0.0, 1.5, -4.0),
        fov_y_deg: 60.0,
    };
    // It reaches the back wall after about 0.63 s: a quarter second into the spread.
    check_golden("fireball-wall-hit", &frame(world, 0.9, camera));
}

#[test]
fn fireball_catching_a_ball() {
    let mut config = WorldConfig::default();
    config.balls.count = 1;
    config.gravity = 0.0;
    let mut world = World::new(config, 1).expect("scene");
    world
        .balls_mut()
        .set(0, DVec3::new(0.0, 1.5, -1.5), DVec3::ZERO);
    world.launch_fireball(Some((DVec3::new(0.0, 1.5, 1.5), DVec3::NEG_Z)));
    let camera = Camera {
        eye: Vec3::new(1.3, 1.9, 0.2),
        target: Vec3::new(0.0, 1.5, -1.5),
        fov_y_deg: 55.0,
    };
    // The hit comes after about 0.45 s; the collapse is under way 0.3 s later.
    check_golden("fireball-ball-hit", &frame(world, 0.75, camera));
}
