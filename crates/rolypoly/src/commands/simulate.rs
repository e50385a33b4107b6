//! `rolypoly simulate` (A3): step a world (and its effects, as every
//! run steps them) a fixed number of steps without a window, optionally writing a trace, and summarise the result.

use std::fmt;
use std::io::{self, Write};
use std::time::{Duration, Instant};

use anyhow::Context;
use rolypoly_gpu::Compute;
use rolypoly_physics::{Event, EventKind, World};

use crate::cli::{SimulateArgs, steps_for};
use crate::engine::Engine;
use crate::series::{self, Sample, SeriesWriter};
use crate::simulation::Simulation;
use crate::trace::{self, TraceWriter, event_kind_name};
use std::fs::File;

/// `rolypoly simulate` on `sim`: its steps, a trace if asked for, and
/// the summary. With `gpu`, its balls are stepped by the GPU engine on the
/// best adapter there is.
pub fn simulate(
    mut sim: Simulation,
    scene_name: &str,
    args: &SimulateArgs,
    seed: u64,
    dt: f64,
    gpu: bool,
) -> anyhow::Result<()> {
    // The trace's scene line is written while the world still holds its
    // balls as the scene made them, on either engine: the GPU engine keeps
    // them in single precision.
    let mut writer = args.trace.as_deref().map(trace::create).transpose()?;
    // The series file is opened before the run, so that a folder that is
    // not there is named before any time is spent.
    let tumblers = sim.world.tumblers().len();
    let mut series = args
        .series
        .as_deref()
        .map(|path| series::create(path, tumblers))
        .transpose()?;
    if let Some(writer) = writer.as_mut() {
        writer.scene(&sim.world, seed)?;
    }
    if gpu {
        sim.move_balls_to_compute(&Compute::headless()?)?;
    }
    let steps = match (args.length.steps, args.length.seconds) {
        (Some(steps), _) => steps,
        (None, Some(seconds)) => steps_for(seconds, dt),
        // clap requires one of the two.
        (None, None) => anyhow::bail!("give the length of the run with --steps or --seconds"),
    };
    let options = Options {
        steps,
        fireball: args.fireball,
        seed,
        every: args.every,
        series_every: args.series_every,
    };
    match (&args.trace, writer) {
        (Some(path), Some(mut writer)) => {
            let summary = run(
                &mut sim,
                scene_name,
                &options,
                Some(&mut writer),
                series.as_mut(),
            )?;
            writer.finish()?;
            if let Some(series) = series {
                series.finish()?;
            }
            // Standard output carries the trace itself; keep it pure JSON Lines.
            if trace::is_stdout(path) {
                Ok(())
            } else {
                print_summary(&summary)
            }
        }
        _ => {
            let summary = run::<io::Sink>(&mut sim, scene_name, &options, None, series.as_mut())?;
            if let Some(series) = series {
                series.finish()?;
            }
            print_summary(&summary)
        }
    }
}

fn print_summary(summary: &Summary) -> anyhow::Result<()> {
    let mut out = io::stdout().lock();
    writeln!(out, "{summary}")
        .and_then(|()| out.flush())
        .context("cannot write to standard output")
}

/// A ball slower than this (m/s) counts as at rest in the summary.
pub const REST_SPEED: f64 = 0.02;

/// What to run.
#[derive(Clone, Debug)]
pub struct Options {
    /// Steps to simulate after the initial state.
    pub steps: u64,
    /// Launch the fireball from the scene's spawn point before the first step.
    pub fireball: bool,
    /// Seed the world was built with; recorded in the trace.
    pub seed: u64,
    /// A state line every this many steps (at least 1).
    pub every: u64,
    /// A series line every this many steps (at least 1).
    pub series_every: u64,
}

/// Event kinds in the order the summary lists them.
const EVENT_KINDS: [&str; 6] = [
    "ball_surface",
    "ball_ball",
    "ball_tumbler",
    "fireball_surface",
    "fireball_ball",
    "fireball_tumbler",
];

/// The outcome of a run, printed as one paragraph.
#[derive(Clone, Debug)]
pub struct Summary {
    /// How the scene is named to the user: "the built-in default scene" or
    /// "scene `FILE`".
    pub scene: String,
    pub seed: u64,
    pub steps: u64,
    pub time: f64,
    pub dt: f64,
    pub wall: Duration,
    pub balls: usize,
    pub balls_alive: usize,
    pub balls_at_rest: usize,
    pub tumblers: usize,
    pub fireball: bool,
    pub kinetic: f64,
    pub potential: f64,
    /// Events per kind, in the order of `EVENT_KINDS`.
    pub events: [u64; 6],
}

impl Summary {
    pub fn total_events(&self) -> u64 {
        self.events.iter().sum()
    }
}

