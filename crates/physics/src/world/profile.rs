//! How long each stage of the last step took, as the step names its
//! stages: for a profiler. Timed on the clock as the step runs, lap after
//! lap, so that the stages add up to the step (less the moments between
//! laps); a step retaken for its energy adds its retake to the same stages.

use std::time::{Duration, Instant};

/// A stage of the step, in the order it runs (see the world's `step`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    /// Pouring balls and the hand's pull.
    Setup,
    /// The broadphase grid, and the balls sorted by its cells.
    Grid,
    /// Finding the contacts.
    Contacts,
    /// Impacts resolved one by one in time order.
    Impacts,
    /// The contact solver's predict stage.
    Solve,
    /// Moving the balls and the tumblers.
    Move,
    /// The solver's project stage.
    Project,
    /// Events and colours, sunk balls pushed apart, the balls written back.
    Report,
    /// The energy check (and any retake's bookkeeping) and the fireball.
    Finish,
}

impl Stage {
    /// Every stage, in order.
    pub const ALL: [Stage; 9] = [
        Stage::Setup,
        Stage::Grid,
        Stage::Contacts,
        Stage::Impacts,
        Stage::Solve,
        Stage::Move,
        Stage::Project,
        Stage::Report,
        Stage::Finish,
    ];

    /// Its name, for a profiler's legend.
    pub fn name(self) -> &'static str {
        match self {
            Stage::Setup => "setup",
            Stage::Grid => "grid",
            Stage::Contacts => "contacts",
            Stage::Impacts => "impacts",
            Stage::Solve => "solve",
            Stage::Move => "move",
            Stage::Project => "project",
            Stage::Report => "report",
            Stage::Finish => "finish",
        }
    }
}

/// The last step's time, stage by stage, and what it worked on.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct StepTimes {
    /// Each stage's time, in the order of [`Stage::ALL`].
    pub stages: [Duration; Stage::ALL.len()],
    /// The whole step, from its start to its end.
    pub total: Duration,
    /// Pairs of balls the solver worked on.
    pub pairs: usize,
    /// Ball-wall contacts and contacts with tumblers the solver worked on.
    pub other_contacts: usize,
    /// Impacts reported (events).
    pub impacts: usize,
}

impl StepTimes {
    /// The time of `stage`.
    pub fn of(&self, stage: Stage) -> Duration {
        self.stages[Stage::ALL.iter().position(|&s| s == stage).unwrap_or(0)]
    }

    /// Adds the time since `clock` to `stage`, and moves `clock` to now.
    pub(super) fn lap(&mut self, stage: Stage, clock: &mut Instant) {
        let now = Instant::now();
        let k = Stage::ALL.iter().position(|&s| s == stage).unwrap_or(0);
        self.stages[k] += now - *clock;
        *clock = now;
    }
}
