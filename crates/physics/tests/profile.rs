//! The step's profile: its stages, timed as it runs, add up to the step's
//! own time as the caller measures it, within a stated share.

mod common;

use common::{build, crowded_pit};
use rolypoly_physics::{Stage, WorldConfig};
use std::time::{Duration, Instant};

/// The stages must cover at least this share of the step as timed from
/// outside (the rest: the call, waking the worker threads, the laps' own
/// clock reads).
const COVERED: f64 = 0.9;

#[test]
fn the_stages_add_up_to_the_step() {
    let mut thousand = WorldConfig::default();
    thousand.balls.count = 1000;
    for (name, cfg, seed) in [
        ("default", WorldConfig::default(), 1),
        ("1000 balls", thousand, 2),
        ("crowded pit", crowded_pit(), 3),
    ] {
        let mut world = build(cfg, seed);
        for _ in 0..60 {
            world.step();
        }
        let mut shares = Vec::new();
        for _ in 0..40 {
            let started = Instant::now();
            world.step();
            let outside = started.elapsed();
            let times = world.step_times();
            let stages: Duration = times.stages.iter().sum();
            assert!(
                stages <= times.total && times.total <= outside,
                "{name}: {times:?} against {outside:?}"
            );
            shares.push(stages.as_secs_f64() / outside.as_secs_f64());
            assert!(
                times.of(Stage::Contacts) > Duration::ZERO
                    && times.of(Stage::Solve) > Duration::ZERO
            );
        }
        shares.sort_by(f64::total_cmp);
        let median = shares[shares.len() / 2];
        assert!(
            median >= COVERED,
            "{name}: the stages cover {:.1} % of the step",
            100.0 * median
        );
        let times = world.step_times();
        assert!(
            times.pairs > 0 || name == "default",
            "{name}: no pairs counted"
        );
    }
}
