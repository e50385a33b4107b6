//! The plots (key F4, or the sandbox panel's plots tab): the run's totals
//! over the last 30 s of simulated time, the series `simulate --series`
//! writes: the energy in its parts; the balls' momentum beside the
//! impulses that changed it (what the walls, floor, tumblers and gravity
//! gave, added up from the first sample: Newton's second law in integral
//! form, drawn); the contacts and impacts a step; and one body's height,
//! speed and spin, for a tumbler its tilt beside the small-angle rolling
//! pendulum's curve. A line marks the moment shown, so that going back
//! (rewind) shows where the run stands in what was plotted; steps taken
//! from there replace what came after.

use std::collections::VecDeque;
use std::path::{Path, PathBuf};

use egui_plot::{Corner, Legend, Line, Plot, PlotUi, VLine};
use glam::DVec3;
use rolypoly_core::series::{FIXED_COLUMNS, Sample, SeriesError, SeriesWriter};
use rolypoly_physics::{BallImpulses, Event, World};

/// How much simulated time the plots keep (s).
const KEPT_SECONDS: f64 = 30.0;

/// The most points a line draws: 30 s at 120 steps a second are 3 600
/// samples, and a plot some 450 pixels wide shows no more than this (a
/// line's points are what the plots cost a frame to lay out and draw).
const MOST_POINTS: usize = 300;

/// The colours of x, y and z.
const AXIS_COLOURS: [egui::Color32; 3] = [
    egui::Color32::from_rgb(230, 90, 80),
    egui::Color32::from_rgb(110, 200, 90),
    egui::Color32::from_rgb(90, 150, 240),
];

/// The body whose own motion is plotted.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Body {
    Ball(usize),
    Tumbler(usize),
}

/// A body's height above the floor (m), speed (m/s) and spin (rad/s).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Motion {
    pub height: f64,
    pub speed: f64,
    pub spin: f64,
}

impl Body {
    /// Its motion in `world`, if it is there (a ball caught is not).
    pub fn motion(self, world: &World) -> Option<Motion> {
        let floor = world.room().min.y;
        match self {
            Body::Ball(i) => {
                let balls = world.balls();
                (balls.alive().get(i) == Some(&true)).then(|| Motion {
                    height: balls.positions()[i].y - floor,
                    speed: balls.velocities()[i].length(),
                    spin: balls.spins()[i].length(),
                })
            }
            Body::Tumbler(t) => world.tumblers().get(t).map(|t| Motion {
                height: t.center_of_mass().y - floor,
                speed: t.linear_velocity().length(),
                spin: t.angular_velocity().length(),
            }),
        }
    }

    fn name(self) -> String {
        match self {
            Body::Ball(i) => format!("ball {i}"),
            Body::Tumbler(t) => format!("tumbler {t}"),
        }
    }
}

/// A sample, and the plotted body's motion then.
struct Kept {
    sample: Sample,
    body: Option<(Body, Motion)>,
}

/// The plots and the samples they show.
pub struct Plots {
    /// Whether its window shows.
    pub open: bool,
    /// Whether the sandbox panel shows them as its tab.
    pub docked: bool,
    kept: VecDeque<Kept>,
    /// The step the world stands at (the cursor).
    now: u64,
    /// The body whose motion is plotted: the one the hand holds, or as
    /// chosen in the plots.
    body: Option<Body>,
    /// The rolling pendulum's angular frequency (rad/s) for the tumblers.
    rocking: f64,
}

impl Default for Plots {
    fn default() -> Plots {
        Plots {
            open: false,
            docked: false,
            kept: VecDeque::new(),
            now: 0,
            body: Some(Body::Tumbler(0)),
            rocking: 0.0,
        }
    }
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
    /// Whether samples are wanted: the window or the panel's tab shows them.
    pub fn wanted(&self) -> bool {
        self.open || self.docked
    }

    /// Takes a sample of `world`, whose last step reported `events`, if it
    /// has stepped since the last one. A world that went back moves the
    /// cursor only; a step from there drops the samples after it. A body
    /// the hand holds becomes the plotted one.
    pub fn record(&mut self, world: &World, events: &[Event]) {
        let step = world.step_count();
        let (seen, went_back) = (self.now, step < self.now);
        self.now = step;
        self.rocking = world
            .tumbler_shape()
            .rocking_frequency(world.config().gravity);
        if let Some(i) = world.held_ball() {
            self.body = Some(Body::Ball(i));
        } else if let Some(t) = world.grabbed() {
            self.body = Some(Body::Tumbler(t));
        }
        if step == seen && !self.kept.is_empty() || went_back {
            return;
        }
        while self.kept.back().is_some_and(|k| k.sample.step >= step) {
            self.kept.pop_back();
        }
        let body = self
            .body
            .and_then(|body| body.motion(world).map(|motion| (body, motion)));
        self.kept.push_back(Kept {
            sample: Sample::of(world, events),
            body,
        });
        let newest = self.kept.back().map_or(0.0, |k| k.sample.time);
        while self
            .kept
            .front()
            .is_some_and(|k| k.sample.time < newest - KEPT_SECONDS)
        {
            self.kept.pop_front();
        }
    }

