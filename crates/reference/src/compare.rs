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

/// The structural similarity of `test` to `reference` (Wang et al. 2004),
/// pictures of one size: the mean, over every place an 11 x 11 Gaussian
/// window (sigma 1.5) fits, of how alike the two are there in mean, in
/// contrast and in structure, measured on luma (Rec. 601) in [0, 1].
/// 1 is the same picture; it falls as detail is lost, blurred or moved.
pub fn ssim(reference: &RgbaImage, test: &RgbaImage) -> f64 {
    assert_eq!(
        reference.dimensions(),
        test.dimensions(),
        "pictures of one size"
    );
    const RADIUS: usize = 5;
    const SIGMA: f64 = 1.5;
    // Wang et al.'s constants, for values of range 1.
    const C1: f64 = 0.01 * 0.01;
    const C2: f64 = 0.03 * 0.03;
    let (width, height) = (reference.width() as usize, reference.height() as usize);
    assert!(
        width > 2 * RADIUS && height > 2 * RADIUS,
        "pictures larger than the window"
    );
    let luma = |image: &RgbaImage| -> Vec<f64> {
        image
            .pixels()
            .map(|p| (0.299 * p[0] as f64 + 0.587 * p[1] as f64 + 0.114 * p[2] as f64) / 255.0)
            .collect()
    };
    let (a, b) = (luma(reference), luma(test));
    let kernel: Vec<f64> = {
        let raw: Vec<f64> = (0..=2 * RADIUS)
            .map(|k| (-0.5 * ((k as f64 - RADIUS as f64) / SIGMA).powi(2)).exp())
            .collect();
        let sum: f64 = raw.iter().sum();
        raw.into_iter().map(|w| w / sum).collect()
    };
    let blur = |values: &[f64]| window_means(values, width, height, &kernel);
    let product =
        |p: &[f64], q: &[f64]| -> Vec<f64> { p.iter().zip(q).map(|(x, y)| x * y).collect() };
    let (mean_a, mean_b) = (blur(&a), blur(&b));
    let (aa, bb, ab) = (
        blur(&product(&a, &a)),
        blur(&product(&b, &b)),
        blur(&product(&a, &b)),
    );
    let places = mean_a.len();
    let sum: f64 = (0..places)
        .map(|k| {
            let (ma, mb) = (mean_a[k], mean_b[k]);
            let var_a = aa[k] - ma * ma;
            let var_b = bb[k] - mb * mb;
            let cov = ab[k] - ma * mb;
            ((2.0 * ma * mb + C1) * (2.0 * cov + C2))
                / ((ma * ma + mb * mb + C1) * (var_a + var_b + C2))
        })
        .sum();
    sum / places as f64
}

/// The means of `values` (`width` x `height`) under the separable window
/// `kernel`, at every place it fits: along rows, then down columns.
fn window_means(values: &[f64], width: usize, height: usize, kernel: &[f64]) -> Vec<f64> {
    let span = kernel.len();
    let (inner_w, inner_h) = (width + 1 - span, height + 1 - span);
    let mut rows = Vec::with_capacity(inner_w * height);
    for y in 0..height {
        let row = &values[y * width..(y + 1) * width];
        rows.extend((0..inner_w).map(|x| {
            row[x..x + span]
                .iter()
                .zip(kernel)
                .map(|(v, w)| v * w)
                .sum::<f64>()
        }));
    }
    let mut means = Vec::with_capacity(inner_w * inner_h);
    for y in 0..inner_h {
        means.extend((0..inner_w).map(|x| {
            kernel
                .iter()
                .enumerate()
                .map(|(k, w)| rows[(y + k) * inner_w + x] * w)
                .sum::<f64>()
        }));
    }
    means
}

#[cfg(test)]
mod tests {
    use super::*;

    fn picture(width: u32, height: u32, shade: impl Fn(u32, u32) -> u8) -> RgbaImage {
        RgbaImage::from_fn(width, height, |x, y| {
            let v = shade(x, y);
            image::Rgba([v, v, v, 255])
        })
    }

    /// Flat pictures have no contrast or structure to compare: only their
    /// means, as (2 a b + C1) / (a^2 + b^2 + C1).
    #[test]
    fn flat_pictures_compare_by_their_means() {
        for (a, b) in [(100u8, 100u8), (100, 150), (20, 240)] {
            let (x, y) = (a as f64 / 255.0, b as f64 / 255.0);
            let c1 = 0.01f64 * 0.01;
            let expected = (2.0 * x * y + c1) / (x * x + y * y + c1);
            let got = ssim(&picture(32, 24, |_, _| a), &picture(32, 24, |_, _| b));
            assert!((got - expected).abs() < 1e-9, "{a} {b}: {got} {expected}");
        }
    }

    /// A picture is its own twin; the measure is symmetric; and it falls
    /// the more a detailed picture is blurred or shifted.
    #[test]
    fn detail_lost_or_moved_lowers_it() {
        let stripes = |x: u32, y: u32| {
            if (x / 2 + y / 3).is_multiple_of(2) {
                40
            } else {
                210
            }
        };
        let sharp = picture(64, 48, stripes);
        assert!((ssim(&sharp, &sharp) - 1.0).abs() < 1e-12);
        let blurred = |reach: u32| {
            picture(64, 48, |x, y| {
                let xs = x.saturating_sub(reach)..=(x + reach).min(63);
                let n = xs.clone().count() as u32;
                (xs.map(|u| stripes(u, y) as u32).sum::<u32>() / n) as u8
            })
        };
        let (little, more) = (ssim(&sharp, &blurred(1)), ssim(&sharp, &blurred(2)));
        assert!(little < 0.95 && more < little, "{little} {more}");
        assert!((ssim(&blurred(1), &sharp) - little).abs() < 1e-12);
        let moved = picture(64, 48, |x, y| stripes(x + 1, y));
        assert!(ssim(&sharp, &moved) < 0.9);
    }
}
