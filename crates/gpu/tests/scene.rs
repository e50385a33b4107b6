//! What a user sees the GPU engine do: reruns that repeat to the bit, the
//! fireball catching balls, tumblers shoved by balls and righting
//! themselves, a thrown ball, a restart, the default scene at rest.

mod common;

use common::*;
use glam::DVec3;
use rolypoly_physics::{EventKind, WorldConfig};

fn crowded_default(balls: usize) -> WorldConfig {
    let mut config = WorldConfig::default();
    config.balls.count = balls;
    config.balls.pour.rate = 0.0;
    config.fireball.starts_active = true;
    config
}

fn bits(state: &rolypoly_gpu::BallState) -> Vec<u32> {
    state
        .positions
        .iter()
        .chain(&state.velocities)
        .chain(&state.spins)
        .flat_map(|v| v.to_array().map(f32::to_bits))
        .collect()
}

/// `balls` balls, five tumblers and the fireball, `steps` steps: the same
/// seed gives the same bits, ball for ball and tumbler for tumbler, and
/// another seed others.
fn rerun_repeats_every_bit(balls: usize, steps: u32) {
    let compute = compute();
    let run = |seed| {
        let (mut world, mut gpu) = build(&compute, crowded_default(balls), seed);
        for _ in 0..steps {
            step(&mut world, &mut gpu);
        }
        let tumblers: Vec<_> = world.tumblers().iter().map(|t| t.bottom_center()).collect();
        (bits(&gpu.read().unwrap()), tumblers)
    };
    let first = run(3);
    assert_eq!(first, run(3));
    assert_ne!(first.0, run(4).0, "another seed, another run");
}

#[test]
fn a_rerun_repeats_every_bit() {
    rerun_repeats_every_bit(1500, 240);
}

/// Shorter, for a slower adapter (SwiftShader): still more balls than a
/// small world's one workgroup sweeps.
#[test]
fn a_short_rerun_repeats_every_bit() {
    rerun_repeats_every_bit(1100, 30);
}

#[test]
fn a_snapshot_put_back_steps_on_to_the_same_bits() {
    let compute = compute();
    for (count, seed) in [(400, 1), (2500, 7)] {
        let (mut world, mut balls) = build(&compute, crowded_default(count), seed);
        for _ in 0..60 {
            step(&mut world, &mut balls);
        }
        let (saved_world, saved) = (world.clone(), balls.snapshot().expect("a snapshot"));
        let run_on = |world: &mut rolypoly_physics::World, balls: &mut rolypoly_gpu::GpuBalls| {
            for _ in 0..90 {
                step(world, balls);
            }
            // The tumblers too: the pushes of the last steps before the
            // snapshot, still on their way, reach them after it.
            let tumblers: Vec<_> = world
                .tumblers()
                .iter()
                .map(|t| (t.bottom_center(), t.angular_velocity()))
                .collect();
            (bits(&balls.read().unwrap()), balls.steps(), tumblers)
        };
        let first = run_on(&mut world, &mut balls);
        // Back in the same engine, and in a fresh one of the same scene.
        world = saved_world.clone();
        balls
            .restore(&saved)
            .expect("the same engine takes it back");
        assert_eq!(
            first,
            run_on(&mut world, &mut balls),
            "{count} balls, seed {seed}"
        );
        let (_, mut fresh) = build(&compute, crowded_default(count), seed);
        let mut world = saved_world.clone();
        fresh
            .restore(&saved)
            .expect("an engine of the same scene takes it");
        assert_eq!(
            first,
            run_on(&mut world, &mut fresh),
            "{count} balls, seed {seed}, fresh"
        );
        // Another scene's engine refuses it and keeps its own balls.
        let (_, mut other) = build(&compute, crowded_default(count + 1), seed);
        let before = bits(&other.read().unwrap());
        assert!(other.restore(&saved).is_err());
        assert_eq!(before, bits(&other.read().unwrap()));
    }
}

