//! The on-screen HUD (egui): frame rate, timings, counts, modes, the seed,
//! a small plot of the total energy, and the help panel (I7).

use crate::egui_paint::{EguiPainter, Painted};
use rolypoly_fx::Effects;
use rolypoly_physics::World;
use rolypoly_render::Gpu;
use std::collections::VecDeque;
use winit::window::Window;

/// The numbers the HUD shows, updated every frame.
pub struct HudState {
    pub seed: u64,
    pub fps: f64,
    pub frame_time: f64,
    pub step_time: f64,
    pub render_cpu: f64,
    /// The quality level drawn, and why.
    pub quality: String,
    /// What the hand holds, if anything: its facts.
    pub held: Option<String>,
    /// How far behind the furthest point of the run the world stands (s),
    /// after going back.
    pub rewound: f64,
    pub balls_alive: usize,
    pub balls_total: usize,
    /// Which engine steps the balls, and where: "cpu", or "gpu on ADAPTER"
    /// (whose balls stay there, so that only their count is shown).
    pub engine: String,
    pub particles: (usize, usize),
    pub dropped: u64,
    pub paused: bool,
    pub grabbing: bool,
    /// The keys' help shows.
    pub help: bool,
    /// The caption of the view of the frame shown (V, Shift+V).
    pub view: String,
    /// Why the watched folder's shaders are not drawn with (the last good
    /// ones are), until a save fixes them.
    pub shader_error: Option<String>,
    /// Simulated seconds per real one, as the player set it.
    pub time_scale: f64,
    /// A line for the player (a refused throw, a saved file), and until
    /// when it shows.
    pub message: Option<(String, std::time::Instant)>,
    pub sim_time: f64,
    /// Simulated time per real time, smoothed: below 1 when the steps
    /// cannot keep up and the world runs in slow motion.
    pub pace: f64,
    /// Total energy, one sample every few frames.
    pub energy: VecDeque<f32>,
    frames: u64,
}

const ENERGY_SAMPLES: usize = 240;

/// How long the HUD's rates take to follow a change (seconds).
const SMOOTHING: f64 = 0.5;

/// `average` moved towards `sample`, a frame of `elapsed` seconds later:
/// smoothed over time, not frames, so that the numbers can be read at 60
/// frames a second and still tell the truth within a frame or two at one.
fn smooth(average: f64, sample: f64, elapsed: f64) -> f64 {
    let weight = 1.0 - (-elapsed / SMOOTHING).exp();
    average + weight * (sample - average)
}

impl HudState {
    pub fn new(seed: u64, balls: usize) -> HudState {
        HudState {
            seed,
            fps: 0.0,
            frame_time: 0.0,
            step_time: 0.0,
            render_cpu: 0.0,
            quality: String::new(),
            held: None,
            rewound: 0.0,
            balls_alive: balls,
            balls_total: balls,
            engine: "cpu".into(),
            particles: (0, 0),
            dropped: 0,
            paused: false,
            grabbing: false,
            help: false,
            view: String::new(),
            shader_error: None,
            time_scale: 1.0,
            message: None,
            sim_time: 0.0,
            pace: 1.0,
            energy: VecDeque::with_capacity(ENERGY_SAMPLES),
            frames: 0,
        }
    }

    /// Notes a frame of `elapsed` seconds that skipped `skipped` of them.
    pub fn pace(&mut self, elapsed: f64, skipped: f64) {
        if elapsed > 0.0 {
            let pace = (1.0 - skipped / elapsed).clamp(0.0, 1.0);
            self.pace = smooth(self.pace, pace, elapsed);
        }
    }

    pub fn frame(
        &mut self,
        elapsed: f64,
        world: &World,
        fx: &Effects,
        paused: bool,
        grabbing: bool,
    ) {
        self.frames += 1;
        if elapsed > 0.0 {
            self.frame_time = smooth(self.frame_time, elapsed, elapsed);
            self.fps = 1.0 / self.frame_time.max(1e-6);
        }
        self.balls_alive = world.balls().alive().iter().filter(|a| **a).count();
        self.balls_total = world.balls().len();
        let stats = fx.stats();
        self.particles = (stats.live, stats.capacity);
        self.dropped = stats.dropped;
        self.paused = paused;
        self.grabbing = grabbing;
        self.sim_time = world.time();
        if self.frames.is_multiple_of(4) && !paused {
            if self.energy.len() == ENERGY_SAMPLES {
                self.energy.pop_front();
            }
            self.energy.push_back(world.energy().total() as f32);
        }
    }
}

