//! The GPU engine alone on the bench's pit, for runs the three-engine
//! bench would take hours over (a 100 000-ball pit to 10 s on lavapipe):
//! every half second of simulated time, the deepest overlap then and
//! since the start, the share of balls at rest and the escapes, measured
//! as `versus_rapier` measures them; at the end, steps per second (timed
//! to the end of the GPU's work, the measuring left out).
//!
//! `cargo run --release -p rolypoly-bench --example gpu_pit_alone --
//! 100000 10s [frictionless]`

use rolypoly_bench::gpu_pit::GpuPit;
use rolypoly_bench::pit::{FRICTION, Pit, PitEngine};
use rolypoly_bench::quality::{Quality, measure};
use std::time::{Duration, Instant};

/// Simulated seconds between two measurements.
const TURN: f64 = 0.5;

fn main() {
    if let Err(e) = run() {
        eprintln!("gpu_pit_alone: {e}");
        std::process::exit(2);
    }
}

fn run() -> Result<(), String> {
    let usage = "usage: gpu_pit_alone BALLS SECONDSs [frictionless]";
    let args: Vec<String> = std::env::args().skip(1).collect();
    let count: usize = args
        .first()
        .and_then(|a| a.parse().ok())
        .filter(|&n| n > 0)
        .ok_or(usage)?;
    let seconds: f64 = args
        .get(1)
        .and_then(|a| a.strip_suffix('s')?.parse().ok())
        .filter(|&s: &f64| s > 0.0 && s.is_finite())
        .ok_or(usage)?;
    let friction = match args.get(2).map(String::as_str) {
        None => FRICTION,
        Some("frictionless") => 0.0,
        Some(_) => return Err(usage.into()),
    };
    let pit = Pit::new(count, 1).with_ball_friction(friction);
    let compute = rolypoly_gpu::Compute::headless().map_err(|e| e.to_string())?;
    println!(
        "{count} balls, friction {friction} between balls, on {}",
        compute.adapter
    );
    let mut gpu = GpuPit::new(&pit, &compute)?;
    // A run shorter than a turn is one turn that long: a million balls on
    // a software adapter take seconds a step.
    let span = TURN.min(seconds);
    let per_turn = (span / pit.dt).round().max(1.0) as usize;
    let turns = (seconds / span).round().max(1.0) as usize;
    let (mut positions, mut velocities) = (Vec::new(), Vec::new());
    let mut worst = Quality::default();
    let mut stepping = Duration::ZERO;
    for turn in 1..=turns {
        let started = Instant::now();
        for _ in 0..per_turn {
            gpu.step();
        }
        gpu.finish();
        stepping += started.elapsed();
        gpu.read(&mut positions, &mut velocities);
        let now = measure(&pit, &positions, &velocities);
        worst = worst.worst(now);
        println!(
            "t {:5.1} s: overlap {:6.2} mm (deepest {:6.2}), resting {:5.1} %, escapes {}",
            (turn * per_turn) as f64 * pit.dt,
            1e3 * now.max_penetration,
            1e3 * worst.max_penetration,
            100.0 * now.resting as f64 / count as f64,
            worst.escapes
        );
    }
    let steps = turns * per_turn;
    println!(
        "{:.2} steps/s, dispatches a step: {}",
        steps as f64 / stepping.as_secs_f64(),
        gpu.dispatches_per_step()
    );
    Ok(())
}
