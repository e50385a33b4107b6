//! What the physics reports after a step (P9). The particle effects and the
//! trace consume these; the physics knows nothing of either.

use crate::room::Surface;
use glam::DVec3;
use serde::{Deserialize, Serialize};

/// Which bodies met.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum EventKind {
    /// A ball hit one of the room's surfaces.
    BallSurface {
        /// The ball's number.
        ball: usize,
        /// The surface.
        surface: Surface,
    },
    /// Two balls hit each other.
    BallBall {
        /// One ball's number.
        a: usize,
        /// The other's.
        b: usize,
    },
    /// A ball hit a tumbler.
    BallTumbler {
        /// The ball's number.
        ball: usize,
        /// The tumbler's number.
        tumbler: usize,
        /// Which of its six spheres.
        sphere: usize,
    },
    /// The fireball hit a surface.
    FireballSurface {
        /// The surface.
        surface: Surface,
    },
    /// The fireball caught a ball.
    FireballBall {
        /// The ball's number.
        ball: usize,
    },
    /// The fireball hit a tumbler.
    FireballTumbler {
        /// The tumbler's number.
        tumbler: usize,
        /// Which of its six spheres.
        sphere: usize,
    },
}

/// One impact: where, along which normal, and how hard.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Event {
    /// Which bodies met.
    pub kind: EventKind,
    /// The contact point in world space.
    pub point: DVec3,
    /// The contact normal, pointing from the second body (or the surface)
    /// towards the first.
    pub normal: DVec3,
    /// Approach speed along the normal just before the impact (m/s).
    pub speed: f64,
    /// When it happened, in seconds after the step's start (0 to the
    /// step's `dt`): what places its sound to the sample.
    pub within_step: f64,
}

impl EventKind {
    /// The same event with every ball number passed through `f`.
    pub(crate) fn renumber_balls(self, f: impl Fn(usize) -> usize) -> EventKind {
        match self {
            EventKind::BallSurface { ball, surface } => EventKind::BallSurface {
                ball: f(ball),
                surface,
            },
            EventKind::BallBall { a, b } => EventKind::BallBall { a: f(a), b: f(b) },
            EventKind::BallTumbler {
                ball,
                tumbler,
                sphere,
            } => EventKind::BallTumbler {
                ball: f(ball),
                tumbler,
                sphere,
            },
            EventKind::FireballBall { ball } => EventKind::FireballBall { ball: f(ball) },
            other => other,
        }
    }
}
