//! How many fixed physics steps a frame runs: real time, in steps of the
//! world's `dt`, unless the steps cannot keep up.

use std::time::Duration;

/// Most simulated time one frame may catch up on (seconds): after a long
/// stall (a dragged window, a debugger) the world skips ahead rather than
/// spiral. A quarter of a second keeps cheap steps in real time down to
/// four frames a second, as a software renderer may draw.
pub const MAX_CATCH_UP: f64 = 0.25;

/// Most time one frame spends stepping. A world whose steps cannot keep up
/// with real time (a pit of 100 000 balls on a small machine) runs in slow
/// motion at a frame rate that stays usable, rather than take every step
/// real time asks for in frames of whole seconds; one step always runs.
pub const STEP_BUDGET_PER_FRAME: Duration = Duration::from_millis(33);

/// Real time not yet simulated.
#[derive(Debug, Default)]
pub struct FixedSteps {
    behind: f64,
    /// Real time skipped so far, never to be simulated (seconds).
    skipped: f64,
}

impl FixedSteps {
    /// Adds `elapsed` seconds of real time and runs `step` once per `dt` of
    /// it, until caught up, or the steps have simulated [`MAX_CATCH_UP`],
    /// or they have taken [`STEP_BUDGET_PER_FRAME`] by `spent` (the time
    /// since the frame began stepping). Stopped short, it forgets the time
    /// it could not simulate. Returns how many steps ran.
    pub fn advance(
        &mut self,
        elapsed: f64,
        dt: f64,
        mut spent: impl FnMut() -> Duration,
        mut step: impl FnMut(),
    ) -> u32 {
        self.behind += elapsed;
        let max_steps = max_steps_per_frame(dt);
        let mut steps = 0;
        while self.behind >= dt {
            if steps == max_steps || (steps > 0 && spent() >= STEP_BUDGET_PER_FRAME) {
                // Skip ahead instead of catching up.
                self.skipped += (self.behind - dt).max(0.0);
                self.behind = self.behind.min(dt);
                break;
            }
            step();
            self.behind -= dt;
            steps += 1;
        }
        steps
    }

    /// Real time skipped so far, never to be simulated (seconds).
    pub fn skipped(&self) -> f64 {
        self.skipped
    }
}

/// Steps of `dt` that simulate [`MAX_CATCH_UP`]; at least one.
fn max_steps_per_frame(dt: f64) -> u32 {
    (MAX_CATCH_UP / dt).round().max(1.0) as u32
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::cell::Cell;

    const DT: f64 = 1.0 / 120.0;

    /// Runs frames of `frame` seconds whose steps each take `cost`; returns
    /// the steps of each frame.
    fn frames(count: usize, frame: f64, cost: Duration) -> Vec<u32> {
        let mut clock = FixedSteps::default();
        (0..count)
            .map(|_| {
                let spent = Cell::new(Duration::ZERO);
                clock.advance(frame, DT, || spent.get(), || spent.set(spent.get() + cost))
            })
            .collect()
    }

    #[test]
    fn cheap_steps_keep_real_time() {
        // 60 frames a second at 120 steps a second: two steps a frame,
        // exactly, for as long as it runs.
        let steps = frames(600, 1.0 / 60.0, Duration::from_micros(30));
        assert!(steps.iter().all(|&s| s == 2), "{steps:?}");
        // An uneven frame rate still adds up to real time.
        let mut clock = FixedSteps::default();
        let ran: u32 = [0.013, 0.021, 0.017, 0.009, 0.040]
            .iter()
            .map(|&frame| clock.advance(frame, DT, || Duration::ZERO, || {}))
            .sum();
        assert_eq!(ran, (0.1 / DT) as u32);
    }

    #[test]
    fn a_slow_renderer_with_cheap_steps_keeps_real_time() {
        // Five frames a second, as a software renderer draws a room: each
        // frame runs the 24 steps of its fifth of a second.
        let steps = frames(50, 0.2, Duration::from_micros(30));
        assert!(steps.iter().all(|&s| s == 24), "{steps:?}");
    }

    #[test]
    fn a_stall_skips_ahead_instead_of_catching_up() {
        let mut clock = FixedSteps::default();
        let steps = clock.advance(2.0, DT, || Duration::ZERO, || {});
        assert_eq!(steps, 30, "a quarter of a second of steps");
        assert!((clock.skipped() - (2.0 - 30.0 * DT - clock.behind)).abs() < 1e-9);
        // The next ordinary frame runs what it always would.
        assert!(clock.advance(1.0 / 60.0, DT, || Duration::ZERO, || {}) <= 3);
    }

    #[test]
    fn steps_that_cannot_keep_up_run_slow_motion_at_a_usable_frame_rate() {
        // Steps of 80 ms: real time asks for twelve a frame, and would
        // take frames of about a second. One runs per frame instead, the world
        // at a sixth of real time or so but the view still moving.
        let steps = frames(100, 0.1, Duration::from_millis(80));
        assert!(steps.iter().all(|&s| s == 1), "{steps:?}");
        // What is skipped is what did not run: simulated plus skipped
        // plus what is still owed adds up to the real time.
        let mut clock = FixedSteps::default();
        let mut ran = 0;
        for _ in 0..100 {
            let spent = Cell::new(Duration::ZERO);
            let tick = || spent.set(spent.get() + Duration::from_millis(80));
            ran += clock.advance(0.1, DT, || spent.get(), tick);
        }
        let accounted = f64::from(ran) * DT + clock.skipped() + clock.behind;
        assert!((accounted - 10.0).abs() < 1e-9, "{accounted}");
        assert!((clock.skipped() - (10.0 - 100.0 * DT)).abs() < DT + 1e-9);
        // Steps of 10 ms: four fit in the budget, not the twelve asked for.
        let steps = frames(100, 0.1, Duration::from_millis(10));
        assert!(steps.iter().all(|&s| s == 4), "{steps:?}");
    }
}
