//! A recorded run as a file (JSON Lines): a first line with the seed, the
//! scene the world began from, the ticks the recording spans and a digest
//! of its end state; then one line per input, with its tick.

use std::path::Path;

use anyhow::Context;
use serde::{Deserialize, Serialize};

use super::Timed;

/// The version of the file's layout this program writes and reads.
pub const REPLAY_FORMAT: u32 = 1;

/// A recorded run.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ReplayLog {
    /// [`REPLAY_FORMAT`].
    pub format: u32,
    /// The seed of the world's random start.
    pub seed: u64,
    /// The name of the scene the world's line began from.
    pub name: String,
    /// That scene's settings, as a scene file.
    pub scene: String,
    /// Ticks from the line's start to where the recording starts.
    pub from_tick: u64,
    /// Ticks from the line's start to where it ends.
    pub to_tick: u64,
    /// [`super::Sandbox::digest`] at `to_tick`.
    pub end_digest: String,
    /// Every input from the line's start, in order.
    #[serde(skip)]
    pub inputs: Vec<Timed>,
}

impl ReplayLog {
    /// The file's text.
    pub fn to_text(&self) -> String {
        let mut text = serde_json::to_string(self).unwrap_or_default();
        text.push('\n');
        for input in &self.inputs {
            text += &serde_json::to_string(input).unwrap_or_default();
            text.push('\n');
        }
        text
    }

    /// Reads the text of a file named `origin`; errors name its line.
    pub fn parse(text: &str, origin: &str) -> anyhow::Result<ReplayLog> {
        let mut lines = text
            .lines()
            .enumerate()
            .filter(|(_, l)| !l.trim().is_empty());
        let (_, first) = lines
            .next()
            .with_context(|| format!("{origin}: the file is empty, not a recording"))?;
        let mut log: ReplayLog = serde_json::from_str(first)
            .map_err(|e| anyhow::anyhow!("{origin}:1: not a rolypoly recording: {e}"))?;
        if log.format != REPLAY_FORMAT {
            anyhow::bail!(
                "{origin}:1: a recording of format {}, this program reads format {REPLAY_FORMAT}",
                log.format
            );
        }
        let mut last = 0;
        for (i, line) in lines {
            let timed: Timed = serde_json::from_str(line)
                .map_err(|e| anyhow::anyhow!("{origin}:{}: {e}", i + 1))?;
            if timed.tick < last || timed.tick > log.to_tick {
                anyhow::bail!(
                    "{origin}:{}: tick {} is out of order (after {last}, at most {})",
                    i + 1,
                    timed.tick,
                    log.to_tick
                );
            }
            last = timed.tick;
            log.inputs.push(timed);
        }
        if log.from_tick > log.to_tick {
            anyhow::bail!(
                "{origin}:1: the recording starts at tick {} after it ends at {}",
                log.from_tick,
                log.to_tick
            );
        }
        Ok(log)
    }

    /// Reads the recording at `path`.
    pub fn read(path: &Path) -> anyhow::Result<ReplayLog> {
        let text = std::fs::read_to_string(path)
            .with_context(|| format!("cannot read recording `{}`", path.display()))?;
        ReplayLog::parse(&text, &path.display().to_string())
    }

    /// Writes it to `path`.
    pub fn write(&self, path: &Path) -> anyhow::Result<()> {
        std::fs::write(path, self.to_text())
            .with_context(|| format!("cannot write recording `{}`", path.display()))
    }
}
