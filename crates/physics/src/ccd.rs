//! Exact impacts within a step: when they happen, and what a wall does.
//!
//! Between impacts a ball follows the parabola `x + u t + g t^2 / 2` exactly,
//! so the time of impact on each wall is a root of a quadratic. Bouncing at
//! that instant, rather than at the end of the step, is what makes a dropped
//! ball rebound to e^2 of its height and lets nothing pass through a wall at
//! any speed. Gravity moves two balls alike, so between impacts they close
//! along a straight line, and their time of impact is a root too.

use glam::DVec3;

/// The first time in `[0, horizon]` at which the distance
/// `d0 + an t + gn t^2 / 2` to a wall reaches zero while decreasing.
pub(crate) fn first_impact(d0: f64, an: f64, gn: f64, horizon: f64) -> Option<f64> {
    let inwards = |t: f64| an + gn * t < 0.0;
    let accept = |t: f64| (t >= 0.0 && t <= horizon && inwards(t)).then_some(t);
    if d0 <= 0.0 {
        // Touching (or in): an impact now if moving, or being pulled, inwards;
        // a touching ball thrown off while gravity pulls it back lands again.
        if an < 0.0 || (an == 0.0 && gn < 0.0) {
            return Some(0.0);
        }
        return if d0 == 0.0 && gn < 0.0 {
            accept(-2.0 * an / gn)
        } else {
            None
        };
    }
    if gn == 0.0 {
        return if an < 0.0 { accept(-d0 / an) } else { None };
    }
    let disc = an * an - 2.0 * gn * d0;
    if disc < 0.0 {
        return None;
    }
    // Numerically stable roots of (gn/2) t^2 + an t + d0 = 0.
    let q = -0.5 * (an + an.signum() * disc.sqrt());
    let (r1, r2) = if q == 0.0 {
        let t = (-2.0 * d0 / gn).max(0.0).sqrt();
        (-t, t)
    } else {
        (q / (0.5 * gn), d0 / q)
    };
    let (lo, hi) = if r1 <= r2 { (r1, r2) } else { (r2, r1) };
    accept(lo).or_else(|| accept(hi))
}

/// The first time in `[0, horizon]` at which two spheres whose centres
/// differ by `d + v t` touch (their centres `reach` apart) while closing.
/// Touching or overlapping and closing: an impact now.
pub(crate) fn first_touch(d: DVec3, v: DVec3, reach: f64, horizon: f64) -> Option<f64> {
    let closing = d.dot(v);
    if closing >= 0.0 {
        return None;
    }
    let c = d.length_squared() - reach * reach;
    if c <= 0.0 {
        return Some(0.0);
    }
    let a = v.length_squared();
    let disc = closing * closing - a * c;
    if disc < 0.0 {
        return None;
    }
    // The smaller root of a t^2 + 2 closing t + c = 0, in the stable form.
    let t = c / (-closing + disc.sqrt());
    (t <= horizon).then_some(t)
}

/// For two spheres whose centres differ by `d + v t`, apart and closing,
/// the normal along which their contact is solved within `horizon`, and
/// the gap left along it at t = 0: the line of centres at first touch if
/// they touch within the horizon; else, if they pass by faster than
/// `pass_by_speed`, the line of centres at their closest approach in it.
/// `None` where the line of centres at t = 0 serves.
///
/// A speculative contact keeps the gap along its normal from closing; taken
/// along the line of centres at the start, it would stop two balls that
/// were only passing close by (a ghost collision, which costs energy).
/// Along these normals it binds only on balls that really meet. Balls that
/// slide slowly past each other (in a heap, say) keep the line of centres,
/// which holds them apart whatever the solver's other contacts do to them.
pub(crate) fn contact_normal(
    d: DVec3,
    v: DVec3,
    reach: f64,
    horizon: f64,
    pass_by_speed: f64,
) -> Option<(DVec3, f64)> {
    let a = v.length_squared();
    let b = d.dot(v);
    let c = d.length_squared() - reach * reach;
    if c <= 0.0 || b >= 0.0 || a == 0.0 {
        return None;
    }
    let disc = b * b - a * c;
    let touch = (disc >= 0.0).then(|| c / (-b + disc.sqrt()));
    let t = match touch {
        Some(t) if t <= horizon => t,
        _ if a > pass_by_speed * pass_by_speed => (-b / a).min(horizon),
        _ => return None,
    };
    let n = (d + v * t).normalize();
    Some((n, d.dot(n) - reach))
}

