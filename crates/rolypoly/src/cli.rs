//! The command line (SPEC A1-A3): global scene options and the subcommands.

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand};

use crate::scene::Overrides;

/// Help section of the options shared by every command.
const SCENE_HEADING: &str = "Scene options";

/// How long `rolypoly` runs when it is given no subcommand, in seconds.
pub const DEFAULT_SECONDS: f64 = 10.0;

/// rolypoly: a 3D toy room where roly-poly tumblers rock, balls bounce and a
/// fireball tears through.
///
/// Without a subcommand it simulates the scene for 10 seconds and prints a
/// summary. Every constant of a scene comes from a TOML scene file that
/// overrides the built-in default (see scenes/default.toml for the format).
#[derive(Debug, Parser)]
#[command(
    name = "rolypoly",
    version,
    about,
    long_about,
    propagate_version = true
)]
pub struct Cli {
    #[command(flatten)]
    pub scene: SceneArgs,

    #[command(subcommand)]
    pub command: Option<Command>,
}

/// Options that choose and adjust the scene; accepted before or after the
/// subcommand.
#[derive(Debug, Args)]
pub struct SceneArgs {
    /// Scene file (TOML) whose keys override the built-in default scene.
    #[arg(long, value_name = "FILE", global = true, help_heading = SCENE_HEADING)]
    pub scene: Option<PathBuf>,

    /// Seed of the random start (ball positions and velocities); the same
    /// seed gives the same run, step for step.
    #[arg(
        long,
        value_name = "N",
        default_value_t = 1,
        global = true,
        help_heading = SCENE_HEADING
    )]
    pub seed: u64,

    /// Number of balls (overrides balls.count of the scene; 0 ..= 1000000).
    #[arg(long, value_name = "N", global = true, help_heading = SCENE_HEADING)]
    pub balls: Option<usize>,

    /// Gravity in m/s^2 (overrides gravity of the scene; 0 ..= 100).
    #[arg(
        long,
        value_name = "G",
        global = true,
        help_heading = SCENE_HEADING,
        allow_negative_numbers = true
    )]
    pub gravity: Option<f64>,
}

impl SceneArgs {
    /// The command-line settings that override the scene file.
    pub fn overrides(&self) -> Overrides {
        Overrides {
            balls: self.balls,
            gravity: self.gravity,
        }
    }
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Simulate a scene without a window or GPU and print a summary, or
    /// write a JSON Lines trace of every body, the energy and the events.
    Simulate(SimulateArgs),
}

#[derive(Debug, Args)]
pub struct SimulateArgs {
    #[command(flatten)]
    pub length: Length,

    /// Write a JSON Lines trace to FILE (`-` for standard output): a scene
    /// line, then a state line at step 0, every K steps and at the last step.
    #[arg(long, value_name = "FILE|-")]
    pub trace: Option<PathBuf>,

    /// Write a state line every K steps (K >= 1); each line carries all
    /// events since the previous one.
    #[arg(
        long,
        value_name = "K",
        default_value_t = 1,
        value_parser = clap::value_parser!(u64).range(1..)
    )]
    pub every: u64,

    /// Launch the fireball from the scene's spawn point before the first step.
    #[arg(long)]
    pub fireball: bool,
}

/// How long to simulate: exactly one of the two.
#[derive(Debug, Args)]
#[group(required = true, multiple = false)]
pub struct Length {
    /// Number of fixed time steps to simulate.
    #[arg(long, value_name = "N")]
    pub steps: Option<u64>,

    /// Simulated seconds, rounded to the nearest whole number of steps.
    #[arg(long, value_name = "S", value_parser = parse_seconds)]
    pub seconds: Option<f64>,
}

/// A length of simulated time: finite and not negative.
fn parse_seconds(text: &str) -> Result<f64, String> {
    let seconds: f64 = text
        .parse()
        .map_err(|_| format!("`{text}` is not a number of seconds"))?;
    if seconds.is_finite() && (0.0..=1e9).contains(&seconds) {
        Ok(seconds)
    } else {
        Err(format!(
            "{seconds} is out of range: allowed 0 ..= 1000000000"
        ))
    }
}

/// The number of steps that covers `seconds` at time step `dt`.
pub fn steps_for(seconds: f64, dt: f64) -> u64 {
    // Both are range-checked, so the quotient is finite and not negative.
    (seconds / dt).round() as u64
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::CommandFactory;

    #[test]
    fn cli_is_well_formed() {
        Cli::command().debug_assert();
    }

    #[test]
    fn scene_options_go_before_or_after_the_subcommand() {
        let cli =
            Cli::try_parse_from(["rolypoly", "--seed", "7", "simulate", "--steps", "3"]).unwrap();
        assert_eq!(cli.scene.seed, 7);
        let cli =
            Cli::try_parse_from(["rolypoly", "simulate", "--steps", "3", "--seed", "8"]).unwrap();
        assert_eq!(cli.scene.seed, 8);
    }

    #[test]
    fn steps_and_seconds_are_exclusive_and_one_is_required() {
        assert!(Cli::try_parse_from(["rolypoly", "simulate"]).is_err());
        assert!(
            Cli::try_parse_from(["rolypoly", "simulate", "--steps", "3", "--seconds", "1"])
                .is_err()
        );
        assert!(Cli::try_parse_from(["rolypoly", "simulate", "--seconds", "-1"]).is_err());
        assert!(
            Cli::try_parse_from(["rolypoly", "simulate", "--steps", "1", "--every", "0"]).is_err()
        );
    }

    #[test]
    fn seconds_round_to_steps() {
        assert_eq!(steps_for(10.0, 1.0 / 120.0), 1200);
        assert_eq!(steps_for(0.0, 1.0 / 120.0), 0);
    }
}
