//! A fixed-capacity ring of particles (X5): allocated once, spawned at the
//! tail, retired from the head. Spawning into a full ring fails and is
//! counted; nothing is allocated per particle.

use crate::particle::Particle;
use serde::{Deserialize, Serialize};

/// The ring is full: the particle was not spawned.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Full;

/// Particles in a ring of fixed capacity, spawned at the tail, retired at the head.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct ParticleRing {
    slots: Vec<Particle>,
    head: usize,
    len: usize,
    dropped: u64,
}

impl ParticleRing {
    /// An empty ring of `capacity` slots (at least one), filled with `blank`.
    pub fn new(capacity: usize, blank: Particle) -> ParticleRing {
        ParticleRing {
            slots: vec![blank; capacity.max(1)],
            head: 0,
            len: 0,
            dropped: 0,
        }
    }

    /// How many particles it holds at most.
    pub fn capacity(&self) -> usize {
        self.slots.len()
    }

    /// Particles between head and tail (some may have died already and wait
    /// for the head to pass them; see [`ParticleRing::live`]).
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether it holds no particles.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// How many spawns failed because the ring was full.
    pub fn dropped(&self) -> u64 {
        self.dropped
    }

    /// Adds a particle at the tail, or fails (and counts it) when full.
    pub fn spawn(&mut self, particle: Particle) -> Result<usize, Full> {
        if self.len == self.slots.len() {
            self.dropped += 1;
            return Err(Full);
        }
        let index = (self.head + self.len) % self.slots.len();
        self.slots[index] = particle;
        self.len += 1;
        Ok(index)
    }

    /// Ages every particle by `dt` and retires the dead ones at the head.
    pub fn update(&mut self, dt: f32) {
        let capacity = self.slots.len();
        for k in 0..self.len {
            self.slots[(self.head + k) % capacity].age += dt;
        }
        while self.len > 0 && !self.slots[self.head].alive() {
            self.head = (self.head + 1) % capacity;
            self.len -= 1;
        }
    }

    /// The particles in spawn order, oldest first, dead ones included.
    pub fn iter(&self) -> impl Iterator<Item = &Particle> {
        let capacity = self.slots.len();
        (0..self.len).map(move |k| &self.slots[(self.head + k) % capacity])
    }

    /// The living particles, oldest first.
    pub fn live(&self) -> impl Iterator<Item = &Particle> {
        self.iter().filter(|p| p.alive())
    }

    /// Empties the ring (the count of refused spawns stays).
    pub fn clear(&mut self) {
        self.head = 0;
        self.len = 0;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::particle::ParticleKind;
    use glam::Vec3;

    fn particle(tag: f32, life: f32) -> Particle {
        Particle::new(
            ParticleKind::Trail,
            Vec3::new(tag, 0.0, 0.0),
            life,
            1.0,
            1.0,
        )
    }

    #[test]
    fn capacity_is_respected_and_a_full_ring_fails_cleanly() {
        let mut ring = ParticleRing::new(4, particle(0.0, 1.0));
        for i in 0..4 {
            assert!(ring.spawn(particle(i as f32, 1.0)).is_ok());
        }
        assert_eq!(ring.spawn(particle(9.0, 1.0)), Err(Full));
        assert_eq!(ring.spawn(particle(9.0, 1.0)), Err(Full));
        assert_eq!(ring.len(), 4);
        assert_eq!(ring.dropped(), 2);
    }

    #[test]
    fn order_is_kept_and_the_head_retires_the_dead() {
        let mut ring = ParticleRing::new(4, particle(0.0, 1.0));
        ring.spawn(particle(0.0, 0.5)).unwrap();
        ring.spawn(particle(1.0, 2.0)).unwrap();
        ring.spawn(particle(2.0, 0.5)).unwrap();
        ring.update(1.0);
        // The first died and left; the third died but waits behind the second.
        assert_eq!(ring.len(), 2);
        let tags: Vec<f32> = ring.live().map(|p| p.origin.x).collect();
        assert_eq!(tags, [1.0]);
        // The ring wraps around: spawn until full again, order preserved.
        for i in 3..5 {
            ring.spawn(particle(i as f32, 2.0)).unwrap();
        }
        let tags: Vec<f32> = ring.iter().map(|p| p.origin.x).collect();
        assert_eq!(tags, [1.0, 2.0, 3.0, 4.0]);
        assert!(ring.spawn(particle(5.0, 1.0)).is_err());
        ring.update(1.5);
        // 1 and 2 are dead now; 3 and 4 live on.
        let tags: Vec<f32> = ring.iter().map(|p| p.origin.x).collect();
        assert_eq!(tags, [3.0, 4.0]);
        ring.update(1.0);
        assert!(ring.is_empty());
    }

    #[test]
    fn no_allocation_after_start_up() {
        let mut ring = ParticleRing::new(64, particle(0.0, 1.0));
        let storage = ring.slots.as_ptr();
        for round in 0..1000 {
            for _ in 0..10 {
                let _ = ring.spawn(particle(round as f32, 0.05));
            }
            ring.update(0.02);
        }
        assert_eq!(ring.slots.as_ptr(), storage, "the ring's storage moved");
        assert_eq!(ring.capacity(), 64);
    }
}
