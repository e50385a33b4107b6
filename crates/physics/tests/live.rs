//! What a player changes while the world runs: settings taken at the next
//! step, settings that wait for a rebuild, and thrown balls.

mod common;

use common::{build, empty_room};
use glam::DVec3;
use rolypoly_physics::{World, WorldConfig};

/// One ball at rest in mid-air in an empty room.
fn lone_ball(gravity: f64) -> World {
    let mut cfg = empty_room();
    cfg.gravity = gravity;
    let mut world = build(cfg, 1);
    world.throw_ball(DVec3::new(0.0, 3.0, 0.0), DVec3::ZERO);
    world
}

#[test]
fn tuned_gravity_is_the_next_steps_acceleration() {
    for (before, after) in [(9.81, 3.0), (9.81, 0.0), (1.62, 24.8)] {
        let mut world = lone_ball(before);
        let dt = world.config().solver.dt;
        world.step();
        let v0 = world.balls().velocities()[0].y;
        assert!((v0 + before * dt).abs() < 1e-12, "{v0}");
        let mut cfg = world.config().clone();
        cfg.gravity = after;
        world.tune(&cfg);
        world.step();
        let dv = world.balls().velocities()[0].y - v0;
        assert!(
            (dv + after * dt).abs() < 1e-12,
            "gravity {after}: dv {dv}, expected {}",
            -after * dt
        );
        assert!(!world.needs_rebuild(&cfg));
    }
}

/// Height of a ball's first rebound off the floor after a drop from 1.5 m
/// in a room whose restitution is tuned to `e` after the world is built.
fn rebound_ratio(e: f64) -> f64 {
    let mut world = lone_ball(9.81);
    let mut cfg = world.config().clone();
    cfg.room.restitution = e;
    cfg.balls.restitution = e;
    cfg.solver.bounce_threshold = 0.0;
    world.tune(&cfg);
    let r = world.config().balls.radius;
    let floor = world.room().min.y;
    let drop = world.balls().positions()[0].y - floor - r;
    let mut fell = false;
    let mut top: f64 = 0.0;
    for _ in 0..2000 {
        world.step();
        let v = world.balls().velocities()[0].y;
        let h = world.balls().positions()[0].y - floor - r;
        if v > 0.0 {
            fell = true;
            top = top.max(h);
        } else if fell {
            break;
        }
    }
    top / drop
}

#[test]
fn tuned_restitution_gives_the_rebound_of_e_squared() {
    for e in [0.3, 0.6, 0.9] {
        let ratio = rebound_ratio(e);
        assert!(
            (ratio - e * e).abs() < 0.01 * e * e,
            "e = {e}: rebound {ratio}, expected {}",
            e * e
        );
    }
}

#[test]
fn sizes_and_counts_wait_for_a_rebuild() {
    let world = build(WorldConfig::default(), 3);
    let base = world.config().clone();
    type Change = (&'static str, fn(&mut WorldConfig));
    let changes: [Change; 6] = [
        ("ball count", |c| c.balls.count += 1),
        ("ball radius", |c| c.balls.radius *= 1.1),
        ("ball mass", |c| c.balls.mass *= 2.0),
        ("room size", |c| c.room.size.x += 1.0),
        ("time step", |c| c.solver.dt *= 0.5),
        ("tumbler places", |c| {
            c.tumblers.placements.pop().map_or((), drop)
        }),
    ];
    for (what, change) in changes {
        let mut cfg = base.clone();
        change(&mut cfg);
        assert!(world.needs_rebuild(&cfg), "{what}");
        let mut tuned = build(WorldConfig::default(), 3);
        tuned.tune(&cfg);
        assert_eq!(tuned.config(), &base, "{what} was taken while running");
    }
    let mut cfg = base.clone();
    cfg.gravity = 5.0;
    cfg.room.friction = 0.1;
    cfg.solver.iterations = 3;
    cfg.grab.stiffness *= 2.0;
    cfg.fireball.speed = 2.0;
    assert!(!world.needs_rebuild(&cfg));
}

#[test]
fn a_thrown_ball_flies_the_parabola_and_stays_in_the_room() {
    let mut world = lone_ball(9.81);
    world
        .balls_mut()
        .set(0, DVec3::new(0.0, 0.5, 3.0), DVec3::ZERO);
    let g = world.config().gravity;
    let dt = world.config().solver.dt;
    let from = DVec3::new(-1.0, 2.0, 0.0);
    let v = DVec3::new(2.0, 1.0, -0.5);
    let k = world.throw_ball(from, v);
    assert_eq!((k, world.balls().len()), (1, 2));
    let steps = 30;
    for _ in 0..steps {
        world.step();
    }
    let t = steps as f64 * dt;
    let expected = from + v * t - DVec3::Y * (0.5 * g * t * t);
    let at = world.balls().positions()[k];
    assert!(at.distance(expected) < 1e-9, "{at} vs {expected}");
}

#[test]
fn balls_thrown_into_a_crowd_stay_in_the_room_and_go_on_reset() {
    for seed in [4, 5, 6] {
        let mut world = build(WorldConfig::default(), seed);
        let start = world.balls().len();
        let room = *world.room();
        let mut rng = rolypoly_physics::Rng::new(seed);
        for i in 0..400 {
            if i % 4 == 0 {
                // From anywhere, even outside the room or inside a tumbler.
                let from = room.min
                    + (room.max - room.min) * DVec3::new(rng.unit(), rng.unit(), rng.unit());
                world.throw_ball(from * 1.2, rng.direction() * 8.0);
            }
            world.step();
        }
        assert_eq!(world.balls().len(), start + 100);
        let b = world.balls();
        for i in 0..b.len() {
            let p = b.positions()[i];
            assert!(p.is_finite() && b.velocities()[i].is_finite(), "ball {i}");
            if b.alive()[i] {
                assert!(
                    room.contains_sphere(p, b.radii()[i], 1e-6),
                    "ball {i} at {p}"
                );
            }
        }
        world.reset_balls().unwrap();
        assert_eq!(world.balls().len(), start);
        for _ in 0..10 {
            world.step();
        }
    }
}

#[test]
fn the_same_throws_at_the_same_steps_give_the_same_bits() {
    let run = || {
        let mut world = build(WorldConfig::default(), 9);
        for i in 0..240 {
            if i % 30 == 5 {
                world.throw_ball(DVec3::new(0.0, 2.0, 2.0), DVec3::new(0.3, 0.0, -6.0));
            }
            if i == 100 {
                let mut cfg = world.config().clone();
                cfg.gravity = 2.0;
                world.tune(&cfg);
            }
            world.step();
        }
        world
    };
    let (a, b) = (run(), run());
    assert_eq!(a.balls(), b.balls());
    assert_eq!(a.tumblers(), b.tumblers());
}
