//! The hand: a ray picks a tumbler or a ball, the hand holds it by a
//! spring and lets go (I5).
//!
//! A tumbler is held at the point grabbed, by the scene's spring-damper. A
//! ball is held at its centre by a critically damped spring whose
//! stiffness is scaled by the ball's mass (as MuJoCo's perturbation and
//! Box2D's mouse joint do), so that every ball follows the hand alike,
//! and its weight is carried: it settles on the hand's point without
//! sagging and without overshoot, and flies off with its speed when let
//! go.

use crate::tumbler::Grip;
use glam::DVec3;
use serde::{Deserialize, Serialize};

use super::World;

/// How fast a held ball follows the hand: the spring's natural angular
/// frequency (rad/s), about three times a second, critically damped.
const BALL_HAND_OMEGA: f64 = 20.0;
/// The most the hand accelerates a ball (m/s²): fifty times gravity, so a
/// fling is fast but never a teleport.
const BALL_HAND_MAX_ACCELERATION: f64 = 500.0;

/// A ball held by the hand: which, and the point it is pulled to.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub(crate) struct BallHold {
    pub ball: usize,
    pub target: DVec3,
}

/// A ball hit by a pick ray.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BallPick {
    /// The ball's number.
    pub ball: usize,
    /// Where the ray hit it (m).
    pub point: DVec3,
    /// Distance along the ray.
    pub distance: f64,
}

/// Where a ray `origin + t dir` (`dir` of unit length) first meets the
/// sphere at `centre` of `radius`, for t >= 0 (from inside, where it leaves).
fn ray_hits_sphere(origin: DVec3, dir: DVec3, centre: DVec3, radius: f64) -> Option<f64> {
    let oc = origin - centre;
    let b = oc.dot(dir);
    let disc = b * b - (oc.length_squared() - radius * radius);
    if disc < 0.0 {
        return None;
    }
    let hit = -b - disc.sqrt();
    let hit = if hit >= 0.0 { hit } else { -b + disc.sqrt() };
    (hit >= 0.0).then_some(hit)
}

/// A tumbler hit by a pick ray.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pick {
    /// The tumbler hit.
    pub tumbler: usize,
    /// Where the ray hit it (m).
    pub point: DVec3,
    /// Distance along the ray.
    pub distance: f64,
}

impl World {
    /// The nearest tumbler sphere hit by the ray `origin + t dir`, t >= 0.
    pub fn pick(&self, origin: DVec3, dir: DVec3) -> Option<Pick> {
        let dir = dir.try_normalize()?;
        let mut best: Option<Pick> = None;
        for (ti, t) in self.tumblers.iter().enumerate() {
            for (si, s) in self.shape.spheres.iter().enumerate() {
                let c = t.sphere_center(&self.shape, si);
                let Some(hit) = ray_hits_sphere(origin, dir, c, s.radius) else {
                    continue;
                };
                if best.is_none_or(|p| hit < p.distance) {
                    best = Some(Pick {
                        tumbler: ti,
                        point: origin + dir * hit,
                        distance: hit,
                    });
                }
            }
        }
        best
    }

    /// The nearest live ball hit by the ray `origin + t dir`, t >= 0.
    pub fn pick_ball(&self, origin: DVec3, dir: DVec3) -> Option<BallPick> {
        let dir = dir.try_normalize()?;
        let b = &self.balls;
        (0..b.len())
            .filter(|&i| b.alive[i])
            .filter_map(|i| {
                let hit = ray_hits_sphere(origin, dir, b.position[i], b.radius[i])?;
                Some(BallPick {
                    ball: i,
                    point: origin + dir * hit,
                    distance: hit,
                })
            })
            .min_by(|p, q| p.distance.total_cmp(&q.distance))
    }

    /// Takes hold of ball `ball` by its centre, where it stands: the hand
    /// pulls it on from there (see [`World::drag_to`]).
    pub fn hold_ball(&mut self, ball: usize) {
        if ball < self.balls.len() && self.balls.alive[ball] {
            self.release();
            self.ball_hold = Some(BallHold {
                ball,
                target: self.balls.position[ball],
            });
        }
    }

    /// The ball being held, if any.
    pub fn held_ball(&self) -> Option<usize> {
        self.ball_hold.map(|h| h.ball)
    }

    /// The hand's pull on a held ball for a step of `dt`: its velocity
    /// after a step of the critically damped spring towards the hand,
    /// solved implicitly (stable at any step), with its weight carried.
    pub(super) fn pull_held_ball(&mut self, dt: f64) {
        let Some(hold) = self.ball_hold else {
            return;
        };
        let i = hold.ball;
        if !self.balls.alive.get(i).copied().unwrap_or(false) {
            self.ball_hold = None;
            return;
        }
        let (x, v) = (self.balls.position[i], self.balls.velocity[i]);
        let w = BALL_HAND_OMEGA;
        // v' = v + dt (w² (target - x - dt v') - 2 w v'), and gravity's
        // dt g taken back.
        let pulled = (v + dt * w * w * (hold.target - x)) / (1.0 + 2.0 * w * dt + w * w * dt * dt);
        let carried = pulled + DVec3::Y * (self.config.gravity * dt);
        let change = (carried - v).clamp_length_max(BALL_HAND_MAX_ACCELERATION * dt);
        self.balls.velocity[i] = v + change;
    }

    /// Takes hold of tumbler `tumbler` at world point `point` (I5).
    pub fn grab(&mut self, tumbler: usize, point: DVec3) {
        self.ball_hold = None;
        if let Some(t) = self.tumblers.get_mut(tumbler) {
            let anchor = t.orientation.inverse() * (point - t.center);
            t.grip = Some(Grip {
                anchor,
                target: point,
            });
        }
    }

    /// Moves the hand holding a tumbler or a ball; it follows through its
    /// spring.
    pub fn drag_to(&mut self, target: DVec3) {
        if let Some(hold) = &mut self.ball_hold {
            hold.target = target;
        }
        for t in &mut self.tumblers {
            if let Some(g) = &mut t.grip {
                g.target = target;
            }
        }
    }

    /// Lets go: the tumbler or ball keeps the motion it has.
    pub fn release(&mut self) {
        self.ball_hold = None;
        for t in &mut self.tumblers {
            t.grip = None;
        }
    }

    /// Index of the tumbler being held, if any.
    pub fn grabbed(&self) -> Option<usize> {
        self.tumblers.iter().position(|t| t.grip.is_some())
    }
}
