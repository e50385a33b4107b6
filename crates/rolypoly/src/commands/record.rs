//! `rolypoly record`: a run drawn frame by frame off-screen into a clip.

use rolypoly_render::{LightConfig, QualityChoice};

use crate::cli::{RecordArgs, steps_for};
use crate::clip::{frame_count, write_clip};
use crate::frames::Frames;
use crate::simulation::Simulation;

/// Records `sim` from now for `args.seconds`, `args.clip.fps` frames a
/// simulated second, into `args.out`, drawn at the scene's `quality`
/// unless the flags say otherwise. With `gpu`, the GPU engine steps the
/// balls, on the device that draws them.
pub fn record(
    mut sim: Simulation,
    light: &LightConfig,
    quality: QualityChoice,
    gpu: bool,
    args: &RecordArgs,
) -> anyhow::Result<()> {
    let sim = &mut sim;
    if args.frame.fireball {
        sim.world.launch_fireball(None);
    }
    let mut frames = Frames::new(sim.world.config(), quality, &args.frame, args.clip.size)?;
    if gpu {
        frames.move_balls_to_gpu(sim)?;
    }
    let count = frame_count(args.seconds, args.clip.fps);
    let dt = sim.world.config().solver.dt;
    let mut steps_done = 0;
    write_clip(&args.out, args.clip.size, args.clip.fps, count, |k| {
        // Frame k shows the moment k / fps, the same step `render --time`
        // would stop at.
        let steps = steps_for(f64::from(k) / f64::from(args.clip.fps), dt);
        sim.ticks(steps - steps_done);
        steps_done = steps;
        sim.check_gpu()?;
        frames.draw(sim, light)
    })?;
    let (width, height) = args.clip.size;
    println!(
        "wrote {} ({count} frames of {width}x{height} at {} frames per second, t = 0 to {:.3} s, {})",
        args.out.display(),
        args.clip.fps,
        sim.world.time(),
        frames.describe()
    );
    Ok(())
}