const KEYS: [(&str, &str); 24] = [
    ("mouse", "look around"),
    ("W A S D", "move"),
    ("F", "fireball on / off"),
    ("B", "throw a ball"),
    ("hold Left Shift", "freeze time (the camera still moves)"),
    ("P", "pause / go on"),
    (".", "one step while paused"),
    (
        ", and Backspace",
        "back one step, back one second (the last 30 s)",
    ),
    ("[ and ]", "slower, faster (1/16x to 4x)"),
    ("Tab", "sandbox panel: scenes, settings, save"),
    ("R", "record the inputs / stop and write them"),
    (
        "G",
        "grab mode: drag a tumbler or a ball with the left button",
    ),
    ("I", "re-initialise the balls"),
    (
        "V / Shift+V",
        "the next / previous view of the frame's passes (Tab's panel lists them)",
    ),
    (
        "O",
        "orbit the body in the middle of the view (move the mouse to turn, wheel to zoom), or fly again",
    ),
    (
        "1 to 6",
        "debug views: contacts, impulses, velocities, grid, rest, centre of mass",
    ),
    ("F3", "profiler: the step's stages and the frame's passes"),
    (
        "F4",
        "plots: energy, momentum beside its impulses, a body, a tilt beside theory",
    ),
    ("M", "mute the sound / play it again"),
    ("H or F1", "this help"),
    ("F12", "screenshot (PNG)"),
    ("Esc", "release the mouse"),
    ("Esc again", "quit"),
    ("click", "capture the mouse again"),
];

pub struct Hud {
    context: egui::Context,
    input: egui_winit::State,
    painter: EguiPainter,
}

impl Hud {
    pub fn new(window: &Window, gpu: &Gpu, format: wgpu::TextureFormat) -> Hud {
        let context = egui::Context::default();
        let input = egui_winit::State::new(
            context.clone(),
            egui::ViewportId::ROOT,
            window,
            None,
            None,
            None,
        );
        Hud {
            context,
            input,
            painter: EguiPainter::new(gpu, format),
        }
    }

    pub fn on_event(&mut self, window: &Window, event: &winit::event::WindowEvent) {
        let _ = self.input.on_window_event(window, event);
    }

    /// Whether a text field has the keyboard (the panel's file name).
    pub fn typing(&self) -> bool {
        self.context.text_edit_focused()
    }

    /// Draws the HUD over the frame in `target`, after `panel` (drawn
    /// first, so that the HUD's windows keep out of the space it takes).
    pub fn draw(
        &mut self,
        window: &Window,
        gpu: &Gpu,
        target: &wgpu::TextureView,
        size: [u32; 2],
        s: &HudState,
        mut panel: impl FnMut(&mut egui::Ui),
    ) -> Painted {
        let raw = self.input.take_egui_input(window);
        let mut output = self.context.run_ui(raw, |ui| {
            panel(ui);
            // The help goes beside the panel, not over it.
            let ctx = ui.ctx();
            let beside_panel = ctx.content_rect().right() - ui.available_rect_before_wrap().right();
            egui::Window::new("rolypoly")
                .anchor(egui::Align2::LEFT_TOP, [8.0, 8.0])
                .resizable(false)
                .collapsible(true)
                .show(ctx, |ui| {
                    ui.label(format!(
                        "{:.0} fps, {:.1} ms a frame",
                        s.fps,
                        1e3 * s.frame_time
                    ));
                    ui.label(format!(
                        "physics {:.3} ms a step, rendering CPU {:.2} ms",
                        1e3 * s.step_time,
                        1e3 * s.render_cpu
                    ));
                    ui.label(&s.quality);
                    if let Some(held) = &s.held {
                        ui.label(held);
                    }
                    if s.engine == "cpu" {
                        ui.label(format!(
                            "balls {} of {}, engine cpu",
                            s.balls_alive, s.balls_total
                        ));
                    } else {
                        ui.label(format!("{} balls, engine {}", s.balls_total, s.engine));
                    }
                    ui.label(format!(
                        "particles {} of {} ({} dropped)",
                        s.particles.0, s.particles.1, s.dropped
                    ));
                    ui.label(format!("time {:.2} s, seed {}", s.sim_time, s.seed));
                    let mut modes = Vec::new();
                    if s.paused {
                        modes.push("PAUSED".to_string());
                    }
                    if s.grabbing {
                        modes.push("GRAB MODE".to_string());
                    }
                    if s.time_scale != 1.0 {
                        modes.push(format!("TIME x{}", s.time_scale));
                    }
                    if s.pace < 0.95 && !s.paused {
                        // The steps cannot keep up with real time.
                        modes.push(format!("SLOW MOTION {}", percent(s.pace)));
                    }
                    if s.rewound > 0.0 {
                        modes.push(format!(
                            "REWOUND {:.2} s: the first run plays on",
                            s.rewound
                        ));
                    }
                    if !modes.is_empty() {
                        ui.colored_label(egui::Color32::from_rgb(255, 200, 80), modes.join("  "));
                    }
                    if let Some((message, until)) = &s.message
                        && std::time::Instant::now() < *until
                    {
                        ui.colored_label(egui::Color32::from_rgb(255, 200, 80), message);
                    }
                    ui.label(format!("view {}", s.view));
                    energy_plot(ui, &s.energy);
                    ui.small("H or F1: keys, Tab: sandbox panel");
                });
            if let Some(error) = &s.shader_error {
                egui::Window::new("Shader error")
                    .anchor(egui::Align2::LEFT_BOTTOM, [8.0, -8.0])
                    .resizable(false)
                    .collapsible(false)
                    .show(ctx, |ui| {
                        ui.colored_label(egui::Color32::from_rgb(255, 110, 90), error);
                        ui.small("the last good shaders draw until the file is saved without it");
                    });
            }
            if s.help {
                egui::Window::new("Keys")
                    .anchor(egui::Align2::RIGHT_TOP, [-8.0 - beside_panel, 8.0])
                    .resizable(false)
                    .show(ctx, |ui| {
                        egui::Grid::new("keys").striped(true).show(ui, |ui| {
                            for (key, what) in KEYS {
                                ui.strong(key);
                                ui.label(what);
                                ui.end_row();
                            }
                        });
                    });
            }
        });
        self.input
            .handle_platform_output(window, std::mem::take(&mut output.platform_output));
        self.painter.paint(gpu, &self.context, output, target, size)
    }
}

