//! Measures the physics crate makes of a world's state, for plots.

use pyo3::prelude::*;

use crate::arrays::read_rows;
use crate::errors::value_error;

/// The angle of repose in degrees of the heap that ``positions`` ((N, 3)
/// ball centres, every ball of ``radius``) form around the vertical line
/// through ``axis`` (x, z): the slope of a line fitted to the cone's
/// flank, as the physics crate measures it (``angle_of_repose``). None
/// where the balls form no flank to fit.
#[pyfunction]
#[pyo3(signature = (positions, radius, axis=(0.0, 0.0)))]
pub fn angle_of_repose(
    positions: &Bound<'_, PyAny>,
    radius: f64,
    axis: (f64, f64),
) -> PyResult<Option<f64>> {
    if !(radius.is_finite() && radius > 0.0) {
        return Err(value_error(format!(
            "radius = {radius}: give a radius above 0"
        )));
    }
    let positions = read_rows(positions, "positions")?;
    if let Some(i) = positions.iter().position(|p| !p.is_finite()) {
        return Err(value_error(format!("positions: row {i} is not finite")));
    }
    Ok(rolypoly_physics::angle_of_repose(
        &positions,
        radius,
        [axis.0, axis.1],
    ))
}
