//! How a crowded step uses the threads: its stages hand work to the other
//! workers dozens of times a step, between stages that run on one thread.
//!
//! A rayon worker that finds no work spins for a while and then sleeps;
//! waking it takes tens of microseconds, on a 2-core machine about as long
//! as a stage's share of the work. So while a step runs, every other worker
//! keeps looking for work instead of sleeping: the next stage's halves then
//! start on both threads at once. The results do not depend on this, only
//! the time.

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::time::{Duration, Instant};

/// Runs `work` on a worker thread, the pool's other workers kept awake and
/// looking for work until it returns. Allocates nothing.
pub(crate) fn with_workers_awake<R: Send>(work: impl FnOnce() -> R + Send) -> R {
    let done = AtomicBool::new(false);
    let owner = AtomicUsize::new(usize::MAX);
    let keepers = rayon::current_num_threads().saturating_sub(1);
    let (result, ()) = rayon::join(
        || {
            let own = rayon::current_thread_index().unwrap_or(usize::MAX);
            owner.store(own, Ordering::Release);
            let result = work();
            done.store(true, Ordering::Release);
            result
        },
        || keep_awake(keepers, &done, &owner),
    );
    result
}

/// Runs `count` keepers, each on whichever worker takes it: one that finds
/// itself on the working thread returns at once, since it would otherwise
/// wait for that thread's work, and so for itself.
fn keep_awake(count: usize, done: &AtomicBool, owner: &AtomicUsize) {
    let keep = || {
        if rayon::current_thread_index() != Some(owner.load(Ordering::Acquire)) {
            look_for_work_until(done);
        }
    };
    match count {
        0 => {}
        1 => keep(),
        _ => {
            rayon::join(keep, || keep_awake(count - 1, done, owner));
        }
    }
}

/// How long a keeper looks for work without finding any before it gives
/// up: longer than a crowded step's stretches on one thread, yet short.
/// Two steps at once in one pool may each bury the other's keeper under
/// their own work on the same thread; each keeper would then wait for the
/// other forever, where giving up costs this pause.
const PATIENCE: Duration = Duration::from_millis(2);

/// Runs pending jobs of the pool, or spins, until `done`, or until it has
/// found no work for [`PATIENCE`].
fn look_for_work_until(done: &AtomicBool) {
    let mut last_work = Instant::now();
    while !done.load(Ordering::Acquire) {
        match rayon::yield_now() {
            Some(rayon::Yield::Executed) => last_work = Instant::now(),
            Some(rayon::Yield::Idle) if last_work.elapsed() > PATIENCE => return,
            Some(rayon::Yield::Idle) => std::hint::spin_loop(),
            None => return,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rayon::prelude::*;

    fn pool(threads: usize) -> rayon::ThreadPool {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("a thread pool")
    }

    #[test]
    fn the_work_runs_with_its_parallel_parts_and_every_keeper_returns() {
        for threads in [1, 2, 3, 4] {
            let pool = pool(threads);
            for _ in 0..20 {
                let sum: u64 = pool.install(|| {
                    with_workers_awake(|| (0..10_000u64).into_par_iter().map(|k| k * k).sum())
                });
                assert_eq!(
                    sum,
                    (0..10_000u64).map(|k| k * k).sum(),
                    "{threads} threads"
                );
            }
        }
    }

    #[test]
    fn two_crowded_steps_at_once_in_one_pool_both_finish() {
        // Each step's keeper may end up on the thread that holds the other
        // step, buried under it: the keepers must give way, not wait for
        // each other.
        for threads in [2, 3] {
            let pool = pool(threads);
            std::thread::scope(|s| {
                for _ in 0..2 {
                    s.spawn(|| {
                        for _ in 0..300 {
                            let sum: u64 = pool.install(|| {
                                with_workers_awake(|| {
                                    (0..20_000u64).into_par_iter().map(|k| k % 7).sum()
                                })
                            });
                            assert_eq!(sum, (0..20_000u64).map(|k| k % 7).sum());
                        }
                    });
                }
            });
        }
    }

    #[test]
    fn a_keeper_that_finds_no_work_gives_up() {
        // As when the step it waits for lies buried under it.
        let never = AtomicBool::new(false);
        let start = Instant::now();
        pool(2).install(|| look_for_work_until(&never));
        let waited = start.elapsed();
        assert!(waited >= PATIENCE, "gave up after {waited:?}");
    }

    #[test]
    fn works_from_outside_any_pool_and_nested() {
        assert_eq!(with_workers_awake(|| 7), 7);
        let nested = pool(2).install(|| with_workers_awake(|| with_workers_awake(|| 8)));
        assert_eq!(nested, 8);
    }
}
