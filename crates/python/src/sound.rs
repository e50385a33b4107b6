//! `rolypoly.sound`: a run's sound as a NumPy array, the same samples as
//! `rolypoly sound` writes (J1).

use numpy::{PyArray1, PyArray2, PyArrayMethods};
use pyo3::prelude::*;
use rolypoly_core::frames::chosen_camera;
use rolypoly_core::sound::{Recording, listener_of};
use rolypoly_core::steps_for;
use rolypoly_gpu::GpuError;

use crate::errors::{gpu_error, value_error};
use crate::render::read_camera;
use crate::world::World;

/// Longest sound, in simulated seconds, as `--seconds` allows.
const MAX_SECONDS: f64 = 3600.0;

/// Steps ``world`` on for ``seconds`` of simulated time and returns its
/// sound, heard from ``camera`` (``(eye, target)``; ``None``: the overview
/// that :func:`render` draws from), as ``rolypoly sound`` makes it: a
/// (frames, 2) float32 array of left and right samples at 48 000 a second,
/// each within ±0.891 (-1 dBFS). The scene's ``sound.*`` keys set the
/// volume and the materials. A world on the GPU engine has its balls read
/// back each step to be heard.
#[pyfunction]
#[pyo3(signature = (world, seconds, camera=None))]
pub fn sound<'py>(
    py: Python<'py>,
    world: &Bound<'py, World>,
    seconds: f64,
    camera: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyArray2<f32>>> {
    if !(seconds > 0.0 && seconds <= MAX_SECONDS) {
        return Err(value_error(format!(
            "seconds = {seconds} is out of range: allowed > 0 and <= {MAX_SECONDS}"
        )));
    }
    let eye_target = camera.map(read_camera).transpose()?;
    let mut world = world.try_borrow_mut()?;
    let run = &mut world.run;
    let camera = chosen_camera(
        eye_target.map(|(e, t)| [e.x, e.y, e.z, t.x, t.y, t.z]),
        run.sim.world.config(),
    );
    let steps = steps_for(seconds, run.sim.world.config().solver.dt);
    let frames = py.detach(|| {
        let mut recording = Recording::new(&run.scene.data.sound, &run.sim, listener_of(&camera));
        for _ in 0..steps {
            run.tick()?;
            recording.hear(&mut run.sim)?;
        }
        Ok::<_, GpuError>(recording.frames().to_vec())
    });
    let frames = frames.map_err(|e| gpu_error(&e))?;
    let n = frames.len();
    let flat: Vec<f32> = frames.into_iter().flatten().collect();
    PyArray1::from_vec(py, flat).reshape([n, 2])
}
