//! The tumbler's paint: a texture made here, in the mesh's UV space.
//!
//! Alpha marks paint that takes each tumbler's own colour (its coat); the
//! face, the trim and the hair keep their colours. UVs follow
//! [`crate::tumbler_mesh()`]: `u` around the axis with the front at 0.25, `v`
//! from the top (0) to the bottom (1) along the same curve as the mesh rings.

use image::{Rgba, RgbaImage};
use rolypoly_physics::SphereSpec;

pub const WIDTH: u32 = 512;
pub const HEIGHT: u32 = 512;

/// The height on the axis of a texel row, matching the mesh's ring spacing.
fn height_at(v: f64, lo: f64, hi: f64) -> f64 {
    hi - (hi - lo) * (0.5 - 0.5 * (std::f64::consts::PI * v).cos())
}

fn mix(a: [f64; 3], b: [f64; 3], t: f64) -> [f64; 3] {
    let t = t.clamp(0.0, 1.0);
    [
        a[0] + (b[0] - a[0]) * t,
        a[1] + (b[1] - a[1]) * t,
        a[2] + (b[2] - a[2]) * t,
    ]
}

/// 1 inside a disc of radius `r` around the origin, 0 outside, with a soft rim.
fn disc(x: f64, y: f64, r: f64) -> f64 {
    let d = (x * x + y * y).sqrt();
    ((r - d) / (0.15 * r + 0.002)).clamp(0.0, 1.0)
}

/// Paints the tumbler made of `spheres` (sphere 0 is the round bottom).
pub fn tumbler_paint(spheres: &[SphereSpec]) -> RgbaImage {
    let (lo, hi) = rolypoly_physics::axis_extent(spheres);
    let bottom = spheres[0];
    // The head: the highest sphere that is not a small knot on top.
    let head = spheres
        .iter()
        .filter(|s| s.radius >= 0.25 * bottom.radius)
        .fold(
            bottom,
            |best, s| if s.height > best.height { *s } else { best },
        );
    let knot_start = head.height + 0.75 * head.radius;
    let neck = head.height - 0.8 * head.radius;

    let skin = [0.98, 0.86, 0.74];
    let hair = [0.06, 0.05, 0.05];
    let gold = [0.95, 0.72, 0.25];
    let coat = [0.92, 0.92, 0.92];
    let cream = [1.0, 0.97, 0.88];

    let mut img = RgbaImage::new(WIDTH, HEIGHT);
    for py in 0..HEIGHT {
        let v = (py as f64 + 0.5) / HEIGHT as f64;
        let y = height_at(v, lo, hi);
        for px in 0..WIDTH {
            let u = (px as f64 + 0.5) / WIDTH as f64;
            // Angle from the front, in radians, in -pi..pi.
            let mut a = (u - 0.25) * std::f64::consts::TAU;
            if a > std::f64::consts::PI {
                a -= std::f64::consts::TAU;
            }
            let (rgb, tinted) = if y >= knot_start {
                (hair, 0.0)
            } else if y >= neck {
                // The face, drawn on the head in arc lengths (metres).
                let r = head.radius;
                let x = a * r * 0.9;
                let h = y - head.height;
                let mut c = skin;
                // Hair framing the face from behind and above.
                let behind = (a.abs() - 1.3).max(0.0) + ((h - 0.45 * r).max(0.0) * 6.0);
                c = mix(c, hair, (behind * 4.0).min(1.0));
                let eyes = disc(x - 0.32 * r, h - 0.12 * r, 0.09 * r)
                    + disc(x + 0.32 * r, h - 0.12 * r, 0.09 * r);
                let shine = disc(x - 0.29 * r, h - 0.16 * r, 0.03 * r)
                    + disc(x + 0.35 * r, h - 0.16 * r, 0.03 * r);
                let cheeks = disc(x - 0.5 * r, h + 0.15 * r, 0.14 * r)
                    + disc(x + 0.5 * r, h + 0.15 * r, 0.14 * r);
                // A smile: a thin arc below the eyes.
                let smile_d = ((x * x + (h + 0.05 * r).powi(2)).sqrt() - 0.3 * r).abs();
                let smile = if h < -0.2 * r && x.abs() < 0.22 * r {
                    ((0.035 * r - smile_d) / (0.01 * r)).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                c = mix(c, [0.95, 0.45, 0.45], cheeks * 0.6);
                c = mix(c, [0.55, 0.12, 0.12], smile);
                c = mix(c, hair, eyes);
                c = mix(c, [1.0, 1.0, 1.0], shine);
                (c, 0.0)
            } else {
                // The coat: tinted, with a gold collar and belt, cream flowers
                // around the belly and a darker round bottom.
                let collar = ((neck - y) < 0.025) as u8 as f64;
                let belt_y = bottom.height + 0.55 * bottom.radius;
                let belt = ((y - belt_y).abs() < 0.02) as u8 as f64;
                let mut c = coat;
                let mut tint = 1.0;
                if y < belt_y {
                    c = [0.72, 0.72, 0.72];
                }
                // Flowers: eight around, on the belly.
                let sector = std::f64::consts::TAU / 8.0;
                let da = (a + sector * 0.5).rem_euclid(sector) - sector * 0.5;
                let belly_y = 0.5 * (belt_y + neck);
                let fx = da * 0.22;
                let fy = y - belly_y;
                let petals = (0..5)
                    .map(|k| {
                        let t = k as f64 * std::f64::consts::TAU / 5.0;
                        disc(fx - 0.03 * t.cos(), fy - 0.03 * t.sin(), 0.022)
                    })
                    .fold(0.0, f64::max);
                let heart = disc(fx, fy, 0.014);
                if petals > 0.0 {
                    c = mix(c, cream, petals);
                    tint = 1.0 - petals;
                }
                if heart > 0.0 {
                    c = mix(c, gold, heart);
                    tint *= 1.0 - heart;
                }
                if collar + belt > 0.0 {
                    c = gold;
                    tint = 0.0;
                }
                (c, tint)
            };
            let to_srgb = |x: f64| (255.0 * x.clamp(0.0, 1.0).powf(1.0 / 2.2)).round() as u8;
            img.put_pixel(
                px,
                py,
                Rgba([
                    to_srgb(rgb[0]),
                    to_srgb(rgb[1]),
                    to_srgb(rgb[2]),
                    (255.0 * tinted).round() as u8,
                ]),
            );
        }
    }
    img
}
