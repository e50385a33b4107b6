//! The frame rate as `--log-events` reports it once a second: the frames
//! drawn a second, the 95th percentile of their times, which a mean hides
//! (a frame in twenty that stalls is a stutter a player sees), and where
//! the mean frame's time went.

/// Where a frame's time went (s).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FrameParts {
    /// Stepping the world and its sound.
    pub simulation: f64,
    /// Recording the frame's passes.
    pub render_cpu: f64,
    /// The HUD and panel on the CPU.
    pub hud_cpu: f64,
    /// Waiting on the GPU: acquiring, frames in flight, submitting,
    /// presenting.
    pub gpu_wait: f64,
}

/// The frames of the second being counted.
#[derive(Default)]
pub struct FrameRate {
    /// Seconds counted so far in this second.
    counted: f64,
    /// Each frame's time (s), since the last report.
    times: Vec<f64>,
    /// Their parts, summed.
    parts: FrameParts,
}

/// One second's figures.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrameRateReport {
    /// Frames drawn a second.
    pub fps: f64,
    /// The 95th percentile of the frames' times (ms).
    pub p95_ms: f64,
    /// Where the mean frame's time went (ms).
    pub mean_ms: FrameParts,
}

impl FrameRate {
    /// Counts a frame that took `seconds` since the one before, `parts`
    /// of it spent as they say; once a second's worth has been counted,
    /// the figures of those frames.
    pub fn push(&mut self, seconds: f64, parts: FrameParts) -> Option<FrameRateReport> {
        self.counted += seconds;
        self.times.push(seconds);
        let sum = &mut self.parts;
        sum.simulation += parts.simulation;
        sum.render_cpu += parts.render_cpu;
        sum.hud_cpu += parts.hud_cpu;
        sum.gpu_wait += parts.gpu_wait;
        if self.counted < 1.0 {
            return None;
        }
        let per_frame_ms = 1e3 / self.times.len() as f64;
        let report = FrameRateReport {
            fps: self.times.len() as f64 / self.counted,
            p95_ms: 1e3 * percentile(&mut self.times, 0.95),
            mean_ms: FrameParts {
                simulation: sum.simulation * per_frame_ms,
                render_cpu: sum.render_cpu * per_frame_ms,
                hud_cpu: sum.hud_cpu * per_frame_ms,
                gpu_wait: sum.gpu_wait * per_frame_ms,
            },
        };
        self.counted = 0.0;
        self.times.clear();
        self.parts = FrameParts::default();
        Some(report)
    }
}

/// The value below which a share `q` of `values` lies (the nearest rank:
/// the smallest value with at least that share at or below it).
fn percentile(values: &mut [f64], q: f64) -> f64 {
    values.sort_by(f64::total_cmp);
    let rank = (q * values.len() as f64).ceil() as usize;
    values[rank.clamp(1, values.len()) - 1]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_steady_rate_reports_its_rate_and_its_frame_time() {
        for fps in [12.0, 30.0, 59.0, 144.0] {
            let mut rate = FrameRate::default();
            let report = std::iter::repeat_n(1.0 / fps, 1000)
                .find_map(|t| {
                    let parts = FrameParts {
                        gpu_wait: 0.5 * t,
                        ..FrameParts::default()
                    };
                    rate.push(t, parts)
                })
                .expect("a second passes");
            assert!(
                (report.mean_ms.gpu_wait - 500.0 / fps).abs() < 1e-6,
                "{report:?}"
            );
            assert!((report.fps - fps).abs() < 1e-6 * fps, "{report:?}");
            assert!((report.p95_ms - 1e3 / fps).abs() < 1e-9, "{report:?}");
        }
    }

    #[test]
    fn one_stall_in_twenty_frames_shows_in_the_95th_percentile_not_below() {
        // 19 frames of 20 ms and one of 100 ms, over and over: the 95th
        // percentile is the last of the quick ones; two stalls in twenty
        // lift it to the stall.
        let mut rate = FrameRate::default();
        let times = (0..200).map(|k| if k % 20 == 19 { 0.1 } else { 0.02 });
        let report = times
            .clone()
            .find_map(|t| rate.push(t, FrameParts::default()))
            .expect("a second");
        assert!((report.p95_ms - 20.0).abs() < 1e-9, "{report:?}");
        let mut rate = FrameRate::default();
        let times = (0..200).map(|k| if k % 10 == 9 { 0.1 } else { 0.02 });
        let report = times
            .clone()
            .find_map(|t| rate.push(t, FrameParts::default()))
            .expect("a second");
        assert!((report.p95_ms - 100.0).abs() < 1e-9, "{report:?}");
    }
}
