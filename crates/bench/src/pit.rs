//! The ball pit both engines simulate: the same spheres, box, materials,
//! time step and starting state.
//!
//! A pit has two Coulomb friction coefficients, one between a ball and a
//! wall and one between two balls, and no rolling resistance: Rapier has
//! none to match ours with.

use glam::DVec3;

/// One ball's starting state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Start {
    /// Where its centre starts (m).
    pub position: DVec3,
    /// Its velocity at the start (m/s).
    pub velocity: DVec3,
}

/// N equal spheres dropped in a closed box (inner size `size`, floor at
/// y = 0, centred on x = z = 0).
#[derive(Clone, Debug, PartialEq)]
pub struct Pit {
    /// Every ball's radius (m).
    pub radius: f64,
    /// Every ball's mass (kg).
    pub mass: f64,
    /// Restitution of every contact, ball-ball and ball-wall.
    pub restitution: f64,
    /// Coulomb friction between a ball and a wall.
    pub wall_friction: f64,
    /// Coulomb friction between two balls (0: they slide on each other
    /// without friction).
    pub ball_friction: f64,
    /// Gravitational acceleration, along -y (m/s²).
    pub gravity: f64,
    /// The fixed time step (s).
    pub dt: f64,
    /// The box's inner size (m).
    pub size: DVec3,
    /// Each ball's starting state.
    pub start: Vec<Start>,
}

/// Advances a pit one step at a time and reads the balls back.
pub trait PitEngine {
    /// The engine's name, as the table prints it.
    fn name(&self) -> String;
    /// Advances the pit by one time step (an engine on another device may
    /// only have queued it: see [`PitEngine::finish`]).
    fn step(&mut self);
    /// Waits until every step asked for is done; timed with the steps.
    fn finish(&mut self) {}
    /// Writes every ball's position and linear velocity, in `Pit::start` order.
    fn read(&self, positions: &mut Vec<DVec3>, velocities: &mut Vec<DVec3>);
}

/// Coulomb friction between balls in the headline table.
pub const FRICTION: f64 = 0.5;

/// Layers of balls in the starting lattice; the box is as wide as it must be.
const LAYERS: usize = 8;
/// Lattice spacing in ball radii: a small gap between neighbours.
const SPACING: f64 = 2.5;

impl Pit {
    /// `count` balls of radius 0.1 m and mass 1 kg on a jittered lattice
    /// `LAYERS` deep, with small random velocities, in a box just wide
    /// enough for the lattice and half again as tall; frictionless between
    /// balls (see [`Pit::with_ball_friction`]).
    pub fn new(count: usize, seed: u64) -> Pit {
        let radius = 0.1;
        let spacing = SPACING * radius;
        let per_layer = count.div_ceil(LAYERS).max(1);
        let side = (per_layer as f64).sqrt().ceil() as usize;
        let width = side as f64 * spacing;
        let height = 1.5 * LAYERS as f64 * spacing;
        let jitter = 0.4 * (spacing - 2.0 * radius);
        let mut rng = rolypoly_physics::Rng::new(seed);
        let start = (0..count)
            .map(|k| {
                let (layer, cell) = (k / (side * side), k % (side * side));
                let (ix, iz) = (cell % side, cell / side);
                let site = DVec3::new(
                    (ix as f64 + 0.5) * spacing - 0.5 * width,
                    (layer as f64 + 0.5) * spacing,
                    (iz as f64 + 0.5) * spacing - 0.5 * width,
                );
                let wobble = DVec3::new(
                    rng.range(-jitter, jitter),
                    rng.range(-jitter, jitter),
                    rng.range(-jitter, jitter),
                );
                Start {
                    position: site + wobble,
                    velocity: rng.direction() * rng.range(0.0, 1.0),
                }
            })
            .collect();
        Pit {
            radius,
            mass: 1.0,
            restitution: 0.8,
            wall_friction: 0.5,
            ball_friction: 0.0,
            gravity: 9.81,
            dt: 1.0 / 60.0,
            size: DVec3::new(width, height, width),
            start,
        }
    }

    /// The same pit with Coulomb friction `mu` between balls.
    pub fn with_ball_friction(mut self, mu: f64) -> Pit {
        self.ball_friction = mu;
        self
    }
}
