//! The balls (P2-P5), kept as one array per field so that the hot loops walk
//! contiguous memory and a later scale-up to many balls stays cheap.

use crate::room::Surface;
use glam::DVec3;
use serde::{Deserialize, Serialize};

/// From this many live balls on, work over every ball runs on all threads.
pub(crate) const PARALLEL_BALLS: usize = 2048;

/// From this many balls on, a pass that does little per ball (a copy, a
/// gather, a sum) runs on all threads. Below, waking the other threads and
/// waiting for them costs more than the pass.
pub(crate) const PARALLEL_LIGHT_PASSES: usize = 32768;

/// What colour a ball has taken on (P5): white until it hits something.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Tint {
    /// The scene's ball colour.
    White,
    /// The colour of the surface it hit last.
    Surface(Surface),
    /// The colour of the tumbler it hit last.
    Tumbler(usize),
    /// The colour its scene gave placed ball `k`.
    Placed(usize),
}

/// Uniform solid spheres. Velocities are instantaneous velocities at the
/// current time; `spin` is the angular velocity, which friction with the
/// surfaces couples to the sliding velocity so that balls roll.
#[derive(Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Balls {
    pub(crate) position: Vec<DVec3>,
    pub(crate) velocity: Vec<DVec3>,
    pub(crate) spin: Vec<DVec3>,
    pub(crate) radius: Vec<f64>,
    pub(crate) mass: Vec<f64>,
    pub(crate) inv_mass: Vec<f64>,
    pub(crate) tint: Vec<Tint>,
    pub(crate) alive: Vec<bool>,
}

impl Clone for Balls {
    fn clone(&self) -> Balls {
        let mut copy = Balls::default();
        copy.clone_from(self);
        copy
    }

    /// Field by field into the storage there is: the world keeps a copy of
    /// its balls from before each step (see [`crate::World::step`]), and
    /// copying into fresh memory every step would cost more than the copy.
    /// Many balls are copied on two threads, each about half the bytes.
    fn clone_from(&mut self, source: &Balls) {
        let Balls {
            position,
            velocity,
            spin,
            radius,
            mass,
            inv_mass,
            tint,
            alive,
        } = self;
        let mut motion = || {
            position.clone_from(&source.position);
            velocity.clone_from(&source.velocity);
            spin.clone_from(&source.spin);
        };
        let mut rest = || {
            radius.clone_from(&source.radius);
            mass.clone_from(&source.mass);
            inv_mass.clone_from(&source.inv_mass);
            tint.clone_from(&source.tint);
            alive.clone_from(&source.alive);
        };
        if source.len() >= PARALLEL_LIGHT_PASSES {
            rayon::join(motion, rest);
        } else {
            motion();
            rest();
        }
    }
}

impl Balls {
    pub(crate) fn with_uniform(count: usize, radius: f64, mass: f64) -> Balls {
        Balls {
            position: vec![DVec3::ZERO; count],
            velocity: vec![DVec3::ZERO; count],
            spin: vec![DVec3::ZERO; count],
            radius: vec![radius; count],
            mass: vec![mass; count],
            inv_mass: vec![1.0 / mass; count],
            tint: vec![Tint::White; count],
            alive: vec![true; count],
        }
    }

    /// Balls from their fields, one entry per ball in each: centres,
    /// velocities, spins, radii, masses, colours and whether each is in
    /// play. For balls simulated elsewhere and read back (the GPU engine).
    #[allow(clippy::too_many_arguments)]
    pub fn from_parts(
        position: Vec<DVec3>,
        velocity: Vec<DVec3>,
        spin: Vec<DVec3>,
        radius: Vec<f64>,
        mass: Vec<f64>,
        tint: Vec<Tint>,
        alive: Vec<bool>,
    ) -> Balls {
        let inv_mass = mass.iter().map(|m| 1.0 / m).collect();
        Balls {
            position,
            velocity,
            spin,
            radius,
            mass,
            inv_mass,
            tint,
            alive,
        }
    }

    /// How many balls there are, caught ones included.
    pub fn len(&self) -> usize {
        self.position.len()
    }

    /// Whether every column holds a value for each ball (balls read from
    /// bytes may not).
    pub fn columns_agree(&self) -> bool {
        let n = self.len();
        [
            self.velocity.len(),
            self.spin.len(),
            self.radius.len(),
            self.mass.len(),
            self.inv_mass.len(),
            self.tint.len(),
            self.alive.len(),
        ]
        .iter()
        .all(|&len| len == n)
    }

