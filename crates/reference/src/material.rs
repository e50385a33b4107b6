//! How a surface reflects: a diffuse base and the real-time frame's
//! Blinn-Phong highlight made a lobe that conserves energy.
//!
//! The real-time highlight adds `specular (n . h)^s` of the light, however
//! wide the lobe. Here the lobe is the normalised Blinn-Phong
//! distribution, `rho (s + 8) / (8 pi) (n . h)^s`, with its reflectance
//! `rho = 8 specular / (s + 8)` chosen to keep the highlight's peak where
//! the real-time frame has it; the diffuse base keeps the rest, `1 - rho`
//! of its albedo. What is reflected never exceeds what arrives.

use glam::{Vec2, Vec3};
use rolypoly_render::Finish;
use std::f32::consts::PI;

use crate::sampler::Sampler;

/// Where a surface's colour comes from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Albedo {
    /// One colour all over.
    Flat(Vec3),
    /// The wooden floor's planks in this colour.
    Wood(Vec3),
    /// Plaster of this colour.
    Plaster(Vec3),
    /// The tumblers' paint, its coat in this colour.
    Painted(Vec3),
}

/// A surface: its colour, its highlight and the light it gives off.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Material {
    /// Its colour (linear albedo).
    pub albedo: Albedo,
    /// Its highlight.
    pub finish: Finish,
    /// The radiance it emits (W / (m^2 sr), in the frame's units).
    pub emission: Vec3,
}

impl Material {
    /// A diffuse surface of one colour, without highlight or light.
    pub fn matte(albedo: Vec3) -> Material {
        Material {
            albedo: Albedo::Flat(albedo),
            finish: Finish {
                specular: 0.0,
                shininess: 1.0,
            },
            emission: Vec3::ZERO,
        }
    }
}

/// The reflection at one point: the material with its colour there, in
/// the frame of its shading normal.
#[derive(Clone, Copy, Debug)]
pub struct Bsdf {
    normal: Vec3,
    diffuse: Vec3,
    glossy: f32,
    shininess: f32,
    /// The chance of sampling the lobe rather than the base.
    lobe_share: f32,
}

/// A direction drawn from the reflection.
#[derive(Clone, Copy, Debug)]
pub struct Bounce {
    /// Where the light comes from.
    pub dir: Vec3,
    /// The reflection's value for it.
    pub value: Vec3,
    /// The chance density it was drawn with (per steradian).
    pub pdf: f32,
}

impl Bsdf {
    /// The reflection of a surface of colour `albedo` and highlight
    /// `finish` with normal `normal`.
    pub fn new(albedo: Vec3, finish: Finish, normal: Vec3) -> Bsdf {
        let s = finish.shininess;
        let glossy = (8.0 * finish.specular / (s + 8.0)).clamp(0.0, 1.0);
        let diffuse = albedo * (1.0 - glossy);
        let weight = diffuse.dot(Vec3::splat(1.0 / 3.0)) + glossy;
        Bsdf {
            normal,
            diffuse,
            glossy,
            shininess: s,
            lobe_share: if weight > 0.0 { glossy / weight } else { 0.0 },
        }
    }

    /// The reflection from `incoming` to `outgoing` (both away from the
    /// surface), per steradian.
    pub fn value(&self, outgoing: Vec3, incoming: Vec3) -> Vec3 {
        let n = self.normal;
        if n.dot(incoming) <= 0.0 || n.dot(outgoing) <= 0.0 {
            return Vec3::ZERO;
        }
        let half = (outgoing + incoming).normalize();
        let lobe = self.glossy * (self.shininess + 8.0) / (8.0 * PI)
            * n.dot(half).max(0.0).powf(self.shininess);
        self.diffuse / PI + Vec3::splat(lobe)
    }

    /// The density with which [`Bsdf::sample`] draws `incoming`.
    pub fn pdf(&self, outgoing: Vec3, incoming: Vec3) -> f32 {
        let n = self.normal;
        let cos = n.dot(incoming);
        if cos <= 0.0 || n.dot(outgoing) <= 0.0 {
            return 0.0;
        }
        let half = (outgoing + incoming).normalize();
        let s = self.shininess;
        let lobe = (s + 1.0) / (2.0 * PI) * n.dot(half).max(0.0).powf(s)
            / (4.0 * outgoing.dot(half)).max(1e-8);
        self.lobe_share * lobe + (1.0 - self.lobe_share) * cos / PI
    }

