//! Quality levels: what a frame is drawn with, traded against its cost, and
//! the automatic choice that steps down until a slow adapter keeps up.
//!
//! The levels trade what a software renderer pays most for (measured pass
//! by pass on lavapipe; see docs/rendering.md): the pixels the scene is lit
//! at, the multisamples of each, and the shadow filter's taps. Every level
//! draws the same scene, lit and shadowed, with every effect of the light.

use std::time::Duration;

use crate::renderer::RenderSettings;

/// How finely a frame is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Quality {
    /// Half the resolution, one sample per pixel, shadow taps 2 a side
    /// (4 in all), the tumblers' coarse mesh where there is one.
    Low,
    /// Full resolution, one sample per pixel, shadow taps 2 a side (4 in
    /// all).
    Medium,
    /// Full resolution, MSAA 4x, shadow taps 4 a side (16 in all).
    High,
}

impl Quality {
    /// Every level, lowest first.
    pub const ALL: [Quality; 3] = [Quality::Low, Quality::Medium, Quality::High];

    /// The level's name, as flags and scene files write it.
    pub fn name(self) -> &'static str {
        match self {
            Quality::Low => "low",
            Quality::Medium => "medium",
            Quality::High => "high",
        }
    }

    /// The settings the level draws with.
    pub fn settings(self) -> RenderSettings {
        let high = RenderSettings::default();
        match self {
            Quality::High => high,
            Quality::Medium => RenderSettings {
                msaa: 1,
                shadow_taps: 2,
                ..high
            },
            Quality::Low => RenderSettings {
                msaa: 1,
                shadow_taps: 2,
                shadow_size: 512,
                resolution: 0.5,
                coarse_tumblers: true,
                ..high
            },
        }
    }

    /// The next level down, if there is one.
    pub fn lower(self) -> Option<Quality> {
        match self {
            Quality::High => Some(Quality::Medium),
            Quality::Medium => Some(Quality::Low),
            Quality::Low => None,
        }
    }
}

/// A level, or the automatic choice.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum QualityChoice {
    /// This level, always.
    Fixed(Quality),
    /// High, stepped down while frames are slow (see [`AutoQuality`]).
    Auto,
}

/// Auto: a window finds its own level; off-screen frames draw it as high.
impl Default for QualityChoice {
    fn default() -> Self {
        QualityChoice::Auto
    }
}

impl QualityChoice {
    /// Every name a choice is written as.
    pub const NAMES: [&'static str; 4] = ["high", "medium", "low", "auto"];

    /// The choice's name.
    pub fn name(self) -> &'static str {
        match self {
            QualityChoice::Fixed(q) => q.name(),
            QualityChoice::Auto => "auto",
        }
    }

    /// The choice written as `name`, if it is one of [`Self::NAMES`].
    pub fn from_name(name: &str) -> Option<QualityChoice> {
        if name == "auto" {
            return Some(QualityChoice::Auto);
        }
        Quality::ALL
            .into_iter()
            .find(|q| q.name() == name)
            .map(QualityChoice::Fixed)
    }

    /// The level drawn first: auto starts high.
    pub fn first(self) -> Quality {
        match self {
            QualityChoice::Fixed(q) => q,
            QualityChoice::Auto => Quality::High,
        }
    }
}

/// Frames per second the automatic choice holds a window to on a software
/// renderer (with a GPU: the display's rate), unless `render.target_fps`
/// says otherwise.
pub const AUTO_TARGET_FPS: f64 = 30.0;
/// Frames left unwatched after a level starts: the first ones build
/// pipelines and targets, and say nothing of the level's pace.
const SETTLE_FRAMES: usize = 5;
/// Time watched at each level before it is judged.
const WATCH: Duration = Duration::from_secs(1);
/// Fewest frames a level is judged on.
const MIN_WATCHED: usize = 4;

/// The automatic choice: starts high, watches the frame times over the
/// first seconds and steps down one level whenever the median frame of a
/// second's watch is slower than the target; it stops watching at the first
/// level that keeps up, or at the lowest. A median, so that one slow frame
/// (a scene switch, a window dragged) moves nothing.
#[derive(Clone, Debug)]
pub struct AutoQuality {
    level: Quality,
    target: Duration,
    skipped: usize,
    watched: Vec<Duration>,
    settled: bool,
    reason: String,
}

impl AutoQuality {
    /// Starts at high, aiming at `target_fps` frames per second.
    pub fn new(target_fps: f64) -> AutoQuality {
        AutoQuality {
            level: Quality::High,
            target: Duration::from_secs_f64(1.0 / target_fps),
            skipped: 0,
            watched: Vec::new(),
            settled: false,
            reason: "auto: watching the frame time".to_owned(),
        }
    }

    /// The level now.
    pub fn level(&self) -> Quality {
        self.level
    }

    /// Why the level is what it is, in words for the HUD.
    pub fn reason(&self) -> &str {
        &self.reason
    }

    /// Whether it has stopped watching.
    pub fn settled(&self) -> bool {
        self.settled
    }

