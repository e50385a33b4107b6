//! The tumbler against the analytic rolling pendulum (P6).

mod common;

use common::{build, empty_room, tumbler_at};
use glam::DVec3;
use rolypoly_physics::{SphereSpec, World};

/// R, a and k from the six spheres, computed here independently of the engine.
fn rolling_pendulum_omega(spheres: &[SphereSpec], g: f64) -> f64 {
    let m: f64 = spheres.iter().map(|s| s.mass).sum();
    let com = spheres.iter().map(|s| s.mass * s.height).sum::<f64>() / m;
    let big_r = spheres[0].radius;
    let a = -com;
    // Moment about a horizontal axis through the centre of mass:
    // each solid sphere 2/5 m r^2 plus m d^2 (parallel axis).
    let i: f64 = spheres
        .iter()
        .map(|s| 0.4 * s.mass * s.radius * s.radius + s.mass * (s.height - com).powi(2))
        .sum();
    let k2 = i / m;
    (g * a / (k2 + (big_r - a).powi(2))).sqrt()
}

fn single_tumbler(tilt_deg: f64, damping: f64) -> World {
    let mut cfg = empty_room();
    cfg.tumblers.damping = damping;
    cfg.tumblers.placements = vec![tumbler_at(0.0, 0.0, DVec3::X, tilt_deg)];
    build(cfg, 1)
}

#[test]
fn small_rocking_period_matches_the_rolling_pendulum() {
    let mut w = single_tumbler(5.0, 0.0);
    let cfg = w.config().clone();
    let omega = rolling_pendulum_omega(&cfg.tumblers.spheres, cfg.gravity);
    let expected = std::f64::consts::TAU / omega;
    let dt = cfg.solver.dt;
    // Tilted about x, the axis leans towards +/- z: time its zero crossings.
    let mut crossings = Vec::new();
    let mut prev = w.tumblers()[0].axis().z;
    let mut max_contact_speed: f64 = 0.0;
    let mut max_rock_speed: f64 = 0.0;
    while crossings.len() < 9 && w.time() < 60.0 {
        w.step();
        let t = &w.tumblers()[0];
        let z = t.axis().z;
        if (prev < 0.0) != (z < 0.0) {
            // Linear interpolation within the step.
            crossings.push(w.time() - dt + dt * prev / (prev - z));
        }
        prev = z;
        max_contact_speed = max_contact_speed.max(t.contact_velocity().length());
        max_rock_speed = max_rock_speed.max(t.linear_velocity().length());
        assert!(
            !t.sliding(),
            "a gently rocking tumbler must roll, not slide"
        );
    }
    assert_eq!(crossings.len(), 9, "the tumbler stopped rocking");
    let period = (crossings[8] - crossings[0]) / 4.0;
    let err = (period - expected).abs() / expected;
    println!(
        "period {period:.5} s, analytic {expected:.5} s, error {:.3}%",
        100.0 * err
    );
    assert!(
        err < 0.02,
        "period {period:.4} s, rolling pendulum {expected:.4} s ({:.2}%)",
        100.0 * err
    );
    // Rolling without slipping: the contact point stays still while the body moves.
    assert!(max_rock_speed > 0.01);
    assert!(
        max_contact_speed < 1e-9 * max_rock_speed.max(1.0),
        "contact point moved at {max_contact_speed} m/s"
    );
}

#[test]
fn undamped_rocking_keeps_its_energy() {
    let mut w = single_tumbler(20.0, 0.0);
    let e0 = w.energy().total();
    let mut worst: f64 = 0.0;
    for _ in 0..1200 {
        w.step();
        worst = worst.max((w.energy().total() - e0).abs());
    }
    println!("worst energy deviation {worst:e} J of {e0} J");
    assert!(worst < 1e-6 * e0, "energy drifted by {worst} J of {e0} J");
}

#[test]
fn released_at_sixty_degrees_it_rights_itself_and_rests() {
    let mut w = single_tumbler(60.0, WorldDefaults::damping());
    let start = w.tumblers()[0].tilt();
    assert!((start.to_degrees() - 60.0).abs() < 1e-9);
    let mut max_tilt: f64 = 0.0;
    for _ in 0..(40.0 / w.config().solver.dt) as usize {
        w.step();
        max_tilt = max_tilt.max(w.tumblers()[0].tilt());
    }
    let t = &w.tumblers()[0];
    assert!(
        max_tilt < 60.0f64.to_radians() + 1e-6,
        "it tipped further than released"
    );
    assert!(
        t.tilt().to_degrees() < 0.5,
        "still tilted {:.2} degrees",
        t.tilt().to_degrees()
    );
    assert!(t.linear_velocity().length() < 0.01);
    assert!(t.angular_velocity().length() < 0.05);
}

struct WorldDefaults;
impl WorldDefaults {
    fn damping() -> f64 {
        rolypoly_physics::WorldConfig::default().tumblers.damping
    }
}

#[test]
fn rolling_tumbler_moves_over_the_floor_as_it_rocks() {
    // While it rocks, the bottom sphere's centre moves R times the rocking rate.
    let mut w = single_tumbler(30.0, 0.0);
    let r = w.tumbler_shape().bottom_radius;
    for _ in 0..30 {
        w.step();
        let t = &w.tumblers()[0];
        let expected = r * t.angular_velocity().x.abs();
        let centre_speed = (t.linear_velocity()
            - t.angular_velocity()
                .cross(t.center_of_mass() - t.bottom_center()))
        .length();
        assert!((centre_speed - expected).abs() < 1e-9 * (1.0 + expected));
    }
}
