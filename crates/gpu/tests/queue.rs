//! Steps queued ahead: the CPU takes a step's report (the tumblers'
//! pushes, the catches, the impacts) `REPORT_DELAY` steps later, so a GPU
//! that keeps up is never waited for; and the delay is counted in steps,
//! whatever the GPU's pace.

mod common;

use std::time::{Duration, Instant};

use common::*;
use glam::DVec3;
use rolypoly_gpu::{GpuBalls, REPORT_DELAY};
use rolypoly_physics::{EventKind, Surface, World, WorldConfig};

/// Steps `frames` frames of two steps each, as a 60 Hz display shows the
/// scene's 120 steps a second, each frame lasting at least `frame`; the
/// blocking waits they took.
fn paced(world: &mut World, balls: &mut GpuBalls, frames: u32, frame: Duration) -> u64 {
    let before = balls.blocking_waits();
    for _ in 0..frames {
        let start = Instant::now();
        step(world, balls);
        step(world, balls);
        if let Some(rest) = frame.checked_sub(start.elapsed()) {
            std::thread::sleep(rest);
        }
    }
    balls.blocking_waits() - before
}

/// The longest the adapter took over one step of `world`, each waited for.
fn slowest_step(world: &mut World, balls: &mut GpuBalls) -> Duration {
    (0..10)
        .map(|_| {
            let start = Instant::now();
            step(world, balls);
            balls.finish().unwrap();
            start.elapsed()
        })
        .max()
        .unwrap()
}

#[test]
fn a_gpu_that_keeps_up_is_never_waited_for() {
    let compute = compute();
    for seed in [1, 2] {
        // The default scene, whose five tumblers and catching fireball make
        // every step report, listened to as the program listens.
        let mut config = WorldConfig::default();
        config.fireball.starts_active = true;
        config.fireball.consumes_balls = true;
        let (mut world, mut balls) = build(&compute, config, seed);
        balls.listen(true);
        let slowest = slowest_step(&mut world, &mut balls);
        // A frame four times as long as the adapter's two steps: the
        // display's pace on a GPU that keeps up (60 Hz at most).
        let frame = (8 * slowest).max(Duration::from_secs_f64(1.0 / 60.0));
        let waits = paced(&mut world, &mut balls, 60, frame);
        eprintln!(
            "seed {seed}: {waits} blocking waits in 120 steps, a frame of {:.1} ms (the adapter's slowest step {:.1} ms)",
            frame.as_secs_f64() * 1e3,
            slowest.as_secs_f64() * 1e3
        );
        assert_eq!(waits, 0, "seed {seed}");
        assert!(world.tumblers().iter().all(|t| t.tilt().is_finite()));
    }
}

#[test]
fn a_cpu_that_runs_ahead_of_the_gpu_waits_and_counts_it() {
    // A thousand balls stepped back to back, faster than a software
    // adapter runs them.
    let compute = compute();
    let mut config = WorldConfig::default();
    config.balls.count = 1000;
    let (mut world, mut balls) = build(&compute, config, 3);
    let slowest = slowest_step(&mut world, &mut balls);
    // Whether the driver queues a submission behind a busy one, or
    // returns only once the one before is done (lavapipe does).
    step(&mut world, &mut balls);
    let start = Instant::now();
    step(&mut world, &mut balls);
    let queues = start.elapsed() < slowest / 4;
    let before = balls.blocking_waits();
    for _ in 0..40 {
        step(&mut world, &mut balls);
    }
    let waits = balls.blocking_waits() - before;
    eprintln!(
        "{waits} blocking waits in 40 steps unpaced; the driver {} (a step {:.1} ms)",
        if queues {
            "queues submissions"
        } else {
            "returns from a submission once the one before is done"
        },
        slowest.as_secs_f64() * 1e3
    );
    if queues {
        // The CPU ran ahead until the reports due were not back.
        assert!(waits >= 10, "{waits}");
    } else {
        // Every report is back when due: a wait counted would be one
        // miscounted.
        assert_eq!(waits, 0);
    }
}

/// The step whose report handed on a dropped ball's first bounce, and the
/// bounce, from the GPU engine; and the step the CPU engine reports it in.
fn first_bounce_steps(pace: Option<Duration>) -> (u64, u64) {
    let mut config = empty_room(DVec3::new(2.0, 3.0, 2.0), 0);
    let r = config.balls.radius;
    config.balls.placements = vec![placed(DVec3::new(0.0, r + 0.5, 0.0), DVec3::ZERO)];
    let mut cpu = World::new(config.clone(), 1).unwrap();
    let mut events = Vec::new();
    let on_cpu = (1..)
        .find(|_| {
            cpu.step();
            cpu.take_events(&mut events);
            !events.is_empty()
        })
        .unwrap();
    let compute = compute();
    let (mut world, mut balls) = build(&compute, config, 1);
    balls.listen(true);
    events.clear();
    let on_gpu = (1..)
        .find(|_| {
            step(&mut world, &mut balls);
            if let Some(pace) = pace {
                balls.finish().unwrap();
                std::thread::sleep(pace);
            }
            balls.take_events(&mut events);
            !events.is_empty()
        })
        .unwrap();
    let floor = EventKind::BallSurface {
        ball: 0,
        surface: Surface::Floor,
    };
    assert_eq!(events[0].kind, floor, "{events:?}");
    (on_gpu, on_cpu)
}

#[test]
fn a_steps_events_are_handed_on_report_delay_steps_later_whatever_the_gpus_pace() {
    // Whether the GPU is waited for each step or runs ahead, the bounce
    // comes REPORT_DELAY steps after the step it happened in (the CPU
    // engine's).
    for pace in [None, Some(Duration::from_millis(5))] {
        let (on_gpu, on_cpu) = first_bounce_steps(pace);
        assert_eq!(on_gpu, on_cpu + REPORT_DELAY, "{pace:?}");
    }
}

#[test]
fn the_events_in_flight_are_handed_on_at_once_when_asked() {
    let mut config = empty_room(DVec3::new(2.0, 3.0, 2.0), 0);
    let r = config.balls.radius;
    config.balls.placements = vec![placed(DVec3::new(0.0, r + 0.5, 0.0), DVec3::ZERO)];
    let (on_gpu, on_cpu) = first_bounce_steps(None);
    assert_eq!(on_gpu - on_cpu, REPORT_DELAY);
    // Stopped on the bounce's step, the engine holds it until asked.
    let compute = compute();
    let (mut world, mut balls) = build(&compute, config, 1);
    balls.listen(true);
    let mut events = Vec::new();
    for _ in 0..on_cpu {
        step(&mut world, &mut balls);
        balls.take_events(&mut events);
    }
    assert!(events.is_empty(), "{events:?}");
    balls.take_events_in_flight().unwrap();
    balls.take_events(&mut events);
    assert_eq!(events.len(), 1, "{events:?}");
    // Handed on once: not again when due.
    for _ in 0..REPORT_DELAY + 1 {
        step(&mut world, &mut balls);
        balls.take_events(&mut events);
    }
    assert_eq!(events.len(), 1, "{events:?}");
}
