//! `rolypoly record`: a run drawn frame by frame off-screen into a clip,
//! heard as it runs: an MP4 carries the sound, `--audio` writes it alone.

use std::path::{Path, PathBuf};

use anyhow::Context;
use rolypoly_render::{LightConfig, QualityChoice};
use rolypoly_sound::SoundConfig;

use crate::cli::{RecordArgs, steps_for};
use crate::clip::{ClipKind, find_ffmpeg, frame_count, write_clip};
use crate::simulation::Simulation;
use crate::sound::{Recording, listener_of, mux, ticks_heard};

/// Records `sim` from now for `args.seconds`, `args.clip.fps` frames a
/// simulated second, into `args.out`, drawn at the scene's `quality`
/// unless the flags say otherwise, and heard as `sound` says. With `gpu`,
/// the GPU engine steps the balls, on the device that draws them.
pub fn record(
    mut sim: Simulation,
    light: &LightConfig,
    (quality, sound): (QualityChoice, &SoundConfig),
    gpu: bool,
    args: &RecordArgs,
) -> anyhow::Result<()> {
    let sim = &mut sim;
    if args.frame.fireball {
        sim.world.launch_fireball(None);
    }
    let mut frames = args
        .frame
        .frames(sim.world.config(), quality, args.clip.size)?;
    if gpu {
        frames.move_balls_to_gpu(sim)?;
    }
    let mut recording = Recording::new(sound, sim, listener_of(&frames.camera()));
    let with_sound = sound.enabled && ClipKind::of(&args.out)? == ClipKind::Mp4;
    if with_sound {
        // Named for the clip asked for, not the working file.
        find_ffmpeg(&args.out)?;
    }
    // An MP4 with sound is the video alone first, then the two together.
    let video = if with_sound {
        beside(&args.out, "video.mp4")
    } else {
        args.out.clone()
    };
    let count = frame_count(args.seconds, args.clip.fps);
    let dt = sim.world.config().solver.dt;
    let mut steps_done = 0;
    write_clip(&video, args.clip.size, args.clip.fps, count, |k| {
        // Frame k shows the moment k / fps, the same step `render --time`
        // would stop at.
        let steps = steps_for(f64::from(k) / f64::from(args.clip.fps), dt);
        ticks_heard(sim, steps - steps_done, &mut recording)?;
        steps_done = steps;
        sim.check_gpu()?;
        if k == 0 {
            // On the temporal path the first frame draws its history of
            // the first moment first, as `render` does.
            frames.draw_at(sim, steps, light)
        } else {
            frames.draw(sim, light)
        }
    })?;
    // The last frame is shown for 1 / fps: the sound runs to its end.
    let end = steps_for(f64::from(count) / f64::from(args.clip.fps), dt);
    ticks_heard(sim, end - steps_done, &mut recording)?;
    if let Some(audio) = &args.audio {
        recording.write_wav(audio)?;
    }
    if with_sound {
        let wav = beside(&args.out, "sound.wav");
        let muxed = recording
            .write_wav(&wav)
            .and_then(|()| mux(&video, &wav, &args.out));
        let _ = std::fs::remove_file(&video);
        let _ = std::fs::remove_file(&wav);
        muxed.with_context(|| format!("cannot write `{}`", args.out.display()))?;
    }
    let (width, height) = args.clip.size;
    println!(
        "wrote {} ({count} frames of {width}x{height} at {} frames per second, t = 0 to {:.3} s, {}{})",
        args.out.display(),
        args.clip.fps,
        f64::from(count - 1) / f64::from(args.clip.fps),
        frames.describe(),
        if with_sound { ", with sound" } else { "" }
    );
    Ok(())
}

/// A working file beside `out`, named after it: `clip.mp4` gives
/// `.clip.mp4.video.mp4`.
fn beside(out: &Path, what: &str) -> PathBuf {
    let name = out
        .file_name()
        .map_or_else(Default::default, |n| n.to_string_lossy().into_owned());
    out.with_file_name(format!(".{name}.{what}"))
}
