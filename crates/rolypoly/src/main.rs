//! `rolypoly`: parse the command line, run, and report any error as one
//! message with its causes and a non-zero exit status (A4).

use std::io::Write;
use std::process::ExitCode;

use clap::Parser;
use rolypoly::cli::Cli;

fn main() -> ExitCode {
    let cli = Cli::parse();
    match rolypoly::run(&cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) if rolypoly::is_broken_pipe(&error) => ExitCode::SUCCESS,
        Err(error) => {
            // `{:#}` prints the whole cause chain, separated by ": ".
            let _ = writeln!(std::io::stderr().lock(), "error: {error:#}");
            ExitCode::FAILURE
        }
    }
}
