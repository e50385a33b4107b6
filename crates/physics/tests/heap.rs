//! A poured heap (F2): balls poured from a spout onto the floor stand at an
//! angle of repose that rises with friction and with rolling resistance
//! between them, and come to rest.

mod common;

use common::{build, empty_room};
use glam::DVec3;
use rolypoly_physics::{PourConfig, World, angle_of_repose};

const RADIUS: f64 = 0.04;

/// A thousand balls poured from a spout 0.8 m above the floor, with the
/// given friction and rolling resistance between balls (and on the floor),
/// run until poured and settled. Returns the world.
fn poured_heap(friction: f64, rolling_resistance: f64, seed: u64) -> World {
    let mut cfg = empty_room();
    cfg.room.size = DVec3::new(2.0, 1.5, 2.0);
    cfg.room.friction = 0.5;
    cfg.room.rolling_resistance = rolling_resistance;
    cfg.balls.count = 1000;
    cfg.balls.radius = RADIUS;
    cfg.balls.mass = 0.03;
    cfg.balls.restitution = 0.3;
    cfg.balls.friction = friction;
    cfg.balls.rolling_resistance = rolling_resistance;
    cfg.balls.pour = PourConfig {
        rate: 200.0,
        spout: DVec3::new(0.0, 0.8, 0.0),
        radius: 0.15,
    };
    let mut world = build(cfg, seed);
    let dt = world.config().solver.dt;
    while world.balls_to_pour() > 0 {
        world.step();
        assert!(world.time() < 30.0, "the spout never emptied");
    }
    for _ in 0..(4.0 / dt) as usize {
        world.step();
    }
    world
}

/// The heap's angle in degrees, of the balls at rest on it.
fn angle(world: &World) -> f64 {
    let b = world.balls();
    let resting: Vec<DVec3> = (0..b.len())
        .filter(|&k| b.alive()[k] && b.velocities()[k].length() < 0.05)
        .map(|k| b.positions()[k])
        .collect();
    angle_of_repose(&resting, RADIUS, [0.0, 0.0]).unwrap_or(0.0)
}

/// The share of the balls that move faster than a centimetre a second.
fn moving_share(world: &World) -> f64 {
    let b = world.balls();
    let moving = b.velocities().iter().filter(|v| v.length() > 0.01).count();
    moving as f64 / b.len() as f64
}

#[test]
fn the_angle_of_repose_rises_with_friction_between_balls() {
    for seed in [1, 2] {
        let slippery = poured_heap(0.05, 0.05, seed);
        let rough = poured_heap(0.8, 0.05, seed + 10);
        let (low, high) = (angle(&slippery), angle(&rough));
        println!("friction 0.05: {low:.1} deg, 0.8: {high:.1} deg");
        assert!(
            high > low + 5.0,
            "friction 0.05: {low:.1} deg, 0.8: {high:.1} deg"
        );
        for heap in [&slippery, &rough] {
            assert!(
                moving_share(heap) < 0.1,
                "{:.0} % still move",
                100.0 * moving_share(heap)
            );
        }
    }
}

#[test]
fn the_angle_of_repose_rises_with_rolling_resistance() {
    for seed in [3, 4] {
        let rolling = poured_heap(0.3, 0.0, seed);
        let resisting = poured_heap(0.3, 0.3, seed + 10);
        let (low, high) = (angle(&rolling), angle(&resisting));
        println!("rolling resistance 0: {low:.1} deg, 0.3: {high:.1} deg");
        assert!(
            high > low + 5.0,
            "rolling resistance 0: {low:.1} deg, 0.3: {high:.1} deg"
        );
    }
}
