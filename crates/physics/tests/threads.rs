//! The step runs on all threads where that pays; its result must not depend
//! on how many there are (P10).

mod common;

use common::{build, crowded_pit, state_bits};
use rolypoly_physics::World;

fn run_on(threads: usize, steps: usize) -> (World, usize) {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("a thread pool");
    pool.install(|| {
        let mut w = build(crowded_pit(), 11);
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
