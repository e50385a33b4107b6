//! Friction between a ball and a tumbler (F1): Coulomb friction at the
//! contact point along two tangents, each held within `mu` times the
//! normal impulse of the stage, so that a spinning ball throws a tumbler
//! and a tumbler's turn carries a ball along.
//!
//! The ball's coefficient rules the pair (`balls.friction`): a tumbler has
//! a coefficient for its floor alone. The tumbler's side of each tangent row
//! is its response to an impulse there, rolling or sliding on the floor as
//! it is (see [`crate::Tumbler`]), as for the normal row.

use crate::tumbler::Response;
use glam::DVec3;

use super::{Bodies, BodyRef, Contact, Contacts};

/// A contact's two friction rows: their directions, masses, the tumbler's
/// response along each, and the impulses accumulated over a stage.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct TangentRows {
    tangents: [DVec3; 2],
    mass: [f64; 2],
    response: [Response; 2],
    impulse: [f64; 2],
}

impl Bodies<'_> {
    /// Readies a ball-tumbler contact's friction rows for a stage, from
    /// nothing; other contacts have none.
    pub(super) fn prepare_friction(&self, c: &mut Contact) {
        c.slide = TangentRows::default();
        let (BodyRef::Ball(i), BodyRef::Tumbler(..)) = (c.a, c.b) else {
            return;
        };
        if c.friction <= 0.0 {
            return;
        }
        let (t1, t2) = c.normal.any_orthonormal_pair();
        let arm = c.point - self.balls.position[i];
        let inv_inertia = self.balls.inv_inertia(i);
        for (k, t) in [t1, t2].into_iter().enumerate() {
            let ball = self.balls.inv_mass[i] + arm.cross(t).length_squared() * inv_inertia;
            let (tumbler, response) = self.response(c.b, c.point, t);
            let w = ball + tumbler;
            c.slide.tangents[k] = t;
            c.slide.mass[k] = if w > 0.0 { 1.0 / w } else { 0.0 };
            c.slide.response[k] = response;
        }
    }

    /// One Gauss-Seidel update of a ball-tumbler contact's friction rows,
    /// within `mu` times the normal impulse of the stage so far.
    pub(super) fn solve_friction(&mut self, c: &mut Contact) {
        let (BodyRef::Ball(i), BodyRef::Tumbler(..)) = (c.a, c.b) else {
            return;
        };
        let limit = c.friction * c.impulse;
        if limit <= 0.0 && c.slide.impulse == [0.0; 2] {
            return;
        }
        let arm = c.point - self.balls.position[i];
        let inv_inertia = self.balls.inv_inertia(i);
        for k in 0..2 {
            let t = c.slide.tangents[k];
            let ball = self.balls.velocity[i] + self.balls.spin[i].cross(arm);
            let slip = (ball - self.velocity(c.b, c.point)).dot(t);
            let held = &mut c.slide.impulse[k];
            let total = (*held - c.slide.mass[k] * slip).clamp(-limit, limit);
            let delta = total - *held;
            *held = total;
            self.balls.velocity[i] += t * (delta * self.balls.inv_mass[i]);
            self.balls.spin[i] += arm.cross(t) * (delta * inv_inertia);
            let response = c.slide.response[k];
            self.push(c.b, t, &response, -delta);
        }
    }
}

impl Contacts {
    /// The impulse the tumblers gave balls over a stage, normal and
    /// friction, through the ball-tumbler contacts `solved` tells (N s).
    pub(super) fn tumbler_impulse_on_balls<F>(&self, solved: F) -> DVec3
    where
        F: Fn(&Contact) -> bool,
    {
        self.tumbler_contacts
            .iter()
            .filter(|c| matches!((c.a, c.b), (BodyRef::Ball(_), BodyRef::Tumbler(..))) && solved(c))
            .fold(DVec3::ZERO, |sum, c| {
                let [t1, t2] = c.slide.tangents;
                let [f1, f2] = c.slide.impulse;
                sum + c.normal * c.impulse + t1 * f1 + t2 * f2
            })
    }
}
