//! The rolypoly program: the command line, the headless commands, the
//! window and its sandbox, on top of `rolypoly_core` (the scene and the
//! run).
//!
//! The binary (`main.rs`) only parses arguments and reports errors; the
//! pieces live here so that tests and later front ends can reuse them.

#![warn(missing_docs)]

// clap turns doc comments into --help text: the command line's flattened
// groups and its subcommand field, which should add nothing to that text,
// carry none.
#[allow(missing_docs)]
pub mod cli;
pub mod commands;
pub mod egui_paint;
pub mod legend;
pub mod sandbox;
pub mod window;

// The scene and the run are the library's; the program's own paths to
// them (`crate::scene`, ...) lead there.
pub use rolypoly_core::{clip, engine, frames, progress, scene, series, simulation, sound, trace};

use std::io;

pub use commands::run;

/// True when `error` comes from a closed pipe (`rolypoly ... | head`): the
/// reader has what it wanted, so this is no failure to report.
pub fn is_broken_pipe(error: &anyhow::Error) -> bool {
    error.chain().any(|cause| {
        cause
            .downcast_ref::<io::Error>()
            .is_some_and(|e| e.kind() == io::ErrorKind::BrokenPipe)
    })
}
