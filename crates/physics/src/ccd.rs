//! Exact ball-wall impacts within a step.
//!
//! Between impacts a ball follows the parabola `x + u t + g t^2 / 2` exactly,
//! so the time of impact on each wall is a root of a quadratic. Bouncing at
//! that instant, rather than at the end of the step, is what makes a dropped
//! ball rebound to e^2 of its height and lets nothing pass through a wall at
//! any speed.

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

#[cfg(test)]
mod tests {
    use super::*;

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
