//! The program's commands, a file each: the window (no subcommand),
//! `simulate`, `render`, `record`, `replay`, `sound`, `make-tumbler-obj`
//! and `shaders`; and the checks every command's outputs pass before any
//! work.

use std::path::Path;

use anyhow::Context;
use rolypoly_physics::World;

use crate::cli::{Cli, Command};
use crate::engine::Engine;
use crate::scene::{self, BUILTIN_ORIGIN};
use crate::simulation::Simulation;
use crate::{clip, trace};

mod make_tumbler_obj;
mod record;
mod render;
mod replay;
mod run;
mod shaders;
mod simulate;
mod sound;

/// Runs the program for parsed arguments.
pub fn run(cli: &Cli) -> anyhow::Result<()> {
    let frame = match &cli.command {
        Some(Command::Render(args)) => Some(&args.frame),
        Some(Command::Record(args)) => Some(&args.frame),
        Some(Command::Replay(args)) => Some(&args.frame),
        _ => None,
    };
    if frame.is_some_and(|f| f.lists_views()) {
        // The views are the renderer's, whatever the scene.
        print!("{}", rolypoly_render::FrameView::list());
        return Ok(());
    }
    check_outputs(cli)?;
    rolypoly_gpu::set_program_gpu_timeout(cli.gpu.gpu_timeout);
    match &cli.command {
        // A recording carries its own scene and seed.
        Some(Command::Replay(args)) => return replay::replay(args, &cli.window, cli.scene.engine),
        // The shaders are the program's, whatever the scene.
        Some(Command::Shaders(args)) => return shaders::export(args),
        _ => {}
    }
    let scene_args = &cli.scene;
    let path = scene_args.scene.as_deref();
    let scene = scene::load_scene_with(path, &scene_args.overrides())?;
    let scene_name = match path {
        Some(path) => format!("scene `{}`", path.display()),
        None => format!("the {BUILTIN_ORIGIN}"),
    };
    let seed = scene_args.seed;
    let world = World::new(scene.world.clone(), seed)
        .with_context(|| format!("cannot build {scene_name}"))?;
    let gpu = scene.engine == Engine::Gpu;
    match &cli.command {
        None => run::window(world, scene, path, seed, &cli.window),
        Some(Command::Simulate(args)) => simulate::simulate(
            Simulation::new(world, scene.effects, seed),
            &scene_name,
            args,
            seed,
            scene.world.solver.dt,
            gpu,
        ),
        Some(Command::Render(args)) => render::render(
            Simulation::new(world, scene.effects, seed),
            &args.frame.effects.apply(&scene.light),
            scene.quality,
            gpu,
            args,
        ),
        Some(Command::Record(args)) => record::record(
            Simulation::new(world, scene.effects, seed),
            &args.frame.effects.apply(&scene.light),
            (scene.quality, &scene.sound),
            gpu,
            args,
        ),
        Some(Command::Sound(args)) => sound::sound(
            Simulation::new(world, scene.effects, seed),
            &scene.sound,
            gpu,
            args,
        ),
        Some(Command::Replay(args)) => replay::replay(args, &cli.window, cli.scene.engine),
        Some(Command::Shaders(args)) => shaders::export(args),
        Some(Command::MakeTumblerObj(args)) => {
            make_tumbler_obj::make_tumbler_obj(world.config(), args)
        }
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
            file_in_folder(args.out()?)?;
            named_for(args.out()?, "png", "frames are PNG images")
        }
        Some(Command::Record(args)) => {
            // A folder of PNGs is made if need be, in a folder that is.
            clip::ClipKind::of(&args.out)?;
            if let Some(audio) = &args.audio {
                file_in_folder(audio)?;
                named_for(audio, "wav", "the sound is a WAV file")?;
            }
            file_in_folder(&args.out)
        }
        Some(Command::Sound(args)) => {
            file_in_folder(&args.out)?;
            named_for(&args.out, "wav", "the sound is a WAV file")
        }
        Some(Command::Replay(args)) => match &args.out {
            Some(out) => {
                clip::ClipKind::of(out)?;
                file_in_folder(out)
            }
            None => Ok(()),
        },
        Some(Command::MakeTumblerObj(args)) => {
            file_in_folder(&args.out)?;
            named_for(&args.out, "obj", "the mesh is a Wavefront OBJ file")
        }
        // The export checks its folder itself, before writing anything.
        Some(Command::Shaders(_)) => Ok(()),
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
