//! A recorded run as a file (JSON Lines): a first line with the seed, the
//! scene the world began from, the ticks the recording spans and a digest
//! of its end state; then one line per input, with its tick.

use std::path::Path;

use anyhow::Context;
use serde::{Deserialize, Serialize};

use super::{Input, Timed};

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
            .map_err(|e| anyhow::anyhow!("{origin}:1: not a rolypoly recording: {}", shown(&e)))?;
        if log.format != REPLAY_FORMAT {
            anyhow::bail!(
                "{origin}:1: a recording of format {}, this program reads format {REPLAY_FORMAT}",
                log.format
            );
        }
        let mut last = 0;
        for (i, line) in lines {
            let timed: Timed = serde_json::from_str(line)
                .map_err(|e| anyhow::anyhow!("{origin}:{}: {}", i + 1, shown(&e)))?;
            if timed.tick < last || timed.tick > log.to_tick {
                anyhow::bail!(
                    "{origin}:{}: tick {} is out of order (after {last}, at most {})",
                    i + 1,
                    timed.tick,
                    log.to_tick
                );
            }
            // Loading a scene starts the journal over, so a recording holds
            // none; one would throw away the state the replay rebuilds.
            if matches!(timed.input, Input::Load { .. }) {
                anyhow::bail!(
                    "{origin}:{}: a recording holds no scene load (one starts a new recording)",
                    i + 1
                );
            }
            // A number beyond an f32 reads as infinite (a camera's): the
            // view would be lost, and the log not written back.
            if !writes_back(&timed) {
                anyhow::bail!("{origin}:{}: a number out of range", i + 1);
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

/// A parser's message, which quotes names from the file, on one line and
/// without the file's control characters (a name may hold `\n` or ESC).
fn shown(e: &serde_json::Error) -> String {
    e.to_string()
        .chars()
        .map(|c| {
            if c.is_control() {
                c.escape_default().to_string()
            } else {
                c.to_string()
            }
        })
        .collect()
}

/// Whether `timed` reads back from its text as it is.
fn writes_back(timed: &Timed) -> bool {
    serde_json::to_string(timed)
        .ok()
        .and_then(|text| serde_json::from_str::<Timed>(&text).ok())
        .is_some_and(|again| again == *timed)
}
