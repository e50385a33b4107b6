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

mod envelope;

use std::collections::VecDeque;
use std::path::{Path, PathBuf};

use envelope::Envelope;

use egui_plot::{Corner, Legend, Line, Plot, VLine};
use glam::DVec3;
use rolypoly_core::series::{FIXED_COLUMNS, Sample, SeriesError, SeriesWriter};
use rolypoly_physics::{BallImpulses, Event, World};

/// How much simulated time the plots keep (s).
const KEPT_SECONDS: f64 = 30.0;

/// The most points a line draws, about: 30 s at 120 steps a second are
/// 3 600 samples, and a plot some 450 pixels wide needs no more than a
/// point every three pixels (a line's points are what the plots cost a
/// frame to lay out and tessellate). Each slice of `KEPT_SECONDS` over half
/// this draws its lowest and highest point.
const MOST_POINTS: usize = 150;

/// The width of a line's slices (s): see [`MOST_POINTS`] (0.4 s).
const SLICE_SECONDS: f64 = KEPT_SECONDS / (MOST_POINTS / 2) as f64;

/// The energy plot's lines: their names, and the series' columns.
const ENERGY: [(&str, &str); 4] = [
    ("translational", "kinetic_translational"),
    ("rotational", "kinetic_rotational"),
    ("potential", "potential"),
    ("total", "total"),
];

/// The counts plot's lines: their names, and the series' columns.
const COUNTS: [(&str, &str); 3] = [
    ("contacts", "contacts"),
    ("impacts", "impacts"),
    ("on surfaces", "surface_impacts"),
];

/// The impulses plot's lines: their names, and which impulses.
const IMPULSES: [(&str, ImpulseOf); 3] = [
    ("walls and floor", |g| g.surfaces),
    ("tumblers", |g| g.tumblers),
    ("gravity", |g| g.gravity),
];

/// The body plot's lines: their names, and what of the motion.
const MOTION: [(&str, MotionOf); 3] = [
    ("height (m)", |m| m.height),
    ("speed (m/s)", |m| m.speed),
    ("spin (rad/s)", |m| m.spin),
];

/// A sample is a pass over the balls: up to this many the plots take one
/// every step, above it every n-th step, n the balls over this rounded up,
/// so that sampling costs a step at most what this many balls' sampling
/// does (at 10 000 balls every fifth step, the steps `simulate --series
/// --series-every 5` writes).
const BALLS_SAMPLED_EVERY_STEP: usize = 2_000;

/// The colours of x, y and z.
const AXIS_COLOURS: [egui::Color32; 3] = [
    egui::Color32::from_rgb(230, 90, 80),
    egui::Color32::from_rgb(110, 200, 90),
    egui::Color32::from_rgb(90, 150, 240),
];

/// The body whose own motion is plotted.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Body {
    /// The ball of this number.
    Ball(usize),
    /// The tumbler of this number.
    Tumbler(usize),
}

/// A body's height above the floor (m), speed (m/s) and spin (rad/s).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Motion {
    /// Its centre's (a tumbler's: its centre of mass's) height (m).
    pub height: f64,
    /// Its speed (m/s).
    pub speed: f64,
    /// Its angular speed (rad/s).
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
    /// The balls' momentum as the impulses tell it: the first sample's
    /// (afresh after a step not seen: the plots were closed, the world went
    /// back), then every later step's impulses added on; `None` where the
    /// engine counts no impulses.
    told: Option<DVec3>,
    /// The momentum's change since the sample before less the impulses of
    /// the steps between (N s); 0 where it is told afresh.
    gap: f64,
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
    /// The impulses of the steps seen since the last sample, if every one
    /// was.
    since: Option<BallImpulses>,
    /// The lines drawn, kept up with the samples.
    lines: Lines,
}

