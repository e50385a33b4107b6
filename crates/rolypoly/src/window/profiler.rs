//! The profiler (key F3): where a frame's time goes. The physics step's stages
//! (as the step names them, summed over the frame's steps) as a stacked bar
//! per frame; the frame, the physics, the rendering on the CPU and the
//! GPU's passes (by timestamp queries, where the adapter has them) plotted
//! over the last seconds; and what the step worked on beside them.

use std::collections::VecDeque;
use std::time::Duration;

use egui_plot::{Bar, BarChart, Legend, Line, Plot};
use rolypoly_physics::{Stage, StepTimes};
use rolypoly_render::PassTimes;

/// Frames kept for the plots: five seconds at 60 a second.
const KEPT: usize = 300;
/// Frames shown as bars.
const BARS: usize = 90;

/// What one frame cost, and what its steps worked on.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FrameProfile {
    /// When it began (s since the window opened).
    pub at: f64,
    /// The whole frame, from the one before.
    pub frame: Duration,
    /// The frame's steps, stage by stage, summed (the counts: the last
    /// step's).
    pub steps: StepTimes,
    /// How many steps it ran.
    pub step_count: u32,
    /// Recording the frame's passes on the CPU.
    pub render_cpu: Duration,
    /// The HUD and panel on the CPU.
    pub ui: Duration,
    /// Waiting on the GPU: for a surface texture and the frames in flight,
    /// in the submissions (where a software renderer draws) and in
    /// presenting. The GPU's time, not the pass that happened to wait.
    pub gpu_wait: Duration,
    /// The GPU's passes, of the latest frame whose timestamps came back.
    pub gpu: Option<PassTimes>,
    /// Shadow faces drawn (those whose casters or light moved).
    pub shadow_faces: u32,
    /// Balls in play.
    pub balls: usize,
}

/// The profiler's window and the frames it shows.
#[derive(Default)]
pub struct Profiler {
    /// Whether its window shows.
    pub open: bool,
    frames: VecDeque<FrameProfile>,
}

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

impl Profiler {
    /// Keeps `frame`, forgetting the oldest beyond five seconds' worth.
    pub fn push(&mut self, frame: FrameProfile) {
        if self.frames.len() == KEPT {
            self.frames.pop_front();
        }
        self.frames.push_back(frame);
    }

    /// Draws the window, if open.
    pub fn show(&self, ctx: &egui::Context) {
        if !self.open {
            return;
        }
        let Some(last) = self.frames.back() else {
            return;
        };
        egui::Window::new("profiler (F3)")
            .default_width(460.0)
            .show(ctx, |ui| {
                let s = &last.steps;
                ui.label(format!(
                    "frame {:.1} ms: {} steps, physics {:.2} ms, rendering CPU {:.2} ms, HUD CPU \
                     {:.2} ms, waiting on the GPU {:.1} ms ({} shadow faces drawn)",
                    ms(last.frame),
                    last.step_count,
                    ms(s.total),
                    ms(last.render_cpu),
                    ms(last.ui),
                    ms(last.gpu_wait),
                    last.shadow_faces
                ));
                ui.label(format!(
                    "balls {}, pairs {}, solver rows {}, impacts {}",
                    last.balls,
                    s.pairs,
                    s.pairs + s.other_contacts,
                    s.impacts
                ));
                match last.gpu {
                    Some(gpu) => ui.label(
                        gpu.named()
                            .map(|(name, t)| format!("{name} {:.2} ms", ms(t)))
                            .join(", "),
                    ),
                    None => ui.label("GPU passes: this adapter has no timestamp queries"),
                };
                ui.label("The step's stages, each frame (ms):");
                Plot::new("stages")
                    .height(130.0)
                    .legend(Legend::default())
                    .show(ui, |plot| {
                        for chart in self.stage_bars() {
                            plot.bar_chart(chart);
                        }
                    });
                ui.label("Over the last seconds (ms):");
                Plot::new("over time")
                    .height(130.0)
                    .legend(Legend::default())
                    .show(ui, |plot| {
                        for line in self.lines() {
                            plot.line(line);
                        }
                    });
            });
    }

    /// A stacked bar per frame of the last ones, a layer per stage.
    fn stage_bars(&self) -> Vec<BarChart> {
        let shown: Vec<&FrameProfile> = self.frames.iter().rev().take(BARS).rev().collect();
        let mut charts: Vec<BarChart> = Vec::new();
        for stage in Stage::ALL {
            let bars = shown
                .iter()
                .enumerate()
                .map(|(k, f)| Bar::new(k as f64, ms(f.steps.of(stage))).width(0.9))
                .collect();
            let mut chart = BarChart::new(stage.name(), bars);
            if !charts.is_empty() {
                let below: Vec<&BarChart> = charts.iter().collect();
                chart = chart.stack_on(&below);
            }
            charts.push(chart);
        }
        charts
    }

    /// The frame, the physics, the CPU's rendering, the wait on the GPU and
    /// the GPU's passes, over the frames kept.
    fn lines(&self) -> Vec<Line<'static>> {
        let series = |name: &'static str, value: fn(&FrameProfile) -> Option<Duration>| {
            let points: Vec<[f64; 2]> = self
                .frames
                .iter()
                .filter_map(|f| value(f).map(|d| [f.at, ms(d)]))
                .collect();
            Line::new(name, points)
        };
        vec![
            series("frame", |f| Some(f.frame)),
            series("physics", |f| Some(f.steps.total)),
            series("rendering CPU", |f| Some(f.render_cpu)),
            series("waiting on the GPU", |f| Some(f.gpu_wait)),
            series("GPU passes", |f| {
                f.gpu.map(|g| g.named().iter().map(|(_, t)| *t).sum())
            }),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frame(at: f64, stage_ms: u64) -> FrameProfile {
        let mut steps = StepTimes::default();
        for t in &mut steps.stages {
            *t = Duration::from_millis(stage_ms);
        }
        FrameProfile {
            at,
            frame: Duration::from_millis(16),
            steps,
            ..FrameProfile::default()
        }
    }

    #[test]
    fn it_keeps_five_seconds_of_frames_and_stacks_a_layer_per_stage() {
        let mut profiler = Profiler::default();
        for k in 0..1000 {
            profiler.push(frame(k as f64 / 60.0, k % 3));
        }
        assert_eq!(profiler.frames.len(), KEPT);
        assert_eq!(profiler.frames[0].at, 700.0 / 60.0);
        let charts = profiler.stage_bars();
        assert_eq!(charts.len(), Stage::ALL.len());
        assert_eq!(profiler.lines().len(), 5);
    }
}
