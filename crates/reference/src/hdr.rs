//! The reference's linear radiance, unclipped, as an OpenEXR file.

use std::path::Path;

use crate::render::Radiance;

/// Writes `radiance` to `path` as 32-bit float RGB.
pub fn write_exr(radiance: &Radiance, path: &Path) -> Result<(), exr::error::Error> {
    exr::prelude::write_rgb_file(
        path,
        radiance.width as usize,
        radiance.height as usize,
        |x, y| {
            let p = radiance.at(x as u32, y as u32);
            (p.x, p.y, p.z)
        },
    )
}