fn event_index(kind: &EventKind) -> usize {
    let name = event_kind_name(kind);
    EVENT_KINDS.iter().position(|&k| k == name).unwrap_or(0)
}

/// Runs `options.steps` steps of `sim`, as every run steps it (the world,
/// its balls on either engine, the effects). With a trace (whose scene
/// line is written), writes the state at step 0, then every
/// `options.every` steps and at the last step, each state line carrying
/// the events since the previous one; with a series, its line at step 0,
/// every `options.series_every` steps and at the last step.
pub fn run<W: Write>(
    sim: &mut Simulation,
    scene: &str,
    options: &Options,
    mut trace: Option<&mut TraceWriter<W>>,
    mut series: Option<&mut SeriesWriter<File>>,
) -> anyhow::Result<Summary> {
    let started = Instant::now();
    let every = options.every.max(1);
    if options.fireball {
        sim.world.launch_fireball(None);
    }
    if let Some(trace) = trace.as_deref_mut() {
        sim.with_balls(|sim| trace.state(&sim.world, &[]))??;
    }
    if let Some(series) = series.as_deref_mut() {
        series.sample(&sample(sim, &[])?)?;
    }
    let series_every = options.series_every.max(1);

    let mut events = [0u64; 6];
    let mut pending = Vec::new();
    for step in 1..=options.steps {
        sim.step()?;
        if step == options.steps {
            // The GPU engine's last reports are still on their way.
            sim.hand_on_events_in_flight()?;
        }
        for event in sim.last_events() {
            events[event_index(&event.kind)] += 1;
        }
        pending.extend_from_slice(sim.last_events());
        if let Some(series) = series.as_deref_mut()
            && (step % series_every == 0 || step == options.steps)
        {
            let last = sim.last_events().to_vec();
            series.sample(&sample(sim, &last)?)?;
        }
        match trace.as_deref_mut() {
            Some(trace) => {
                if step % every == 0 || step == options.steps {
                    sim.with_balls(|sim| trace.state(&sim.world, &pending))??;
                    pending.clear();
                }
            }
            None => pending.clear(),
        }
    }

    let wall = started.elapsed();
    Ok(sim.with_balls(|sim| summarize(&sim.world, scene, options, wall, events))?)
}

/// The series' sample of `sim` now, whose last step reported `events`;
/// on the GPU engine, which counts no impulses, without them.
fn sample(sim: &mut Simulation, events: &[Event]) -> anyhow::Result<Sample> {
    let sample = sim.with_balls(|sim| Sample::of(&sim.world, events))?;
    Ok(match sim.engine() {
        Engine::Gpu => sample.without_impulses(),
        Engine::Cpu => sample,
    })
}

fn summarize(
    world: &World,
    scene: &str,
    options: &Options,
    wall: Duration,
    events: [u64; 6],
) -> Summary {
    let balls = world.balls();
    let alive = balls.alive();
    let at_rest = balls
        .velocities()
        .iter()
        .zip(alive)
        .filter(|(v, alive)| **alive && v.length() < REST_SPEED)
        .count();
    let energy = world.energy();
    Summary {
        scene: scene.to_owned(),
        seed: options.seed,
        steps: world.step_count(),
        time: world.time(),
        dt: world.config().solver.dt,
        wall,
        balls: balls.len(),
        balls_alive: alive.iter().filter(|&&a| a).count(),
        balls_at_rest: at_rest,
        tumblers: world.tumblers().len(),
        fireball: world.fireball().is_some(),
        kinetic: energy.kinetic,
        potential: energy.potential,
        events,
    }
}

impl fmt::Display for Summary {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "Simulated {} steps ({:.3} s at dt = {:.6} s) of {} with seed {} in {:.3} s of wall time. ",
            self.steps,
            self.time,
            self.dt,
            self.scene,
            self.seed,
            self.wall.as_secs_f64()
        )?;
        write!(
            f,
            "{} balls ({} in play, {} at rest below {REST_SPEED} m/s), {} tumblers, fireball {}. ",
            self.balls,
            self.balls_alive,
            self.balls_at_rest,
            self.tumblers,
            if self.fireball { "flying" } else { "absent" },
        )?;
        write!(
            f,
            "Final energy: kinetic {:.4} J, potential {:.4} J, total {:.4} J. ",
            self.kinetic,
            self.potential,
            self.kinetic + self.potential
        )?;
        write!(f, "{} collision events", self.total_events())?;
        let parts: Vec<String> = EVENT_KINDS
            .iter()
            .zip(self.events)
            .filter(|(_, n)| *n > 0)
            .map(|(kind, n)| format!("{n} {}", kind.replace('_', "-")))
            .collect();
        if parts.is_empty() {
            f.write_str(".")
        } else {
            write!(f, " ({}).", parts.join(", "))
        }
    }
}
