//! A run's totals step by step, as a table: the energy in its parts, the
//! balls' linear momentum beside the impulses that changed it, how many
//! contacts and impacts the step had, and each tumbler's tilt. A few numbers a step where a trace writes every body:
//! what a plot beside its theory needs (`simulate --series`, Python's
//! `World.series`).
//!
//! The file is CSV with a header line of [`columns`]; numbers are written
//! as the shortest text that reads back to the same bits, so two runs'
//! files compare byte for byte.

use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::Path;

use glam::DVec3;
use rolypoly_physics::{BallImpulses, Event, EventKind, World};

/// The columns every series has, in order, before one `tumbler_K_tilt` a
/// tumbler. Units: s, J, kg m/s (N s for the impulses), counts.
pub const FIXED_COLUMNS: [&str; 23] = [
    "step",
    "time",
    "kinetic_translational",
    "kinetic_rotational",
    "potential",
    "total",
    "momentum_x",
    "momentum_y",
    "momentum_z",
    "surface_impulse_x",
    "surface_impulse_y",
    "surface_impulse_z",
    "tumbler_impulse_x",
    "tumbler_impulse_y",
    "tumbler_impulse_z",
    "guard_impulse_x",
    "guard_impulse_y",
    "guard_impulse_z",
    "gravity_impulse_y",
    "poured_momentum_y",
    "contacts",
    "impacts",
    "surface_impacts",
];

/// Every column of a series of a world with `tumblers` tumblers: the fixed
/// ones, then `tumbler_0_tilt` (rad, from upright) onwards.
pub fn columns(tumblers: usize) -> Vec<String> {
    FIXED_COLUMNS
        .iter()
        .map(|c| (*c).to_owned())
        .chain((0..tumblers).map(|k| format!("tumbler_{k}_tilt")))
        .collect()
}

/// The totals of a world after one step.
#[derive(Clone, Debug, PartialEq)]
pub struct Sample {
    /// Steps taken.
    pub step: u64,
    /// Simulated time (s).
    pub time: f64,
    /// Energy of motion along paths: the balls', the tumblers' centres of
    /// mass and the fireball's (J).
    pub translational: f64,
    /// Energy of turning: the balls' spin and the tumblers' rotation about
    /// their centres of mass (J).
    pub rotational: f64,
    /// Energy of height above the floor, balls and tumblers (J).
    pub potential: f64,
    /// Linear momentum of the balls (kg m/s).
    pub momentum: DVec3,
    /// What changed it in the step, besides gravity's `M g dt` and the
    /// balls' impacts on one another (see [`BallImpulses`]); `None` where
    /// the engine does not count them (the GPU engine), written as `NaN`.
    pub impulses: Option<BallImpulses>,
    /// Contacts the step's solver worked on: ball pairs, balls on walls
    /// and on tumblers (its rows, as the profiler counts them).
    pub contacts: usize,
    /// Impacts the step reported (its events).
    pub impacts: usize,
    /// Those of them on the room's walls, floor and ceiling.
    pub surface_impacts: usize,
    /// Each tumbler's tilt from upright (rad).
    pub tilts: Vec<f64>,
}

impl Sample {
    /// The totals of `world` as it stands, whose last step reported
    /// `events`.
    pub fn of(world: &World, events: &[Event]) -> Sample {
        let g = world.config().gravity;
        let floor = world.room().min.y;
        let balls = world.balls();
        let mut sample = Sample {
            step: world.step_count(),
            time: world.time(),
            translational: 0.0,
            rotational: 0.0,
            potential: 0.0,
            momentum: balls.momentum(),
            impulses: Some(world.ball_impulses()),
            contacts: {
                let times = world.step_times();
                times.pairs + times.other_contacts
            },
            impacts: events.len(),
            surface_impacts: events
                .iter()
                .filter(|e| {
                    matches!(
                        e.kind,
                        EventKind::BallSurface { .. } | EventKind::FireballSurface { .. }
                    )
                })
                .count(),
            tilts: world.tumblers().iter().map(|t| t.tilt()).collect(),
        };
        for i in (0..balls.len()).filter(|&i| balls.alive()[i]) {
            let (m, v) = (balls.masses()[i], balls.velocities()[i]);
            sample.translational += 0.5 * m * v.length_squared();
            sample.rotational += 0.5 * balls.inertia(i) * balls.spins()[i].length_squared();
            sample.potential += m * g * (balls.positions()[i].y - floor);
        }
        let shape = world.tumbler_shape();
        for t in world.tumblers() {
            let v = t.linear_velocity();
            let moving = 0.5 * shape.mass * v.length_squared();
            sample.translational += moving;
            sample.rotational += t.kinetic_energy(shape) - moving;
            sample.potential += shape.mass * g * (t.center_of_mass().y - floor);
        }
        if let Some(f) = world.fireball() {
            sample.translational += f.kinetic_energy();
        }
        sample
    }

