//! The hand holding a ball (I5, T6): picked by a ray, pulled to the hand's
//! point by a critically damped spring scaled by its mass, carried against
//! gravity, and flung with the hand's speed when let go.

mod common;

use common::{build, empty_room};
use glam::DVec3;
use rolypoly_physics::{BallPlacement, World};

fn world_with(balls: &[(DVec3, f64)]) -> World {
    let mut cfg = empty_room();
    cfg.balls.placements = balls
        .iter()
        .map(|&(at, mass)| {
            let mut p = BallPlacement::new(at, DVec3::ZERO);
            p.mass = Some(mass);
            p
        })
        .collect();
    build(cfg, 1)
}

fn steps(world: &World, seconds: f64) -> usize {
    (seconds / world.config().solver.dt).round() as usize
}

#[test]
fn a_ray_picks_the_nearest_ball_it_meets() {
    let r = empty_room().balls.radius;
    let world = world_with(&[
        (DVec3::new(0.0, r, 0.0), 0.25),
        (DVec3::new(0.0, r, -1.0), 0.25),
        (DVec3::new(1.0, r, 0.0), 0.25),
    ]);
    let eye = DVec3::new(0.0, r, 3.0);
    let pick = world
        .pick_ball(eye, DVec3::NEG_Z)
        .expect("a ball on the ray");
    assert_eq!(pick.ball, 0);
    assert!((pick.distance - (3.0 - r)).abs() < 1e-9);
    assert!((pick.point - DVec3::new(0.0, r, r)).length() < 1e-9);
    assert!(world.pick_ball(eye, DVec3::Y).is_none());
}

#[test]
fn a_held_ball_settles_on_the_hand_without_overshoot_whatever_its_mass() {
    let r = empty_room().balls.radius;
    for (target, mass) in [
        (DVec3::new(1.0, 1.5, 0.5), 0.25),
        (DVec3::new(-2.0, 0.8, -1.0), 5.0),
        (DVec3::new(0.3, 2.5, 1.5), 0.02),
    ] {
        let start = DVec3::new(0.0, r, 0.0);
        let mut world = world_with(&[(start, mass)]);
        world.hold_ball(0);
        assert_eq!(world.held_ball(), Some(0));
        world.drag_to(target);
        let total = (target - start).length();
        let mut closest = total;
        for _ in 0..steps(&world, 2.0) {
            world.step();
            let gone = (world.balls().positions()[0] - start).dot(target - start) / total;
            // Critically damped: it does not swing past the hand's point (a
            // spring damped half as much would by 16 % of the way; the
            // step's split of gravity leaves a few millimetres).
            assert!(
                gone <= total * 1.005,
                "mass {mass}: overshot by {}",
                gone - total
            );
            closest = closest.min((world.balls().positions()[0] - target).length());
        }
        let at = world.balls().positions()[0];
        assert!(
            (at - target).length() < 0.01,
            "mass {mass}: {at} against {target}"
        );
        assert!(world.balls().velocities()[0].length() < 0.05);
        assert!(closest < 0.01);
    }
}

#[test]
fn the_pull_is_scaled_by_mass_so_light_and_heavy_balls_move_alike() {
    let r = empty_room().balls.radius;
    let mut paths = Vec::new();
    for mass in [0.05, 0.25, 20.0] {
        let mut world = world_with(&[(DVec3::new(0.0, r, 0.0), mass)]);
        world.hold_ball(0);
        world.drag_to(DVec3::new(1.5, 1.0, 0.0));
        let mut path = Vec::new();
        for _ in 0..steps(&world, 0.5) {
            world.step();
            path.push(world.balls().positions()[0]);
        }
        paths.push(path);
    }
    for path in &paths[1..] {
        for (a, b) in path.iter().zip(&paths[0]) {
            assert!((*a - *b).length() < 1e-9, "{a} against {b}");
        }
    }
}

#[test]
fn a_ball_swung_and_let_go_flies_off_with_the_hands_speed() {
    let r = empty_room().balls.radius;
    for (speed, seed_height) in [(2.0, 1.5), (4.0, 2.0), (1.0, 1.0)] {
        let mut world = world_with(&[(DVec3::new(-2.5, r, 0.0), 0.25)]);
        let dt = world.config().solver.dt;
        world.hold_ball(0);
        let mut hand = DVec3::new(-2.5, seed_height, 0.0);
        world.drag_to(hand);
        for _ in 0..steps(&world, 1.0) {
            world.step();
        }
        // Swing the hand along +x at `speed` for half a second.
        for _ in 0..steps(&world, 0.5) {
            hand.x += speed * dt;
            world.drag_to(hand);
            world.step();
        }
        let v = world.balls().velocities()[0];
        assert!((v.x - speed).abs() < 0.05 * speed, "{v} against {speed}");
        world.release();
        assert_eq!(world.held_ball(), None);
        // Let go, it flies: the next step changes its velocity by gravity alone.
        let before = world.balls().velocities()[0];
        world.step();
        let after = world.balls().velocities()[0];
        let g = world.config().gravity;
        assert!(
            (after - before - DVec3::new(0.0, -g * dt, 0.0)).length() < 1e-9,
            "{before} -> {after}"
        );
    }
}

#[test]
fn holding_a_ball_lets_go_of_a_tumbler_and_a_restart_lets_go_of_the_ball() {
    let mut cfg = rolypoly_physics::WorldConfig::default();
    cfg.balls.count = 5;
    let mut world = build(cfg, 2);
    let point = world.tumblers()[0].center_of_mass();
    world.grab(0, point);
    assert_eq!(world.grabbed(), Some(0));
    world.hold_ball(3);
    assert_eq!((world.grabbed(), world.held_ball()), (None, Some(3)));
    world.grab(1, world.tumblers()[1].center_of_mass());
    assert_eq!((world.grabbed(), world.held_ball()), (Some(1), None));
    world.hold_ball(2);
    world.reset_balls().unwrap();
    assert_eq!(world.held_ball(), None);
}
