//! Where the sound is heard from (J1): the camera's position and facing.
//! A source is panned by equal power from its direction, attenuated with
//! its distance, and delayed by sound's travel.

use glam::DVec3;
use std::f64::consts::FRAC_PI_2;

/// The speed of sound in air at 20 °C (m/s).
pub const SPEED_OF_SOUND: f64 = 343.0;

/// Nearer than this (m), a source is as loud as at this distance: the
/// listener's head has a size.
const NEAREST: f64 = 0.5;

/// The listener: a head at `position` looking along `forward`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Listener {
    /// Where the head is.
    pub position: DVec3,
    /// Where it looks (need not be unit length; the room's up is +y).
    pub forward: DVec3,
}

/// How a source at some point is heard: each ear's gain, and its delay.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Placement {
    /// The left and right channels' gains, distance included.
    pub gains: [f32; 2],
    /// The distance to the head (m).
    pub distance: f64,
    /// How long the sound takes to arrive (s).
    pub delay: f64,
}

impl Listener {
    /// The direction to the head's right.
    pub fn right(&self) -> DVec3 {
        self.forward
            .cross(DVec3::Y)
            .try_normalize()
            .unwrap_or(DVec3::X)
    }

    /// How a source at `point` is heard: its side from the right-ear
    /// direction's cosine x (-1 full left, 1 full right), panned by equal
    /// power (left cos, right sin of (x + 1) π/4), and 1/distance.
    pub fn place(&self, point: DVec3) -> Placement {
        let to = point - self.position;
        let distance = to.length();
        let side = to
            .try_normalize()
            .map_or(0.0, |d| d.dot(self.right()))
            .clamp(-1.0, 1.0);
        let angle = (side + 1.0) * 0.5 * FRAC_PI_2;
        let fall = 1.0 / distance.max(NEAREST);
        Placement {
            gains: [(angle.cos() * fall) as f32, (angle.sin() * fall) as f32],
            distance,
            delay: distance / SPEED_OF_SOUND,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ear() -> Listener {
        Listener {
            position: DVec3::new(0.0, 1.5, 2.0),
            forward: DVec3::new(0.0, 0.0, -3.0),
        }
    }

    #[test]
    fn the_pan_keeps_the_power_and_follows_the_side() {
        let ear = ear();
        for (x, z) in [
            (0.0, -3.0),
            (-2.0, 2.0),
            (4.0, 1.0),
            (-1.0, -1.0),
            (0.0, 5.0),
        ] {
            let at = DVec3::new(x, 1.5, z);
            let p = ear.place(at);
            let d = (at - ear.position).length();
            let power = (p.gains[0] as f64).powi(2) + (p.gains[1] as f64).powi(2);
            // Equal power: the two gains' squares sum to 1/d².
            assert!((power * d * d - 1.0).abs() < 1e-5, "({x}, {z}): {power}");
            assert!((p.delay - d / SPEED_OF_SOUND).abs() < 1e-12);
            let side = (at - ear.position).normalize().dot(ear.right());
            assert_eq!(p.gains[0] > p.gains[1], side < -1e-9, "({x}, {z})");
        }
        // Straight ahead, and straight behind: the two ears alike.
        let ahead = ear.place(DVec3::new(0.0, 1.5, -3.0)).gains;
        assert!((ahead[0] - ahead[1]).abs() < 1e-6);
    }

    #[test]
    fn loudness_falls_as_one_over_distance_beyond_the_head() {
        let ear = ear();
        let at = |d: f64| ear.place(ear.position + DVec3::new(0.0, 0.0, -d)).gains[0];
        assert!((at(2.0) / at(4.0) - 2.0).abs() < 1e-5);
        assert!((at(1.0) / at(3.0) - 3.0).abs() < 1e-5);
        assert_eq!(at(0.1), at(0.3), "nearer than the head: as at its size");
    }
}
