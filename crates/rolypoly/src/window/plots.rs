//! The plots (key F4): the run's totals over the last 30 s of simulated
//! time, the series `simulate --series` writes: the energy in its parts,
//! the momentum, the contacts and impacts a step, and one tumbler's tilt
//! beside the small-angle rolling pendulum's curve. A line marks the moment
//! shown, so that going back (rewind) shows where the run stands in what
//! was plotted; steps taken from there replace what came after.

use std::collections::VecDeque;
use std::path::{Path, PathBuf};

use egui_plot::{Corner, Legend, Line, Plot, VLine};
use rolypoly_core::series::{FIXED_COLUMNS, Sample, SeriesError, SeriesWriter};
use rolypoly_physics::{Event, World};

/// How much simulated time the plots keep (s).
const KEPT_SECONDS: f64 = 30.0;

/// The plots' window and the samples it shows.
#[derive(Default)]
pub struct Plots {
    /// Whether its window shows (and samples are taken).
    pub open: bool,
    samples: VecDeque<Sample>,
    /// The step the world stands at (the cursor).
    now: u64,
    /// The tumbler whose tilt is plotted.
    tumbler: usize,
    /// The rolling pendulum's angular frequency (rad/s) for the tumblers.
    rocking: f64,
}

/// The theory's curve through a tumbler's last swing: the small-angle
/// rolling pendulum `|A cos(w (t - t0))|`, its amplitude `A` and phase
/// `t0` from the last peak of the tilt.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Swing {
    /// The peak's time (s).
    pub at: f64,
    /// The peak's tilt (rad).
    pub amplitude: f64,
}

impl Plots {
    /// Takes a sample of `world`, whose last step reported `events`, if it
    /// has stepped since the last one. A world that went back moves the
    /// cursor only; a step from there drops the samples after it.
    pub fn record(&mut self, world: &World, events: &[Event]) {
        let step = world.step_count();
        let (seen, went_back) = (self.now, step < self.now);
        self.now = step;
        self.rocking = world
            .tumbler_shape()
            .rocking_frequency(world.config().gravity);
        if step == seen && !self.samples.is_empty() || went_back {
            return;
        }
        while self.samples.back().is_some_and(|s| s.step >= step) {
            self.samples.pop_back();
        }
        self.samples.push_back(Sample::of(world, events));
        let newest = self.samples.back().map_or(0.0, |s| s.time);
        while self
            .samples
            .front()
            .is_some_and(|s| s.time < newest - KEPT_SECONDS)
        {
            self.samples.pop_front();
        }
        let tumblers = self.samples.back().map_or(0, |s| s.tilts.len());
        if self.tumbler >= tumblers {
            self.tumbler = 0;
        }
    }

    /// The samples kept, oldest first.
    #[cfg(test)]
    pub fn samples(&self) -> impl Iterator<Item = &Sample> {
        self.samples.iter()
    }

    /// Writes the samples kept as `simulate --series` writes its lines.
    pub fn export(&self, path: &Path) -> Result<(), SeriesError> {
        let tumblers = self.samples.back().map_or(0, |s| s.tilts.len());
        let file = std::fs::File::create(path).map_err(|source| SeriesError {
            name: path.display().to_string(),
            source,
        })?;
        let mut writer = SeriesWriter::new(file, path.display().to_string(), tumblers)?;
        for sample in &self.samples {
            writer.sample(sample)?;
        }
        writer.finish().map(drop)
    }

    /// The last peak of tumbler `k`'s tilt among the samples kept: a
    /// sample above both neighbours, past the first.
    pub fn last_swing(&self, k: usize) -> Option<Swing> {
        let tilt = |s: &Sample| s.tilts.get(k).copied();
        let shown: Vec<&Sample> = self.samples.iter().filter(|s| s.step <= self.now).collect();
        shown.windows(3).rev().find_map(|w| {
            let (a, b, c) = (tilt(w[0])?, tilt(w[1])?, tilt(w[2])?);
            (b > a && b >= c && b > 1e-4).then_some(Swing {
                at: w[1].time,
                amplitude: b,
            })
        })
    }

