//! The step runs on all threads where that pays; its result must not depend
//! on how many there are (P10).

mod common;

use common::{build, crowded_pit, state_bits};
use glam::DVec3;
use rolypoly_physics::{World, WorldConfig};

fn run_on(threads: usize, steps: usize) -> (World, usize) {
    run_scene_on(crowded_pit(), threads, steps)
}

fn run_scene_on(cfg: WorldConfig, threads: usize, steps: usize) -> (World, usize) {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("a thread pool");
    pool.install(|| {
        let mut w = build(cfg, 11);
        let mut events = 0;
        for _ in 0..steps {
            w.step();
            events += w.drain_events().count();
        }
        (w, events)
    })
}

#[test]
fn results_are_bit_identical_on_one_two_and_three_threads() {
    let (one, events_one) = run_on(1, 150);
    for threads in [2, 3] {
        let (many, events_many) = run_on(threads, 150);
        assert_eq!(events_one, events_many, "{threads} threads: events differ");
        assert!(
            state_bits(&one) == state_bits(&many),
            "{threads} threads: the states differ"
        );
    }
    // The run did crowd the balls: most of them touch the floor or others.
    assert!(events_one > 1000, "only {events_one} events");
}

#[test]
fn a_crowd_large_enough_to_split_even_the_light_passes_is_bit_identical_too() {
    // Copies, gathers and sums over the balls run on all threads only from
    // tens of thousands of balls on.
    let mut cfg = crowded_pit();
    cfg.room.size = DVec3::new(6.0, 3.0, 6.0);
    cfg.balls.count = 40_000;
    cfg.balls.radius = 0.05;
    let (one, events_one) = run_scene_on(cfg.clone(), 1, 6);
    let (two, events_two) = run_scene_on(cfg, 2, 6);
    assert_eq!(events_one, events_two, "2 threads: events differ");
    assert!(
        state_bits(&one) == state_bits(&two),
        "2 threads: the states differ"
    );
    assert_eq!(one.balls().len(), 40_000);
}
