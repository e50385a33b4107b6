//! The GPU engine against physics: the laws the CPU engine is held to,
//! checked on whatever adapter there is (lavapipe in CI).

mod common;

use common::*;
use glam::DVec3;
use std::time::Instant;

#[test]
fn a_pit_of_balls_settles_without_overlap_or_escape() {
    let compute = compute();
    for (count, seed) in [(2000, 1), (5000, 7)] {
        let side = if count > 3000 { 6.0 } else { 4.0 };
        let mut config = empty_room(DVec3::new(side, 3.0, side), count);
        config.balls.radius = 0.1;
        config.balls.restitution = 0.8;
        config.balls.friction = 0.3;
        config.room.restitution = 0.8;
        config.balls.speed_max = 1.0;
        config.balls.start_fill = 0.6;
        let (mut world, mut balls) = build(&compute, config, seed);
        let (min, max) = (world.room().min, world.room().max);
        let started = Instant::now();
        let mut worst: f64 = 0.0;
        for s in 0..1200 {
            step(&mut world, &mut balls);
            if s % 200 == 199 {
                let state = balls.read().unwrap();
                let (overlap, escaped) = overlap_and_escapes(&state, min, max);
                eprintln!(
                    "{count} balls t {:.2}: overlap {:.1} mm, escaped {escaped}, rest {:.3}, ke {:.2}",
                    (s + 1) as f64 / 120.0,
                    overlap * 1e3,
                    share_at_rest(&state, 0.05),
                    state.kinetic_energy()
                );
                worst = worst.max(overlap);
                assert_eq!(escaped, 0);
            }
        }
        eprintln!(
            "{count} balls: {:.1} steps/s",
            1200.0 / started.elapsed().as_secs_f64()
        );
        let state = balls.read().unwrap();
        assert!(worst < 0.010, "{count} balls overlap {worst}");
        assert!(share_at_rest(&state, 0.05) >= 0.99);
    }
}
