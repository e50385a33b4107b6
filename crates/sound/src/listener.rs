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
