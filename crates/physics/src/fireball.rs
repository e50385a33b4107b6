//! The fireball (P8): a sphere with a ball's mass that flies at constant
//! speed, ignores gravity, and bounces off everything it meets.

use glam::DVec3;
use serde::{Deserialize, Serialize};

/// The fireball: a sphere flying at constant speed through the room.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Fireball {
    /// Its centre (m).
    pub position: DVec3,
    /// Its velocity (m/s).
    pub velocity: DVec3,
    /// Its radius (m).
    pub radius: f64,
    /// The mass it strikes with (kg).
    pub mass: f64,
    /// The constant speed it keeps whatever it hits.
    pub speed: f64,
}

impl Fireball {
    /// After an impulse turned it, it flies on at its constant speed.
    pub(crate) fn restore_speed(&mut self, fallback: DVec3) {
        let len = self.velocity.length();
        let dir = if len > 1e-12 {
            self.velocity / len
        } else {
            fallback
        };
        self.velocity = dir * self.speed;
    }

    /// Kinetic energy of its flight (J).
    pub fn kinetic_energy(&self) -> f64 {
        0.5 * self.mass * self.speed * self.speed
    }
}
