//! The GPU engine against physics: the laws the CPU engine is held to,
//! checked on whatever adapter there is (lavapipe in CI). The larger pits
//! are left out of a plain `cargo test`: on a software Vulkan they take
//! tens of minutes, where a GPU takes seconds; `scripts/gpu-check` runs
//! them on a GPU (`--include-ignored`).

mod common;

use common::*;
use glam::DVec3;
use std::time::Instant;

/// A pit of balls with friction between them settles: no overlap deeper
/// than 10 mm at any time, none escaping, 99 % at rest at 10 s. The pit is
/// more than four of the solver's blocks of 256 balls, so contacts across
/// the blocks' edges are worked out as they are in a large one.
#[test]
fn a_pit_of_balls_settles_without_overlap_or_escape() {
    pits_settle(&[(1200, 1)], 0.3, 0.99);
}

/// The same law for more balls and other seeds.
#[test]
#[ignore = "tens of minutes on a software Vulkan; scripts/gpu-check runs it on a GPU"]
fn larger_pits_of_balls_settle_without_overlap_or_escape() {
    pits_settle(&[(2000, 3), (5000, 7), (20000, 11)], 0.3, 0.99);
}

/// Without friction between balls nothing but their contacts takes a
/// pile's trembling out: where the solver's sweeps leave its pushes
/// unsolved (its blocks' edges), it never comes to rest. A frictionless
/// pile steps slowest of all on a software Vulkan (0.5 steps/s at 1 100
/// balls on two cores), so this law runs on a GPU only.
#[test]
#[ignore = "tens of minutes on a software Vulkan; scripts/gpu-check runs it on a GPU"]
fn frictionless_pits_come_to_rest() {
    pits_settle(&[(2500, 2), (4000, 5), (20000, 13)], 0.0, 0.98);
}

/// Each pit of `(balls, seed)` with ball-on-ball friction `friction`
/// settles: overlap under 10 mm and `resting` of the balls at rest at 10 s.
fn pits_settle(pits: &[(usize, u64)], friction: f64, resting: f64) {
    for &(count, seed) in pits {
        let (worst, at_rest) = settle_pit(count, seed, friction);
        assert!(worst < 0.010, "{count} balls, seed {seed}: overlap {worst}");
        assert!(
            at_rest >= resting,
            "{count} balls, seed {seed}: {at_rest} at rest"
        );
    }
}

/// A pit of `count` balls dropped as the bench drops them, with Coulomb
/// friction `friction` between balls, run for 10 s: the deepest overlap
/// seen (m; every few steps through the landing, where the deepest come
/// and go within a step or two) and the share at rest at the end. No ball
/// may leave the room.
fn settle_pit(count: usize, seed: u64, friction: f64) -> (f64, f64) {
    let compute = compute();
    // The room's floor grows with the pit, so that the pile is as deep.
    let side = 4.0 * (count as f64 / 2000.0).sqrt().max(0.75);
    let mut config = empty_room(DVec3::new(side, 3.0, side), count);
    config.balls.radius = 0.1;
    config.balls.restitution = 0.8;
    config.balls.friction = friction;
    config.room.restitution = 0.8;
    config.balls.speed_max = 1.0;
    config.balls.start_fill = 0.6;
    // The bench's step, twice the default: balls fall further into
    // each other, and a blow passes down a column within one step.
    config.solver.dt = 1.0 / 60.0;
    let (mut world, mut balls) = build(&compute, config, seed);
    let (min, max) = (world.room().min, world.room().max);
    let started = Instant::now();
    let mut worst: f64 = 0.0;
    let steps = 600;
    for s in 1..=steps {
        step(&mut world, &mut balls);
        if (s <= 120 && s % 3 == 0) || s % 100 == 0 {
            let state = balls.read().unwrap();
            let (overlap, escaped) = overlap_and_escapes(&state, min, max);
            if s % 60 == 0 {
                eprintln!(
                    "{count} balls, friction {friction}, t {:.2} ({:.0} s in): overlap {:.1} mm (worst {:.1}), escaped {escaped}, rest {:.3}, ke {:.2}",
                    s as f64 / 60.0,
                    started.elapsed().as_secs_f64(),
                    overlap * 1e3,
                    worst.max(overlap) * 1e3,
                    share_at_rest(&state, 0.05),
                    state.kinetic_energy()
                );
            }
            worst = worst.max(overlap);
            assert_eq!(escaped, 0, "{count} balls, friction {friction}");
        }
    }
    eprintln!(
        "{count} balls: {:.1} steps/s",
        f64::from(steps) / started.elapsed().as_secs_f64()
    );
    let state = balls.read().unwrap();
    (worst, share_at_rest(&state, 0.05))
}

