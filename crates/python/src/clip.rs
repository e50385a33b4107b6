//! `rolypoly.record`: a run drawn frame by frame into a clip, as
//! `rolypoly record` writes it (an animated GIF, an MP4 through ffmpeg, or
//! a folder of numbered PNGs).

use std::io;
use std::path::PathBuf;

use pyo3::prelude::*;
use rolypoly_core::clip::{ClipKind, frame_count, write_clip};
use rolypoly_core::steps_for;
use rolypoly_gpu::GpuError;

use crate::errors::{DeviceError, io_error, value_error};
use crate::render::{FrameOptions, held_balls, with_frames};
use crate::world::World;

/// Longest clip, in simulated seconds, as `--seconds` allows.
const MAX_SECONDS: f64 = 3600.0;

/// Steps ``world`` on for ``seconds`` of simulated time and writes it to
/// ``path``, ``fps`` frames a simulated second, as ``rolypoly record``
/// does: ``.gif`` an animated GIF, ``.mp4`` an H.264 video (through the
/// program ffmpeg), a name ending in ``/`` (or without an extension) a
/// folder of numbered PNGs. Frame k shows the world ``k / fps`` seconds
/// from now. ``size``, ``camera``, ``quality``, ``show`` and ``view`` are
/// :func:`render`'s. Returns the number of frames written.
#[pyfunction]
#[pyo3(signature = (world, path, seconds=3.0, fps=30, size=(640, 360), camera=None, quality=None, show=None, view=None))]
#[allow(clippy::too_many_arguments)]
pub fn record(
    py: Python<'_>,
    world: &Bound<'_, World>,
    path: PathBuf,
    seconds: f64,
    fps: i64,
    size: (i64, i64),
    camera: Option<&Bound<'_, PyAny>>,
    quality: Option<&str>,
    show: Option<&Bound<'_, PyAny>>,
    view: Option<&str>,
) -> PyResult<u32> {
    if !(seconds > 0.0 && seconds <= MAX_SECONDS) {
        return Err(value_error(format!(
            "seconds = {seconds} is out of range: allowed > 0 and <= {MAX_SECONDS}"
        )));
    }
    let fps = u32::try_from(fps)
        .ok()
        .filter(|f| (1..=60).contains(f))
        .ok_or_else(|| value_error(format!("fps = {fps} is out of range: allowed 1 ..= 60")))?;
    ClipKind::of(&path).map_err(|e| value_error(format!("{e:#}")))?;
    let options = FrameOptions::read(size, camera, quality, show, view)?;
    let mut world = world.try_borrow_mut()?;
    let run = &mut world.run;
    let count = frame_count(seconds, fps);
    let dt = run.sim.world.config().solver.dt;
    let written = py.detach(|| {
        let mut done = 0;
        write_clip(&path, options.size, fps, count, |k| {
            // Frame k shows the moment k / fps, the step `render --time`
            // would stop at.
            let steps = steps_for(f64::from(k) / f64::from(fps), dt);
            for _ in done..steps {
                run.tick()?;
            }
            done = steps;
            let held = held_balls(run).map_err(|e| anyhow::anyhow!("{e}"))?;
            let sim = held.as_ref().unwrap_or(&run.sim);
            with_frames(run, &options, |frames, light, camera| {
                frames.draw_from(sim, light, camera)
            })
        })
    });
    written.map_err(|e| clip_error(&e))?;
    Ok(count)
}

/// A file that could not be written is an `OSError`, the adapter's trouble
/// a `DeviceError`.
fn clip_error(error: &anyhow::Error) -> PyErr {
    let message = format!("{error:#}");
    if let Some(io) = error.chain().find_map(|c| c.downcast_ref::<io::Error>()) {
        return io_error(io.kind(), message);
    }
    if error
        .chain()
        .any(|c| c.downcast_ref::<GpuError>().is_some())
    {
        return DeviceError::new_err(message);
    }
    pyo3::exceptions::PyRuntimeError::new_err(message)
}
