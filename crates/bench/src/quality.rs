//! How well an engine kept the pit: measured the same way for both engines
//! from the balls' positions and velocities alone.

use glam::{DVec3, IVec3};
use std::collections::HashMap;

use crate::pit::Pit;

/// A ball is at rest below this speed (m/s).
pub const REST_SPEED: f64 = 0.05;

/// How well an engine keeps the pit's balls apart, inside the box and at rest.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Quality {
    /// Deepest overlap of two balls, or of a ball and a wall (metres).
    pub max_penetration: f64,
    /// Balls whose centre is outside the box.
    pub escapes: usize,
    /// Translational kinetic energy of all balls (J).
    pub kinetic_energy: f64,
    /// The fastest ball's speed (m/s).
    pub max_speed: f64,
    /// Balls inside the box slower than [`REST_SPEED`].
    pub resting: usize,
}

impl Quality {
    /// Whether every ball is slower than [`REST_SPEED`].
    pub fn at_rest(&self) -> bool {
        self.max_speed < REST_SPEED
    }

    /// The worse of two measurements, for the worst over a run.
    pub fn worst(self, other: Quality) -> Quality {
        Quality {
            max_penetration: self.max_penetration.max(other.max_penetration),
            escapes: self.escapes.max(other.escapes),
            kinetic_energy: self.kinetic_energy.max(other.kinetic_energy),
            max_speed: self.max_speed.max(other.max_speed),
            resting: self.resting.min(other.resting),
        }
    }
}

/// Measures one state of the pit.
pub fn measure(pit: &Pit, positions: &[DVec3], velocities: &[DVec3]) -> Quality {
    let r = pit.radius;
    let lo = DVec3::new(-0.5 * pit.size.x, 0.0, -0.5 * pit.size.z);
    let hi = DVec3::new(0.5 * pit.size.x, pit.size.y, 0.5 * pit.size.z);
    let mut q = Quality::default();
    let inside = |p: &DVec3| p.is_finite() && p.cmpge(lo).all() && p.cmple(hi).all();
    for (p, v) in positions.iter().zip(velocities) {
        if !inside(p) {
            q.escapes += 1;
            continue;
        }
        let into_wall = (lo + DVec3::splat(r) - *p).max(*p - (hi - DVec3::splat(r)));
        q.max_penetration = q.max_penetration.max(into_wall.max_element());
        q.kinetic_energy += 0.5 * pit.mass * v.length_squared();
        q.max_speed = q.max_speed.max(v.length());
        q.resting += usize::from(v.length() < REST_SPEED);
    }
    // Pairs of balls inside: hash the centres into cells one diameter wide,
    // so every overlapping pair shares a cell or sits in neighbouring ones.
    let cell = |p: DVec3| (p / (2.0 * r)).floor().as_ivec3();
    let mut cells: HashMap<IVec3, Vec<usize>> = HashMap::new();
    for (i, p) in positions.iter().enumerate().filter(|(_, p)| inside(p)) {
        cells.entry(cell(*p)).or_default().push(i);
    }
    for (i, p) in positions.iter().enumerate().filter(|(_, p)| inside(p)) {
        let c = cell(*p);
        for dz in -1..=1 {
            for dy in -1..=1 {
                for dx in -1..=1 {
                    let Some(others) = cells.get(&(c + IVec3::new(dx, dy, dz))) else {
                        continue;
                    };
                    for &j in others.iter().filter(|&&j| j > i) {
                        let overlap = 2.0 * r - p.distance(positions[j]);
                        q.max_penetration = q.max_penetration.max(overlap);
                    }
                }
            }
        }
    }
    q
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pit::Start;

    fn pit_of(positions: &[DVec3]) -> Pit {
        let mut pit = Pit::new(positions.len(), 1);
        pit.size = DVec3::new(2.0, 2.0, 2.0);
        pit.start = positions
            .iter()
            .map(|&position| Start {
                position,
                velocity: DVec3::ZERO,
            })
            .collect();
        pit
    }

    #[test]
    fn finds_the_deepest_overlap_between_balls_and_with_walls() {
        let positions = [
            DVec3::new(0.0, 0.5, 0.0),
            DVec3::new(0.17, 0.5, 0.0), // 0.03 into the first
            DVec3::new(0.5, 0.08, 0.5), // 0.02 into the floor
            DVec3::new(-0.5, 0.5, -0.5),
        ];
        let pit = pit_of(&positions);
        let velocities = [DVec3::ZERO, DVec3::X * 0.01, DVec3::ZERO, DVec3::Y * 2.0];
        let q = measure(&pit, &positions, &velocities);
        assert!((q.max_penetration - 0.03).abs() < 1e-12, "{q:?}");
        assert_eq!(q.escapes, 0);
        assert!((q.kinetic_energy - 0.5 * (0.0001 + 4.0)).abs() < 1e-12);
        assert!(!q.at_rest());
        assert_eq!(q.resting, 3);
    }

    #[test]
    fn counts_balls_outside_the_box_as_escaped() {
        let positions = [
            DVec3::new(0.0, -0.05, 0.0),
            DVec3::new(1.5, 0.5, 0.0),
            DVec3::new(0.0, f64::NAN, 0.0),
            DVec3::new(0.0, 0.1, 0.0),
        ];
        let pit = pit_of(&positions);
        let q = measure(&pit, &positions, &[DVec3::ZERO; 4]);
        assert_eq!(q.escapes, 3);
        assert!(q.at_rest());
        assert_eq!(q.resting, 1, "escaped balls are not counted");
        assert!(q.max_penetration <= 1e-12);
    }
}
