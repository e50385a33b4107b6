//! From radiance to a picture, as the real-time frame's last pass does it
//! (tonemap.wgsl): exposure, the ACES filmic curve, sRGB.

use glam::Vec3;
use image::{Rgba, RgbaImage};

use crate::render::Radiance;

/// Narkowicz's fit of the ACES filmic curve, as tonemap.wgsl's `aces`.
pub fn aces(x: Vec3) -> Vec3 {
    let (a, b, c, d, e) = (2.51, 0.03, 2.43, 0.59, 0.14);
    ((x * (a * x + b)) / (x * (c * x + d) + e)).clamp(Vec3::ZERO, Vec3::ONE)
}

/// sRGB's transfer function, to 8 bits, as the output's sRGB format
/// stores a value.
fn encode(c: f32) -> u8 {
    let s = if c <= 0.003_130_8 {
        12.92 * c
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    };
    (s * 255.0).round().clamp(0.0, 255.0) as u8
}

/// The picture of `radiance` at `exposure`.
pub fn to_picture(radiance: &Radiance, exposure: f32) -> RgbaImage {
    let mut out = RgbaImage::new(radiance.width, radiance.height);
    for (pixel, value) in out.pixels_mut().zip(&radiance.pixels) {
        let c = aces(*value * exposure);
        *pixel = Rgba([encode(c.x), encode(c.y), encode(c.z), 255]);
    }
    out
}
