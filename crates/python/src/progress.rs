//! A progress bar over a long `World.step`: tqdm's, where tqdm is
//! installed (`tqdm.auto`, so a notebook gets its widget), else none.

use pyo3::exceptions::PyImportError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// Seconds a `step` runs before its bar shows, when not asked for at once:
/// short steps print nothing.
const SHOW_AFTER_SECONDS: f64 = 1.0;

/// The bar of one `step` call, or none.
pub struct Progress<'py> {
    bar: Option<Bound<'py, PyAny>>,
}

impl<'py> Progress<'py> {
    /// A bar of `total` steps as `wanted` asks: `None` a bar where tqdm is
    /// installed, shown once stepping has lasted a second; `Some(true)` a
    /// bar at once, tqdm required; `Some(false)` none.
    pub fn new(py: Python<'py>, total: u64, wanted: Option<bool>) -> PyResult<Progress<'py>> {
        if wanted == Some(false) || total == 0 {
            return Ok(Progress { bar: None });
        }
        let tqdm = match py.import("tqdm.auto") {
            Ok(module) => module.getattr("tqdm")?,
            Err(_) if wanted.is_none() => return Ok(Progress { bar: None }),
            Err(_) => {
                return Err(PyImportError::new_err(
                    "progress=True draws its bar with tqdm, which is not installed here: \
                     pip install tqdm, or step with progress=None (a bar where tqdm is \
                     installed) or False",
                ));
            }
        };
        let options = PyDict::new(py);
        options.set_item("total", total)?;
        options.set_item("unit", "step")?;
        options.set_item("desc", "rolypoly")?;
        let delay = if wanted == Some(true) {
            0.0
        } else {
            SHOW_AFTER_SECONDS
        };
        options.set_item("delay", delay)?;
        Ok(Progress {
            bar: Some(tqdm.call((), Some(&options))?),
        })
    }

    /// `steps` more done.
    pub fn advance(&self, steps: u64) -> PyResult<()> {
        if let Some(bar) = &self.bar {
            bar.call_method1("update", (steps,))?;
        }
        Ok(())
    }

    /// The bar closed, whether the steps ended or were stopped.
    pub fn close(self) -> PyResult<()> {
        if let Some(bar) = &self.bar {
            bar.call_method0("close")?;
        }
        Ok(())
    }
}
