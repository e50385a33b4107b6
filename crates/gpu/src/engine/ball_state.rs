//! The balls as read back from the GPU, and what the tests and the bench
//! measure of them.

use glam::{DVec3, Vec3};
use rolypoly_physics::{Balls, Tint};

/// The balls as read back: one entry per ball, thrown ones included.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BallState {
    /// Centres (m).
    pub positions: Vec<Vec3>,
    /// Velocities (m/s).
    pub velocities: Vec<Vec3>,
    /// Angular velocities (rad/s).
    pub spins: Vec<Vec3>,
    /// Radii (m).
    pub radii: Vec<f32>,
    /// Inverse masses (1/kg).
    pub inverse_masses: Vec<f32>,
    /// Whether each is still in play (not caught by the fireball).
    pub alive: Vec<bool>,
    /// The colour each shows.
    pub colors: Vec<[f32; 3]>,
    /// What each took its colour from.
    pub tints: Vec<Tint>,
}

impl BallState {
    /// Kinetic energy of the live balls, moving and turning (J).
    pub fn kinetic_energy(&self) -> f64 {
        (0..self.positions.len())
            .filter(|&i| self.alive[i])
            .map(|i| {
                let m = 1.0 / f64::from(self.inverse_masses[i]);
                let r = f64::from(self.radii[i]);
                let inertia = 0.4 * m * r * r;
                0.5 * m * self.velocities[i].as_dvec3().length_squared()
                    + 0.5 * inertia * self.spins[i].as_dvec3().length_squared()
            })
            .sum()
    }

    /// The balls as the CPU engine keeps them (see [`rolypoly_physics::World::put_balls`]).
    pub fn to_balls(&self) -> Balls {
        let vectors = |v: &[Vec3]| v.iter().map(|v| v.as_dvec3()).collect();
        Balls::from_parts(
            vectors(&self.positions),
            vectors(&self.velocities),
            vectors(&self.spins),
            self.radii.iter().map(|&r| f64::from(r)).collect(),
            self.inverse_masses
                .iter()
                .map(|&m| 1.0 / f64::from(m))
                .collect(),
            self.tints.clone(),
            self.alive.clone(),
        )
    }

    /// Total momentum of the live balls (N s).
    pub fn momentum(&self) -> DVec3 {
        (0..self.positions.len())
            .filter(|&i| self.alive[i])
            .map(|i| self.velocities[i].as_dvec3() / f64::from(self.inverse_masses[i]))
            .sum()
    }
}
