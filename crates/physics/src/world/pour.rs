//! Pouring (see [`crate::PourConfig`]): the random balls wait out of the
//! room and are let go from the spout's mouth, falling, one after another
//! at the scene's rate, each from a random point of the mouth that no ball
//! covers, as sand runs from a funnel onto a heap.

use crate::balls::Tint;
use glam::DVec3;
use serde::{Deserialize, Serialize};

use super::{BuildError, World};

/// How many random points of the mouth a ball due tries in one step before
/// it waits for the next.
const TRIES_PER_BALL: usize = 4;

/// How fast a ball leaves the spout, straight down (m/s): as from a funnel
/// that the balls have fallen some centimetres through, so that each clears
/// the mouth for the next within a few steps. (The mouth passes at most
/// about a third of its area's worth of balls times this speed a second.)
const STREAM_SPEED: f64 = 1.0;

/// Which random balls are still to pour, and how many are due.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
pub(super) struct Pour {
    /// The next ball to let go, and one past the last.
    next: usize,
    end: usize,
    /// Balls due but not yet let go (the rate times the time, less those).
    owed: f64,
}

impl Pour {
    /// Balls waiting to be poured.
    pub fn waiting(&self) -> usize {
        self.end - self.next
    }

    /// Whether the balls it would let go are among `balls` balls.
    pub fn within(&self, balls: usize) -> bool {
        self.next <= self.end && self.end <= balls && self.owed.is_finite()
    }
}

impl World {
    /// Whether the scene pours its random balls.
    pub(super) fn pours(&self) -> bool {
        self.config.balls.pour.rate > 0.0
    }

    /// Checks that the spout's mouth lies in the room with room for a ball
    /// under it.
    pub(super) fn check_spout(&self) -> Result<(), BuildError> {
        let pour = &self.config.balls.pour;
        let r = self.config.balls.radius;
        let reach = DVec3::new(pour.radius + r, r, pour.radius + r);
        let fits = pour.spout.is_finite()
            && pour.radius >= 0.0
            && (pour.spout - reach).cmpge(self.room.min).all()
            && (pour.spout + reach).cmple(self.room.max).all();
        if fits {
            Ok(())
        } else {
            Err(BuildError(format!(
                "the spout at {} with mouth radius {} (balls.pour) does not fit in the room with balls of radius {r}",
                pour.spout, pour.radius
            )))
        }
    }

    /// Parks the random balls `first..` to be poured.
    pub(super) fn park_for_pouring(&mut self, first: usize) {
        let spout = self.config.balls.pour.spout;
        for ball in first..self.balls.len() {
            self.balls.set(ball, spout, DVec3::ZERO);
            self.balls.spin[ball] = DVec3::ZERO;
            self.balls.alive[ball] = false;
            self.balls.tint[ball] = Tint::White;
        }
        self.pour = Pour {
            next: first,
            end: self.balls.len(),
            owed: 0.0,
        };
    }

    /// Random balls still waiting to be poured.
    pub fn balls_to_pour(&self) -> usize {
        self.pour.waiting()
    }

    /// Lets go the balls due this step (before the step, so that a new
    /// ball's energy is the world's before the step starts).
    pub(super) fn pour_due_balls(&mut self) {
        if self.pour.waiting() == 0 {
            return;
        }
        let rate = self.config.balls.pour.rate;
        self.pour.owed += rate * self.config.solver.dt;
        while self.pour.owed >= 1.0 && self.pour.waiting() > 0 {
            let Some(at) = self.clear_point_of_mouth() else {
                // The mouth is covered: the balls due wait, but no more
                // than a step's worth pile up.
                self.pour.owed = self.pour.owed.min(1.0 + rate * self.config.solver.dt);
                return;
            };
            let ball = self.pour.next;
            self.balls
                .set(ball, at, DVec3::new(0.0, -STREAM_SPEED, 0.0));
            self.balls.alive[ball] = true;
            self.poured += self.balls.mass[ball] * self.balls.velocity[ball];
            self.pour.next += 1;
            self.pour.owed -= 1.0;
        }
    }

    /// A random point of the spout's mouth where a new ball would touch no
    /// other, if one of a few tries finds one.
    fn clear_point_of_mouth(&mut self) -> Option<DVec3> {
        let pour = &self.config.balls.pour;
        let (spout, mouth, r) = (pour.spout, pour.radius, self.config.balls.radius);
        for _ in 0..TRIES_PER_BALL {
            // Uniform over the disc: the radius as the root of a uniform draw.
            let across = mouth * self.rng.unit().sqrt();
            let angle = std::f64::consts::TAU * self.rng.unit();
            let at = spout + DVec3::new(across * angle.cos(), 0.0, across * angle.sin());
            let b = &self.balls;
            let covered = (0..b.len()).any(|k| {
                b.alive[k] && b.position[k].distance_squared(at) < (b.radius[k] + r).powi(2)
            });
            if !covered {
                return Some(at);
            }
        }
        None
    }
}
