//! `World.write_trace`: the program's trace writer driven as
//! `rolypoly simulate --trace` drives it, so that the same scene and seed
//! give the same bytes.

use std::path::Path;

use pyo3::prelude::*;
use rolypoly_core::trace::{self, TraceError};
use rolypoly_physics::Event;

use crate::errors::{gpu_error, io_error, one_line};
use crate::run::Run;

/// Writes the scene line and the state now, then steps `steps` times,
/// writing the state every `every` steps and at the last, each line with
/// the events since the one before.
pub fn write_trace(run: &mut Run, path: &Path, steps: u64, every: u64) -> PyResult<()> {
    let mut writer = trace::create(path).map_err(|e| trace_error(&e))?;
    let seed = run.seed;
    match run.scene_balls().map_err(|e| gpu_error(&e))? {
        None => writer.scene(&run.sim.world, seed),
        Some(balls) => {
            let world = &mut run.sim.world;
            world.put_balls(balls);
            let written = writer.scene(world, seed);
            world.take_balls();
            written
        }
    }
    .map_err(|e| trace_error(&e))?;
    run.sim
        .with_balls(|sim| writer.state(&sim.world, &[]))
        .map_err(|e| gpu_error(&e))?
        .map_err(|e| trace_error(&e))?;
    let mut since: Vec<Event> = Vec::new();
    for step in 1..=steps {
        if step == steps {
            run.last_tick()
        } else {
            run.tick()
        }
        .map_err(|e| gpu_error(&e))?;
        since.extend_from_slice(run.last_events());
        if step % every == 0 || step == steps {
            run.sim
                .with_balls(|sim| writer.state(&sim.world, &since))
                .map_err(|e| gpu_error(&e))?
                .map_err(|e| trace_error(&e))?;
            since.clear();
        }
    }
    writer.finish().map_err(|e| trace_error(&e))?;
    Ok(())
}

fn trace_error(error: &TraceError) -> PyErr {
    io_error(error.source.kind(), one_line(error))
}
