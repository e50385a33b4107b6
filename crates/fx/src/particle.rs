//! Particles and their curves (X5): each kind has a size curve and an alpha
//! curve over its normalised life `s` in 0..1, scaled by per-particle
//! constants `k_scale` and `k_alpha`: a particle's size is `k_scale` times
//! its size curve, its alpha `k_alpha` times its alpha curve.

use glam::Vec3;
use serde::{Deserialize, Serialize};

/// What a particle is for, which picks its curves.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum ParticleKind {
    /// Dropped along the fireball's path: shrinks and fades.
    Trail,
    /// Spreads in a wall the fireball hit: grows slowly, then shrinks
    /// sharply; its alpha is inversely proportional to its size.
    WallHit,
    /// Falls into a ball the fireball hit, arriving at the centre exactly
    /// when its life ends, shrinking on the way.
    Collapse,
    /// The energy burst when a collapse ends: grows and fades.
    Burst,
}

/// Where the wall-hit size curve turns from slow growth to a sharp fall.
pub const WALL_HIT_PEAK: f32 = 0.75;

impl ParticleKind {
    /// Size over normalised life, before `k_scale`.
    pub fn size(self, s: f32) -> f32 {
        let s = s.clamp(0.0, 1.0);
        match self {
            ParticleKind::Trail => 1.0 - s,
            ParticleKind::WallHit => {
                if s < WALL_HIT_PEAK {
                    0.5 + 0.5 * s / WALL_HIT_PEAK
                } else {
                    let t = (s - WALL_HIT_PEAK) / (1.0 - WALL_HIT_PEAK);
                    1.0 - t * t
                }
            }
            ParticleKind::Collapse => 1.0 - 0.8 * s,
            ParticleKind::Burst => 0.2 + 0.8 * s.sqrt(),
        }
    }

    /// Alpha over normalised life, before `k_alpha`, at most 1.
    pub fn alpha(self, s: f32) -> f32 {
        let s = s.clamp(0.0, 1.0);
        match self {
            ParticleKind::Trail => (1.0 - s) * (1.0 - s),
            // Inversely proportional to size: small cubes glow brightest.
            ParticleKind::WallHit => (0.5 / self.size(s).max(1e-3)).min(1.0),
            ParticleKind::Collapse => 0.4 + 0.6 * s,
            ParticleKind::Burst => 1.0 - s,
        }
    }
}

/// One particle: a small glowing cube.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Particle {
    /// What it is for.
    pub kind: ParticleKind,
    /// Where it was born, and where it goes: a collapse particle moves in a
    /// straight line from `origin` to `target` over its life; the others stay.
    pub origin: Vec3,
    /// Where a collapse particle ends; the others' `origin`.
    pub target: Vec3,
    /// Seconds since birth.
    pub age: f32,
    /// Seconds it lives.
    pub life: f32,
    /// Its size at the curve's 1 (metres).
    pub k_scale: f32,
    /// Its alpha at the curve's 1.
    pub k_alpha: f32,
    /// A fixed random turn, so cubes do not all line up.
    pub spin: Vec3,
}

impl Particle {
    /// A particle of `kind` born at `origin`, living `life` seconds, staying where it is.
    pub fn new(
        kind: ParticleKind,
        origin: Vec3,
        life: f32,
        k_scale: f32,
        k_alpha: f32,
    ) -> Particle {
        Particle {
            kind,
            origin,
            target: origin,
            age: 0.0,
            life,
            k_scale,
            k_alpha,
            spin: Vec3::ZERO,
        }
    }

    /// Normalised life: 0 at birth, 1 at death.
    pub fn progress(&self) -> f32 {
        (self.age / self.life).min(1.0)
    }

    /// Whether it still lives.
    pub fn alive(&self) -> bool {
        self.age < self.life
    }

    /// Where it is now.
    pub fn position(&self) -> Vec3 {
        self.origin.lerp(self.target, self.progress())
    }

    /// Its size now (metres).
    pub fn size(&self) -> f32 {
        self.k_scale * self.kind.size(self.progress())
    }

    /// Its opacity now, at most 1.
    pub fn alpha(&self) -> f32 {
        (self.k_alpha * self.kind.alpha(self.progress())).min(1.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn samples() -> impl Iterator<Item = f32> {
        (0..=100).map(|i| i as f32 / 100.0)
    }

    #[test]
    fn trail_shrinks_and_fades_monotonically() {
        let k = ParticleKind::Trail;
        let pairs: Vec<(f32, f32)> = samples().map(|s| (k.size(s), k.alpha(s))).collect();
        for w in pairs.windows(2) {
            assert!(w[1].0 < w[0].0 && w[1].1 <= w[0].1, "{w:?}");
        }
        assert_eq!(k.size(1.0), 0.0);
        assert_eq!(k.alpha(1.0), 0.0);
    }

    #[test]
    fn wall_hit_grows_slowly_then_shrinks_sharply_with_alpha_inverse_to_size() {
        let k = ParticleKind::WallHit;
        let rise = (k.size(WALL_HIT_PEAK) - k.size(0.0)) / WALL_HIT_PEAK;
        let fall = (k.size(WALL_HIT_PEAK) - k.size(1.0)) / (1.0 - WALL_HIT_PEAK);
        assert!(rise > 0.0, "it must grow first");
        assert!(
            fall > 4.0 * rise,
            "the fall ({fall}/life) must be much sharper than the rise ({rise}/life)"
        );
        for s in samples() {
            let (size, alpha) = (k.size(s), k.alpha(s));
            if alpha < 1.0 {
                assert!(
                    (alpha * size - 0.5).abs() < 1e-5,
                    "alpha x size = {} at {s}",
                    alpha * size
                );
            }
        }
        // Monotone on each side of the peak.
        for w in samples().collect::<Vec<_>>().windows(2) {
            let (a, b) = (k.size(w[0]), k.size(w[1]));
            if w[1] <= WALL_HIT_PEAK {
                assert!(b > a);
            } else if w[0] >= WALL_HIT_PEAK {
                assert!(b < a);
            }
        }
    }

    #[test]
    fn collapse_arrives_at_the_centre_exactly_at_the_end_of_its_life() {
        let mut p = Particle::new(
            ParticleKind::Collapse,
            Vec3::new(0.5, 1.0, -0.2),
            0.4,
            0.05,
            1.0,
        );
        p.target = Vec3::new(0.1, 1.1, 0.0);
        let start = p.position().distance(p.target);
        let mut last = start;
        for i in 1..=40 {
            p.age = 0.4 * i as f32 / 40.0;
            let d = p.position().distance(p.target);
            assert!(d <= last + 1e-6);
            last = d;
        }
        assert!(last < 1e-3 * start, "{last} m from the centre at the end");
        assert!(ParticleKind::Collapse.size(1.0) < ParticleKind::Collapse.size(0.0));
    }

    #[test]
    fn burst_grows_and_fades() {
        let k = ParticleKind::Burst;
        assert!(k.size(1.0) > 3.0 * k.size(0.0));
        assert!(k.alpha(1.0) < k.alpha(0.0));
    }
}