/// Every line the plots draw, as the envelope of the samples kept.
struct Lines {
    /// The body whose motion they hold.
    body: Option<Body>,
    energy: [Envelope; 4],
    momentum: [Envelope; 3],
    told: [Envelope; 3],
    impulses: [Envelope; 3],
    counts: [Envelope; 3],
    motion: [Envelope; 3],
    tilts: Vec<Envelope>,
}

impl Lines {
    /// No lines, the body's motion to be of `body`.
    fn new(body: Option<Body>) -> Lines {
        let empty = || Envelope::new(SLICE_SECONDS);
        Lines {
            body,
            energy: std::array::from_fn(|_| empty()),
            momentum: std::array::from_fn(|_| empty()),
            told: std::array::from_fn(|_| empty()),
            impulses: std::array::from_fn(|_| empty()),
            counts: std::array::from_fn(|_| empty()),
            motion: std::array::from_fn(|_| empty()),
            tilts: Vec::new(),
        }
    }

    /// The lines through `kept`, the motion of `body`.
    fn through<'k>(kept: impl Iterator<Item = &'k Kept>, body: Option<Body>) -> Lines {
        let mut lines = Lines::new(body);
        for k in kept {
            lines.push(k);
        }
        lines
    }

    /// Adds a sample later than all before.
    fn push(&mut self, k: &Kept) {
        let (s, t) = (&k.sample, k.sample.time);
        for (line, (_, name)) in self.energy.iter_mut().zip(ENERGY) {
            line.push(t, s.value(column(name)));
        }
        for (line, (_, name)) in self.counts.iter_mut().zip(COUNTS) {
            line.push(t, s.value(column(name)));
        }
        for axis in 0..3 {
            self.momentum[axis].push(t, s.momentum[axis]);
            self.told[axis].push(t, k.told.map_or(f64::NAN, |p| p[axis]));
        }
        for (line, (_, of)) in self.impulses.iter_mut().zip(IMPULSES) {
            line.push(t, s.impulses.map_or(f64::NAN, |given| of(&given).length()));
        }
        let motion = k.body.filter(|(b, _)| Some(*b) == self.body);
        for (line, (_, of)) in self.motion.iter_mut().zip(MOTION) {
            line.push(t, motion.map_or(f64::NAN, |(_, m)| of(&m)));
        }
        self.tilts
            .resize_with(s.tilts.len(), || Envelope::new(SLICE_SECONDS));
        for (line, tilt) in self.tilts.iter_mut().zip(&s.tilts) {
            line.push(t, *tilt);
        }
    }

    /// Forgets the slices that end before `time`.
    fn forget_before(&mut self, time: f64) {
        let Lines {
            energy,
            momentum,
            told,
            impulses,
            counts,
            motion,
            tilts,
            ..
        } = self;
        let fixed: [&mut [Envelope]; 6] = [energy, momentum, told, impulses, counts, motion];
        for line in fixed.into_iter().flatten().chain(tilts) {
            line.forget_before(time);
        }
    }
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
            since: None,
            lines: Lines::new(Some(Body::Tumbler(0))),
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

    /// Sees `world`, whose last step reported `events`, and takes a sample
    /// of it if it has stepped since the last one and the step is one
    /// sampled (every step up to 2 000 balls, fewer above); the steps
    /// between add their impulses to the next sample's. A world that went
    /// back moves the cursor only; a step from there drops the samples
    /// after it. A body the hand holds becomes the plotted one.
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
        if went_back {
            self.since = None;
        }
        if step == seen && !self.kept.is_empty() || went_back {
            return;
        }
        let before = self.kept.len();
        while self.kept.back().is_some_and(|k| k.sample.step >= step) {
            self.kept.pop_back();
        }
        if self.kept.len() < before {
            self.redraw_lines();
        }
        self.since = self.since.filter(|_| step == seen + 1).map(|mut since| {
            since += world.ball_impulses();
            since
        });
        let every = world
            .balls()
            .len()
            .div_ceil(BALLS_SAMPLED_EVERY_STEP)
            .max(1) as u64;
        if !step.is_multiple_of(every) && !self.kept.is_empty() {
            return;
        }
        let body = self
            .body
            .and_then(|body| body.motion(world).map(|motion| (body, motion)));
        let sample = Sample::of(world, events);
        let last = self.kept.back();
        let (told, gap) = match (
            sample.impulses,
            self.since.take(),
            last.and_then(|k| k.told),
        ) {
            (None, ..) => (None, 0.0),
            (Some(_), Some(given), Some(told)) => {
                let given = given.total();
                let change = sample.momentum - last.map_or(DVec3::ZERO, |k| k.sample.momentum);
                (Some(told + given), (change - given).length())
            }
            (Some(_), ..) => (Some(sample.momentum), 0.0),
        };
        let kept = Kept {
            sample,
            body,
            told,
            gap,
        };
        if self.lines.body != self.body {
            self.redraw_lines();
        }
        self.lines.push(&kept);
        self.kept.push_back(kept);
        self.since = Some(BallImpulses::default());
        let newest = self.kept.back().map_or(0.0, |k| k.sample.time);
        while self
            .kept
            .front()
            .is_some_and(|k| k.sample.time < newest - KEPT_SECONDS)
        {
            self.kept.pop_front();
        }
        self.lines.forget_before(newest - KEPT_SECONDS);
    }

    /// Draws the lines afresh through the samples kept: after some were
    /// dropped, or for another body.
    fn redraw_lines(&mut self) {
        self.lines = Lines::through(self.kept.iter(), self.body);
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
        let shown = self
            .kept
            .partition_point(|kept| kept.sample.step <= self.now);
        let tilt = |i: usize| self.kept[i].sample.tilts.get(k).copied();
        (1..shown.saturating_sub(1)).rev().find_map(|i| {
            let (a, b, c) = (tilt(i - 1)?, tilt(i)?, tilt(i + 1)?);
            (b > a && b >= c && b > 1e-4).then_some(Swing {
                at: self.kept[i].sample.time,
                amplitude: b,
            })
        })
    }

    /// The rolling pendulum's tilt at `t` through `swing`.
    pub fn theory(&self, swing: Swing, t: f64) -> f64 {
        (swing.amplitude * (self.rocking * (t - swing.at)).cos()).abs()
    }

    /// The balls' momentum as the impulses tell it at each sample kept: the
    /// first sample's (afresh after a step not seen), then every later
    /// step's impulses added on; and the worst gap between the momentum's change
    /// from one sample to the next and the impulses of the steps between
    /// (N s). `None` where the engine counts no impulses.
    pub fn momentum_from_impulses(&self) -> Option<(impl Iterator<Item = (f64, DVec3)> + '_, f64)> {
        self.kept.back()?.told?;
        let worst = self.kept.iter().map(|k| k.gap).fold(0.0, f64::max);
        let told = self
            .kept
            .iter()
            .map(|k| (k.sample.time, k.told.unwrap_or(DVec3::NAN)));
        Some((told, worst))
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
        // Each section draws only while open: a plot's lines are what the
        // plots cost a frame.
        let section =
            |ui: &mut egui::Ui, title: &str, open: bool, add: &mut dyn FnMut(&mut egui::Ui)| {
                egui::CollapsingHeader::new(title)
                    .default_open(open)
                    .show(ui, |ui| add(ui));
            };
        let lines = &self.lines;
        section(ui, "Energy (J)", true, &mut |ui| {
            let names = ENERGY.map(|(name, _)| name);
            lines_plot(
                ui,
                "energy",
                100.0,
                Corner::RightTop,
                &names,
                &lines.energy,
                now,
            )
        });
        section(ui, "Momentum (kg m/s)", true, &mut |ui| {
            self.momentum_plot(ui, now)
        });
        section(ui, "What pushed the balls a step (N s)", false, &mut |ui| {
            ui.small("each impulse's length");
            let names = IMPULSES.map(|(name, _)| name);
            lines_plot(
                ui,
                "impulses",
                70.0,
                Corner::LeftTop,
                &names,
                &lines.impulses,
                now,
            )
        });
        section(ui, "A step's contacts and impacts", false, &mut |ui| {
            let names = COUNTS.map(|(name, _)| name);
            lines_plot(
                ui,
                "counts",
                70.0,
                Corner::LeftTop,
                &names,
                &lines.counts,
                now,
            )
        });
        egui::CollapsingHeader::new("One body")
            .default_open(true)
            .show(ui, |ui| self.body_plots(ui, now));
        ui.button("export CSV")
            .clicked()
            .then(|| folder.join(format!("rolypoly-series-{}.csv", self.now)))
    }

    /// The balls' momentum, beside it the same told by the impulses.
    fn momentum_plot(&self, ui: &mut egui::Ui, now: f64) {
        ui.small("wide: the balls' own; thin: the first plus every step's impulses since");
        let told = self.momentum_from_impulses();
        Plot::new("momentum")
            .height(100.0)
            .legend(Legend::default().position(Corner::LeftTop))
            .show(ui, |plot| {
                for (axis, name) in ["x", "y", "z"].into_iter().enumerate() {
                    let colour = AXIS_COLOURS[axis];
                    // The legend names the thin lines, in their own colour;
                    // an unnamed line is not in it.
                    let wide = if told.is_some() { "" } else { name };
                    plot.line(
                        Line::new(wide, self.lines.momentum[axis].points())
                            .color(colour.gamma_multiply(0.45))
                            .width(4.0),
                    );
                    if told.is_some() {
                        let points = self.lines.told[axis].points();
                        plot.line(Line::new(name, points).color(colour).width(1.0));
                    }
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

    /// The chosen body's height, speed and spin; for a tumbler its tilt
    /// beside the rolling pendulum's curve.
    fn body_plots(&mut self, ui: &mut egui::Ui, now: f64) {
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
        if self.lines.body != self.body {
            self.redraw_lines();
        }
        let names = MOTION.map(|(name, _)| name);
        lines_plot(
            ui,
            "body",
            80.0,
            Corner::LeftTop,
            &names,
            &self.lines.motion,
            now,
        );
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
                // From just before the last peak on, a swing or so, every
                // sample is drawn, the simulation's beside the theory's.
                let swing = self.last_swing(k);
                let since = swing.map_or(f64::INFINITY, |swing| swing.at - 0.5);
                let from = self.kept.partition_point(|kept| kept.sample.time < since);
                let recent = self.kept.range(from..);
                if let Some(tilts) = self.lines.tilts.get(k) {
                    let mut simulated = tilts.points_before(since);
                    simulated.extend(recent.clone().map(|kept| {
                        let tilt = kept.sample.tilts.get(k).copied();
                        [kept.sample.time, tilt.unwrap_or(f64::NAN)]
                    }));
                    plot.line(Line::new("simulated", simulated));
                }
                if let Some(swing) = swing {
                    let theory: Vec<[f64; 2]> = recent
                        .map(|kept| [kept.sample.time, self.theory(swing, kept.sample.time)])
                        .collect();
                    plot.line(Line::new("theory, from the last swing", theory));
                }
                plot.vline(cursor(now));
            });
    }
}

/// A plot (`id`) of `lines` named `names`, with the cursor at `now`.
fn lines_plot(
    ui: &mut egui::Ui,
    id: &'static str,
    height: f32,
    legend: Corner,
    names: &[&'static str],
    lines: &[Envelope],
    now: f64,
) {
    Plot::new(id)
        .height(height)
        .legend(Legend::default().position(legend))
        .show(ui, |plot| {
            for (name, envelope) in names.iter().zip(lines) {
                plot.line(Line::new(*name, envelope.points()));
            }
            plot.vline(cursor(now));
        });
}

/// One kind of a step's impulses.
type ImpulseOf = fn(&BallImpulses) -> DVec3;

/// One part of a body's motion.
type MotionOf = fn(&Motion) -> f64;

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
    fn the_lines_drawn_are_the_samples_and_follow_going_back_and_the_body_chosen() {
        for seed in [2, 8] {
            let mut world = World::new(WorldConfig::default(), seed).unwrap();
            let mut back = World::new(WorldConfig::default(), seed).unwrap();
            let mut plots = Plots::default();
            for k in 0..600 {
                world.step();
                plots.record(&world, &[]);
                if k < 300 {
                    back.step();
                }
            }
            let is_a_sample = |plots: &Plots, [t, v]: [f64; 2], k: usize| {
                plots.samples().any(|s| s.time == t && s.value(k) == v)
            };
            let total = column("total");
            let points = plots.lines.energy[3].points();
            assert!(points.len() <= MOST_POINTS + 3, "{}", points.len());
            assert!(points.iter().all(|p| is_a_sample(&plots, *p, total)));
            // The highest total energy kept is drawn.
            let top = plots.samples().map(|s| s.total()).fold(f64::MIN, f64::max);
            assert!(points.iter().any(|p| p[1] == top));
            // Back to step 300 and on one step: nothing drawn after it.
            plots.record(&back, &[]);
            back.step();
            plots.record(&back, &[]);
            let points = plots.lines.energy[3].points();
            assert_eq!(points.last().unwrap()[0], back.time());
            assert!(points.iter().all(|p| is_a_sample(&plots, *p, total)));
            // Another body: its motion only, from the samples taken since.
            plots.body = Some(Body::Ball(3));
            for _ in 0..10 {
                back.step();
                plots.record(&back, &[]);
            }
            let heights = plots.lines.motion[0].points();
            let floor = back.room().min.y;
            assert_eq!(
                heights.last().unwrap()[1],
                back.balls().positions()[3].y - floor
            );
            let finite = heights.iter().filter(|p| p[1].is_finite()).count();
            assert!((1..=20).contains(&finite), "{finite}");
        }
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
    fn a_crowded_room_is_sampled_every_few_steps_and_its_impulses_still_add_up() {
        for (seed, balls) in [(2, 2_500), (5, 4_500)] {
            let mut config = WorldConfig::default();
            config.balls.count = balls;
            config.room.size = glam::DVec3::new(16.0, 6.0, 16.0);
            let mut world = World::new(config, seed).unwrap();
            let mut plots = Plots::default();
            for _ in 0..60 {
                world.step();
                plots.record(&world, &[]);
            }
            let every = balls.div_ceil(BALLS_SAMPLED_EVERY_STEP) as u64;
            assert!(every > 1);
            let steps: Vec<u64> = plots.samples().map(|s| s.step).collect();
            let expected: Vec<u64> = std::iter::once(1)
                .chain((every..=60).step_by(every as usize))
                .collect();
            assert_eq!(steps, expected, "{balls} balls");
            // Across the steps not sampled their impulses still tell the
            // momentum's change.
            let (told, worst) = plots.momentum_from_impulses().unwrap();
            let scale: f64 = world.balls().masses().iter().map(|m| m * 5.0).sum();
            let last = told.last().unwrap().1;
            let own = world.balls().momentum();
            assert!((last - own).length() <= 1e-9 * scale, "{last} {own}");
            assert!(worst <= 1e-12 * scale, "{balls} balls: {worst}");
            // Without the steps between the balance would not hold.
            let only_sampled: f64 = plots
                .samples()
                .collect::<Vec<_>>()
                .windows(2)
                .map(|w| (w[1].momentum - w[0].momentum - w[1].impulses.unwrap().total()).length())
                .fold(0.0, f64::max);
            assert!(
                only_sampled > 1e3 * worst.max(1e-15 * scale),
                "{only_sampled} {worst}"
            );
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
