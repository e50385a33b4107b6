//! The window's quality level: the scene's choice (`render.quality`, the
//! panel's "quality", `--quality`), and under auto the level the frames'
//! drawing times led to.

use std::time::Duration;

use rolypoly_render::{AUTO_TARGET_FPS, AutoQuality, Quality, QualityChoice, RenderSettings};

/// What the window draws with, and why.
pub struct WindowQuality {
    choice: QualityChoice,
    auto: AutoQuality,
    /// Multisamples at every level, where `--window-msaa` fixes them.
    msaa: Option<u32>,
}

impl WindowQuality {
    /// The window's quality under `choice`, with `msaa` samples at every
    /// level where given.
    pub fn new(choice: QualityChoice, msaa: Option<u32>) -> WindowQuality {
        WindowQuality {
            choice,
            auto: AutoQuality::new(AUTO_TARGET_FPS),
            msaa,
        }
    }

    /// The level drawn now.
    pub fn level(&self) -> Quality {
        match self.choice {
            QualityChoice::Fixed(level) => level,
            QualityChoice::Auto => self.auto.level(),
        }
    }

    /// The renderer's settings for the level now.
    pub fn settings(&self) -> RenderSettings {
        let level = self.level().settings();
        RenderSettings {
            msaa: self.msaa.unwrap_or(level.msaa),
            ..level
        }
    }

    /// Takes the scene's choice now and the time the last frame spent
    /// drawing (its time less the simulation's: a scene whose physics is
    /// slow is not drawn more coarsely for it); says whether the level
    /// changed. A new choice of auto starts watching afresh from high.
    pub fn update(&mut self, choice: QualityChoice, drawing: Duration) -> bool {
        let before = self.level();
        if choice != self.choice {
            self.choice = choice;
            self.auto = AutoQuality::new(AUTO_TARGET_FPS);
        } else if choice == QualityChoice::Auto && !drawing.is_zero() {
            self.auto.observe(drawing);
        }
        self.level() != before
    }

    /// The level and why, for the HUD.
    pub fn describe(&self) -> String {
        match self.choice {
            QualityChoice::Fixed(level) => format!("quality {} (chosen)", level.name()),
            QualityChoice::Auto => {
                format!("quality {} ({})", self.level().name(), self.auto.reason())
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_chosen_level_holds_however_slow_the_frames() {
        let mut quality = WindowQuality::new(QualityChoice::Fixed(Quality::High), None);
        for _ in 0..300 {
            assert!(!quality.update(
                QualityChoice::Fixed(Quality::High),
                Duration::from_millis(500)
            ));
        }
        assert_eq!(quality.level(), Quality::High);
        assert_eq!(quality.settings(), Quality::High.settings());
    }

    #[test]
    fn auto_steps_down_on_slow_frames_and_a_new_choice_takes_over() {
        let mut quality = WindowQuality::new(QualityChoice::Auto, Some(4));
        let changes = (0..300)
            .filter(|_| quality.update(QualityChoice::Auto, Duration::from_millis(200)))
            .count();
        assert_eq!(changes, 2);
        assert_eq!(quality.level(), Quality::Low);
        // The fixed multisamples hold at every level.
        assert_eq!(quality.settings().msaa, 4);
        assert!(quality.describe().contains("low"), "{}", quality.describe());
        // Choosing auto again starts over from high.
        assert!(quality.update(QualityChoice::Fixed(Quality::Medium), Duration::ZERO));
        assert!(quality.update(QualityChoice::Auto, Duration::ZERO));
        assert_eq!(quality.level(), Quality::High);
    }
}
