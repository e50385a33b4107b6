//! `rolypoly sound`: a run's sound alone, made without drawing, to a WAV
//! file (J1).

use crate::cli::{SoundArgs, steps_for};
use crate::frames::chosen_camera;
use crate::simulation::Simulation;
use crate::sound::{Recording, listener_of, ticks_heard};
use rolypoly_sound::SoundConfig;

/// The sound of `sim` for `args.seconds`, heard from the camera `--camera`
/// gives (or the overview), as `config` says, into `args.out`; with `gpu`,
/// the balls stepped on the GPU engine (and read back to be heard).
pub fn sound(
    mut sim: Simulation,
    config: &SoundConfig,
    gpu: bool,
    args: &SoundArgs,
) -> anyhow::Result<()> {
    if gpu {
        sim.move_balls_to_compute(&rolypoly_gpu::Compute::headless()?)?;
    }
    if args.fireball {
        sim.world.launch_fireball(None);
    }
    let camera = chosen_camera(args.camera, sim.world.config());
    let mut recording = Recording::new(config, &sim, listener_of(&camera));
    let steps = steps_for(args.seconds, sim.world.config().solver.dt);
    ticks_heard(&mut sim, steps, &mut recording)?;
    recording.write_wav(&args.out)?;
    let frames = recording.frames();
    let loudest = frames
        .iter()
        .fold(0.0f32, |m, f| m.max(f[0].abs()).max(f[1].abs()));
    println!(
        "wrote {} ({:.3} s of stereo sound at {} Hz, t = 0 to {:.3} s, loudest sample {:.1} dBFS{})",
        args.out.display(),
        frames.len() as f64 / f64::from(rolypoly_sound::SAMPLE_RATE),
        rolypoly_sound::SAMPLE_RATE,
        sim.world.time(),
        20.0 * f64::from(loudest.max(1e-10)).log10(),
        if config.enabled {
            ""
        } else {
            "; sound.enabled is false: silence"
        }
    );
    Ok(())
}