    /// Draws where light comes from, by the lobe (its half vector from
    /// `(n . h)^s`) or by the base (the cosine), as each reflects.
    pub fn sample(&self, outgoing: Vec3, rng: &mut Sampler) -> Option<Bounce> {
        let pick = rng.uniform();
        let (u1, u2) = (rng.uniform(), rng.uniform());
        let frame = orthonormal(self.normal);
        let incoming = if pick < self.lobe_share {
            let cos = u1.powf(1.0 / (self.shininess + 1.0));
            let half = frame.local(cos, u2);
            2.0 * outgoing.dot(half) * half - outgoing
        } else {
            frame.local(u1.sqrt(), u2)
        };
        let pdf = self.pdf(outgoing, incoming);
        (pdf > 0.0).then(|| Bounce {
            dir: incoming,
            value: self.value(outgoing, incoming),
            pdf,
        })
    }
}

/// An orthonormal frame around a unit vector (Duff et al. 2017).
pub struct Frame {
    tangent: Vec3,
    bitangent: Vec3,
    normal: Vec3,
}

/// The frame around `n`.
pub fn orthonormal(n: Vec3) -> Frame {
    let sign = 1.0f32.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    Frame {
        tangent: Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x),
        bitangent: Vec3::new(b, sign + n.y * n.y * a, -n.y),
        normal: n,
    }
}

impl Frame {
    /// The direction at `cos` from the normal, turned by `turn` of a full
    /// circle around it.
    pub fn local(&self, cos: f32, turn: f32) -> Vec3 {
        let sin = (1.0 - cos * cos).max(0.0).sqrt();
        let (s, c) = (2.0 * PI * turn).sin_cos();
        let v = Vec2::new(c, s) * sin;
        self.tangent * v.x + self.bitangent * v.y + self.normal * cos
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The share of light from `outgoing` reflected anywhere, by
    /// importance sampling.
    fn albedo_seen_from(bsdf: &Bsdf, outgoing: Vec3, n: u64) -> Vec3 {
        let mut sum = Vec3::ZERO;
        for i in 0..n {
            let mut rng = Sampler::new(5, i, 0);
            if let Some(b) = bsdf.sample(outgoing, &mut rng) {
                sum += b.value * b.dir.dot(bsdf.normal) / b.pdf;
            }
        }
        sum / n as f32
    }

    #[test]
    fn reflects_no_more_than_arrives_and_keeps_the_highlight_peak() {
        let n = Vec3::new(0.3, 0.9, -0.2).normalize();
        for (specular, shininess) in [(0.9, 110.0), (0.55, 60.0), (0.35, 40.0), (0.04, 8.0)] {
            let finish = Finish {
                specular,
                shininess,
            };
            let bsdf = Bsdf::new(Vec3::ONE, finish, n);
            for tilt in [0.0f32, 0.6, 1.2] {
                let frame = orthonormal(n);
                let outgoing = frame.local(tilt.cos(), 0.3);
                let reflected = albedo_seen_from(&bsdf, outgoing, 40_000);
                assert!(
                    reflected.max_element() < 1.01,
                    "{specular} {shininess} {tilt}: {reflected}"
                );
                // A white surface seen head on keeps nearly all of it.
                if tilt == 0.0 {
                    assert!(reflected.min_element() > 0.95, "{reflected}");
                }
            }
            // The lobe's peak (mirror direction) adds `specular / pi` per
            // steradian, as the real-time highlight adds `specular` of the
            // light in its units (where diffuse adds albedo, here albedo/pi).
            let lobe_only = Bsdf::new(Vec3::ZERO, finish, n);
            let peak = lobe_only.value(n, n).x;
            assert!(
                (peak * PI - specular).abs() < 1e-4 * specular.max(1.0),
                "{peak}"
            );
        }
    }

    #[test]
    fn the_density_is_the_one_sampled_from() {
        // Integrates to one over the hemisphere, by uniform sampling.
        let n = Vec3::Y;
        let bsdf = Bsdf::new(
            Vec3::splat(0.5),
            Finish {
                specular: 0.55,
                shininess: 60.0,
            },
            n,
        );
        let outgoing = Vec3::new(0.5, 0.8, 0.0).normalize();
        let frame = orthonormal(n);
        let count = 400_000;
        let mut total = 0.0f64;
        for i in 0..count {
            let mut rng = Sampler::new(9, i, 1);
            let dir = frame.local(rng.uniform(), rng.uniform());
            total += f64::from(bsdf.pdf(outgoing, dir)) * 2.0 * std::f64::consts::PI;
        }
        let integral = total / count as f64;
        // Directions of the lobe that fall below the surface are lost.
        assert!(integral > 0.97 && integral < 1.01, "{integral}");
    }
}
