//! The rolypoly toy room as a library, below the program and the Python
//! package: scene files (their keys, defaults and checks), the run that
//! steps the world and its effects ([`simulation`]) with its balls on
//! either engine ([`balls`]),
//! its state as bytes ([`snapshot`]), traces of it, and what both front ends draw and hear of a run (the
//! frames of a moment, clips, the sound). No command line, no window, no
//! audio device.

#![warn(missing_docs)]

pub mod balls;
pub mod clip;
pub mod engine;
pub mod frames;
pub mod progress;
pub mod scene;
pub mod series;
pub mod simulation;
pub mod snapshot;
pub mod sound;
pub mod trace;

/// The number of steps that covers `seconds` at time step `dt`.
pub fn steps_for(seconds: f64, dt: f64) -> u64 {
    // Both are range-checked, so the quotient is finite and not negative.
    (seconds / dt).round() as u64
}
