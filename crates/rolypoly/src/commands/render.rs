//! `rolypoly render`: a run to a moment, that frame as a PNG.

use anyhow::Context;
use rolypoly_render::{LightConfig, QualityChoice};

use crate::cli::{RenderArgs, steps_for};
use crate::frames::Frames;
use crate::simulation::Simulation;

/// Runs `sim` to the requested time and writes that frame, drawn at the
/// scene's `quality` unless the flags say otherwise. With `gpu`, the GPU
/// engine steps the balls, on the device that draws them.
pub fn render(
    mut sim: Simulation,
    light: &LightConfig,
    quality: QualityChoice,
    gpu: bool,
    args: &RenderArgs,
) -> anyhow::Result<()> {
    let sim = &mut sim;
    if args.frame.fireball {
        sim.world.launch_fireball(None);
    }
    let mut frames = Frames::new(sim.world.config(), quality, &args.frame, args.size)?;
    if gpu {
        frames.move_balls_to_gpu(sim)?;
    }
    sim.ticks(steps_for(args.time, sim.world.config().solver.dt));
    sim.check_gpu()?;
    let image = frames.draw(sim, light)?;
    image
        .save_with_format(&args.out, image::ImageFormat::Png)
        .with_context(|| format!("cannot write `{}`", args.out.display()))?;
    let (width, height) = args.size;
    println!(
        "wrote {} ({width}x{height}, t = {:.3} s, {})",
        args.out.display(),
        sim.world.time(),
        frames.describe()
    );
    Ok(())
}
