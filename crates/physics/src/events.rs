//! What the physics reports after a step (P9). The particle effects and the
//! trace consume these; the physics knows nothing of either.

use crate::room::Surface;
use glam::DVec3;

/// Which bodies met.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum EventKind {
    BallSurface {
        ball: usize,
        surface: Surface,
    },
    BallBall {
        a: usize,
        b: usize,
    },
    BallTumbler {
        ball: usize,
        tumbler: usize,
        sphere: usize,
    },
    FireballSurface {
        surface: Surface,
    },
    FireballBall {
        ball: usize,
    },
    FireballTumbler {
        tumbler: usize,
        sphere: usize,
    },
}

/// One impact: where, along which normal, and how hard.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Event {
    pub kind: EventKind,
    /// The contact point in world space.
    pub point: DVec3,
    /// The contact normal, pointing from the second body (or the surface)
    /// towards the first.
    pub normal: DVec3,
    /// Approach speed along the normal just before the impact (m/s).
    pub speed: f64,
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
