//! Invariants over long runs: nothing leaves the room, nothing becomes NaN,
//! everything comes to rest, and reruns are bit-identical (P4, P10).

mod common;

use common::{build, state_bits};
use glam::DVec3;
use rolypoly_physics::{World, WorldConfig};

fn assert_inside_and_finite(w: &World, step: usize) {
    let room = *w.room();
    let b = w.balls();
    for i in 0..b.len() {
        let p = b.positions()[i];
        assert!(
            p.is_finite() && b.velocities()[i].is_finite(),
            "ball {i} NaN at step {step}"
        );
        assert!(
            room.contains_sphere(p, b.radii()[i], 1e-9),
            "ball {i} left the room at step {step}: {p}"
        );
    }
    let shape = w.tumbler_shape();
    for (k, t) in w.tumblers().iter().enumerate() {
        assert!(t.center_of_mass().is_finite() && t.angular_velocity().is_finite());
        for s in 0..shape.spheres.len() {
            let c = t.sphere_center(shape, s);
            // The floor holds the bottom exactly; other spheres may touch it
            // only when a tumbler is tipped over, never pass through walls.
            assert!(
                room.contains_sphere(c, shape.spheres[s].radius, 1e-3),
                "tumbler {k} sphere {s} outside at step {step}: {c}"
            );
        }
    }
    if let Some(f) = w.fireball() {
        assert!(f.position.is_finite());
        assert!(
            room.contains_sphere(f.position, f.radius, 1e-9),
            "fireball left at step {step}"
        );
    }
}

#[test]
fn a_thousand_fast_balls_and_the_fireball_never_escape() {
    let mut cfg = WorldConfig::default();
    cfg.balls.count = 1000;
    cfg.balls.speed_min = 20.0;
    cfg.balls.speed_max = 100.0;
    cfg.fireball.speed = 40.0;
    let mut w = build(cfg, 9);
    w.launch_fireball(None);
    for step in 0..100_000 {
        w.step();
        w.drain_events().for_each(drop);
        if step % 100 == 0 || step > 99_900 {
            assert_inside_and_finite(&w, step);
        }
        if step % 5000 == 4999 {
            // Keep it lively: fresh fast balls every so often.
            w.reset_balls().expect("balls fit");
        }
    }
    assert_inside_and_finite(&w, 100_000);
    let fb = w.fireball().expect("fireball still there");
    assert!(
        (fb.velocity.length() - fb.speed).abs() < 1e-9 * fb.speed,
        "fireball speed changed"
    );
}

#[test]
fn balls_start_in_the_share_of_the_room_they_are_given_or_the_world_says_why() {
    let mut cfg = WorldConfig::default();
    cfg.balls.count = 2000;
    cfg.balls.start_fill = 0.25;
    let w = build(cfg.clone(), 3);
    let top = 0.25 * w.room().max.y;
    let heights = w.balls().positions().iter().map(|p| p.y);
    let highest = heights.clone().fold(f64::MIN, f64::max);
    assert!(
        highest + cfg.balls.radius <= top + 1e-9,
        "ball above the fill: {highest}"
    );
    // Spread through that share, not heaped on the floor.
    let lowest = heights.fold(f64::MAX, f64::min);
    assert!(highest - lowest > 0.5 * (top - 2.0 * cfg.balls.radius));
    assert_inside_and_finite(&w, 0);

    // Too thin a share for one ball, or none at all, is an error naming it.
    for fill in [0.01, 0.0, f64::NAN] {
        cfg.balls.start_fill = fill;
        let e = World::new(cfg.clone(), 3).err().expect("cannot be built");
        assert!(e.to_string().contains("balls.start_fill"), "{e}");
    }
}

#[test]
fn the_default_scene_comes_to_rest_within_two_minutes() {
    let mut w = build(WorldConfig::default(), 1);
    let dt = w.config().solver.dt;
    let mut rest_at = None;
    for step in 0..(120.0 / dt) as usize {
        w.step();
        w.drain_events().for_each(drop);
        let b = w.balls();
        let fastest_ball = b
            .velocities()
            .iter()
            .map(|v| v.length())
            .fold(0.0, f64::max);
        let fastest_tumbler = w
            .tumblers()
            .iter()
            .map(|t| t.linear_velocity().length())
            .fold(0.0, f64::max);
        if fastest_ball < 0.01 && fastest_tumbler < 0.01 {
            rest_at.get_or_insert(step as f64 * dt);
        } else {
            rest_at = None;
        }
        if step % 600 == 0 {
            assert_inside_and_finite(&w, step);
        }
    }
    let rest_at = rest_at.expect("still moving after 120 s");
    println!("the default scene comes to rest after {rest_at:.1} s");
    // Upright again, and the balls resting on something.
    for t in w.tumblers() {
        assert!(t.tilt().to_degrees() < 1.0);
    }
}

#[test]
fn same_seed_gives_bit_identical_states_other_seed_differs() {
    let run = |seed: u64| {
        let mut w = build(WorldConfig::default(), seed);
        w.launch_fireball(Some((
            DVec3::new(0.0, 1.0, 2.0),
            DVec3::new(1.0, 0.2, -1.0),
        )));
        let mut states = Vec::new();
        for step in 0..1500 {
            w.step();
            if step == 700 {
                w.grab(1, w.tumblers()[1].sphere_center(w.tumbler_shape(), 4));
            }
            if step > 700 && step < 900 {
                let target = DVec3::new(2.0 + (step as f64 * 0.05).sin(), 0.8, -1.0);
                w.drag_to(target);
            }
            if step == 900 {
                w.release();
                w.reset_balls().expect("balls fit");
            }
            let events: Vec<_> = w.drain_events().map(|e| format!("{e:?}")).collect();
            states.push((state_bits(&w), events));
        }
        states
    };
    let a = run(42);
    let b = run(42);
    let c = run(43);
    assert!(a == b, "two runs with the same seed differ");
    assert!(a != c, "another seed gives the same run");
}

/// A bed of 100 000 balls packed from the start, where one band of the
/// crowd's pairs holds more than half of a run's: its first steps run and
/// keep every ball in the room. (Splitting such a run between threads once
/// handed the whole run on again, without end.)
#[test]
fn a_hundred_thousand_balls_packed_from_the_start_step() {
    let mut cfg = WorldConfig::default();
    cfg.balls.count = 100_000;
    cfg.balls.radius = 0.1;
    cfg.balls.start_fill = 0.4;
    cfg.room.size = glam::DVec3::new(24.0, 5.0, 24.0);
    let mut w = World::new(cfg, 1).expect("scene builds");
    for _ in 0..3 {
        w.step();
    }
    let room = *w.room();
    assert!(
        w.balls()
            .positions()
            .iter()
            .all(|p| { p.is_finite() && p.cmpge(room.min).all() && p.cmple(room.max).all() })
    );
}
