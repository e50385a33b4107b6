//! The run's sound as the program makes it (J1): heard from the camera a
//! step at a time, and kept for a WAV file or an MP4's sound track.

use std::path::Path;
use std::process::{Command, Stdio};

use anyhow::Context;
use glam::DVec3;
use rolypoly_gpu::GpuError;
use rolypoly_physics::{Balls, EventKind};
use rolypoly_render::Camera;
use rolypoly_sound::{Listener, SoundConfig, Soundtrack, write_wav};

use crate::simulation::Simulation;

/// Where `camera` hears from: its eye, facing its target.
pub fn listener_of(camera: &Camera) -> Listener {
    Listener {
        position: camera.eye.as_dvec3(),
        forward: (camera.target - camera.eye).as_dvec3(),
    }
}

/// A run's sound, kept whole.
pub struct Recording {
    track: Soundtrack,
    listener: Listener,
    frames: Vec<[f32; 2]>,
}

impl Recording {
    /// The sound of `sim` from its next step on, as `config` says, heard by
    /// `listener`.
    pub fn new(config: &SoundConfig, sim: &Simulation, listener: Listener) -> Recording {
        Recording {
            track: Soundtrack::new(config, &sim.world),
            listener,
            frames: Vec::new(),
        }
    }

    /// Hears the step `sim` just took. On the GPU engine its balls are read
    /// back for it: the sound reads each struck ball's size and place.
    pub fn hear(&mut self, sim: &mut Simulation) -> Result<(), GpuError> {
        let (track, listener) = (&mut self.track, &self.listener);
        sim.with_balls(|sim| track.hear_step(&sim.world, sim.last_events(), listener))?;
        self.frames.append(&mut self.track.take_frames());
        Ok(())
    }

    /// The samples so far, left and right.
    pub fn frames(&self) -> &[[f32; 2]] {
        &self.frames
    }

    /// Writes the samples to the WAV file `path`.
    pub fn write_wav(&self, path: &Path) -> anyhow::Result<()> {
        write_wav(path, &self.frames).with_context(|| format!("cannot write `{}`", path.display()))
    }
}

/// The GPU engine's balls as the live sound hears them without reading
/// them back each step (a million balls would stall the frame): their
/// sizes and masses, read back once and again when their count changes
/// (a throw, a restart), each standing still where it last struck. So a
/// struck ball rings at its pitch and loudness from where it struck; the
/// balls' rolling, which needs their motion, is not heard. A recording
/// reads the balls back every step instead ([`Recording::hear`]).
#[derive(Default)]
pub struct StandIns {
    balls: Balls,
}

impl StandIns {
    /// The stand-ins for `sim`'s balls after its last step: moved to where
    /// its events struck them.
    pub fn after_step(&mut self, sim: &Simulation) -> Result<&Balls, GpuError> {
        if self.balls.len() != sim.ball_count() {
            let mut balls = sim.balls.read(&sim.world)?.into_owned();
            for i in 0..balls.len() {
                let at = balls.positions()[i];
                balls.set(i, at, DVec3::ZERO);
            }
            self.balls = balls;
        }
        let radius = |i: usize| self.balls.radii().get(i).copied();
        let mut moved = Vec::new();
        for event in sim.last_events() {
            // The normal points from what a ball met towards the ball.
            let (p, n) = (event.point, event.normal);
            match event.kind {
                EventKind::BallSurface { ball, .. } | EventKind::BallTumbler { ball, .. } => {
                    moved.extend(radius(ball).map(|r| (ball, p + n * r)));
                }
                EventKind::BallBall { a, b } => {
                    moved.extend(radius(a).map(|r| (a, p + n * r)));
                    moved.extend(radius(b).map(|r| (b, p - n * r)));
                }
                EventKind::FireballBall { ball } if radius(ball).is_some() => {
                    moved.push((ball, p));
                }
                _ => {}
            }
        }
        for (ball, at) in moved {
            self.balls.set(ball, at, DVec3::ZERO);
        }
        Ok(&self.balls)
    }
}

/// Steps `sim` `steps` times, hearing each step; a GPU engine that fails
/// stops it, and says why.
pub fn ticks_heard(
    sim: &mut Simulation,
    steps: u64,
    recording: &mut Recording,
) -> anyhow::Result<()> {
    for _ in 0..steps {
        sim.tick();
        sim.check_gpu()?;
        recording.hear(sim)?;
    }
    Ok(())
}

/// Writes `out`, the MP4 `video` with the WAV `sound` as its sound track
/// (AAC), through ffmpeg; the video's frames are copied as they are.
pub fn mux(video: &Path, sound: &Path, out: &Path) -> anyhow::Result<()> {
    let output = Command::new("ffmpeg")
        .args(["-loglevel", "error", "-y", "-i"])
        .arg(video)
        .arg("-i")
        .arg(sound)
        .args([
            "-map", "0:v", "-map", "1:a", "-c:v", "copy", "-c:a", "aac", "-b:a", "192k",
        ])
        .args(["-movflags", "+faststart"])
        .arg(out)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .output()
        .context("cannot start ffmpeg to add the sound")?;
    if !output.status.success() {
        let said = String::from_utf8_lossy(&output.stderr);
        anyhow::bail!(
            "ffmpeg failed to add the sound ({}): {}",
            output.status,
            said.trim().lines().last().unwrap_or("it said nothing")
        );
    }
    Ok(())
}