/// A ball's velocity `u` and `spin` just after it meets a wall with inward
/// normal `n`: its normal speed reversed and scaled by `restitution`
/// (0 to come to rest on it), then Coulomb friction `friction` at the
/// contact point, at most enough to roll. Returns them with the normal
/// impulse the wall gave.
pub(crate) fn bounce_off_wall(
    (u, spin): (DVec3, DVec3),
    n: DVec3,
    (radius, mass, inertia): (f64, f64, f64),
    restitution: f64,
    friction: f64,
) -> (DVec3, DVec3, f64) {
    let speed = -n.dot(u);
    let mut u = u + (1.0 + restitution) * speed * n;
    let mut spin = spin;
    let normal_impulse = mass * (1.0 + restitution) * speed;
    let arm = -radius * n;
    let slip = u + spin.cross(arm);
    let slip = slip - slip.dot(n) * n;
    let slip_speed = slip.length();
    if slip_speed > 0.0 {
        let j =
            (friction * normal_impulse).min(slip_speed / (1.0 / mass + radius * radius / inertia));
        let impulse = -slip / slip_speed * j;
        u += impulse / mass;
        spin += arm.cross(impulse) / inertia;
    }
    (u, spin, normal_impulse)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spheres_touch_when_their_centres_are_two_radii_apart() {
        // 1 m apart, closing at 2 m/s, touching at 0.5 m: at t = 0.25.
        let d = DVec3::new(1.0, 0.0, 0.0);
        let v = DVec3::new(-2.0, 0.0, 0.0);
        let t = first_touch(d, v, 0.5, 1.0).unwrap();
        assert!((t - 0.25).abs() < 1e-15);
        assert_eq!(first_touch(d, v, 0.5, 0.2), None);
        // Leaving, or passing by too far to the side: never.
        assert_eq!(first_touch(d, -v, 0.5, 1.0), None);
        let by = DVec3::new(-2.0, 0.0, 0.0);
        assert_eq!(first_touch(DVec3::new(1.0, 0.6, 0.0), by, 0.5, 9.0), None);
        // Overlapping and closing: now; overlapping and leaving: never.
        assert_eq!(
            first_touch(DVec3::new(0.4, 0.0, 0.0), v, 0.5, 1.0),
            Some(0.0)
        );
        assert_eq!(first_touch(DVec3::new(0.4, 0.0, 0.0), -v, 0.5, 1.0), None);
    }

    #[test]
    fn a_glancing_touch_is_found_at_the_right_distance() {
        let d = DVec3::new(3.0, 0.3, 0.0);
        let v = DVec3::new(-1.0, 0.0, 0.0);
        let t = first_touch(d, v, 0.5, 10.0).unwrap();
        assert!(((d + v * t).length() - 0.5).abs() < 1e-12);
    }

    #[test]
    fn a_frictionless_elastic_wall_reverses_the_normal_speed_only() {
        let u = DVec3::new(1.0, -3.0, 2.0);
        let (after, spin, impulse) =
            bounce_off_wall((u, DVec3::ZERO), DVec3::Y, (0.1, 2.0, 0.008), 1.0, 0.0);
        assert_eq!(after, DVec3::new(1.0, 3.0, 2.0));
        assert_eq!(spin, DVec3::ZERO);
        assert!((impulse - 12.0).abs() < 1e-12);
    }

    #[test]
    fn friction_at_a_wall_never_spins_a_ball_past_rolling() {
        // Sliding fast with friction enough: it leaves rolling, v = w r.
        let u = DVec3::new(4.0, -1.0, 0.0);
        let (r, m) = (0.1, 1.0);
        let inertia = 0.4 * m * r * r;
        let (after, spin, _) =
            bounce_off_wall((u, DVec3::ZERO), DVec3::Y, (r, m, inertia), 0.0, 10.0);
        let contact_velocity = after + spin.cross(-r * DVec3::Y);
        assert!(contact_velocity.length() < 1e-12, "{contact_velocity}");
        // Rolling keeps 5/7 of the sliding speed (angular momentum about the contact).
        assert!((after.x - 4.0 * 5.0 / 7.0).abs() < 1e-12);
    }

    #[test]
    fn linear_approach() {
        assert_eq!(first_impact(1.0, -2.0, 0.0, 1.0), Some(0.5));
        assert_eq!(first_impact(1.0, -2.0, 0.0, 0.4), None);
        assert_eq!(first_impact(1.0, 2.0, 0.0, 10.0), None);
    }

    #[test]
    fn falling_onto_the_floor() {
        // d = 1 - g t^2 / 2 with g = 2: hits at t = 1.
        let t = first_impact(1.0, 0.0, -2.0, 2.0).unwrap();
        assert!((t - 1.0).abs() < 1e-12);
    }

    #[test]
    fn thrown_up_towards_the_ceiling_but_falling_short() {
        // distance to ceiling 1, up at 1 m/s, decelerating at 10: never reaches.
        assert_eq!(first_impact(1.0, -1.0, 10.0, 5.0), None);
        // up at 10 m/s: reaches it on the way up.
        let t = first_impact(1.0, -10.0, 10.0, 5.0).unwrap();
        assert!((1.0 - 10.0 * t + 5.0 * t * t).abs() < 1e-12);
        assert!(-10.0 + 10.0 * t < 0.0);
    }

    #[test]
    fn touching_and_moving_in_is_an_impact_now() {
        assert_eq!(first_impact(0.0, -1.0, 0.0, 1.0), Some(0.0));
        assert_eq!(first_impact(0.0, 0.0, -9.81, 1.0), Some(0.0));
        // Thrown off the floor: lands again after 2 u / g, if within the horizon.
        let t = first_impact(0.0, 1.0, -10.0, 1.0).unwrap();
        assert!((t - 0.2).abs() < 1e-12);
        assert_eq!(first_impact(0.0, 1.0, -10.0, 0.1), None);
        assert_eq!(first_impact(-0.01, 1.0, 0.0, 1.0), None);
    }
}