    /// The samples kept, oldest first.
    pub fn samples(&self) -> impl ExactSizeIterator<Item = &Sample> + DoubleEndedIterator {
        self.kept.iter().map(|k| &k.sample)
    }

    /// Writes the samples kept as `simulate --series` writes its lines.
    pub fn export(&self, path: &Path) -> Result<(), SeriesError> {
        let tumblers = self.samples().last().map_or(0, |s| s.tilts.len());
        let file = std::fs::File::create(path).map_err(|source| SeriesError {
            name: path.display().to_string(),
            source,
        })?;
        let mut writer = SeriesWriter::new(file, path.display().to_string(), tumblers)?;
        for sample in self.samples() {
            writer.sample(sample)?;
        }
        writer.finish().map(drop)
    }

    /// The last peak of tumbler `k`'s tilt among the samples kept: a
    /// sample above both neighbours, past the first.
    pub fn last_swing(&self, k: usize) -> Option<Swing> {
        let tilt = |s: &Sample| s.tilts.get(k).copied();
        let shown: Vec<&Sample> = self.samples().filter(|s| s.step <= self.now).collect();
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

    /// The balls' momentum as the impulses tell it: the first sample's,
    /// then every later step's impulses added on, afresh after a gap in
    /// the samples (the plots were closed); and the worst step's gap
    /// between the momentum's change and its impulses (N s). `None` where
    /// the engine counts no impulses.
    pub fn momentum_from_impulses(&self) -> Option<(Vec<(f64, DVec3)>, f64)> {
        let mut samples = self.samples();
        let first = samples.next()?;
        let (mut told, mut last) = (first.momentum, first);
        let mut worst = 0.0f64;
        let mut points = vec![(first.time, told)];
        for s in samples {
            let given = s.impulses?.total();
            if s.step == last.step + 1 {
                told += given;
                worst = worst.max((s.momentum - last.momentum - given).length());
            } else {
                told = s.momentum;
            }
            points.push((s.time, told));
            last = s;
        }
        Some((points, worst))
    }

    /// Draws the plots' window, if open; `Some(path)` when its export
    /// button was pressed, with the file it asks for in `folder`.
    pub fn show(&mut self, ctx: &egui::Context, folder: &Path) -> Option<PathBuf> {
        if !self.open {
            return None;
        }
        let mut export = None;
        egui::Window::new("plots (F4)")
            .default_width(460.0)
            .default_height(660.0)
            .show(ctx, |ui| {
                egui::ScrollArea::vertical()
                    .auto_shrink([false, true])
                    .show(ui, |ui| export = self.contents(ui, folder));
            });
        export
    }

    /// The plots, in the window or the panel's tab.
    pub fn contents(&mut self, ui: &mut egui::Ui, folder: &Path) -> Option<PathBuf> {
        let now = self
            .samples()
            .rev()
            .find(|s| s.step <= self.now)
            .map_or(0.0, |s| s.time);
        let cursor = || cursor(now);
        // Each section draws only while open: a plot's lines are what the
        // plots cost a frame.
        let section =
            |ui: &mut egui::Ui, title: &str, open: bool, add: &mut dyn FnMut(&mut egui::Ui)| {
                egui::CollapsingHeader::new(title)
                    .default_open(open)
                    .show(ui, |ui| add(ui));
            };
        section(ui, "Energy (J)", true, &mut |ui| {
            self.columns_plot(
                ui,
                "energy",
                100.0,
                Corner::RightTop,
                &[
                    ("translational", "kinetic_translational"),
                    ("rotational", "kinetic_rotational"),
                    ("potential", "potential"),
                    ("total", "total"),
                ],
                now,
            )
        });
        section(ui, "Momentum (kg m/s)", true, &mut |ui| {
            self.momentum_plot(ui, now)
        });
        section(ui, "What pushed the balls a step (N s)", false, &mut |ui| {
            self.impulses_plot(ui, now)
        });
        section(ui, "A step's contacts and impacts", false, &mut |ui| {
            self.columns_plot(
                ui,
                "counts",
                70.0,
                Corner::LeftTop,
                &[
                    ("contacts", "contacts"),
                    ("impacts", "impacts"),
                    ("on surfaces", "surface_impacts"),
                ],
                now,
            )
        });
        egui::CollapsingHeader::new("One body")
            .default_open(true)
            .show(ui, |ui| self.body_plots(ui, &cursor));
        ui.button("export CSV")
            .clicked()
            .then(|| folder.join(format!("rolypoly-series-{}.csv", self.now)))
    }

    /// The balls' momentum, beside it the same told by the impulses, and
    /// what pushed them a step.
    fn momentum_plot(&self, ui: &mut egui::Ui, now: f64) {
        ui.small("wide: the balls' own; thin: the first plus every step's impulses since");
        let told = self.momentum_from_impulses();
        Plot::new("momentum")
            .height(100.0)
            .legend(Legend::default().position(Corner::LeftTop))
            .show(ui, |plot| {
                for (axis, name) in ["x", "y", "z"].into_iter().enumerate() {
                    let colour = AXIS_COLOURS[axis];
                    let k = column("momentum_x") + axis;
                    // The thin line first: the legend takes its colour.
                    if let Some((points, _)) = &told {
                        let points: Vec<[f64; 2]> =
                            thinned(points.iter()).map(|(t, p)| [*t, p[axis]]).collect();
                        plot.line(Line::new(name, points).color(colour).width(1.0));
                    }
                    plot.line(
                        self.line(name, k)
                            .color(colour.gamma_multiply(0.45))
                            .width(4.0),
                    );
                }
                plot.vline(cursor(now));
            });
        match told {
            Some((_, worst)) => ui.small(format!(
                "a step's change less its impulses: at most {worst:.1e} N s over the plot"
            )),
            None => ui.small("this engine counts no impulses"),
        };
    }

    /// The lengths of what pushed the balls a step.
    fn impulses_plot(&self, ui: &mut egui::Ui, now: f64) {
        ui.small("each impulse's length");
        let length =
            |s: &Sample, of: ImpulseOf| s.impulses.map_or(f64::NAN, |given| of(&given).length());
        Plot::new("impulses")
            .height(70.0)
            .legend(Legend::default().position(Corner::LeftTop))
            .show(ui, |plot| {
                let lines: [(&str, ImpulseOf); 3] = [
                    ("walls and floor", |g| g.surfaces),
                    ("tumblers", |g| g.tumblers),
                    ("gravity", |g| g.gravity),
                ];
                for (name, of) in lines {
                    let points: Vec<[f64; 2]> = thinned(self.samples())
                        .map(|s| [s.time, length(s, of)])
                        .collect();
                    plot.line(Line::new(name, points));
                }
                plot.vline(cursor(now));
            });
    }

    /// The chosen body's height, speed and spin; for a tumbler its tilt
    /// beside the rolling pendulum's curve.
    fn body_plots(&mut self, ui: &mut egui::Ui, cursor: &dyn Fn() -> VLine) {
        let tumblers = self.samples().last().map_or(0, |s| s.tilts.len());
        ui.horizontal(|ui| {
            let shown = self.body.map_or("none".to_owned(), Body::name);
            egui::ComboBox::from_label("body plotted (or what the hand holds, G)")
                .selected_text(shown)
                .show_ui(ui, |ui| {
                    ui.selectable_value(&mut self.body, None, "none");
                    for t in 0..tumblers {
                        let name = Body::Tumbler(t).name();
                        ui.selectable_value(&mut self.body, Some(Body::Tumbler(t)), name);
                    }
                    if !matches!(self.body, Some(Body::Ball(_))) {
                        ui.selectable_value(&mut self.body, Some(Body::Ball(0)), "a ball");
                    }
                });
            if let Some(Body::Ball(i)) = &mut self.body {
                let label = ui.label("ball number");
                ui.add(egui::DragValue::new(i)).labelled_by(label.id);
            }
        });
        let Some(body) = self.body else {
            return;
        };
        let motion = |pick: fn(&Motion) -> f64| -> Vec<[f64; 2]> {
            let of_body = self.kept.iter().filter_map(|k| match k.body {
                Some((b, m)) if b == body => Some((k.sample.time, m)),
                _ => None,
            });
            let all: Vec<(f64, Motion)> = of_body.collect();
            thinned(all.iter()).map(|(t, m)| [*t, pick(m)]).collect()
        };
        Plot::new("body")
            .height(80.0)
            .legend(Legend::default().position(Corner::LeftTop))
            .show(ui, |plot: &mut PlotUi| {
                plot.line(Line::new("height (m)", motion(|m| m.height)));
                plot.line(Line::new("speed (m/s)", motion(|m| m.speed)));
                plot.line(Line::new("spin (rad/s)", motion(|m| m.spin)));
                plot.vline(cursor());
            });
        let Body::Tumbler(k) = body else {
            return;
        };
        if k >= tumblers {
            return;
        }
        ui.label(format!(
            "Tilt (rad) of tumbler {k}; rolling pendulum: T = {:.3} s",
            std::f64::consts::TAU / self.rocking
        ));
        Plot::new("tilt")
            .height(90.0)
            .legend(Legend::default().position(Corner::LeftTop))
            .show(ui, |plot| {
                plot.line(self.line("simulated", FIXED_COLUMNS.len() + k));
                if let Some(swing) = self.last_swing(k) {
                    let since: Vec<&Sample> = self
                        .samples()
                        .filter(|s| s.time >= swing.at - 0.5)
                        .collect();
                    let theory: Vec<[f64; 2]> = thinned(since.iter())
                        .map(|s| [s.time, self.theory(swing, s.time)])
                        .collect();
                    plot.line(Line::new("theory, from the last swing", theory));
                }
                plot.vline(cursor());
            });
    }

    /// A plot (`id`) of the series' `columns` (legend name, column), with
    /// the cursor at `now`.
    fn columns_plot(
        &self,
        ui: &mut egui::Ui,
        id: &'static str,
        height: f32,
        legend: Corner,
        columns: &[(&'static str, &str)],
        now: f64,
    ) {
        Plot::new(id)
            .height(height)
            .legend(Legend::default().position(legend))
            .show(ui, |plot| {
                for (name, name_of_column) in columns {
                    plot.line(self.line(name, column(name_of_column)));
                }
                plot.vline(cursor(now));
            });
    }

    /// Column `k` of the samples against their time.
    fn line(&self, name: &'static str, k: usize) -> Line<'static> {
        let points: Vec<[f64; 2]> = thinned(self.samples())
            .map(|s| [s.time, s.value(k)])
            .collect();
        Line::new(name, points)
    }
}

/// One kind of a step's impulses.
type ImpulseOf = fn(&BallImpulses) -> DVec3;

/// The line that marks the moment shown (unnamed: not in the legend).
fn cursor(now: f64) -> VLine {
    VLine::new("", now).color(egui::Color32::GRAY)
}

/// The series' column named `name`.
fn column(name: &str) -> usize {
    FIXED_COLUMNS
        .iter()
        .position(|c| *c == name)
        .expect("a series column")
}

/// Every so many of `items`, the last always, so that a line draws at
/// most [`MOST_POINTS`] or so.
fn thinned<I>(items: I) -> impl Iterator<Item = I::Item>
where
    I: ExactSizeIterator,
{
    let n = items.len();
    let every = n.div_ceil(MOST_POINTS).max(1);
    items
        .enumerate()
        .filter(move |(k, _)| k % every == 0 || k + 1 == n)
        .map(|(_, item)| item)
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
    fn the_momentum_told_by_the_impulses_is_the_balls_own() {
        for seed in [3, 9] {
            let mut world = World::new(WorldConfig::default(), seed).unwrap();
            let mut plots = Plots::default();
            for _ in 0..400 {
                world.step();
                plots.record(&world, &[]);
            }
            let (told, worst) = plots.momentum_from_impulses().unwrap();
            let last = told.last().unwrap().1;
            let balls = world.balls().momentum();
            // Landing balls: the floor and gravity move it by newtons a step.
            let scale: f64 = (0..world.balls().len())
                .map(|i| world.balls().masses()[i] * 5.0)
                .sum();
            assert!(
                (last - balls).length() <= 1e-9 * scale,
                "seed {seed}: {last} {balls}"
            );
            assert!(worst <= 1e-12 * scale, "seed {seed}: {worst}");
        }
    }

    #[test]
    fn the_plotted_body_is_what_the_hand_holds_or_the_chosen_one() {
        let mut world = World::new(WorldConfig::default(), 4).unwrap();
        let mut plots = Plots::default();
        world.step();
        plots.record(&world, &[]);
        let kept = plots.kept.back().unwrap();
        let (body, motion) = kept.body.unwrap();
        assert_eq!(body, Body::Tumbler(0));
        let t = &world.tumblers()[0];
        assert_eq!(motion.speed, t.linear_velocity().length());
        plots.body = Some(Body::Ball(7));
        world.step();
        plots.record(&world, &[]);
        let (body, motion) = plots.kept.back().unwrap().body.unwrap();
        assert_eq!(body, Body::Ball(7));
        let floor = world.room().min.y;
        assert_eq!(motion.height, world.balls().positions()[7].y - floor);
        assert_eq!(motion.spin, world.balls().spins()[7].length());
    }

    #[test]
    fn a_long_run_draws_at_most_so_many_points_a_line() {
        let items: Vec<usize> = (0..3601).collect();
        let kept: Vec<usize> = thinned(items.iter()).copied().collect();
        assert!(kept.len() <= MOST_POINTS + 1, "{}", kept.len());
        assert_eq!(kept.first(), Some(&0));
        assert_eq!(kept.last(), Some(&3600));
        let few: Vec<usize> = thinned(items[..10].iter()).copied().collect();
        assert_eq!(few, items[..10]);
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