#[test]
fn a_ball_set_on_the_gpu_moves_from_there() {
    let compute = compute();
    for seed in [1, 2] {
        let (mut world, mut balls) = build(&compute, empty_room(DVec3::splat(3.0), 50), seed);
        // Somewhere clear of every other ball and the walls.
        let start = balls.read().unwrap();
        let clear = |p: DVec3| {
            (0..start.positions.len())
                .filter(|&i| i != 7)
                .all(|i| (start.positions[i].as_dvec3() - p).length() > 0.4)
        };
        let at = (0..1000)
            .map(|k| {
                DVec3::new(
                    -1.0 + 0.1 * f64::from(k % 10),
                    0.5 + 0.2 * f64::from(k / 100),
                    -1.0 + 0.2 * f64::from((k / 10) % 10),
                )
            })
            .find(|&p| clear(p))
            .expect("a clear place in a room of 50 balls");
        let towards = DVec3::new(1.0, 0.0, 0.0);
        balls.set_ball(7, at, towards).expect("ball 7 exists");
        let state = balls.read().unwrap();
        assert_eq!(state.positions[7].as_dvec3(), at.as_vec3().as_dvec3());
        assert_eq!(state.velocities[7].as_dvec3(), towards);
        let radius = state.radii[7];
        step(&mut world, &mut balls);
        let after = balls.read().unwrap();
        // Flying freely: a step's travel along x, falling under gravity.
        let dt = world.config().solver.dt;
        assert!((f64::from(after.positions[7].x) - (at.x + dt)).abs() < 1e-5);
        assert!(f64::from(after.positions[7].y) < at.y);
        assert_eq!(after.radii[7], radius, "its size stays");
        assert!(
            balls.set_ball(50, at, towards).is_err(),
            "there is no ball 50"
        );
    }
}

#[test]
fn a_steps_dispatches_are_counted_and_do_not_grow_with_the_balls() {
    let compute = compute();
    let dispatches = |count: usize, side: f64| {
        let (mut world, mut balls) = build(&compute, empty_room(DVec3::splat(side), count), 1);
        assert_eq!(balls.dispatches_per_step(), 0, "none before the first step");
        step(&mut world, &mut balls);
        balls.dispatches_per_step()
    };
    let small = dispatches(500, 3.0);
    let (some, many) = (dispatches(3000, 5.0), dispatches(30_000, 10.0));
    // A world of up to 1024 balls sweeps each stage in one workgroup.
    assert!(small > 0 && small < some, "{small} against {some}");
    // Ten times the balls: the same passes, but for the grid's scan, one
    // level (two dispatches) more for each 1024-fold of cells.
    assert!(many >= some && many <= some + 2, "{some} then {many}");
    // The solver's dispatches each run several sweeps among a block of
    // balls, not one sweep each (119 a step that way), nor one for each of
    // 27 colours of cell (337); the impacts' rounds need no sweeps (83
    // with three rounds of twelve) and take one dispatch each, not two (68);
    // the overlaps are shifted out in the solver's sweeps, not in sixteen
    // dispatches of their own.
    assert!(many <= 40, "{many} dispatches a step");
}

#[test]
fn impacts_count_the_balls_that_meet_a_contact_and_none_at_rest() {
    let compute = compute();
    for (count, side, seed) in [(300, 2.0, 1), (700, 3.0, 6)] {
        let mut config = empty_room(DVec3::new(side, 2.0, side), count);
        config.balls.radius = 0.1;
        config.balls.friction = 0.5;
        config.balls.start_fill = 0.6;
        let (mut world, mut balls) = build(&compute, config, seed);
        // In many dispatches, as a large world is.
        balls.sweep_in_one_group_up_to(0);
        let mut most = vec![0; balls.impact_counts().unwrap().len()];
        for _ in 0..60 {
            step(&mut world, &mut balls);
            let counts = balls.impact_counts().unwrap();
            for (m, l) in most.iter_mut().zip(counts) {
                *m = (*m).max(l);
            }
            assert!(counts.iter().all(|&c| c as usize <= count), "{counts:?}");
        }
        // The fall: balls land on the floor and on each other, and a blow
        // passes on in the later rounds.
        assert!(most[0] > 0 && most[1] > 0, "{count} balls: {most:?}");
        for _ in 60..1200 {
            step(&mut world, &mut balls);
        }
        let state = balls.read().unwrap();
        assert!(share_at_rest(&state, 0.05) > 0.99, "{count} balls");
        let counts = balls.impact_counts().unwrap();
        assert!(
            counts.iter().all(|&c| c == 0),
            "{count} balls at rest: {counts:?}"
        );
    }
}