/// Successive bounce heights of one ball dropped from `drop` (m) onto a
/// floor of restitution `e`: the ratio of the second to the first.
fn rebound_ratio(drop: f64, e: f64) -> f64 {
    let compute = compute();
    let mut config = empty_room(DVec3::new(2.0, 3.0, 2.0), 0);
    config.room.restitution = e;
    config.room.rolling_resistance = 0.0;
    let r = config.balls.radius;
    config.balls.placements = vec![placed(DVec3::new(0.0, r + drop, 0.0), DVec3::ZERO)];
    let (mut world, mut balls) = build(&compute, config, 1);
    let mut apexes = Vec::new();
    let mut last_vy = 0.0f32;
    let mut last_y = 0.0f32;
    for _ in 0..600 {
        step(&mut world, &mut balls);
        let state = balls.read().unwrap();
        let (y, vy) = (state.positions[0].y, state.velocities[0].y);
        if last_vy > 0.0 && vy <= 0.0 {
            apexes.push(f64::from(y.max(last_y)) - r);
        }
        (last_vy, last_y) = (vy, y);
        if apexes.len() == 2 {
            break;
        }
    }
    assert_eq!(apexes.len(), 2, "two bounces from {drop} m");
    apexes[1] / apexes[0]
}

#[test]
fn each_bounce_rises_e_squared_as_high_as_the_last() {
    for (drop, e) in [(1.0, 0.8), (0.6, 0.5), (1.5, 0.9)] {
        let ratio = rebound_ratio(drop, e);
        let law = e * e;
        assert!(
            (ratio / law - 1.0).abs() < 0.02,
            "drop {drop}, e {e}: h1/h0 {ratio}, e² {law}"
        );
    }
}

#[test]
fn a_blow_passes_along_a_row_of_balls_as_in_newtons_cradle() {
    let compute = compute();
    // Rows of two to thirteen balls (the longest a step's impact rounds
    // pass a blow along), each a few millimetres from the next, the first
    // flying at the rest: at each speed, within one step.
    for (count, speed, gap) in [(2, 1.0, 0.001), (5, 2.5, 0.004), (13, 0.7, 0.0)] {
        // The row alone: placed balls only.
        let mut config = empty_room(DVec3::new(8.0, 2.0, 2.0), 0);
        config.gravity = 0.0;
        config.balls.restitution = 1.0;
        config.balls.friction = 0.0;
        config.solver.bounce_threshold = 0.0;
        let r = config.balls.radius;
        config.balls.placements = (0..count)
            .map(|k| {
                let x = -3.0 + k as f64 * (2.0 * r + gap);
                let v = if k == 0 { speed } else { 0.0 };
                placed(DVec3::new(x, 1.0, 0.0), DVec3::new(v, 0.0, 0.0))
            })
            .collect();
        // In one workgroup, as so small a world is, and in many dispatches.
        for in_one_group in [true, false] {
            let (mut world, mut balls) = build(&compute, config.clone(), 3);
            if !in_one_group {
                balls.sweep_in_one_group_up_to(0);
            }
            step(&mut world, &mut balls);
            let state = balls.read().unwrap();
            let last = state.velocities[count - 1];
            assert!(
                (f64::from(last.x) - speed).abs() < 1e-5 * speed && last.y.hypot(last.z) < 1e-6,
                "{count} balls: the last moves at {last} for {speed}"
            );
            for (k, v) in state.velocities[..count - 1].iter().enumerate() {
                assert!(
                    f64::from(v.length()) < 1e-5 * speed,
                    "{count} balls: ball {k} kept {v}"
                );
            }
        }
    }
}

/// `count` balls flying 1 to 3 m/s through an 8 x 4 x 8 m box, every
/// impact elastic and frictionless; every impact bounces, however slow,
/// as in the CPU engine's elastic room.
fn elastic_gas(count: usize) -> rolypoly_physics::WorldConfig {
    let mut config = empty_room(DVec3::new(8.0, 4.0, 8.0), count);
    config.balls.restitution = 1.0;
    config.room.restitution = 1.0;
    config.balls.friction = 0.0;
    config.room.friction = 0.0;
    config.room.rolling_resistance = 0.0;
    config.solver.bounce_threshold = 0.0;
    config.balls.speed_min = 1.0;
    config.balls.speed_max = 3.0;
    config.balls.start_fill = 1.0;
    config
}