    /// The rolling pendulum's tilt at `t` through `swing`.
    pub fn theory(&self, swing: Swing, t: f64) -> f64 {
        (swing.amplitude * (self.rocking * (t - swing.at)).cos()).abs()
    }

    /// Draws the window, if open; `Some(path)` when its export button was
    /// pressed, with the file it asks for in `folder`.
    pub fn show(&mut self, ctx: &egui::Context, folder: &Path) -> Option<PathBuf> {
        if !self.open {
            return None;
        }
        let mut export = None;
        let now_time = self
            .samples
            .iter()
            .rev()
            .find(|s| s.step <= self.now)
            .map_or(0.0, |s| s.time);
        egui::Window::new("plots (F4)")
            .default_width(460.0)
            .show(ctx, |ui| {
                let cursor = || VLine::new("now", now_time).color(egui::Color32::GRAY);
                self.columns_plot(
                    ui,
                    "Energy (J)",
                    110.0,
                    Corner::RightTop,
                    &[
                        ("translational", "kinetic_translational"),
                        ("rotational", "kinetic_rotational"),
                        ("potential", "potential"),
                        ("total", "total"),
                    ],
                    now_time,
                );
                self.columns_plot(
                    ui,
                    "Linear momentum (kg m/s): gravity and the room's surfaces change it",
                    90.0,
                    Corner::LeftTop,
                    &[
                        ("x", "momentum_x"),
                        ("y", "momentum_y"),
                        ("z", "momentum_z"),
                    ],
                    now_time,
                );
                self.columns_plot(
                    ui,
                    "A step's contacts and impacts",
                    80.0,
                    Corner::LeftTop,
                    &[
                        ("contacts", "contacts"),
                        ("impacts", "impacts"),
                        ("on surfaces", "surface_impacts"),
                    ],
                    now_time,
                );
                let tumblers = self.samples.back().map_or(0, |s| s.tilts.len());
                if tumblers > 0 {
                    ui.horizontal(|ui| {
                        ui.label("Tilt (rad) of tumbler");
                        egui::ComboBox::from_id_salt("tumbler")
                            .selected_text(self.tumbler.to_string())
                            .show_ui(ui, |ui| {
                                for k in 0..tumblers {
                                    ui.selectable_value(&mut self.tumbler, k, k.to_string());
                                }
                            });
                        ui.label(format!(
                            "rolling pendulum: T = {:.3} s",
                            std::f64::consts::TAU / self.rocking
                        ));
                    });
                    let k = self.tumbler;
                    Plot::new("tilt")
                        .height(90.0)
                        .legend(Legend::default().position(Corner::LeftTop))
                        .show(ui, |plot| {
                            plot.line(self.line("simulated", FIXED_COLUMNS.len() + k));
                            if let Some(swing) = self.last_swing(k) {
                                let theory: Vec<[f64; 2]> = self
                                    .samples
                                    .iter()
                                    .filter(|s| s.time >= swing.at - 0.5)
                                    .map(|s| [s.time, self.theory(swing, s.time)])
                                    .collect();
                                plot.line(Line::new("theory, from the last swing", theory));
                            }
                            plot.vline(cursor());
                        });
                }
                if ui.button("export CSV").clicked() {
                    export = Some(folder.join(format!("rolypoly-series-{}.csv", self.now)));
                }
            });
        export
    }

