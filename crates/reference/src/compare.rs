//! How far a picture is from the reference, as a person would see it:
//! NVIDIA's FLIP (Andersson et al. 2020), which weighs differences of
//! colour and of edges by what the eye resolves at a viewing distance.
//! 0 is the same picture; 1 the largest difference.

use image::{RgbImage, RgbaImage};

/// The pixels a degree of vision spans: FLIP's default, a 0.7 m wide
/// monitor of 3840 pixels seen from 0.7 m.
pub const FLIP_PIXELS_PER_DEGREE: f32 = nv_flip::DEFAULT_PIXELS_PER_DEGREE;

/// A picture scored against the reference.
#[derive(Clone, Debug)]
pub struct Comparison {
    /// The mean of the error map.
    pub mean: f32,
    /// The error map, coloured (magma: dark is alike, bright is apart).
    pub map: RgbImage,
}

fn rgb(image: &RgbaImage) -> nv_flip::FlipImageRgb8 {
    let bytes: Vec<u8> = image.pixels().flat_map(|p| [p[0], p[1], p[2]]).collect();
    nv_flip::FlipImageRgb8::with_data(image.width(), image.height(), &bytes)
}

/// `test` scored against `reference` (pictures of one size).
pub fn compare(reference: &RgbaImage, test: &RgbaImage) -> Comparison {
    assert_eq!(
        reference.dimensions(),
        test.dimensions(),
        "pictures of one size"
    );
    let error = nv_flip::flip(rgb(reference), rgb(test), FLIP_PIXELS_PER_DEGREE);
    let mean = nv_flip::FlipPool::from_image(&error).mean();
    let colored = error.apply_color_lut(&nv_flip::magma_lut());
    let map = RgbImage::from_raw(reference.width(), reference.height(), colored.to_vec())
        .expect("FLIP's map has the pictures' size");
    Comparison { mean, map }
}
