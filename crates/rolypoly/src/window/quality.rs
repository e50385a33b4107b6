//! The window's quality: the scene's choice (`render.quality`, the panel's
//! "quality", `--quality`), and under auto the render scale and the level
//! that the frames' drawing times led to. Auto moves the scale first (see
//! [`DynamicScale`]) and steps the level down (MSAA, shadow taps, the
//! shadow faces' size) only while the scale is as low as it goes.

use std::time::Duration;

use rolypoly_render::{AutoQuality, DynamicScale, Quality, QualityChoice, RenderSettings};

/// What a frame's drawing time changed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum QualityChange {
    /// Nothing.
    None,
    /// The render scale: the renderer lights the next frame at it.
    Scale,
    /// The level: the renderer is made anew for it.
    Level,
}

/// What the window draws with, and why.
pub struct WindowQuality {
    choice: QualityChoice,
    /// The frames a second auto holds.
    target_fps: f64,
    auto: AutoQuality,
    scale: DynamicScale,
    /// Multisamples at every level, where `--window-msaa` fixes them.
    msaa: Option<u32>,
    /// Whether frames take the temporal path (in place of multisampling).
    temporal: bool,
}

impl WindowQuality {
    /// The window's quality under `choice`, aiming at `target_fps` frames
    /// a second under auto, with `msaa` samples at every level where given,
    /// on the `temporal` path or not.
    pub fn new(
        choice: QualityChoice,
        target_fps: f64,
        msaa: Option<u32>,
        temporal: bool,
    ) -> WindowQuality {
        WindowQuality {
            choice,
            target_fps,
            auto: AutoQuality::new(target_fps),
            scale: DynamicScale::new(target_fps),
            msaa,
            temporal,
        }
    }

    /// The level drawn now.
    pub fn level(&self) -> Quality {
        match self.choice {
            QualityChoice::Fixed(level) => level,
            QualityChoice::Auto => self.auto.level(),
        }
    }

    /// The share of the output's width and height the scene is lit at: the
    /// level's own, or under auto the scale that follows the frame rate.
    pub fn scale(&self) -> f32 {
        match self.choice {
            QualityChoice::Fixed(level) => level.settings().resolution,
            QualityChoice::Auto => self.scale.scale(),
        }
    }

    /// Draws on the temporal path from now on, or not (the renderer is made
    /// anew for it).
    pub fn set_temporal(&mut self, temporal: bool) {
        self.temporal = temporal;
    }

    /// The renderer's settings now.
    pub fn settings(&self) -> RenderSettings {
        let level = self.level().settings();
        RenderSettings {
            msaa: self.msaa.unwrap_or(level.msaa),
            resolution: self.scale(),
            temporal: self.temporal,
            ..level
        }
    }

    /// Takes the scene's choice and target now and the time the last frame
    /// spent drawing (its time less the simulation's and the wait for the
    /// display: a scene whose physics is slow is not drawn more coarsely
    /// for it); says what changed. A new choice or target starts afresh
    /// from high at the full scale.
    pub fn update(
        &mut self,
        choice: QualityChoice,
        target_fps: f64,
        drawing: Duration,
    ) -> QualityChange {
        let (level, scale) = (self.level(), self.scale());
        if choice != self.choice || target_fps != self.target_fps {
            *self = WindowQuality::new(choice, target_fps, self.msaa, self.temporal);
        } else if choice == QualityChoice::Auto
            && !drawing.is_zero()
            && self.scale.observe(drawing).is_none()
            && self.scale.at_least()
        {
            // The scale first: the level only once it can go no lower.
            self.auto.observe(drawing);
        }
        if self.level() != level {
            QualityChange::Level
        } else if self.scale() != scale {
            QualityChange::Scale
        } else {
            QualityChange::None
        }
    }

    /// The level, the scale and why, for the HUD.
    pub fn describe(&self) -> String {
        let temporal = if self.temporal { ", temporal" } else { "" };
        match self.choice {
            QualityChoice::Fixed(level) => {
                format!("quality {}{temporal} (chosen)", level.name())
            }
            QualityChoice::Auto => format!(
                "quality {}, scale {:.2}{temporal} ({}; target {:.0} fps)",
                self.level().name(),
                self.scale(),
                self.auto.reason(),
                self.target_fps
            ),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rolypoly_render::{MAX_SCALE, MIN_SCALE};

    #[test]
    fn a_chosen_level_holds_however_slow_the_frames() {
        let mut quality =
            WindowQuality::new(QualityChoice::Fixed(Quality::High), 30.0, None, false);
        for _ in 0..300 {
            assert_eq!(
                quality.update(
                    QualityChoice::Fixed(Quality::High),
                    30.0,
                    Duration::from_millis(500)
                ),
                QualityChange::None
            );
        }
        assert_eq!(quality.level(), Quality::High);
        assert_eq!(quality.settings(), Quality::High.settings());
    }

    #[test]
    fn auto_lowers_the_scale_first_then_the_level_and_a_new_choice_takes_over() {
        let mut quality = WindowQuality::new(QualityChoice::Auto, 30.0, Some(4), false);
        let changes: Vec<QualityChange> = (0..600)
            .map(|_| quality.update(QualityChoice::Auto, 30.0, Duration::from_millis(200)))
            .filter(|&c| c != QualityChange::None)
            .collect();
        let first_level = changes
            .iter()
            .position(|&c| c == QualityChange::Level)
            .expect("a level step");
        // Every scale step came before the first level step.
        assert!(first_level > 0, "{changes:?}");
        assert!(
            changes[..first_level]
                .iter()
                .all(|&c| c == QualityChange::Scale)
        );
        assert_eq!(
            changes
                .iter()
                .filter(|&&c| c == QualityChange::Level)
                .count(),
            2
        );
        assert_eq!(quality.level(), Quality::Low);
        assert_eq!(quality.scale(), MIN_SCALE);
        assert_eq!(quality.settings().resolution, MIN_SCALE);
        // The fixed multisamples hold at every level.
        assert_eq!(quality.settings().msaa, 4);
        assert!(quality.describe().contains("low"), "{}", quality.describe());
        // Choosing auto again starts over from high, at the full scale.
        assert_eq!(
            quality.update(QualityChoice::Fixed(Quality::Medium), 30.0, Duration::ZERO),
            QualityChange::Level
        );
        assert_eq!(
            quality.settings(),
            RenderSettings {
                msaa: 4,
                ..Quality::Medium.settings()
            }
        );
        assert_eq!(
            quality.update(QualityChoice::Auto, 30.0, Duration::ZERO),
            QualityChange::Level
        );
        assert_eq!(
            (quality.level(), quality.scale()),
            (Quality::High, MAX_SCALE)
        );
    }

    #[test]
    fn a_frame_that_keeps_up_only_at_a_lower_scale_keeps_the_level() {
        // 4 ms that do not scale and 60 ms that do: the scale keeps 30 a
        // second well above the least, and the level stays high.
        let mut quality = WindowQuality::new(QualityChoice::Auto, 30.0, None, false);
        for _ in 0..600 {
            let s = f64::from(quality.scale());
            quality.update(
                QualityChoice::Auto,
                30.0,
                Duration::from_secs_f64((4.0 + 60.0 * s * s) / 1e3),
            );
        }
        assert_eq!(quality.level(), Quality::High);
        assert!(quality.scale() > MIN_SCALE && quality.scale() < MAX_SCALE);
    }
}
