//! Rewind (T6): the last 30 s of the world's line kept as a copy of the
//! whole toy taken every second, and the inputs between them in the
//! journal. Going back to a tick restores the copy before it and steps on
//! to it, playing the inputs as they came; playing on from there, the
//! inputs that came after it the first time are played again as the world
//! reaches them, so that the run is bit for bit the one that happened,
//! until the player does something (see [`super::Sandbox::apply`]): then
//! that future is forgotten and a new one begins.

use std::collections::VecDeque;

use crate::scene::Scene;
use crate::simulation::Simulation;

use super::Timed;

/// How far back the history reaches (simulated seconds).
pub const REWIND_SECONDS: f64 = 30.0;
/// How often a copy of the toy is kept (simulated seconds): going back
/// steps on from the copy before, so at most this much.
const SNAPSHOT_SECONDS: f64 = 1.0;

/// The toy as it stood at the start of a tick.
#[derive(Clone)]
pub(super) struct Snapshot {
    pub tick: u64,
    pub sim: Simulation,
    pub scene: Scene,
    pub thrown: usize,
    /// How many of the journal's inputs came before it.
    pub inputs: usize,
}

/// The copies kept, and the inputs of the first time still ahead.
#[derive(Default)]
pub(super) struct History {
    snapshots: VecDeque<Snapshot>,
    /// After going back: the inputs that came next the first time, played
    /// again as their ticks come, until the player acts.
    pub ahead: VecDeque<Timed>,
    /// The furthest tick of this line of the world reached so far.
    pub furthest: u64,
}

/// Ticks between copies, and ticks kept, for a step of `dt`.
pub(super) fn spacing(dt: f64) -> (u64, u64) {
    let every = (SNAPSHOT_SECONDS / dt).round().max(1.0) as u64;
    (every, (REWIND_SECONDS / dt).round() as u64)
}

impl History {
    /// Forgets everything: a new line of the world begins at `snapshot`.
    pub fn begin(&mut self, snapshot: Snapshot) {
        self.snapshots.clear();
        self.ahead.clear();
        self.furthest = snapshot.tick;
        self.snapshots.push_back(snapshot);
    }

    /// Keeps `snapshot` (in place of any from its tick on, which belonged
    /// to a future now forgotten), and forgets those too old to be needed:
    /// one at or before `keep` ticks ago stays, so that the whole span can
    /// be reached.
    pub fn keep(&mut self, snapshot: Snapshot, keep: u64) {
        while self
            .snapshots
            .back()
            .is_some_and(|s| s.tick >= snapshot.tick)
        {
            self.snapshots.pop_back();
        }
        let oldest_needed = snapshot.tick.saturating_sub(keep);
        self.snapshots.push_back(snapshot);
        while self.snapshots.len() > 1 && self.snapshots[1].tick <= oldest_needed {
            self.snapshots.pop_front();
        }
    }

    /// The latest copy at or before `tick`.
    pub fn before(&self, tick: u64) -> Option<&Snapshot> {
        self.snapshots.iter().rev().find(|s| s.tick <= tick)
    }

    /// The earliest tick that can be gone back to.
    pub fn oldest(&self) -> u64 {
        self.snapshots.front().map_or(0, |s| s.tick)
    }

    /// The player acted at `tick`: the future of the first time is gone,
    /// and with it the copies taken in it.
    pub fn branch(&mut self, tick: u64) {
        self.ahead.clear();
        self.furthest = tick;
        while self.snapshots.back().is_some_and(|s| s.tick > tick) {
            self.snapshots.pop_back();
        }
    }

    /// How many copies are kept.
    pub fn len(&self) -> usize {
        self.snapshots.len()
    }
}
