//! The rolypoly program: scene files, the command line and the headless
//! commands, on top of the `rolypoly_physics` simulation.
//!
//! The binary (`main.rs`) only parses arguments and reports errors; the
//! pieces live here so that tests and later front ends can reuse them.

#![warn(missing_docs)]

// clap turns doc comments into --help text: the command line's flattened
// groups and its subcommand field, which should add nothing to that text,
// carry none.
#[allow(missing_docs)]
pub mod cli;
pub mod clip;
pub mod commands;
pub mod egui_paint;
pub mod engine;
pub mod frames;
pub mod legend;
pub mod progress;
pub mod sandbox;
pub mod scene;
pub mod simulation;
pub mod sound;
pub mod trace;
pub mod window;

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
