//! `rolypoly` for Python: scenes read by the program's own reader, worlds
//! stepped by the program's engines with their state as NumPy arrays, and
//! frames drawn by its renderer. The physics and the drawing are the
//! other crates'; this crate only carries them across.

use pyo3::prelude::*;

mod arrays;
mod balls;
mod checks;
mod clip;
mod errors;
mod events;
mod measures;
mod overrides;
mod progress;
mod render;
mod run;
mod scene;
mod series;
mod sound;
mod trace;
mod tumblers;
mod world;

#[pymodule]
fn _rolypoly(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<scene::Scene>()?;
    m.add_class::<world::World>()?;
    m.add_class::<world::Energy>()?;
    m.add_class::<world::Snapshot>()?;
    m.add_class::<balls::Balls>()?;
    m.add_class::<tumblers::Tumblers>()?;
    m.add_class::<tumblers::Fireball>()?;
    m.add_class::<events::Event>()?;
    m.add_function(wrap_pyfunction!(render::render, m)?)?;
    m.add_function(wrap_pyfunction!(render::overview_camera, m)?)?;
    m.add_function(wrap_pyfunction!(render::frame_views, m)?)?;
    m.add_function(wrap_pyfunction!(clip::record, m)?)?;
    m.add_function(wrap_pyfunction!(sound::sound, m)?)?;
    m.add_function(wrap_pyfunction!(measures::angle_of_repose, m)?)?;
    m.add("DeviceError", m.py().get_type::<errors::DeviceError>())?;
    m.add("MAX_PENDING_EVENTS", run::MAX_PENDING_EVENTS)?;
    // The workspace's version: the package's and the program's.
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
