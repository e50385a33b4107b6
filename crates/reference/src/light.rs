//! The lights: spheres that glow evenly. Drawn towards by sampling the
//! cone in which a point sees the sphere.
//!
//! A reference light has the power of the real-time light it stands for
//! (`rolypoly_render::power_of`): emitted evenly from a small sphere, the
//! same power lights the room by the true inverse square.

use glam::Vec3;
use std::f32::consts::PI;

use crate::material::orthonormal;
use crate::sampler::Sampler;

/// A sphere that glows evenly.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SphereLight {
    /// Its centre (m).
    pub centre: Vec3,
    /// Its radius (m).
    pub radius: f32,
    /// The radiance of its surface.
    pub radiance: Vec3,
}

/// A direction drawn towards a light.
#[derive(Clone, Copy, Debug)]
pub struct LightSample {
    /// Towards the light.
    pub dir: Vec3,
    /// How far to its surface.
    pub distance: f32,
    /// The density it was drawn with (per steradian).
    pub pdf: f32,
}

impl SphereLight {
    /// A sphere of `radius` at `centre` that sends out `intensity`
    /// (W / sr) in every direction: its radiance is the intensity over
    /// the disc it shows.
    pub fn of_intensity(centre: Vec3, radius: f32, intensity: Vec3) -> SphereLight {
        SphereLight {
            centre,
            radius,
            radiance: intensity / (PI * radius * radius),
        }
    }

    /// The cosine of the half-angle of the cone in which `point` sees it,
    /// or `None` from inside it.
    fn cone(&self, point: Vec3) -> Option<(Vec3, f32, f32)> {
        let to_centre = self.centre - point;
        let d2 = to_centre.length_squared();
        let r2 = self.radius * self.radius;
        if d2 <= r2 {
            return None;
        }
        let d = d2.sqrt();
        let sin2 = r2 / d2;
        // 1 - sqrt(1 - sin^2), without the cancellation for small spheres.
        let one_minus_cos = sin2 / (1.0 + (1.0 - sin2).sqrt());
        Some((to_centre / d, d, one_minus_cos))
    }

    /// Draws a direction from `point` to the sphere, evenly over the cone
    /// it fills.
    pub fn sample(&self, point: Vec3, rng: &mut Sampler) -> Option<LightSample> {
        let (axis, d, one_minus_cos) = self.cone(point)?;
        let (u1, u2) = (rng.uniform(), rng.uniform());
        let cos = 1.0 - u1 * one_minus_cos;
        let dir = orthonormal(axis).local(cos, u2);
        // Where that direction meets the sphere (it does, up to rounding
        // at the cone's edge, where it grazes it).
        let along = (point - self.centre).dot(dir);
        let across = (point - self.centre) - along * dir;
        let gap = (self.radius * self.radius - across.length_squared()).max(0.0);
        let distance = (-along - gap.sqrt()).clamp(0.0, d);
        Some(LightSample {
            dir,
            distance,
            pdf: 1.0 / (2.0 * PI * one_minus_cos),
        })
    }

    /// The density with which [`SphereLight::sample`] draws any direction
    /// that meets the sphere from `point`.
    pub fn pdf(&self, point: Vec3) -> f32 {
        self.cone(point).map_or(0.0, |(_, _, one_minus_cos)| {
            1.0 / (2.0 * PI * one_minus_cos)
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn samples_fill_the_cone_the_sphere_fills() {
        let light = SphereLight::of_intensity(Vec3::new(0.0, 3.0, 0.0), 0.2, Vec3::ONE);
        let point = Vec3::new(1.0, 0.0, 0.5);
        let mut rng = Sampler::new(3, 0, 0);
        for _ in 0..1000 {
            let s = light.sample(point, &mut rng).unwrap();
            let hit = point + s.dir * s.distance;
            assert!((hit.distance(light.centre) - light.radius).abs() < 1e-3);
            assert_eq!(s.pdf, light.pdf(point));
        }
        assert!(light.sample(light.centre, &mut rng).is_none());
    }
}