    /// Kinetic and potential (J).
    pub fn total(&self) -> f64 {
        self.translational + self.rotational + self.potential
    }

    /// The sample as one whose engine does not count the impulses.
    pub fn without_impulses(self) -> Sample {
        Sample {
            impulses: None,
            ..self
        }
    }

    /// The value of column `k` of [`columns`] (`NaN` past them).
    pub fn value(&self, k: usize) -> f64 {
        let impulse = |of: fn(&BallImpulses) -> DVec3, axis: usize| {
            self.impulses.map_or(f64::NAN, |given| of(&given)[axis])
        };
        match k {
            0 => self.step as f64,
            1 => self.time,
            2 => self.translational,
            3 => self.rotational,
            4 => self.potential,
            5 => self.total(),
            6..=8 => self.momentum[k - 6],
            9..=11 => impulse(|g| g.surfaces, k - 9),
            12..=14 => impulse(|g| g.tumblers, k - 12),
            15..=17 => impulse(|g| g.guard, k - 15),
            18 => impulse(|g| g.gravity, 1),
            19 => impulse(|g| g.poured, 1),
            20 => self.contacts as f64,
            21 => self.impacts as f64,
            22 => self.surface_impacts as f64,
            _ => self
                .tilts
                .get(k - FIXED_COLUMNS.len())
                .copied()
                .unwrap_or(f64::NAN),
        }
    }

    /// The sample's values in the order of [`columns`].
    pub fn values(&self) -> Vec<f64> {
        (0..FIXED_COLUMNS.len() + self.tilts.len())
            .map(|k| self.value(k))
            .collect()
    }

    /// One CSV line, without its line end. A whole number (a step, a
    /// count) is written without a fraction: `10`, not `10.0`.
    pub fn csv_line(&self) -> String {
        let values: Vec<String> = self.values().iter().map(f64::to_string).collect();
        values.join(",")
    }
}

/// A series could not be written; names the file.
#[derive(Debug, thiserror::Error)]
#[error("cannot write the series to `{name}`")]
pub struct SeriesError {
    /// The file.
    pub name: String,
    /// Why.
    #[source]
    pub source: io::Error,
}

/// Writes a series as CSV: the header, then a line a sample.
pub struct SeriesWriter<W: Write> {
    out: BufWriter<W>,
    name: String,
}

/// Opens `path` for a series of a world with `tumblers` tumblers and
/// writes its header. The folder must exist.
pub fn create(path: &Path, tumblers: usize) -> Result<SeriesWriter<File>, SeriesError> {
    let name = path.display().to_string();
    let file = File::create(path).map_err(|source| SeriesError {
        name: name.clone(),
        source,
    })?;
    SeriesWriter::new(file, name, tumblers)
}

impl<W: Write> SeriesWriter<W> {
    /// A writer into `out`, named `name` in errors, its header written.
    pub fn new(out: W, name: String, tumblers: usize) -> Result<SeriesWriter<W>, SeriesError> {
        let mut writer = SeriesWriter {
            out: BufWriter::new(out),
            name,
        };
        let header = columns(tumblers).join(",");
        writer.line(&header)?;
        Ok(writer)
    }

    /// Writes one sample's line.
    pub fn sample(&mut self, sample: &Sample) -> Result<(), SeriesError> {
        self.line(&sample.csv_line())
    }

