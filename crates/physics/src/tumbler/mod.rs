//! The roly-poly tumbler (P6): a heavy, axisymmetric compound of six spheres
//! whose round bottom rests on the floor and whose centre of mass lies below
//! the bottom sphere's centre, so that gravity always rights it.
//!
//! The bottom sphere never leaves the floor, so its centre `C` stays at height
//! `R`. That removes one degree of freedom exactly (no penetration, no drift)
//! and leaves the tumbler free to rock, spin and move over the floor. At the
//! contact point `P = C - R y` the floor pushes up with a normal force `N` and
//! holds it with friction `f`:
//!
//! * rolling: `P` does not move, `v_C = R w x y`, and `f` is whatever rolling
//!   needs, as long as `|f| <= mu N`;
//! * sliding: `P` slips, and friction is `-mu N` along the slip.
//!
//! Newton-Euler for the centre of mass `G`, with both forces acting at `P`,
//! gives six linear equations in six unknowns per mode ([`grounded_solve`]).
//! The same equations with impulses in place of forces resolve collisions:
//! an impulse `J` at a point `Q` turns the tumbler about its contact point,
//! `I_P dw = (Q - P) x J`, where `I_P` is the inertia about `P` (the torque
//! about the contact point).
//!
//! The bottom never lifts off: where the floor would have to pull it down
//! (a violent spin, a hard knock from below), the floor holds it without
//! friction instead. Tumblers are heavy and low, so this is rare; it keeps
//! the motion energy-consistent.
//!
//! The parts, a file each: [`shape`], the shape and its mass properties;
//! [`grounded`], the grounded equations and their integration over a step.
//! This file holds a tumbler's state and how it answers impulses.

use crate::config::TumblerPlacement;
use glam::{DMat3, DQuat, DVec3};
use serde::{Deserialize, Serialize};

mod grounded;
mod shape;

pub(crate) use grounded::{GroundedParams, grounded_solve};
pub use shape::{TumblerShape, axis_extent};

/// How the round bottom meets the floor during a step.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub(crate) enum FloorMode {
    Rolling,
    /// Slipping along this horizontal unit direction.
    Sliding(DVec3),
}

/// Velocity change of a tumbler per unit impulse.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Response {
    pub angular_velocity: DVec3,
    pub center_velocity: DVec3,
}

/// A spring-damper "hand" holding a tumbler at a point fixed in its body.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Grip {
    /// The grab point in the body frame (relative to the bottom sphere's centre).
    pub anchor: DVec3,
    /// Where the hand pulls the grab point to (world).
    pub target: DVec3,
}

/// One tumbler's state.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Tumbler {
    /// Centre of the bottom sphere; its height is always the floor + R.
    pub(crate) center: DVec3,
    pub(crate) orientation: DQuat,
    /// Velocity of `center` (horizontal).
    pub(crate) center_velocity: DVec3,
    pub(crate) angular_velocity: DVec3,
    pub(crate) mode: FloorMode,
    pub(crate) grip: Option<Grip>,
    /// Copies of the shape's `R` and centre of mass, so that a tumbler can
    /// answer questions about itself.
    pub(crate) bottom_radius: f64,
    pub(crate) com_body: DVec3,
}

impl Tumbler {
    pub(crate) fn new(shape: &TumblerShape, placement: &TumblerPlacement, floor_y: f64) -> Tumbler {
        let axis = DVec3::new(placement.tilt_axis.x, 0.0, placement.tilt_axis.z);
        let orientation = if axis.length_squared() > 0.0 && placement.tilt_deg != 0.0 {
            DQuat::from_axis_angle(axis.normalize(), placement.tilt_deg.to_radians())
        } else {
            DQuat::IDENTITY
        };
        Tumbler {
            center: DVec3::new(placement.x, floor_y + shape.bottom_radius, placement.z),
            orientation,
            center_velocity: DVec3::ZERO,
            angular_velocity: DVec3::ZERO,
            mode: FloorMode::Rolling,
            grip: None,
            bottom_radius: shape.bottom_radius,
            com_body: shape.center_of_mass,
        }
    }

    /// Centre of the bottom sphere (world).
    pub fn bottom_center(&self) -> DVec3 {
        self.center
    }

    /// Its orientation, body frame to world.
    pub fn orientation(&self) -> DQuat {
        self.orientation
    }

    /// The axis of symmetry, pointing from the bottom to the head.
    pub fn axis(&self) -> DVec3 {
        self.orientation * DVec3::Y
    }

    /// Angle between the axis and the vertical, in radians.
    pub fn tilt(&self) -> f64 {
        self.axis().y.clamp(-1.0, 1.0).acos()
    }

    /// Its centre of mass in the world (m).
    pub fn center_of_mass(&self) -> DVec3 {
        self.center + self.orientation * self.com_body
    }

    /// The velocity of its centre of mass (m/s).
    pub fn linear_velocity(&self) -> DVec3 {
        self.center_velocity
            + self
                .angular_velocity
                .cross(self.orientation * self.com_body)
    }

    /// Its angular velocity (rad/s).
    pub fn angular_velocity(&self) -> DVec3 {
        self.angular_velocity
    }

