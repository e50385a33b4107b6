//! The program's errors as Python exceptions: a bad scene, key or value is
//! a `ValueError`, a file that cannot be read or written an `OSError`, a
//! graphics adapter that fails a `rolypoly.DeviceError`. Each carries the
//! program's own one-line message, causes included.

use std::error::Error;
use std::io;

use pyo3::exceptions::{
    PyFileNotFoundError, PyIsADirectoryError, PyOSError, PyPermissionError, PyRuntimeError,
    PyValueError,
};
use pyo3::prelude::*;
use rolypoly_core::scene::SceneError;
use rolypoly_gpu::GpuError;

pyo3::create_exception!(
    rolypoly,
    DeviceError,
    PyRuntimeError,
    "The graphics adapter could not be opened, or failed while it drew or stepped."
);

/// `error` and its causes on one line, separated by ": ", as the program
/// prints them.
pub fn one_line(error: &dyn Error) -> String {
    let mut text = error.to_string();
    let mut cause = error.source();
    while let Some(inner) = cause {
        let part = inner.to_string();
        // A transparent wrapper repeats its cause's text.
        if !text.ends_with(&part) {
            text.push_str(": ");
            text.push_str(&part);
        }
        cause = inner.source();
    }
    text
}

/// An I/O failure as the `OSError` subclass Python would raise, with
/// `message` (which names the file).
pub fn io_error(kind: io::ErrorKind, message: String) -> PyErr {
    match kind {
        io::ErrorKind::NotFound => PyFileNotFoundError::new_err(message),
        io::ErrorKind::PermissionDenied => PyPermissionError::new_err(message),
        io::ErrorKind::IsADirectory => PyIsADirectoryError::new_err(message),
        _ => PyOSError::new_err(message),
    }
}

/// A scene that could not be loaded.
pub fn scene_error(error: &SceneError) -> PyErr {
    match error {
        SceneError::Read { source, .. } => io_error(source.kind(), one_line(error)),
        _ => PyValueError::new_err(one_line(error)),
    }
}

/// The GPU engine's failures: what the scene asks for and it cannot do is
/// a `ValueError`, the adapter's own trouble a `DeviceError`.
pub fn gpu_error(error: &GpuError) -> PyErr {
    match error {
        GpuError::Unsupported(_) | GpuError::Build(_) => PyValueError::new_err(one_line(error)),
        _ => DeviceError::new_err(one_line(error)),
    }
}

/// Drawing failed: the adapter's trouble.
pub fn device_error(error: &anyhow::Error) -> PyErr {
    DeviceError::new_err(format!("{error:#}"))
}

/// A bad argument, in one line.
pub fn value_error(message: impl Into<String>) -> PyErr {
    PyValueError::new_err(message.into())
}
