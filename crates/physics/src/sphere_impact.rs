//! The impact of two solid spheres: restitution along the line of centres
//! and Coulomb friction at the contact point, at the impulse level of
//! rigid-body theory (as in pooltool's frictional inelastic ball-ball
//! model).
//!
//! The normal impulse is the 1-D collision's, `(1 + e) m* v_n`. Friction
//! acts against the sliding velocity of the contact point, which for
//! spheres changes only along itself: an impulse `J` in the tangent plane
//! changes it by `J k` with `k = 1/m1 + r1^2/I1 + 1/m2 + r2^2/I2`, which is
//! `3.5 (1/m1 + 1/m2)` for solid spheres. The pair sticks (its sliding
//! stops) when that takes at most `mu` times the normal impulse, which is
//! when the sliding speed is at most `3.5 mu (1 + e)` times the approach
//! speed; otherwise it slides and the tangential impulse is `mu` times the
//! normal one. Either way momentum is kept, the sliding speed does not
//! grow, and no energy is made.

use crate::balls::sphere_inertia;
use glam::DVec3;

/// One sphere as an impact sees it.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Sphere {
    pub velocity: DVec3,
    pub spin: DVec3,
    pub radius: f64,
    /// 0 for a sphere that does not move.
    pub inv_mass: f64,
}

impl Sphere {
    /// Its inverse moment of inertia (a solid sphere).
    fn inv_inertia(&self) -> f64 {
        if self.inv_mass > 0.0 {
            1.0 / sphere_inertia(1.0 / self.inv_mass, self.radius)
        } else {
            0.0
        }
    }
}

/// How an impact changes the two spheres.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct ImpactChange {
    /// Changes of velocity and spin of the first sphere and of the second.
    pub velocity: [DVec3; 2],
    pub spin: [DVec3; 2],
    /// The normal impulse, along `n` on the first sphere.
    pub normal_impulse: f64,
    /// The friction impulse on the first sphere (in the tangent plane).
    pub friction_impulse: DVec3,
}

/// The velocity of sphere `a`'s surface relative to sphere `b`'s at their
/// contact, `n` the unit normal from `b` towards `a`.
pub(crate) fn contact_slip(a: &Sphere, b: &Sphere, n: DVec3) -> DVec3 {
    (a.velocity - b.velocity) - (a.radius * a.spin + b.radius * b.spin).cross(n)
}

/// The impact of sphere `a` on sphere `b`, touching along `n` (unit, from
/// `b` towards `a`) and approaching (`(va - vb) . n < 0`), with restitution
/// `restitution` and friction coefficient `friction`. `None` if they do not
/// approach or neither can move.
pub(crate) fn collide_spheres(
    a: &Sphere,
    b: &Sphere,
    n: DVec3,
    restitution: f64,
    friction: f64,
) -> Option<ImpactChange> {
    let approach = -(a.velocity - b.velocity).dot(n);
    let w = a.inv_mass + b.inv_mass;
    if approach <= 0.0 || w <= 0.0 {
        return None;
    }
    let normal_impulse = (1.0 + restitution) * approach / w;
    let slip = contact_slip(a, b, n);
    let slip = slip - slip.dot(n) * n;
    let (ia, ib) = (a.inv_inertia(), b.inv_inertia());
    let k = w + a.radius * a.radius * ia + b.radius * b.radius * ib;
    // Stick: the impulse that stops the sliding, if friction can give it.
    let stop = slip / k;
    let limit = friction * normal_impulse;
    let friction_impulse = if stop.length_squared() <= limit * limit {
        -stop
    } else {
        -slip.normalize_or_zero() * limit
    };
    let impulse = n * normal_impulse + friction_impulse;
    // On `a` at -ra n, and the opposite on `b` at +rb n.
    let turn = n.cross(friction_impulse);
    Some(ImpactChange {
        velocity: [impulse * a.inv_mass, -impulse * b.inv_mass],
        spin: [-turn * (a.radius * ia), -turn * (b.radius * ib)],
        normal_impulse,
        friction_impulse,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ball(velocity: DVec3, spin: DVec3) -> Sphere {
        Sphere {
            velocity,
            spin,
            radius: 0.1,
            inv_mass: 4.0,
        }
    }

    fn after(s: &Sphere, change: &ImpactChange, k: usize) -> Sphere {
        Sphere {
            velocity: s.velocity + change.velocity[k],
            spin: s.spin + change.spin[k],
            ..*s
        }
    }

    #[test]
    fn friction_stops_the_sliding_when_it_can_and_never_speeds_it() {
        let n = DVec3::new(1.0, 0.2, -0.3).normalize();
        for (mu, slip) in [(0.0, 1.0), (0.1, 0.2), (0.1, 3.0), (0.5, 1.0), (2.0, 5.0)] {
            let a = ball(
                -2.0 * n + DVec3::new(0.0, 0.0, slip),
                DVec3::new(1.0, -2.0, 0.5),
            );
            let b = ball(DVec3::ZERO, DVec3::new(0.0, 3.0, 0.0));
            let c = collide_spheres(&a, &b, n, 0.8, mu).unwrap();
            let (a2, b2) = (after(&a, &c, 0), after(&b, &c, 1));
            let tangent = |s: DVec3| s - s.dot(n) * n;
            let before = tangent(contact_slip(&a, &b, n)).length();
            let now = tangent(contact_slip(&a2, &b2, n)).length();
            let sticks = before <= 3.5 * mu * 1.8 * 2.0;
            assert!(now <= before + 1e-12, "mu {mu}: {before} -> {now}");
            if sticks {
                assert!(now < 1e-12, "mu {mu}: sticks yet slides at {now}");
            } else {
                let expected = mu * c.normal_impulse;
                assert!((c.friction_impulse.length() - expected).abs() < 1e-12);
            }
        }
    }
}
