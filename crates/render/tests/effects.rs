//! Golden frames of the fireball and its effects (X1-X4): in flight with
//! its trail, spreading in a wall it hit, and collapsing a ball it caught.
//! Tolerance as in `rendering.rs`; `ROLYPOLY_BLESS=1` re-writes the goldens.

use glam::{DVec3, Vec3};
use image::RgbaImage;
use rolypoly_fx::{Effects, EffectsConfig};
use rolypoly_physics::{World, WorldConfig};
use rolypoly_render::{Camera, RenderSettings, SceneView, Snapshot};
use std::path::PathBuf;

const SHARE: f64 = 0.005;
const CHANNEL: u8 = 16;

fn check_golden(name: &str, actual: &RgbaImage) {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../tests/golden");
    let path = dir.join(format!("{name}.png"));
    if std::env::var_os("ROLYPOLY_BLESS").is_some() {
        actual.save(&path).expect("write golden");
        return;
    }
    let golden = image::open(&path)
        .unwrap_or_else(|e| {
            panic!(
                "golden {} missing ({e}); render it with ROLYPOLY_BLESS=1",
                path.display()
            )
        })
        .to_rgba8();
    assert_eq!(golden.dimensions(), actual.dimensions());
    let mut diff = RgbaImage::new(actual.width(), actual.height());
    let mut off = 0usize;
    for (x, y, a) in actual.enumerate_pixels() {
        let d = (0..3)
            .map(|c| a.0[c].abs_diff(golden.get_pixel(x, y).0[c]))
            .max()
            .unwrap_or(0);
        off += (d > CHANNEL) as usize;
        let v = d.saturating_mul(4);
        diff.put_pixel(x, y, image::Rgba([v, v, v, 255]));
    }
    let share = off as f64 / (actual.width() * actual.height()) as f64;
    if share >= SHARE {
        let _ = actual.save(dir.join(format!("{name}-actual.png")));
        let _ = diff.save(dir.join(format!("{name}-diff.png")));
        panic!(
            "{name}: {:.2}% of pixels differ by more than {CHANNEL}/255; see {name}-actual.png and {name}-diff.png",
            100.0 * share
        );
    }
}

/// Runs `world` with its effects for `seconds`, then draws it.
fn frame(mut world: World, seconds: f64, camera: Camera) -> RgbaImage {
    let config = world.config().clone();
    let mut fx = Effects::new(EffectsConfig::default(), 1);
    let mut events = Vec::new();
    for _ in 0..(seconds / config.solver.dt).round() as usize {
        fx.step_with(&mut world, &mut events);
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
