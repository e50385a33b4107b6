//! Pause, single steps and the time scale: how many fixed steps a frame
//! runs. The step itself never changes: slow motion runs fewer steps of the
//! same `dt` per frame, fast motion more.

use std::time::Duration;

use super::fixed_steps::FixedSteps;

/// The time scales offered, slowest first: simulated seconds per real one.
pub const TIME_SCALES: [f64; 7] = [1.0 / 16.0, 0.125, 0.25, 0.5, 1.0, 2.0, 4.0];

/// How the simulation follows real time.
#[derive(Debug)]
pub struct Playback {
    /// Paused until un-paused (P, or the panel).
    latched: bool,
    /// Frozen while Left Shift is held.
    held: bool,
    /// Single steps asked for while frozen, not yet run.
    steps_asked: u32,
    /// Simulated seconds per real second, one of [`TIME_SCALES`].
    scale: f64,
    fixed: FixedSteps,
}

impl Default for Playback {
    fn default() -> Playback {
        Playback {
            latched: false,
            held: false,
            steps_asked: 0,
            scale: 1.0,
            fixed: FixedSteps::default(),
        }
    }
}

impl Playback {
    /// Whether time stands still (paused or held).
    pub fn frozen(&self) -> bool {
        self.latched || self.held
    }

    /// Whether P (or the panel) paused it.
    pub fn paused(&self) -> bool {
        self.latched
    }

    /// Pauses or goes on.
    pub fn set_paused(&mut self, paused: bool) {
        self.latched = paused;
    }

    /// Left Shift held or let go.
    pub fn set_held(&mut self, held: bool) {
        self.held = held;
    }

    /// Asks for one step; it runs at the next frame, and only while time
    /// stands still (a running simulation steps anyway).
    pub fn step_once(&mut self) {
        if self.frozen() {
            self.steps_asked += 1;
        }
    }

    /// Simulated seconds per real one.
    pub fn scale(&self) -> f64 {
        self.scale
    }

    /// The offered time scale nearest to `scale`.
    pub fn set_scale(&mut self, scale: f64) {
        self.scale = TIME_SCALES
            .into_iter()
            .min_by(|a, b| {
                (a.ln() - scale.ln())
                    .abs()
                    .total_cmp(&(b.ln() - scale.ln()).abs())
            })
            .unwrap_or(1.0);
    }

    /// The next time scale up (`faster`) or down, or this one at the end.
    pub fn shift_scale(&mut self, faster: bool) {
        let now = TIME_SCALES
            .iter()
            .position(|&s| s == self.scale)
            .unwrap_or(4);
        let next = if faster {
            (now + 1).min(TIME_SCALES.len() - 1)
        } else {
            now.saturating_sub(1)
        };
        self.scale = TIME_SCALES[next];
    }

    /// Runs `step` as many times as a frame of `elapsed` real seconds asks
    /// for, each a step of `dt`: the steps asked for while frozen, else
    /// `elapsed` times the time scale in fixed steps (see `fixed_steps`).
    /// Returns how many ran.
    pub fn advance(
        &mut self,
        elapsed: f64,
        dt: f64,
        spent: impl FnMut() -> Duration,
        mut step: impl FnMut(),
    ) -> u32 {
        if self.frozen() {
            let steps = std::mem::take(&mut self.steps_asked);
            (0..steps).for_each(|_| step());
            return steps;
        }
        self.steps_asked = 0;
        self.fixed.advance(elapsed * self.scale, dt, spent, step)
    }

    /// Real time skipped so far because the steps could not keep up
    /// (seconds of simulated time).
    pub fn skipped(&self) -> f64 {
        self.fixed.skipped()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const DT: f64 = 1.0 / 120.0;

    /// Steps run by `frames` frames of `frame` seconds.
    fn run(playback: &mut Playback, frames: usize, frame: f64) -> u32 {
        (0..frames)
            .map(|_| playback.advance(frame, DT, || Duration::ZERO, || {}))
            .sum()
    }

    #[test]
    fn a_time_scale_runs_that_share_of_the_steps_per_second() {
        for fps in [30.0, 60.0, 144.0] {
            for (scale, per_second) in [(0.25, 30.0), (1.0 / 16.0, 7.5), (1.0, 120.0), (4.0, 480.0)]
            {
                let mut playback = Playback::default();
                playback.set_scale(scale);
                assert_eq!(playback.scale(), scale);
                // Ten seconds of frames.
                let steps = run(&mut playback, (10.0 * fps) as usize, 1.0 / fps);
                let expected = 10.0 * per_second;
                assert!(
                    (f64::from(steps) - expected).abs() <= 1.0,
                    "{fps} fps at {scale}x: {steps} steps, expected {expected}"
                );
            }
        }
    }

    #[test]
    fn pause_stops_the_steps_and_single_steps_run_one_each() {
        let mut playback = Playback::default();
        assert!(run(&mut playback, 60, 1.0 / 60.0) > 0);
        playback.set_paused(true);
        assert_eq!(run(&mut playback, 120, 1.0 / 60.0), 0);
        for asked in [1, 3] {
            (0..asked).for_each(|_| playback.step_once());
            assert_eq!(run(&mut playback, 1, 1.0 / 60.0), asked);
            assert_eq!(run(&mut playback, 30, 1.0 / 60.0), 0);
        }
        // Holding Shift while paused changes nothing; un-pausing resumes
        // real time without catching up on the pause.
        playback.set_held(true);
        playback.set_paused(false);
        assert_eq!(run(&mut playback, 10, 1.0 / 60.0), 0);
        playback.set_held(false);
        assert_eq!(run(&mut playback, 60, 1.0 / 60.0), 120);
        // A step asked for while running is not kept for a later pause.
        playback.step_once();
        playback.set_paused(true);
        assert_eq!(run(&mut playback, 1, 1.0 / 60.0), 0);
    }

    #[test]
    fn the_scale_moves_through_the_offered_ones_and_stops_at_the_ends() {
        let mut playback = Playback::default();
        let mut seen = vec![playback.scale()];
        for _ in 0..10 {
            playback.shift_scale(false);
            seen.push(playback.scale());
        }
        assert_eq!(playback.scale(), TIME_SCALES[0]);
        for _ in 0..10 {
            playback.shift_scale(true);
        }
        assert_eq!(playback.scale(), 4.0);
        playback.set_scale(0.3);
        assert_eq!(playback.scale(), 0.25);
        playback.set_scale(100.0);
        assert_eq!(playback.scale(), 4.0);
    }
}