    /// Whether there are no balls.
    pub fn is_empty(&self) -> bool {
        self.position.is_empty()
    }

    /// Each ball's centre (m).
    pub fn positions(&self) -> &[DVec3] {
        &self.position
    }

    /// Each ball's velocity (m/s).
    pub fn velocities(&self) -> &[DVec3] {
        &self.velocity
    }

    /// Each ball's angular velocity (rad/s).
    pub fn spins(&self) -> &[DVec3] {
        &self.spin
    }

    /// Each ball's radius (m).
    pub fn radii(&self) -> &[f64] {
        &self.radius
    }

    /// Each ball's mass (kg).
    pub fn masses(&self) -> &[f64] {
        &self.mass
    }

    /// What colour each ball wears.
    pub fn tints(&self) -> &[Tint] {
        &self.tint
    }

    /// Whether each ball is in play (the fireball catches balls).
    pub fn alive(&self) -> &[bool] {
        &self.alive
    }

    /// Moment of inertia of ball `i` (uniform solid sphere).
    pub fn inertia(&self, i: usize) -> f64 {
        sphere_inertia(self.mass[i], self.radius[i])
    }

    /// Inverse moment of inertia of ball `i` (0 for a ball that cannot move).
    pub(crate) fn inv_inertia(&self, i: usize) -> f64 {
        if self.inv_mass[i] > 0.0 {
            1.0 / self.inertia(i)
        } else {
            0.0
        }
    }

    /// The live balls' linear momentum (kg m/s).
    pub fn momentum(&self) -> DVec3 {
        (0..self.len())
            .filter(|&i| self.alive[i])
            .map(|i| self.mass[i] * self.velocity[i])
            .sum()
    }

    /// Kinetic energy of ball `i`, moving and spinning (J).
    pub fn kinetic_energy(&self, i: usize) -> f64 {
        0.5 * self.mass[i] * self.velocity[i].length_squared()
            + 0.5 * self.inertia(i) * self.spin[i].length_squared()
    }

    /// Sets one ball's state, for building scenarios and tests.
    pub fn set(&mut self, i: usize, position: DVec3, velocity: DVec3) {
        self.position[i] = position;
        self.velocity[i] = velocity;
        self.spin[i] = DVec3::ZERO;
    }

    /// Sets one ball's angular velocity (rad/s), for scenarios and tests.
    pub fn set_spin(&mut self, i: usize, spin: DVec3) {
        self.spin[i] = spin;
    }

    /// Keeps the first `len` balls.
    pub(crate) fn truncate(&mut self, len: usize) {
        self.position.truncate(len);
        self.velocity.truncate(len);
        self.spin.truncate(len);
        self.radius.truncate(len);
        self.mass.truncate(len);
        self.inv_mass.truncate(len);
        self.tint.truncate(len);
        self.alive.truncate(len);
    }

    /// Changes one ball's mass, for scenarios with unequal balls.
    pub fn set_mass(&mut self, i: usize, mass: f64) {
        self.mass[i] = mass;
        self.inv_mass[i] = 1.0 / mass;
    }
}

/// Moment of inertia of a uniform solid sphere about its centre.
pub(crate) fn sphere_inertia(mass: f64, radius: f64) -> f64 {
    0.4 * mass * radius * radius
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_copy_kept_between_steps_takes_every_field_into_its_own_storage() {
        let mut source = Balls::with_uniform(3, 0.1, 2.0);
        source.set(1, DVec3::new(1.0, 2.0, 3.0), DVec3::new(-1.0, 0.0, 4.0));
        source.spin[2] = DVec3::new(0.0, 5.0, 0.0);
        source.radius[0] = 0.2;
        source.set_mass(2, 3.0);
        source.tint[1] = Tint::Tumbler(4);
        source.alive[0] = false;
        // A longer copy with other contents, as the one kept last step.
        let mut copy = Balls::with_uniform(5, 0.3, 1.0);
        let storage = copy.position.as_ptr();
        copy.clone_from(&source);
        assert_eq!(copy, source);
        assert_eq!(
            copy.position.as_ptr(),
            storage,
            "the copy moved to new storage"
        );
        assert_eq!(source.clone(), source);
    }
}
