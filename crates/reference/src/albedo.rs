//! The surfaces' colours as the real-time frame paints them: the wooden
//! floor's planks and grain and the walls' plaster, as `wood` and
//! `plaster` in scene.wgsl compute them, and the tumblers' paint, read as
//! the GPU reads its sRGB texture.

use glam::{Vec2, Vec3};
use image::RgbaImage;

fn fract(x: f32) -> f32 {
    x - x.floor()
}

fn fract2(p: Vec2) -> Vec2 {
    p - p.floor()
}

fn smoothstep(edge0: f32, edge1: f32, x: f32) -> f32 {
    let t = ((x - edge0) / (edge1 - edge0)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

fn hash2(p: Vec2) -> f32 {
    let q = fract2(p * Vec2::new(123.34, 456.21));
    let r = q + q.dot(q + Vec2::splat(45.32));
    fract(r.x * r.y)
}

fn value_noise(p: Vec2) -> f32 {
    let i = p.floor();
    let f = fract2(p);
    let u = f * f * (Vec2::splat(3.0) - 2.0 * f);
    let a = hash2(i);
    let b = hash2(i + Vec2::X);
    let c = hash2(i + Vec2::Y);
    let d = hash2(i + Vec2::ONE);
    let lerp = |x: f32, y: f32, t: f32| x + (y - x) * t;
    lerp(lerp(a, b, u.x), lerp(c, d, u.x), u.y)
}

/// The floor's colour at `p` (its x and z): planks 0.2 m wide along x,
/// each with its own shade and grain, dark seams between.
pub fn wood(base: Vec3, p: Vec2) -> Vec3 {
    let plank_width = 0.2;
    let row = (p.y / plank_width).floor();
    let along = p.x + hash2(Vec2::new(row, 7.0)) * 3.0;
    let plank = (along / 1.6).floor();
    let id = Vec2::new(row, plank);
    let shade = 0.82 + 0.3 * hash2(id);
    let grain_pos = Vec2::new(
        along * 3.0,
        (p.y - row * plank_width) * 40.0 + hash2(id) * 10.0,
    );
    let grain =
        value_noise(grain_pos * Vec2::new(0.5, 1.0)) * 0.6 + value_noise(grain_pos * 4.0) * 0.4;
    let rings = 0.5 + 0.5 * (grain * 12.0 + along * 2.0).sin();
    let v = fract(p.y / plank_width);
    let u = fract(along / 1.6);
    let seam = smoothstep(0.0, 0.03, v)
        * smoothstep(1.0, 0.97, v)
        * smoothstep(0.0, 0.004, u)
        * smoothstep(1.0, 0.996, u);
    base * shade * (0.78 + 0.22 * rings) * (0.55 + 0.45 * seam)
}

/// A wall's colour at `p`: a faint plaster texture.
pub fn plaster(base: Vec3, p: Vec3) -> Vec3 {
    let n = value_noise(Vec2::new(p.x, p.y) * 9.0 + Vec2::new(p.z, p.z) * 5.0) * 0.5
        + value_noise(Vec2::new(p.z, p.y) * 23.0 + Vec2::new(p.x, p.x) * 3.0) * 0.5;
    base * (0.93 + 0.07 * n)
}

/// sRGB's transfer function, undone.
fn srgb_to_linear(c: u8) -> f32 {
    let c = f32::from(c) / 255.0;
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// The tumblers' paint as the GPU samples it: sRGB texels made linear,
/// filtered bilinearly, repeating around (u) and clamped top to bottom (v).
#[derive(Clone, Debug)]
pub struct Paint {
    width: usize,
    height: usize,
    /// Linear colour and, in w, how much of the tumbler's own colour.
    texels: Vec<glam::Vec4>,
}

impl Paint {
    /// The paint of this image.
    pub fn new(image: &RgbaImage) -> Paint {
        Paint {
            width: image.width() as usize,
            height: image.height() as usize,
            texels: image
                .pixels()
                .map(|p| {
                    glam::Vec4::new(
                        srgb_to_linear(p[0]),
                        srgb_to_linear(p[1]),
                        srgb_to_linear(p[2]),
                        f32::from(p[3]) / 255.0,
                    )
                })
                .collect(),
        }
    }

    /// The colour of a tumbler of colour `tint` at `uv`.
    pub fn at(&self, uv: Vec2, tint: Vec3) -> Vec3 {
        let x = uv.x * self.width as f32 - 0.5;
        let y = (uv.y * self.height as f32 - 0.5).clamp(0.0, (self.height - 1) as f32);
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let w = self.width as i64;
        let texel = |xi: f32, yi: f32| {
            let col = (xi as i64).rem_euclid(w) as usize;
            let row = (yi as usize).min(self.height - 1);
            self.texels[row * self.width + col]
        };
        let top = texel(x0, y0).lerp(texel(x0 + 1.0, y0), fx);
        let bottom = texel(x0, y0 + 1.0).lerp(texel(x0 + 1.0, y0 + 1.0), fx);
        let p = top.lerp(bottom, fy);
        let rgb = p.truncate();
        rgb.lerp(rgb * tint, p.w)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wood_averages_to_the_shade_the_real_time_bounce_assumes() {
        // lighting.rs takes the floor's grain, planks and seams to darken
        // its colour by 0.84 on average; this port of the shader's wood
        // measures 0.81.
        let n = 400;
        let mut sum = 0.0;
        for i in 0..n {
            for j in 0..n {
                let p = Vec2::new(i as f32, j as f32) * (8.0 / n as f32) - 4.0;
                sum += wood(Vec3::ONE, p).x;
            }
        }
        let mean = sum / (n * n) as f32;
        assert!((mean - 0.84).abs() < 0.05, "{mean}");
    }

    #[test]
    fn paint_reads_linear_colour_and_tints_by_alpha() {
        let mut image = RgbaImage::new(2, 1);
        image.put_pixel(0, 0, image::Rgba([255, 255, 255, 255]));
        image.put_pixel(1, 0, image::Rgba([188, 188, 188, 0]));
        let paint = Paint::new(&image);
        let tint = Vec3::new(1.0, 0.0, 0.0);
        // The centre of texel 0: white, all tinted.
        let c = paint.at(Vec2::new(0.25, 0.5), tint);
        assert!((c - tint).length() < 1e-5, "{c}");
        // Texel 1: sRGB 188 is half as bright in linear light, untinted.
        let c = paint.at(Vec2::new(0.75, 0.5), tint);
        assert!((c - Vec3::splat(0.5029)).length() < 1e-3, "{c}");
    }
}