    /// Flushes what is buffered.
    pub fn finish(mut self) -> Result<W, SeriesError> {
        self.out.flush().map_err(|source| self.error(source))?;
        let name = self.name;
        self.out.into_inner().map_err(|e| SeriesError {
            name,
            source: e.into_error(),
        })
    }

    fn line(&mut self, line: &str) -> Result<(), SeriesError> {
        writeln!(self.out, "{line}").map_err(|source| self.error(source))
    }

    fn error(&self, source: io::Error) -> SeriesError {
        SeriesError {
            name: self.name.clone(),
            source,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rolypoly_physics::WorldConfig;

    #[test]
    fn a_line_has_a_value_for_every_column_and_reads_back_to_its_bits() {
        let mut world = World::new(WorldConfig::default(), 3).unwrap();
        world.step();
        let mut events = Vec::new();
        world.take_events(&mut events);
        let sample = Sample::of(&world, &events);
        let line = sample.csv_line();
        let read: Vec<f64> = line.split(',').map(|v| v.parse().unwrap()).collect();
        assert_eq!(read.len(), columns(world.tumblers().len()).len());
        assert_eq!(read, sample.values());
    }

    #[test]
    fn each_value_sits_under_its_columns_name() {
        let mut world = World::new(WorldConfig::default(), 4).unwrap();
        for _ in 0..20 {
            world.step();
        }
        let sample = Sample::of(&world, &[]);
        let names = columns(world.tumblers().len());
        let at = |name: &str| sample.value(names.iter().position(|c| c == name).unwrap());
        let given = world.ball_impulses();
        assert_eq!(at("momentum_y"), world.balls().momentum().y);
        assert_eq!(at("surface_impulse_x"), given.surfaces.x);
        assert_eq!(at("tumbler_impulse_z"), given.tumblers.z);
        assert_eq!(at("guard_impulse_y"), given.guard.y);
        assert_eq!(at("gravity_impulse_y"), given.gravity.y);
        assert_eq!(at("poured_momentum_y"), given.poured.y);
        assert_eq!(at("surface_impacts"), 0.0);
        assert_eq!(at("tumbler_4_tilt"), world.tumblers()[4].tilt());
        assert!(sample.clone().without_impulses().value(10).is_nan());
    }

    #[test]
    fn the_parts_add_up_to_the_worlds_own_energy() {
        for seed in [1, 2, 3] {
            let mut world = World::new(WorldConfig::default(), seed).unwrap();
            world.launch_fireball(None);
            for _ in 0..50 {
                world.step();
            }
            let sample = Sample::of(&world, &[]);
            assert_eq!(sample.tilts.len(), 5);
            let energy = world.energy();
            let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b.abs().max(1.0);
            assert!(close(sample.total(), energy.total()), "seed {seed}");
            assert!(close(
                sample.translational + sample.rotational,
                energy.kinetic
            ));
            assert!(close(sample.potential, energy.potential));
        }
    }

    #[test]
    fn a_pits_totals_are_its_balls_own() {
        let mut config = WorldConfig::default();
        config.balls.count = 2000;
        config.room.size = glam::DVec3::new(4.0, 3.0, 4.0);
        config.tumblers.placements.clear();
        for seed in [5, 6] {
            let mut world = World::new(config.clone(), seed).unwrap();
            for step in 0..40 {
                world.step();
                if step % 10 != 9 {
                    continue;
                }
                let sample = Sample::of(&world, &[]);
                let balls = world.balls();
                let mut momentum = glam::DVec3::ZERO;
                for i in 0..balls.len() {
                    momentum += balls.masses()[i] * balls.velocities()[i];
                }
                let energy = world.energy();
                let close = |a: f64, b: f64, scale: f64| (a - b).abs() <= 1e-12 * scale;
                assert!(close(sample.total(), energy.total(), energy.total()));
                let scale =
                    balls.masses()[0] * balls.velocities().iter().map(|v| v.length()).sum::<f64>();
                assert!(close(sample.momentum.x, momentum.x, scale));
                assert!(close(sample.momentum.y, momentum.y, scale));
                assert!(close(sample.momentum.z, momentum.z, scale));
                assert!(sample.contacts > 0 || step < 20);
                assert!(sample.tilts.is_empty());
            }
        }
    }
}