/// The largest change of velocity between two states of the same balls.
fn largest_difference(a: &rolypoly_gpu::BallState, b: &rolypoly_gpu::BallState) -> f32 {
    a.velocities
        .iter()
        .zip(&b.velocities)
        .map(|(u, v)| (*u - *v).length())
        .fold(0.0, f32::max)
}

#[test]
fn a_small_world_swept_in_one_workgroup_steps_as_in_many() {
    let compute = compute();
    for (count, side, seed) in [(300, 2.0, 2), (1500, 4.0, 5)] {
        // A pit filling its floor, so that every colour of cell has
        // contacts to sweep.
        let mut config = empty_room(DVec3::new(side, 2.0, side), count);
        config.balls.radius = 0.1;
        config.balls.friction = 0.5;
        config.balls.start_fill = 0.6;
        let (mut world_a, mut a) = build(&compute, config.clone(), seed);
        let (mut world_b, mut b) = build(&compute, config, seed);
        a.sweep_in_one_group_up_to(0);
        b.sweep_in_one_group_up_to(0);
        // Into the thick of the fall, the same way.
        for _ in 0..90 {
            step(&mut world_a, &mut a);
            step(&mut world_b, &mut b);
        }
        let before = a.read().unwrap();
        assert_eq!(bits(&before), bits(&b.read().unwrap()));
        // One step each way. The two are compiled apart, and an adapter
        // may round a multiply-add fused in one and not in the other:
        // they agree to rounding, not to the bit.
        b.sweep_in_one_group_up_to(u32::MAX);
        step(&mut world_a, &mut a);
        step(&mut world_b, &mut b);
        let (after_a, after_b) = (a.read().unwrap(), b.read().unwrap());
        let moved = largest_difference(&before, &after_a);
        let apart = largest_difference(&after_a, &after_b);
        assert!(
            moved > 0.1,
            "{count} balls: the step changed little ({moved} m/s)"
        );
        assert!(
            apart < 1e-4,
            "{count} balls: one workgroup and many dispatches part by {apart} m/s"
        );
    }
}

#[test]
fn the_fireball_catches_the_balls_it_meets() {
    let compute = compute();
    for seed in [1, 6] {
        let mut config = crowded_default(400);
        config.fireball.consumes_balls = true;
        let (mut world, mut balls) = build(&compute, config, seed);
        let mut caught = Vec::new();
        for _ in 0..360 {
            step(&mut world, &mut balls);
            balls.take_events(&mut caught);
        }
        balls.take_events_in_flight().unwrap();
        balls.take_events(&mut caught);
        let state = balls.read().unwrap();
        let dead: Vec<usize> = (0..state.alive.len())
            .filter(|&i| !state.alive[i])
            .collect();
        let mut reported: Vec<usize> = caught
            .iter()
            .map(|e| match e.kind {
                EventKind::FireballBall { ball } => ball,
                other => panic!("{other:?}"),
            })
            .collect();
        reported.sort_unstable();
        assert!(dead.len() >= 3, "seed {seed}: caught {}", dead.len());
        assert_eq!(reported, dead, "seed {seed}: every catch reported once");
    }
}

