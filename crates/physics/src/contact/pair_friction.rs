//! Friction and rolling resistance between two balls in contact, as rows
//! of the predict stage beside each pair's normal row (F1).
//!
//! Friction acts at the contact point against its sliding, within the
//! Coulomb cone: the tangential impulse accumulated over the stage is kept
//! at most `mu` times the normal one, as a vector in the tangent plane (the
//! cone itself, not a pyramid of two tangents). For solid spheres the
//! contact point's sliding changes along the impulse alone, by
//! `1/m1 + r1^2/I1 + 1/m2 + r2^2/I2` per unit, so each update is one
//! division-free step. Rolling resistance resists the balls' relative spin
//! with a torque of at most `mu_r` times the normal impulse times the
//! pair's rolling radius `r1 r2 / (r1 + r2)` (Ai, Chen, Rotter and Ooi,
//! Powder Technology 2011, model A): a ball on a wall, whose rolling
//! radius is its own, feels the room's coefficient the same way.
//!
//! Both start from last step's impulses, so a heap's friction holds from
//! one step to the next instead of building up anew each step.

use crate::balls::{Balls, sphere_inertia};
use glam::DVec3;

use super::PairRow;

/// The friction coefficients of every ball pair.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct PairMaterial {
    /// Coulomb friction coefficient.
    pub friction: f64,
    /// Rolling resistance coefficient.
    pub rolling_resistance: f64,
}

impl PairMaterial {
    /// Whether the pairs have any friction rows to solve.
    pub fn any(&self) -> bool {
        self.friction > 0.0 || self.rolling_resistance > 0.0
    }
}

/// A pair's friction and rolling rows: what an iteration reads beside
/// the pair's [`PairRow`].
#[derive(Clone, Copy, Debug)]
pub(super) struct FrictionRow {
    /// The two balls' radii and inverse moments of inertia.
    radius: [f64; 2],
    inv_inertia: [f64; 2],
    /// Mass along a tangent at the contact point.
    tangent_mass: f64,
    /// Moment of inertia against relative spin.
    rolling_mass: f64,
    friction: f64,
    /// The largest rolling torque impulse per unit normal impulse.
    rolling_arm: f64,
}

/// A pair's accumulated friction impulse (on the first ball, in the
/// tangent plane) and rolling torque impulse (on the first ball).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct FrictionImpulse {
    pub tangent: DVec3,
    pub rolling: DVec3,
}

impl FrictionImpulse {
    /// Last step's impulses as a start for a pair along `normal` with
    /// normal impulse `normal_impulse`: the tangent impulse turned into the
    /// new tangent plane and both cut to what the coefficients allow.
    pub(super) fn starting(
        kept: FrictionImpulse,
        normal: DVec3,
        normal_impulse: f64,
        row: &FrictionRow,
    ) -> FrictionImpulse {
        let tangent = kept.tangent - kept.tangent.dot(normal) * normal;
        FrictionImpulse {
            tangent: clamp_length(tangent, row.friction * normal_impulse),
            rolling: clamp_length(kept.rolling, row.rolling_arm * normal_impulse),
        }
    }
}

/// `v` shortened to length `limit` if it is longer.
#[inline]
fn clamp_length(v: DVec3, limit: f64) -> DVec3 {
    let squared = v.length_squared();
    if squared > limit * limit {
        v * (limit / squared.sqrt())
    } else {
        v
    }
}

impl FrictionRow {
    pub fn new(i: usize, j: usize, balls: &Balls, material: PairMaterial) -> FrictionRow {
        let (ri, rj) = (balls.radius[i], balls.radius[j]);
        let inv_inertia = |k: usize| {
            let w = balls.inv_mass[k];
            if w > 0.0 {
                1.0 / sphere_inertia(balls.mass[k], balls.radius[k])
            } else {
                0.0
            }
        };
        let (ii, ij) = (inv_inertia(i), inv_inertia(j));
        let k_tangent = balls.inv_mass[i] + balls.inv_mass[j] + ri * ri * ii + rj * rj * ij;
        let k_rolling = ii + ij;
        let inverse = |k: f64| if k > 0.0 { 1.0 / k } else { 0.0 };
        FrictionRow {
            radius: [ri, rj],
            inv_inertia: [ii, ij],
            tangent_mass: inverse(k_tangent),
            rolling_mass: inverse(k_rolling),
            friction: material.friction,
            rolling_arm: material.rolling_resistance * ri * rj / (ri + rj),
        }
    }

    /// Applies `impulse` (of friction, and of rolling torque) to the two
    /// balls of `pair`: slots from `first` on.
    #[inline(always)]
    pub fn push(
        &self,
        pair: &PairRow,
        impulse: &FrictionImpulse,
        (velocity, spin): (&mut [DVec3], &mut [DVec3]),
        first: usize,
        inv_mass: &[f64],
    ) {
        let (i, j) = (pair.i as usize, pair.j as usize);
        let (ki, kj) = (i - first, j - first);
        let t = impulse.tangent;
        velocity[ki] += t * inv_mass[i];
        velocity[kj] -= t * inv_mass[j];
        // On i at -ri n, the opposite on j at +rj n: both turn against n x t.
        let turn = pair.normal.cross(t);
        spin[ki] +=
            impulse.rolling * self.inv_inertia[0] - turn * (self.radius[0] * self.inv_inertia[0]);
        spin[kj] -=
            impulse.rolling * self.inv_inertia[1] + turn * (self.radius[1] * self.inv_inertia[1]);
    }

    /// One Gauss-Seidel update of the pair's friction and rolling rows,
    /// their limits set by the pair's accumulated `normal_impulse`.
    #[inline(always)]
    pub fn solve(
        &self,
        pair: &PairRow,
        normal_impulse: f64,
        held: &mut FrictionImpulse,
        (velocity, spin): (&mut [DVec3], &mut [DVec3]),
        first: usize,
        inv_mass: &[f64],
    ) {
        let limit = self.friction * normal_impulse;
        if limit == 0.0 && self.rolling_arm == 0.0 && held.tangent == DVec3::ZERO {
            // Nothing to hold and nothing held: a speculative contact.
            return;
        }
        let (ki, kj) = (pair.i as usize - first, pair.j as usize - first);
        let n = pair.normal;
        let [ri, rj] = self.radius;
        let slip = (velocity[ki] - velocity[kj]) - (ri * spin[ki] + rj * spin[kj]).cross(n);
        let slip = slip - slip.dot(n) * n;
        let tangent = clamp_length(held.tangent - slip * self.tangent_mass, limit);
        let rolling = if self.rolling_arm > 0.0 {
            let relative_spin = spin[ki] - spin[kj];
            clamp_length(
                held.rolling - relative_spin * self.rolling_mass,
                self.rolling_arm * normal_impulse,
            )
        } else {
            DVec3::ZERO
        };
        let change = FrictionImpulse {
            tangent: tangent - held.tangent,
            rolling: rolling - held.rolling,
        };
        *held = FrictionImpulse { tangent, rolling };
        self.push(pair, &change, (velocity, spin), first, inv_mass);
    }
}