#[test]
fn elastic_balls_without_gravity_keep_their_energy_and_momentum() {
    let compute = compute();
    for seed in [2, 9] {
        // A gas: the balls fill 0.4 % of the box, and meet two at a time.
        let mut config = elastic_gas(1000);
        config.gravity = 0.0;
        let (mut world, mut balls) = build(&compute, config, seed);
        let start = balls.read().unwrap().kinetic_energy();
        let mut lowest = start;
        for s in 0..1200 {
            step(&mut world, &mut balls);
            if s % 60 == 59 {
                let now = balls.read().unwrap().kinetic_energy();
                // Single precision rounds each impulse; a gain beyond that is made.
                assert!(
                    now <= start * (1.0 + 1e-4),
                    "seed {seed}: {now} J from {start} J at step {s}"
                );
                lowest = lowest.min(now);
            }
        }
        assert!(
            lowest >= 0.99 * start,
            "seed {seed}: fell to {lowest} J from {start} J"
        );
    }
}

#[test]
fn an_elastic_gas_under_gravity_keeps_its_energy() {
    let compute = compute();
    for (count, seed) in [(100, 2), (100, 5), (200, 3), (200, 8), (400, 4), (400, 9)] {
        let config = elastic_gas(count);
        let g = config.gravity;
        let (mut world, mut balls) = build(&compute, config, seed);
        // Kinetic and potential (from the floor, y = 0), in single precision's sum.
        let energy = |s: &rolypoly_gpu::BallState| {
            let potential: f64 = (0..s.positions.len())
                .map(|i| g * f64::from(s.positions[i].y) / f64::from(s.inverse_masses[i]))
                .sum();
            s.kinetic_energy() + potential
        };
        let start = energy(&balls.read().unwrap());
        let mut lowest = start;
        for s in 0..1200 {
            step(&mut world, &mut balls);
            if s % 60 == 59 {
                let now = energy(&balls.read().unwrap());
                assert!(
                    now <= start * (1.0 + 1e-4),
                    "{count} balls, seed {seed}: {now} J from {start} J at step {s}"
                );
                lowest = lowest.min(now);
            }
        }
        let lost = 1.0 - lowest / start;
        eprintln!(
            "{count} balls, seed {seed}: lost {:.3} % in 10 s",
            100.0 * lost
        );
        assert!(
            lost <= 0.01,
            "{count} balls, seed {seed}: lost {:.2} %",
            100.0 * lost
        );
    }
}

#[test]
fn fast_balls_and_the_fireball_stay_finite_and_in_the_room() {
    fast_balls_stay_in_the_room(3_000);
}

/// The same for a hundred thousand steps (nearly 14 minutes of play).
#[test]
#[ignore = "tens of minutes on a software Vulkan; scripts/gpu-check runs it on a GPU"]
fn fast_balls_and_the_fireball_stay_finite_and_in_the_room_for_100_000_steps() {
    fast_balls_stay_in_the_room(100_000);
}

/// Sixty balls at 8 to 15 m/s and the fireball at 12 m/s in a small room,
/// `steps` steps: none leaves the room and no velocity is NaN or infinite.
fn fast_balls_stay_in_the_room(steps: u32) {
    let compute = compute();
    let mut config = empty_room(DVec3::new(3.0, 2.5, 3.0), 60);
    config.balls.speed_min = 8.0;
    config.balls.speed_max = 15.0;
    config.fireball.starts_active = true;
    config.fireball.consumes_balls = false;
    config.fireball.speed = 12.0;
    let (mut world, mut balls) = build(&compute, config, 4);
    let (min, max) = (world.room().min, world.room().max);
    for s in 0..steps {
        step(&mut world, &mut balls);
        if s % 1000 == 999 || s + 1 == steps {
            let state = balls.read().unwrap();
            let (_, escaped) = overlap_and_escapes(&state, min, max);
            assert_eq!(escaped, 0, "step {s}");
            assert!(state.velocities.iter().all(|v| v.is_finite()), "step {s}");
        }
    }
}
