//! `World.series`: the program's series (`simulate --series`) as NumPy
//! columns, one value a sample, the same numbers the CSV holds.

use pyo3::prelude::*;
use pyo3::types::{PyDict, PyModule};
use rolypoly_core::engine::Engine;
use rolypoly_core::series::{Sample, columns};
use rolypoly_physics::Event;

use crate::arrays::column;
use crate::errors::gpu_error;
use crate::run::Run;

/// The samples of `steps` steps of `run`: the state now, then every
/// `every` steps and at the last, as `simulate --series` takes them.
pub fn samples(run: &mut Run, steps: u64, every: u64) -> PyResult<Vec<Sample>> {
    let mut samples = vec![sample(run, &[])?];
    for step in 1..=steps {
        run.tick().map_err(|e| gpu_error(&e))?;
        if step % every == 0 || step == steps {
            let events = run.last_events().to_vec();
            samples.push(sample(run, &events)?);
        }
    }
    Ok(samples)
}

/// The sample of `run` now, whose last step reported `events`; on the GPU
/// engine, which counts no impulses, without them.
fn sample(run: &mut Run, events: &[Event]) -> PyResult<Sample> {
    let gpu = run.engine() == Engine::Gpu;
    let sample = run
        .sim
        .with_balls(|sim| Sample::of(&sim.world, events))
        .map_err(|e| gpu_error(&e))?;
    Ok(if gpu {
        sample.without_impulses()
    } else {
        sample
    })
}

/// The samples as a dict of column name to a float64 array, in the
/// columns' order; with `frame`, as a pandas DataFrame of those columns.
pub fn to_python<'py>(
    py: Python<'py>,
    samples: &[Sample],
    tumblers: usize,
    frame: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let names = columns(tumblers);
    let rows: Vec<Vec<f64>> = samples.iter().map(Sample::values).collect();
    let table = PyDict::new(py);
    for (k, name) in names.iter().enumerate() {
        let values: Vec<f64> = rows.iter().map(|row| row[k]).collect();
        table.set_item(name, column(py, &values))?;
    }
    if !frame {
        return Ok(table.into_any());
    }
    let pandas = PyModule::import(py, "pandas").map_err(|_| {
        pyo3::exceptions::PyImportError::new_err(
            "frame=True needs pandas (pip install pandas); without it, series() gives a dict of NumPy arrays",
        )
    })?;
    pandas.getattr("DataFrame")?.call1((table,))
}
