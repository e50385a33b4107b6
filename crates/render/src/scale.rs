//! The render scale that follows the frame rate (dynamic resolution): the
//! window lights the scene at a share of its width and height that it
//! picks from the last frames' drawing times, to hold a target frame rate.
//!
//! A frame's drawing time grows with the pixels lit, the square of the
//! scale, over a part that does not (the HUD, presenting). So the scale
//! that meets the aim is the scale now over the square root of the time's
//! ratio to the aim. The scale moves only after a few frames' median, only
//! when that median misses the target or leaves more than a quarter of it
//! unused, by at most 1.4 times at a time, and in steps of 1/32: it
//! settles instead of oscillating, and the targets are made anew only when
//! it moves a step. A frame held to the display's rate (vsync) takes the
//! whole budget and holds the scale: it keeps up.

use std::time::Duration;

/// The least share of the output's width and height the scene is lit at.
pub const MIN_SCALE: f32 = 0.33;
/// The most: the output's own resolution.
pub const MAX_SCALE: f32 = 1.0;
/// Scales are multiples of this (or the least).
const STEP: f32 = 1.0 / 32.0;
/// Frames whose median each decision takes.
const JUDGED: usize = 6;
/// The share of a frame's budget aimed at when the scale moves: room for
/// a slower frame.
const AIM: f64 = 0.85;
/// The scale holds while the median frame takes between these shares of
/// the budget: it keeps up, and no step up would.
const HOLD: std::ops::RangeInclusive<f64> = 0.72..=1.02;
/// The most one decision changes the scale by, as a ratio (the pixels by
/// about twice that).
const MAX_CHANGE: f64 = 1.4;

/// The scale, and the frames judged for its next move.
#[derive(Clone, Debug)]
pub struct DynamicScale {
    budget: Duration,
    scale: f32,
    frames: Vec<Duration>,
}

impl DynamicScale {
    /// Starts at the output's resolution, aiming at `target_fps`.
    pub fn new(target_fps: f64) -> DynamicScale {
        DynamicScale {
            budget: Duration::from_secs_f64(1.0 / target_fps.max(1.0)),
            scale: MAX_SCALE,
            frames: Vec::with_capacity(JUDGED),
        }
    }

    /// The share of the width and height lit now.
    pub fn scale(&self) -> f32 {
        self.scale
    }

    /// The frame time it aims at.
    pub fn budget(&self) -> Duration {
        self.budget
    }

    /// Whether it is as low as it goes: what else a frame costs is then
    /// for the discrete settings to cut.
    pub fn at_least(&self) -> bool {
        self.scale <= MIN_SCALE
    }

    /// Takes the time the last frame spent drawing; returns the new scale
    /// when it moves.
    pub fn observe(&mut self, drawing: Duration) -> Option<f32> {
        self.frames.push(drawing);
        if self.frames.len() < JUDGED {
            return None;
        }
        self.frames.sort_unstable();
        let median = self.frames[JUDGED / 2].as_secs_f64();
        self.frames.clear();
        let share = median / self.budget.as_secs_f64();
        if HOLD.contains(&share) || !share.is_finite() || share <= 0.0 {
            return None;
        }
        let ratio = share / AIM;
        let now = f64::from(self.scale);
        let wanted = (now / ratio.sqrt()).clamp(now / MAX_CHANGE, now * MAX_CHANGE);
        // To the step towards the scale now, so that no move exceeds the
        // most a move may be.
        let steps = wanted as f32 / STEP;
        let steps = if wanted < now {
            steps.ceil()
        } else {
            steps.floor()
        };
        let stepped = (steps * STEP).clamp(MIN_SCALE, MAX_SCALE);
        if stepped == self.scale {
            return None;
        }
        self.scale = stepped;
        Some(stepped)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A frame that costs `fixed` ms plus `per_pixel` ms at full scale,
    /// times the share of pixels lit.
    fn frame(scale: f32, fixed: f64, per_pixel: f64) -> Duration {
        Duration::from_secs_f64((fixed + per_pixel * f64::from(scale * scale)) / 1e3)
    }

    /// The scales a machine of those costs settles at, frame by frame.
    fn run(target_fps: f64, fixed: f64, per_pixel: f64, frames: usize) -> Vec<f32> {
        let mut scale = DynamicScale::new(target_fps);
        (0..frames)
            .map(|_| {
                scale.observe(frame(scale.scale(), fixed, per_pixel));
                scale.scale()
            })
            .collect()
    }

    #[test]
    fn it_settles_where_the_frames_meet_the_target_and_stays() {
        for (fps, fixed, per_pixel) in [(30.0, 8.0, 60.0), (30.0, 2.0, 200.0), (60.0, 4.0, 30.0)] {
            let scales = run(fps, fixed, per_pixel, 600);
            let last = *scales.last().unwrap();
            let time = frame(last, fixed, per_pixel).as_secs_f64();
            let budget = 1.0 / fps;
            assert!(
                time <= 1.02 * budget && time >= 0.6 * budget,
                "{fps} fps, {fixed} + {per_pixel} ms: scale {last}, {time} s"
            );
            // Settled: the last 300 frames hold one scale.
            assert!(scales[300..].iter().all(|&s| s == last), "{scales:?}");
            assert!((MIN_SCALE..=MAX_SCALE).contains(&last));
        }
    }

    #[test]
    fn a_fast_machine_keeps_the_full_resolution_and_a_slow_one_the_least() {
        assert!(run(30.0, 1.0, 10.0, 400).iter().all(|&s| s == MAX_SCALE));
        let slow = run(30.0, 50.0, 100.0, 400);
        assert_eq!(*slow.last().unwrap(), MIN_SCALE);
        let mut scale = DynamicScale::new(30.0);
        for _ in 0..400 {
            scale.observe(frame(scale.scale(), 50.0, 100.0));
        }
        assert!(scale.at_least());
    }

    #[test]
    fn it_moves_by_at_most_its_most_and_in_steps() {
        let scales = run(30.0, 0.0, 2000.0, 200);
        for pair in scales.windows(2) {
            assert!(
                f64::from(pair[1]) >= f64::from(pair[0]) / MAX_CHANGE - 1e-6,
                "{pair:?}"
            );
            let steps = pair[1] / STEP;
            assert!(
                pair[1] == MIN_SCALE || (steps - steps.round()).abs() < 1e-4,
                "{pair:?}"
            );
        }
    }

    #[test]
    fn frames_held_to_the_display_rate_hold_the_scale() {
        // Vsync: every frame takes the budget whatever the scale.
        let mut scale = DynamicScale::new(60.0);
        for _ in 0..400 {
            assert_eq!(scale.observe(Duration::from_secs_f64(1.0 / 60.0)), None);
        }
        assert_eq!(scale.scale(), MAX_SCALE);
    }

    #[test]
    fn one_slow_frame_among_quick_ones_moves_nothing() {
        let mut scale = DynamicScale::new(30.0);
        for k in 0..400 {
            let ms = if k % JUDGED == 0 { 400.0 } else { 20.0 };
            assert_eq!(scale.observe(Duration::from_secs_f64(ms / 1e3)), None);
        }
    }
}