    /// A plot titled `title` of the series' `columns` (legend name, column),
    /// with the cursor at `now`.
    fn columns_plot(
        &self,
        ui: &mut egui::Ui,
        title: &'static str,
        height: f32,
        legend: Corner,
        columns: &[(&'static str, &str)],
        now: f64,
    ) {
        ui.label(title);
        Plot::new(title)
            .height(height)
            .legend(Legend::default().position(legend))
            .show(ui, |plot| {
                for (name, column) in columns {
                    let k = FIXED_COLUMNS
                        .iter()
                        .position(|c| c == column)
                        .expect("a series column");
                    plot.line(self.line(name, k));
                }
                plot.vline(VLine::new("now", now).color(egui::Color32::GRAY));
            });
    }

    /// Column `k` of the samples against their time.
    fn line(&self, name: &'static str, k: usize) -> Line<'static> {
        let points: Vec<[f64; 2]> = self
            .samples
            .iter()
            .filter_map(|s| s.values().get(k).map(|v| [s.time, *v]))
            .collect();
        Line::new(name, points)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rolypoly_core::series;
    use rolypoly_physics::WorldConfig;

    #[test]
    fn going_back_moves_the_cursor_and_stepping_on_replaces_what_came_after() {
        let mut world = World::new(WorldConfig::default(), 2).unwrap();
        let mut back = World::new(WorldConfig::default(), 2).unwrap();
        let mut plots = Plots::default();
        for k in 0..20 {
            world.step();
            plots.record(&world, &[]);
            if k < 10 {
                back.step();
            }
        }
        assert_eq!(plots.samples().count(), 20);
        // Back to step 10: nothing is dropped until a step is taken.
        plots.record(&back, &[]);
        assert_eq!(plots.samples().count(), 20);
        assert_eq!(plots.now, 10);
        back.step();
        plots.record(&back, &[]);
        let steps: Vec<u64> = plots.samples().map(|s| s.step).collect();
        assert_eq!(steps, (1..=11).collect::<Vec<u64>>());
        // Paused: the same step is sampled once.
        plots.record(&back, &[]);
        assert_eq!(plots.samples().count(), 11);
    }

    #[test]
    fn only_the_last_thirty_seconds_are_kept() {
        let mut config = WorldConfig::default();
        config.balls.count = 0;
        config.tumblers.placements.clear();
        config.solver.dt = 0.05;
        let mut world = World::new(config, 1).unwrap();
        let mut plots = Plots::default();
        for _ in 0..1000 {
            world.step();
            plots.record(&world, &[]);
        }
        let first = plots.samples().next().unwrap().time;
        assert!(
            (world.time() - first - KEPT_SECONDS).abs() < 0.051,
            "{first}"
        );
    }

    #[test]
    fn the_export_is_the_series_simulate_writes() {
        let dir = std::env::temp_dir().join(format!("rolypoly-plots-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let mut world = World::new(WorldConfig::default(), 6).unwrap();
        let mut plots = Plots::default();
        let mut expected =
            SeriesWriter::new(Vec::new(), "memory".into(), world.tumblers().len()).unwrap();
        let mut events = Vec::new();
        for _ in 0..30 {
            world.step();
            world.take_events(&mut events);
            plots.record(&world, &events);
            expected
                .sample(&series::Sample::of(&world, &events))
                .unwrap();
        }
        let path = dir.join("out.csv");
        plots.export(&path).unwrap();
        let expected = String::from_utf8(expected.finish().unwrap()).unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), expected);
        assert_eq!(expected.lines().count(), 31);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_rocking_tumblers_theory_curve_goes_through_its_last_swing() {
        let mut config = WorldConfig::default();
        config.balls.count = 0;
        config.tumblers.placements.truncate(1);
        config.tumblers.placements[0].tilt_deg = 6.0;
        config.tumblers.damping = 0.0;
        let mut world = World::new(config, 1).unwrap();
        let mut plots = Plots::default();
        for _ in 0..600 {
            world.step();
            plots.record(&world, &[]);
        }
        let swing = plots.last_swing(0).expect("a peak");
        assert!(
            swing.amplitude > 0.09 && swing.amplitude < 0.11,
            "{swing:?}"
        );
        // Within a period of the peak the simulated tilt follows the curve.
        let period = std::f64::consts::TAU / plots.rocking;
        for s in plots
            .samples()
            .filter(|s| (s.time - swing.at).abs() < 0.5 * period)
        {
            let theory = plots.theory(swing, s.time);
            assert!(
                (s.tilts[0] - theory).abs() < 0.05 * swing.amplitude,
                "t {}: {} against {theory}",
                s.time,
                s.tilts[0]
            );
        }
    }
}
