//! `rolypoly replay`: a recording of the inputs played again, in the
//! window or off-screen into a clip, and its end state checked against the
//! recording's.

use anyhow::Context;
use rolypoly_render::Camera;

use crate::cli::{MAX_CLIP_SECONDS, ReplayArgs, WindowArgs, steps_for};
use crate::clip::{frame_count, write_clip};
use crate::sandbox::{ReplayLog, Sandbox};
use crate::window::fly_camera::FlyCamera;

/// Longest recording played, in hours of simulated time: beyond it, the
/// file is more likely damaged than real, and would keep the player waiting.
const MAX_REPLAY_HOURS: f64 = 10.0;

/// Plays the recording `args.log`: off-screen into `args.out` if given,
/// else in a window opened as `window` says; on `engine` where given,
/// else on the recording's.
pub fn replay(
    args: &ReplayArgs,
    window: &WindowArgs,
    engine: Option<crate::engine::Engine>,
) -> anyhow::Result<()> {
    if args.frame.fireball {
        anyhow::bail!(
            "replay: --fireball does not apply: the recording says when the fireball flies"
        );
    }
    let log = ReplayLog::read(&args.log)?;
    let mut sandbox = Sandbox::for_replay_on(&log, engine)
        .with_context(|| format!("cannot replay `{}`", args.log.display()))?;
    let dt = sandbox.world().config().solver.dt;
    let hours = log.to_tick as f64 * dt / 3600.0;
    if hours > MAX_REPLAY_HOURS {
        anyhow::bail!(
            "`{}` runs {hours:.0} hours of simulated time; a recording is at most {MAX_REPLAY_HOURS} (is it damaged?)",
            args.log.display()
        );
    }
    match &args.out {
        Some(out) => clip(&mut sandbox, &log, args, out),
        None => {
            let mut options = window.options(log.seed, None);
            options.replay_digest = Some(log.end_digest.clone());
            // The world as it was when R was pressed, once the window has
            // its device.
            options.replay_from = Some(log.from_tick);
            crate::window::run(sandbox, options)
        }
    }
}

fn clip(
    sandbox: &mut Sandbox,
    log: &ReplayLog,
    args: &ReplayArgs,
    out: &std::path::Path,
) -> anyhow::Result<()> {
    let config = sandbox.world().config().clone();
    let quality = sandbox.scene().quality;
    let mut frames = args.frame.frames(&config, quality, args.clip.size)?;
    sandbox.use_device(frames.device())?;
    // The world as it was when R was pressed.
    sandbox.replay_until(log.from_tick);
    let dt = config.solver.dt;
    let seconds = (log.to_tick - log.from_tick) as f64 * dt;
    if seconds > MAX_CLIP_SECONDS {
        anyhow::bail!(
            "the recording spans {seconds:.0} s; a clip is at most {MAX_CLIP_SECONDS} s (play it in the window instead)"
        );
    }
    let count = frame_count(seconds, args.clip.fps);
    let overview = Camera::overview(config.room.size.as_vec3());
    write_clip(out, args.clip.size, args.clip.fps, count, |k| {
        let tick = log.from_tick + steps_for(f64::from(k) / f64::from(args.clip.fps), dt);
        sandbox.replay_until(tick.min(log.to_tick));
        let camera = match (&args.frame.camera, &sandbox.view_pose) {
            (None, Some(pose)) => FlyCamera::posed(pose, &overview).camera(),
            _ => frames.camera(),
        };
        let light = args.frame.effects.apply(&sandbox.scene().light);
        frames.draw_from(&sandbox.sim, &light, &camera)
    })?;
    sandbox.replay_until(u64::MAX);
    let (width, height) = args.clip.size;
    println!(
        "wrote {} ({count} frames of {width}x{height}, ticks {} to {} of the recording, {})",
        out.display(),
        log.from_tick,
        log.to_tick,
        frames.describe()
    );
    check_end(sandbox, log)
}

/// The replay's end state against the recording's.
fn check_end(sandbox: &Sandbox, log: &ReplayLog) -> anyhow::Result<()> {
    let digest = sandbox.digest();
    if digest != log.end_digest {
        anyhow::bail!(
            "the replay ends in another state than the recording did (digest {digest}, recorded {}): was it made by another version of rolypoly?",
            log.end_digest
        );
    }
    println!("end state identical to the recording's (digest {digest})");
    Ok(())
}
