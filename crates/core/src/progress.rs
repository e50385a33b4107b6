//! A progress bar on the terminal for work that takes more than a moment
//! (a clip's frames, a reference's rows); nothing where standard error is
//! not a terminal.

use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// The bar shows once the work has taken this long.
const QUIET_FOR: Duration = Duration::from_secs(1);

/// Work counted in steps of one unit.
pub struct Progress {
    bar: ProgressBar,
    start: Instant,
    shown: bool,
}

impl Progress {
    /// Work of `total` steps, each one of `unit` (plural).
    pub fn new(total: u32, unit: &str) -> Progress {
        let bar =
            ProgressBar::with_draw_target(Some(u64::from(total)), ProgressDrawTarget::hidden());
        let template = format!("{{bar:40}} {{pos}}/{{len}} {unit}, {{eta}} left");
        if let Ok(style) = ProgressStyle::with_template(&template) {
            bar.set_style(style);
        }
        Progress {
            bar,
            start: Instant::now(),
            shown: false,
        }
    }

    /// One more step done.
    pub fn advance(&mut self) {
        if !self.shown && self.start.elapsed() >= QUIET_FOR {
            self.bar.set_draw_target(ProgressDrawTarget::stderr());
            self.shown = true;
        }
        self.bar.inc(1);
    }

    /// All done: the bar goes.
    pub fn finish(&self) {
        self.bar.finish_and_clear();
    }
}
