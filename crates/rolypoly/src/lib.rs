//! The rolypoly program: scene files, the command line and the headless
//! commands, on top of the `rolypoly_physics` simulation.
//!
//! The binary (`main.rs`) only parses arguments and reports errors; the
//! pieces live here so that tests and later front ends can reuse them.

pub mod cli;
pub mod record;
pub mod render;
pub mod replay;
pub mod sandbox;
pub mod scene;
pub mod simulate;
pub mod simulation;
pub mod trace;
pub mod window;

use std::io::{self, Write};
use std::path::Path;

use anyhow::Context;
use rolypoly_physics::World;

use cli::{Cli, Command, SimulateArgs, steps_for};
use scene::BUILTIN_ORIGIN;
use simulation::Simulation;

/// Runs the program for parsed arguments.
pub fn run(cli: &Cli) -> anyhow::Result<()> {
    check_outputs(cli)?;
    let scene_args = &cli.scene;
    let path = scene_args.scene.as_deref();
    let scene = scene::load_scene_with(path, &scene_args.overrides())?;
    let config = scene.world.clone();
    let scene_name = match path {
        Some(path) => format!("scene `{}`", path.display()),
        None => format!("the {BUILTIN_ORIGIN}"),
    };
    let dt = config.solver.dt;
    let mut world = World::new(config, scene_args.seed)
        .with_context(|| format!("cannot build {scene_name}"))?;

    match &cli.command {
        None => {
            let w = &cli.window;
            let options = w.options(scene_args.seed, path);
            // The light's switches given as flags are settings like any other.
            let mut scene = scene;
            scene.light = w.effects.apply(&scene.light);
            let name = path.map_or_else(|| "default.toml".to_owned(), |p| p.display().to_string());
            window::run(
                sandbox::Sandbox::with_world(world, scene, &name, scene_args.seed),
                options,
            )
        }
        Some(Command::Simulate(args)) => {
            simulate_command(&mut world, &scene_name, args, scene_args.seed, dt)
        }
        Some(Command::Render(args)) => render::render(
            &mut Simulation::new(world, scene.effects, scene_args.seed),
            &args.frame.effects.apply(&scene.light),
            args,
        ),
        Some(Command::Record(args)) => record::record(
            &mut Simulation::new(world, scene.effects, scene_args.seed),
            &args.frame.effects.apply(&scene.light),
            args,
        ),
        Some(Command::Replay(args)) => replay::replay(args, &cli.window),
        Some(Command::MakeTumblerObj(args)) => render::make_tumbler_obj(world.config(), args),
    }
}

/// Fails at once, before any work, where the run's output could never be
/// written: a file in a folder that does not exist, or screenshots into a
/// folder that is not one.
fn check_outputs(cli: &Cli) -> anyhow::Result<()> {
    let file_in_folder = |out: &Path| {
        let folder = out.parent().filter(|p| !p.as_os_str().is_empty());
        match folder {
            Some(folder) if !folder.is_dir() => anyhow::bail!(
                "cannot write `{}`: the folder `{}` does not exist",
                out.display(),
                folder.display()
            ),
            _ => Ok(()),
        }
    };
    match &cli.command {
        None => {
            let dir = &cli.window.screenshot_dir;
            if dir.is_dir() {
                Ok(())
            } else {
                anyhow::bail!(
                    "--screenshot-dir `{}`: no such folder (F12 writes screenshots there)",
                    dir.display()
                )
            }
        }
        Some(Command::Render(args)) => {
            file_in_folder(&args.out)?;
            named_for(&args.out, "png", "frames are PNG images")
        }
        Some(Command::Record(args)) => {
            // A folder of PNGs is made if need be, in a folder that is.
            record::ClipKind::of(&args.out)?;
            file_in_folder(&args.out)
        }
        Some(Command::Replay(args)) => match &args.out {
            Some(out) => {
                record::ClipKind::of(out)?;
                file_in_folder(out)
            }
            None => Ok(()),
        },
        Some(Command::MakeTumblerObj(args)) => {
            file_in_folder(&args.out)?;
            named_for(&args.out, "obj", "the mesh is a Wavefront OBJ file")
        }
        Some(Command::Simulate(args)) => match &args.trace {
            Some(trace) if !trace::is_stdout(trace) => file_in_folder(trace),
            _ => Ok(()),
        },
    }
}

/// An output is written in one format whatever its name says, so a name
/// that says another (`frame.jpg` for a PNG) is refused rather than left
/// to mislead. A name without an extension says nothing and is kept.
fn named_for(out: &Path, extension: &str, format: &str) -> anyhow::Result<()> {
    match out.extension() {
        Some(ext) if !ext.eq_ignore_ascii_case(extension) => anyhow::bail!(
            "cannot write `{}`: {format}; name the file `.{extension}`",
            out.display()
        ),
        _ => Ok(()),
    }
}

fn simulate_command(
    world: &mut World,
    scene_name: &str,
    args: &SimulateArgs,
    seed: u64,
    dt: f64,
) -> anyhow::Result<()> {
    let steps = match (args.length.steps, args.length.seconds) {
        (Some(steps), _) => steps,
        (None, Some(seconds)) => steps_for(seconds, dt),
        // clap requires one of the two.
        (None, None) => anyhow::bail!("give the length of the run with --steps or --seconds"),
    };
    let options = simulate::Options {
        steps,
        fireball: args.fireball,
        seed,
        every: args.every,
    };
    match &args.trace {
        None => {
            let summary = simulate::run::<io::Sink>(world, scene_name, &options, None)?;
            print_summary(&summary)
        }
        Some(path) => {
            let mut writer = trace::create(path)?;
            let summary = simulate::run(world, scene_name, &options, Some(&mut writer))?;
            writer.finish()?;
            // Standard output carries the trace itself; keep it pure JSON Lines.
            if trace::is_stdout(path) {
                Ok(())
            } else {
                print_summary(&summary)
            }
        }
    }
}

fn print_summary(summary: &simulate::Summary) -> anyhow::Result<()> {
    let mut out = io::stdout().lock();
    writeln!(out, "{summary}")
        .and_then(|()| out.flush())
        .context("cannot write to standard output")
}

/// True when `error` comes from a closed pipe (`rolypoly ... | head`): the
/// reader has what it wanted, so this is no failure to report.
pub fn is_broken_pipe(error: &anyhow::Error) -> bool {
    error.chain().any(|cause| {
        cause
            .downcast_ref::<io::Error>()
            .is_some_and(|e| e.kind() == io::ErrorKind::BrokenPipe)
    })
}
