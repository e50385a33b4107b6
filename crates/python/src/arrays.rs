//! State to and from NumPy. Every read copies into a fresh array that
//! Python owns (changing it changes nothing in the world); every write is
//! read whole and checked before anything changes.

use glam::DVec3;
use numpy::{
    AllowTypeChange, PyArray1, PyArray2, PyArrayLikeDyn, PyArrayMethods, PyUntypedArrayMethods,
};
use pyo3::prelude::*;

use crate::errors::value_error;

/// Rows of three as an (N, 3) float64 array.
pub fn rows3<'py>(
    py: Python<'py>,
    rows: impl ExactSizeIterator<Item = [f64; 3]>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let n = rows.len();
    let mut flat = Vec::with_capacity(3 * n);
    for row in rows {
        flat.extend_from_slice(&row);
    }
    PyArray1::from_vec(py, flat).reshape([n, 3])
}

/// Rows of four as an (N, 4) float64 array.
pub fn rows4<'py>(
    py: Python<'py>,
    rows: impl ExactSizeIterator<Item = [f64; 4]>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let n = rows.len();
    let mut flat = Vec::with_capacity(4 * n);
    for row in rows {
        flat.extend_from_slice(&row);
    }
    PyArray1::from_vec(py, flat).reshape([n, 4])
}

/// Vectors as an (N, 3) float64 array.
pub fn vectors<'py>(py: Python<'py>, items: &[DVec3]) -> PyResult<Bound<'py, PyArray2<f64>>> {
    rows3(py, items.iter().map(|v| v.to_array()))
}

/// An (N,) array of `items`.
pub fn column<'py, T: numpy::Element + Clone>(
    py: Python<'py>,
    items: &[T],
) -> Bound<'py, PyArray1<T>> {
    PyArray1::from_slice(py, items)
}

/// `value` read as `rows` vectors: an (N, 3) array of numbers, or anything
/// NumPy makes one of (a list of triples). `what` names it in messages.
pub fn read_vectors(value: &Bound<'_, PyAny>, what: &str, rows: usize) -> PyResult<Vec<DVec3>> {
    let array: PyArrayLikeDyn<'_, f64, AllowTypeChange> = value.extract().map_err(|e: PyErr| {
        value_error(format!(
            "{what}: expected an array of shape ({rows}, 3) of numbers: {}",
            e.value(value.py())
        ))
    })?;
    let shape = array.shape();
    if shape != [rows, 3] {
        let written = shape
            .iter()
            .map(usize::to_string)
            .collect::<Vec<_>>()
            .join(", ");
        let written = if shape.len() == 1 {
            format!("{written},")
        } else {
            written
        };
        return Err(value_error(format!(
            "{what}: expected an array of shape ({rows}, 3), one row per ball; got shape ({written})"
        )));
    }
    let view = array.as_array();
    Ok(view
        .rows()
        .into_iter()
        .map(|row| DVec3::new(row[0], row[1], row[2]))
        .collect())
}

/// `value` read as rows of three, as many as it has: an (N, 3) array.
pub fn read_rows(value: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<DVec3>> {
    let array: PyArrayLikeDyn<'_, f64, AllowTypeChange> = value.extract().map_err(|e: PyErr| {
        value_error(format!(
            "{what}: expected an array of shape (N, 3) of numbers: {}",
            e.value(value.py())
        ))
    })?;
    let rows = array.shape().first().copied().unwrap_or(0);
    read_vectors(value, what, rows)
}

/// One vector from three numbers. `what` names it in messages.
pub fn read_vector(value: &Bound<'_, PyAny>, what: &str) -> PyResult<DVec3> {
    let array: PyArrayLikeDyn<'_, f64, AllowTypeChange> = value.extract().map_err(|e: PyErr| {
        value_error(format!(
            "{what}: expected three numbers (x, y, z): {}",
            e.value(value.py())
        ))
    })?;
    if array.shape() != [3] {
        return Err(value_error(format!(
            "{what}: expected three numbers (x, y, z)"
        )));
    }
    let view = array.as_array();
    let v = DVec3::new(view[0], view[1], view[2]);
    if !v.is_finite() {
        return Err(value_error(format!("{what}: {} is not finite", show(v))));
    }
    Ok(v)
}

/// A vector as messages show it: `[0.1, 2, -0.5]`.
pub fn show(v: DVec3) -> String {
    format!("[{}, {}, {}]", v.x, v.y, v.z)
}