/// Total energy over the last seconds, as a line.
fn energy_plot(ui: &mut egui::Ui, samples: &VecDeque<f32>) {
    let (rect, _) = ui.allocate_exact_size(egui::vec2(200.0, 40.0), egui::Sense::hover());
    let painter = ui.painter_at(rect);
    painter.rect_filled(rect, 2.0, egui::Color32::from_black_alpha(80));
    if samples.len() < 2 {
        return;
    }
    let (lo, hi) = samples
        .iter()
        .fold((f32::MAX, f32::MIN), |(lo, hi), &e| (lo.min(e), hi.max(e)));
    let span = (hi - lo).max(1e-3);
    let points: Vec<egui::Pos2> = samples
        .iter()
        .enumerate()
        .map(|(i, &e)| {
            let x = rect.left() + rect.width() * i as f32 / (ENERGY_SAMPLES - 1) as f32;
            let y = rect.bottom() - rect.height() * (e - lo) / span;
            egui::pos2(x, y)
        })
        .collect();
    painter.add(egui::Shape::line(
        points,
        egui::Stroke::new(1.5, egui::Color32::from_rgb(120, 220, 255)),
    ));
    painter.text(
        rect.left_top() + egui::vec2(4.0, 2.0),
        egui::Align2::LEFT_TOP,
        format!("energy {:.1} J", samples.back().copied().unwrap_or(0.0)),
        egui::FontId::proportional(11.0),
        egui::Color32::WHITE,
    );
}

/// A share as a percentage with two significant digits: "35 %", "0.52 %".
fn percent(share: f64) -> String {
    let p = 100.0 * share;
    let decimals = if p >= 10.0 {
        0
    } else if p >= 1.0 {
        1
    } else {
        2
    };
    format!("{p:.decimals$} %")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slow_motion_keeps_two_digits_however_slow() {
        assert_eq!(percent(0.35), "35 %");
        assert_eq!(percent(0.042), "4.2 %");
        assert_eq!(percent(0.0049), "0.49 %");
    }

    #[test]
    fn pace_tells_the_truth_at_any_frame_rate() {
        let dt = 1.0 / 120.0;
        // Sixty frames a second, all simulated: real time.
        let mut hud = HudState::new(1, 0);
        (0..600).for_each(|_| hud.pace(1.0 / 60.0, 0.0));
        assert!((hud.pace - 1.0).abs() < 1e-12, "{}", hud.pace);
        // Frames of 1.7 s that simulate one step each: within three
        // frames the HUD says under 1 %, not the share it began with.
        (0..3).for_each(|_| hud.pace(1.7, 1.7 - dt));
        assert!(hud.pace < 0.01, "{}", hud.pace);
        // Back at sixty frames a second, within a second.
        (0..60).for_each(|_| hud.pace(1.0 / 60.0, 0.0));
        assert!(hud.pace > 0.85, "{}", hud.pace);
    }

    #[test]
    fn the_frame_time_follows_slow_frames_at_once_and_fast_ones_smoothly() {
        let mut average = 1.0 / 60.0;
        average = smooth(average, 1.7, 1.7);
        assert!((average - 1.7).abs() < 0.1, "{average}");
        // One odd frame among many moves a 60 Hz reading by a little.
        let mut average = 1.0 / 60.0;
        average = smooth(average, 2.0 / 60.0, 2.0 / 60.0);
        assert!(average < 1.1 / 60.0, "{average}");
    }
}
