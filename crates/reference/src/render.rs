//! A picture's radiance: every pixel's samples averaged, the rows shared
//! among the CPU's threads.

use glam::{Vec2, Vec3};
use rayon::prelude::*;
use rolypoly_render::Camera;

use crate::sampler::Sampler;
use crate::scene::Scene;
use crate::trace::radiance;

/// Linear radiance, a pixel at a time, rows from the top.
#[derive(Clone, Debug, PartialEq)]
pub struct Radiance {
    /// Pixels across.
    pub width: u32,
    /// Pixels down.
    pub height: u32,
    /// `width * height` pixels.
    pub pixels: Vec<Vec3>,
}

impl Radiance {
    /// The pixel at column `x`, row `y`.
    pub fn at(&self, x: u32, y: u32) -> Vec3 {
        self.pixels[(y * self.width + x) as usize]
    }
}

/// The threads a picture is traced on.
pub fn threads() -> usize {
    rayon::current_num_threads()
}

/// The scene seen by `camera` in a `width` x `height` picture, `spp`
/// samples a pixel, each at a point of its own within the pixel (a box
/// filter), drawn from the streams `seed` gives. `row_done` is called as
/// each row is finished, from whichever thread finished it.
pub fn render(
    scene: &Scene,
    camera: &Camera,
    (width, height): (u32, u32),
    spp: u32,
    seed: u64,
    row_done: &(dyn Fn() + Sync),
) -> Radiance {
    let size = Vec2::new(width as f32, height as f32);
    let pixels = (0..height)
        .into_par_iter()
        .flat_map_iter(|y| {
            let row: Vec<Vec3> = (0..width)
                .map(|x| {
                    let pixel = u64::from(y) * u64::from(width) + u64::from(x);
                    let mut sum = Vec3::ZERO;
                    for s in 0..spp {
                        let mut rng = Sampler::new(seed, pixel, u64::from(s));
                        let at = Vec2::new(x as f32 + rng.uniform(), y as f32 + rng.uniform());
                        let (origin, dir) = camera.ray(at, size);
                        sum += radiance(scene, crate::geometry::Ray { origin, dir }, &mut rng);
                    }
                    sum / spp.max(1) as f32
                })
                .collect();
            row_done();
            row
        })
        .collect();
    Radiance {
        width,
        height,
        pixels,
    }
}
