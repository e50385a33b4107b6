//! Friction and rolling resistance between two balls in contact, as rows
//! of both solver stages beside each pair's normal row (F1).
//!
//! Friction acts at the contact point against its sliding, within the
//! Coulomb cone: the tangential impulse accumulated over the stage is kept
//! at most `mu` times the normal one, as a vector in the tangent plane (the
//! cone itself, not a pyramid of two tangents). For solid spheres the
//! contact point's sliding changes along the impulse alone, by
//! `1/m1 + r1^2/I1 + 1/m2 + r2^2/I2 = 3.5 (1/m1 + 1/m2)` per unit, so the
//! tangent row's mass is 2/7 of the normal row's and each update is one
//! division-free step. Rolling resistance resists the balls' relative spin
//! with a torque of at most `mu_r` times the normal impulse times the
//! pair's rolling radius `r1 r2 / (r1 + r2)` (Ai, Chen, Rotter and Ooi,
//! Powder Technology 2011, model A): a ball on a wall, whose rolling
//! radius is its own, feels the room's coefficient the same way.
//!
//! Both start from last step's impulses, so a heap's friction holds from
//! one step to the next instead of building up anew each step. A friction
//! row reads only its impulse beside the pair's normal row, and each ball's
//! radius and lever from arrays by slot: in a large pile the rows are
//! streamed from memory every sweep, and that stream is much of the work.

use crate::balls::Balls;
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

/// The tangent row's mass per unit of the normal row's (see above).
const TANGENT_MASS_SHARE: f64 = 2.0 / 7.0;

/// Per slot, the spin a unit impulse along a ball's surface gives it,
/// `r / I`, and the friction coefficient the rows hold to.
#[derive(Clone, Debug, Default)]
pub(super) struct Levers {
    pub friction: f64,
    turn: Vec<f64>,
}

impl Levers {
    /// Worked out for `balls` and `material`, storage kept.
    pub fn update(&mut self, balls: &Balls, material: PairMaterial) {
        self.friction = material.friction;
        self.turn.clear();
        self.turn
            .extend((0..balls.len()).map(|k| balls.inv_inertia(k) * balls.radius[k]));
    }
}

/// A pair's rolling row, where the balls have rolling resistance.
#[derive(Clone, Copy, Debug)]
pub(super) struct RollingRow {
    inv_inertia: [f64; 2],
    /// Moment of inertia against relative spin.
    mass: f64,
    /// The largest rolling torque impulse per unit normal impulse.
    arm: f64,
}

impl RollingRow {
    pub fn new(i: usize, j: usize, balls: &Balls, material: PairMaterial) -> RollingRow {
        let (ii, ij) = (balls.inv_inertia(i), balls.inv_inertia(j));
        let (ri, rj) = (balls.radius[i], balls.radius[j]);
        RollingRow {
            inv_inertia: [ii, ij],
            mass: if ii + ij > 0.0 { 1.0 / (ii + ij) } else { 0.0 },
            arm: material.rolling_resistance * ri * rj / (ri + rj),
        }
    }
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
        friction: f64,
        rolling: Option<&RollingRow>,
    ) -> FrictionImpulse {
        let tangent = kept.tangent - kept.tangent.dot(normal) * normal;
        let arm = rolling.map_or(0.0, |r| r.arm);
        FrictionImpulse {
            tangent: clamp_length(tangent, friction * normal_impulse),
            rolling: clamp_length(kept.rolling, arm * normal_impulse),
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

/// What the friction rows read of every slot's ball, unchanged by them:
/// its inverse mass, radius and lever.
#[derive(Clone, Copy)]
pub(super) struct BallBuild<'a> {
    pub inv_mass: &'a [f64],
    pub radius: &'a [f64],
    pub levers: &'a Levers,
}

impl<'a> BallBuild<'a> {
    pub fn new(inv_mass: &'a [f64], radius: &'a [f64], levers: &'a Levers) -> BallBuild<'a> {
        BallBuild {
            inv_mass,
            radius,
            levers,
        }
    }
}

/// The balls' velocities and spins from slot `first` on, and what every
/// slot's ball is built of.
pub(super) struct Motion<'a> {
    pub velocity: &'a mut [DVec3],
    pub spin: &'a mut [DVec3],
    pub first: usize,
    pub build: BallBuild<'a>,
}

impl Motion<'_> {
    /// Applies `impulse` (of friction, and of rolling torque) to the two
    /// balls of `pair`.
    #[inline(always)]
    pub fn push(
        &mut self,
        pair: &PairRow,
        impulse: &FrictionImpulse,
        rolling: Option<&RollingRow>,
    ) {
        let (i, j) = (pair.i as usize, pair.j as usize);
        let (ki, kj) = (i - self.first, j - self.first);
        let t = impulse.tangent;
        let BallBuild {
            inv_mass, levers, ..
        } = self.build;
        self.velocity[ki] += t * inv_mass[i];
        self.velocity[kj] -= t * inv_mass[j];
        // On i at -ri n, the opposite on j at +rj n: both turn against n x t.
        let turn = pair.normal.cross(t);
        self.spin[ki] -= turn * levers.turn[i];
        self.spin[kj] -= turn * levers.turn[j];
        if let Some(r) = rolling {
            self.spin[ki] += impulse.rolling * r.inv_inertia[0];
            self.spin[kj] -= impulse.rolling * r.inv_inertia[1];
        }
    }

    /// One Gauss-Seidel update of the pair's friction row, and its rolling
    /// row if it has one, their limits set by the pair's accumulated
    /// `normal_impulse`.
    #[inline(always)]
    pub fn solve(
        &mut self,
        pair: &PairRow,
        normal_impulse: f64,
        held: &mut FrictionImpulse,
        rolling: Option<&RollingRow>,
    ) {
        let limit = self.build.levers.friction * normal_impulse;
        if limit == 0.0 && rolling.is_none() && held.tangent == DVec3::ZERO {
            // Nothing to hold and nothing held: a speculative contact.
            return;
        }
        let (i, j) = (pair.i as usize, pair.j as usize);
        let (ki, kj) = (i - self.first, j - self.first);
        let n = pair.normal;
        let (ri, rj) = (self.build.radius[i], self.build.radius[j]);
        let (spin_i, spin_j) = (self.spin[ki], self.spin[kj]);
        let slip = (self.velocity[ki] - self.velocity[kj]) - (ri * spin_i + rj * spin_j).cross(n);
        let slip = slip - slip.dot(n) * n;
        let mass = TANGENT_MASS_SHARE * pair.mass;
        let tangent = clamp_length(held.tangent - slip * mass, limit);
        let rolling_held = match rolling {
            Some(r) => clamp_length(
                held.rolling - (spin_i - spin_j) * r.mass,
                r.arm * normal_impulse,
            ),
            None => DVec3::ZERO,
        };
        let change = FrictionImpulse {
            tangent: tangent - held.tangent,
            rolling: rolling_held - held.rolling,
        };
        *held = FrictionImpulse {
            tangent,
            rolling: rolling_held,
        };
        self.push(pair, &change, rolling);
    }
}