    /// Takes the time the last frame took; returns the new level when it
    /// steps down.
    pub fn observe(&mut self, frame_time: Duration) -> Option<Quality> {
        if self.settled {
            return None;
        }
        if self.skipped < SETTLE_FRAMES {
            self.skipped += 1;
            return None;
        }
        self.watched.push(frame_time);
        let total: Duration = self.watched.iter().sum();
        if total < WATCH || self.watched.len() < MIN_WATCHED {
            return None;
        }
        self.watched.sort_unstable();
        let median = self.watched[self.watched.len() / 2];
        let ms = median.as_secs_f64() * 1e3;
        let target_ms = self.target.as_secs_f64() * 1e3;
        self.watched.clear();
        self.skipped = 0;
        if median <= self.target {
            self.settled = true;
            self.reason = format!("auto: {ms:.0} ms a frame keeps up with {target_ms:.0} ms");
            return None;
        }
        match self.level.lower() {
            Some(lower) => {
                self.reason = format!(
                    "auto: {} took {ms:.0} ms a frame, over {target_ms:.0} ms",
                    self.level.name()
                );
                self.level = lower;
                Some(lower)
            }
            None => {
                self.settled = true;
                self.reason = format!("auto: lowest level, {ms:.0} ms a frame");
                None
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ms(ms: f64) -> Duration {
        Duration::from_secs_f64(ms / 1e3)
    }

    /// Feeds `frames` frames of `each` and collects the steps down.
    fn feed(auto: &mut AutoQuality, each: Duration, frames: usize) -> Vec<Quality> {
        (0..frames).filter_map(|_| auto.observe(each)).collect()
    }

    #[test]
    fn a_fast_adapter_never_steps_down() {
        for frame in [1.0, 8.0, 16.7, 33.0] {
            let mut auto = AutoQuality::new(AUTO_TARGET_FPS);
            assert!(feed(&mut auto, ms(frame), 2000).is_empty(), "{frame} ms");
            assert_eq!(auto.level(), Quality::High);
            assert!(auto.settled());
        }
    }

    #[test]
    fn a_slow_adapter_steps_down_one_level_at_a_time_to_the_lowest() {
        for frame in [40.0, 150.0, 400.0] {
            let mut auto = AutoQuality::new(AUTO_TARGET_FPS);
            let steps = feed(&mut auto, ms(frame), 200);
            assert_eq!(steps, [Quality::Medium, Quality::Low], "{frame} ms");
            assert!(auto.settled());
            assert!(auto.reason().contains("lowest"), "{}", auto.reason());
        }
    }

    #[test]
    fn it_stops_at_the_first_level_that_keeps_up() {
        let mut auto = AutoQuality::new(AUTO_TARGET_FPS);
        let mut steps = Vec::new();
        for _ in 0..400 {
            // Medium and below keep up.
            let frame = if auto.level() == Quality::High {
                60.0
            } else {
                20.0
            };
            steps.extend(auto.observe(ms(frame)));
        }
        assert_eq!(steps, [Quality::Medium]);
        assert!(auto.settled());
        // Once settled, even slow frames change nothing.
        assert!(feed(&mut auto, ms(500.0), 100).is_empty());
    }

    #[test]
    fn a_few_slow_frames_in_a_fast_second_move_nothing() {
        let mut auto = AutoQuality::new(AUTO_TARGET_FPS);
        let mut steps = Vec::new();
        for k in 0..300 {
            let frame = if k % 5 == 0 { 300.0 } else { 10.0 };
            steps.extend(auto.observe(ms(frame)));
        }
        assert!(steps.is_empty());
        assert_eq!(auto.level(), Quality::High);
    }

    #[test]
    fn the_first_frames_of_a_level_are_not_judged() {
        // Slow warm-up frames, then a fast pace: no step down.
        let mut auto = AutoQuality::new(AUTO_TARGET_FPS);
        let mut steps = feed(&mut auto, ms(900.0), SETTLE_FRAMES);
        steps.extend(feed(&mut auto, ms(10.0), 300));
        assert!(steps.is_empty());
    }

    #[test]
    fn names_read_back() {
        for name in QualityChoice::NAMES {
            assert_eq!(QualityChoice::from_name(name).unwrap().name(), name);
        }
        assert_eq!(QualityChoice::from_name("ultra"), None);
        assert_eq!(QualityChoice::default(), QualityChoice::Auto);
        assert_eq!(QualityChoice::Auto.first(), Quality::High);
    }

    #[test]
    fn each_level_costs_no_more_than_the_one_above() {
        for pair in Quality::ALL.windows(2) {
            let (lower, upper) = (pair[0].settings(), pair[1].settings());
            assert!(lower.msaa <= upper.msaa);
            assert!(lower.resolution <= upper.resolution);
            assert!(lower.shadow_taps <= upper.shadow_taps);
            assert!(lower.shadow_size <= upper.shadow_size);
            assert!(lower.shadows && upper.shadows);
        }
    }
}