    /// The point of the round bottom that touches the floor.
    pub fn contact_point(&self) -> DVec3 {
        self.center - self.bottom_radius * DVec3::Y
    }

    /// Velocity of the material point at the floor contact: zero while rolling.
    pub fn contact_velocity(&self) -> DVec3 {
        self.center_velocity - self.bottom_radius * self.angular_velocity.cross(DVec3::Y)
    }

    /// Whether its bottom slides over the floor rather than rolls.
    pub fn sliding(&self) -> bool {
        matches!(self.mode, FloorMode::Sliding(_))
    }

    /// The hand's hold on it, if held.
    pub fn grip(&self) -> Option<Grip> {
        self.grip
    }

    /// World centre of sphere `i` of `shape`.
    pub fn sphere_center(&self, shape: &TumblerShape, i: usize) -> DVec3 {
        self.center + self.orientation * DVec3::new(0.0, shape.spheres[i].height, 0.0)
    }

    /// Velocity of a world point rigidly attached to the tumbler.
    pub fn point_velocity(&self, point: DVec3) -> DVec3 {
        self.center_velocity + self.angular_velocity.cross(point - self.center)
    }

    /// Inertia about the centre of mass, in world axes.
    pub(crate) fn world_inertia(&self, shape: &TumblerShape) -> DMat3 {
        let r = DMat3::from_quat(self.orientation);
        r * shape.inertia * r.transpose()
    }

    /// Inverse of the inertia about the floor contact point, in world axes:
    /// how an impulse's moment about `P` turns a rolling tumbler.
    pub(crate) fn contact_inertia_inverse(&self, shape: &TumblerShape) -> DMat3 {
        let r = self.center_of_mass() - self.contact_point();
        let shift = DMat3::from_diagonal(DVec3::splat(r.length_squared())) - outer(r, r);
        (self.world_inertia(shape) + shape.mass * shift).inverse()
    }

    /// How the velocities change per unit impulse along `n` at `point`.
    ///
    /// Rolling, the floor's reaction is impulsive too and holds the contact
    /// point: the tumbler turns about it, `I_P dw = (point - P) x n`.
    /// Sliding, the floor pushes only up, with kinetic friction against the
    /// slip, as in [`grounded_solve`].
    pub(crate) fn impulse_response(
        &self,
        shape: &TumblerShape,
        contact_inv: &DMat3,
        friction: f64,
        point: DVec3,
        n: DVec3,
    ) -> Response {
        match self.mode {
            FloorMode::Rolling => {
                let dw = *contact_inv * (point - self.contact_point()).cross(n);
                Response {
                    angular_velocity: dw,
                    center_velocity: self.bottom_radius * dw.cross(DVec3::Y),
                }
            }
            FloorMode::Sliding(_) => {
                let g = self.center_of_mass();
                let sol = grounded_solve(
                    shape,
                    self.orientation,
                    self.mode,
                    friction,
                    n,
                    (point - g).cross(n),
                );
                Response {
                    angular_velocity: sol.dw,
                    center_velocity: sol.planar,
                }
            }
        }
    }

    pub(crate) fn apply_response(&mut self, r: &Response, impulse: f64) {
        self.angular_velocity += r.angular_velocity * impulse;
        self.center_velocity += r.center_velocity * impulse;
    }

    /// Kinetic energy, moving and turning (J).
    pub fn kinetic_energy(&self, shape: &TumblerShape) -> f64 {
        let v = self.linear_velocity();
        let w = self.angular_velocity;
        0.5 * shape.mass * v.length_squared() + 0.5 * w.dot(self.world_inertia(shape) * w)
    }
}

fn outer(a: DVec3, b: DVec3) -> DMat3 {
    DMat3::from_cols(a * b.x, a * b.y, a * b.z)
}

/// `skew(v) * w == v.cross(w)`.
fn skew(v: DVec3) -> DMat3 {
    DMat3::from_cols(
        DVec3::new(0.0, v.z, -v.y),
        DVec3::new(-v.z, 0.0, v.x),
        DVec3::new(v.y, -v.x, 0.0),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::WorldConfig;

    #[test]
    fn impulse_response_matches_pivot_inertia() {
        // The general grounded equations with an impulse must agree with the
        // closed form I_P dw = (Q - P) x J used by the contact solver.
        let cfg = WorldConfig::default();
        let shape = TumblerShape::new(&cfg.tumblers.spheres);
        let mut placement = cfg.tumblers.placements[0];
        placement.tilt_deg = 25.0;
        placement.tilt_axis = DVec3::new(1.0, 0.0, 0.4);
        let t = Tumbler::new(&shape, &placement, 0.0);
        let q = t.sphere_center(&shape, 3) + DVec3::new(0.1, 0.05, -0.02);
        let j = DVec3::new(0.7, -0.3, 1.1);
        let g = t.center_of_mass();
        let sol = grounded_solve(
            &shape,
            t.orientation,
            FloorMode::Rolling,
            0.6,
            j,
            (q - g).cross(j),
        );
        let closed = t.contact_inertia_inverse(&shape) * (q - t.contact_point()).cross(j);
        assert!(
            (sol.dw - closed).length() < 1e-10,
            "{:?} vs {:?}",
            sol.dw,
            closed
        );
    }
}
