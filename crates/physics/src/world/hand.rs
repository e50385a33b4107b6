//! The hand: a ray picks a tumbler, the hand holds it by a spring and
//! lets go (I5).

use crate::tumbler::Grip;
use glam::DVec3;

use super::World;

/// A tumbler hit by a pick ray.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pick {
    /// The tumbler hit.
    pub tumbler: usize,
    /// Where the ray hit it (m).
    pub point: DVec3,
    /// Distance along the ray.
    pub distance: f64,
}

impl World {
    /// The nearest tumbler sphere hit by the ray `origin + t dir`, t >= 0.
    pub fn pick(&self, origin: DVec3, dir: DVec3) -> Option<Pick> {
        let dir = dir.try_normalize()?;
        let mut best: Option<Pick> = None;
        for (ti, t) in self.tumblers.iter().enumerate() {
            for (si, s) in self.shape.spheres.iter().enumerate() {
                let c = t.sphere_center(&self.shape, si);
                let oc = origin - c;
                let b = oc.dot(dir);
                let disc = b * b - (oc.length_squared() - s.radius * s.radius);
                if disc < 0.0 {
                    continue;
                }
                let hit = -b - disc.sqrt();
                let hit = if hit >= 0.0 { hit } else { -b + disc.sqrt() };
                if hit >= 0.0 && best.is_none_or(|p| hit < p.distance) {
                    best = Some(Pick {
                        tumbler: ti,
                        point: origin + dir * hit,
                        distance: hit,
                    });
                }
            }
        }
        best
    }

    /// Takes hold of tumbler `tumbler` at world point `point` (I5).
    pub fn grab(&mut self, tumbler: usize, point: DVec3) {
        if let Some(t) = self.tumblers.get_mut(tumbler) {
            let anchor = t.orientation.inverse() * (point - t.center);
            t.grip = Some(Grip {
                anchor,
                target: point,
            });
        }
    }

    /// Moves the hand holding a tumbler; the tumbler follows through a
    /// spring-damper force at the grab point.
    pub fn drag_to(&mut self, target: DVec3) {
        for t in &mut self.tumblers {
            if let Some(g) = &mut t.grip {
                g.target = target;
            }
        }
    }

    /// Lets go: the tumbler keeps the motion it has.
    pub fn release(&mut self) {
        for t in &mut self.tumblers {
            t.grip = None;
        }
    }

    /// Index of the tumbler being held, if any.
    pub fn grabbed(&self) -> Option<usize> {
        self.tumblers.iter().position(|t| t.grip.is_some())
    }
}