#[test]
fn balls_shove_a_tumbler_which_rights_itself() {
    let compute = compute();
    for speed in [4.0, 6.0] {
        let mut config = WorldConfig::default();
        config.fireball.starts_active = false;
        config.tumblers.placements.truncate(1);
        let t = config.tumblers.placements[0];
        config.balls.count = 0;
        // A volley at the head, from the side.
        config.balls.placements = (0..12)
            .map(|k| {
                let (row, column) = ((k / 3) as f64, (k % 3) as f64 - 1.0);
                let at = DVec3::new(t.x - 0.6 - 0.3 * row, 0.55, t.z + 0.3 * column);
                placed(at, DVec3::new(speed, 0.5, 0.0))
            })
            .collect();
        let (mut world, mut balls) = build(&compute, config, 1);
        let tilt = |world: &rolypoly_physics::World| world.tumblers()[0].tilt();
        let mut early = 0.0f64;
        for _ in 0..240 {
            step(&mut world, &mut balls);
            early = early.max(tilt(&world));
        }
        assert!(
            early.to_degrees() > 3.0,
            "speed {speed}: leaned only {:.2}°",
            early.to_degrees()
        );
        for _ in 0..960 {
            step(&mut world, &mut balls);
        }
        // Still rocking (a roly-poly is barely damped), but less, and about
        // the upright: its axis, averaged over the last two seconds, stands.
        let (mut late, mut axis) = (0.0f64, DVec3::ZERO);
        for _ in 0..240 {
            step(&mut world, &mut balls);
            late = late.max(tilt(&world));
            axis += world.tumblers()[0].axis();
        }
        let mean_tilt = axis.normalize().y.acos().to_degrees();
        assert!(
            late < 0.8 * early,
            "speed {speed}: rocks {:.2}° after {:.2}°",
            late.to_degrees(),
            early.to_degrees()
        );
        assert!(
            mean_tilt < 3.0,
            "speed {speed}: leans {mean_tilt:.2}° on average"
        );
    }
}

#[test]
fn a_thrown_ball_flies_and_a_restart_takes_it_away() {
    let compute = compute();
    let mut config = crowded_default(50);
    config.fireball.starts_active = false;
    let (mut world, mut balls) = build(&compute, config, 2);
    let before = balls.read().unwrap();
    let thrown = balls
        .throw_ball(
            &mut world,
            DVec3::new(0.0, 2.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
        )
        .unwrap();
    assert_eq!((thrown, balls.len()), (50, 51));
    step(&mut world, &mut balls);
    let state = balls.read().unwrap();
    let dt = world.config().solver.dt as f32;
    let g = world.config().gravity as f32;
    let expected = glam::Vec3::new(dt, 2.0 - 0.5 * g * dt * dt, 0.0);
    assert!(
        state.positions[thrown].distance(expected) < 1e-5,
        "{}",
        state.positions[thrown]
    );
    assert!((state.velocities[thrown].y + g * dt).abs() < 1e-5);
    for _ in 0..120 {
        step(&mut world, &mut balls);
    }
    balls.restart(&mut world).unwrap();
    let after = balls.read().unwrap();
    assert_eq!(after.positions.len(), 50, "the thrown ball is gone");
    assert!(after.alive.iter().all(|&a| a));
    assert_eq!(
        after.colors, before.colors,
        "every ball its starting colour"
    );
    assert_ne!(after.positions, before.positions, "new random places");
    let (overlap, escaped) = overlap_and_escapes(&after, world.room().min, world.room().max);
    assert!(overlap < 1e-6 && escaped == 0, "{overlap} {escaped}");
}

#[test]
fn the_default_scene_comes_to_rest() {
    let compute = compute();
    for seed in [1, 2, 3] {
        let (mut world, mut balls) = build(&compute, WorldConfig::default(), seed);
        let fastest = |balls: &rolypoly_gpu::GpuBalls| {
            let state = balls.read().unwrap();
            state
                .velocities
                .iter()
                .map(|v| v.length())
                .fold(0.0, f32::max)
        };
        // Thrown in at speed, the balls are still moving after a second.
        for _ in 0..120 {
            step(&mut world, &mut balls);
        }
        assert!(fastest(&balls) > 0.5, "seed {seed}");
        for _ in 120..2400 {
            step(&mut world, &mut balls);
        }
        let last = fastest(&balls);
        assert!(
            last < 1e-3,
            "seed {seed}: a ball still moves at {last} m/s after 20 s"
        );
    }
}
