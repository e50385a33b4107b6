//! Temporal anti-aliasing with upsampling: what a frame carries to the next.
//!
//! Each frame lights the scene at its render scale with the projection
//! moved by a sub-pixel jitter, so that over [`JITTER_PHASES`] frames every
//! output pixel is sampled at many points. The resolve pass (taa.wgsl)
//! follows each pixel back to where it was the frame before (its motion,
//! written by the scene pass), keeps that history only as far as the
//! current frame's neighbourhood allows (variance clipping in YCoCg), and
//! folds the new sample in weighted by how near it lies to the pixel's
//! centre. A sharpening pass then writes the output.

use glam::{Mat4, Vec2, Vec3};

/// Frames before the jitter repeats: the first 16 points of the Halton
/// (2, 3) sequence spread over a pixel with no two close together.
pub const JITTER_PHASES: u64 = 16;

/// The least frames of history a still picture needs: a full turn of the
/// jitter.
pub const HISTORY_FRAMES: u32 = JITTER_PHASES as u32;

/// Element `index` (from 1) of the van der Corput sequence in `base`: the
/// digits of `index` mirrored about the radix point, in [0, 1).
pub fn halton(mut index: u64, base: u64) -> f32 {
    let mut result = 0.0f64;
    let mut fraction = 1.0f64;
    while index > 0 {
        fraction /= base as f64;
        result += fraction * (index % base) as f64;
        index /= base;
    }
    result as f32
}

/// Where frame `frame`'s sample lies in each lit pixel, from its centre, in
/// pixels: both coordinates in [-0.5, 0.5), x to the right, y down.
pub fn jitter(frame: u64) -> Vec2 {
    let index = frame % JITTER_PHASES + 1;
    Vec2::new(halton(index, 2), halton(index, 3)) - Vec2::splat(0.5)
}

/// How far from an output pixel's centre a sample may fall, as a share of
/// the pixel, where the output's pixels tile the lit ones: the middle half.
/// Surfaces are then shaded near where a frame drawn at the output's size
/// would shade them (its fine texture stays as sharp), while an edge across
/// the pixel is still sampled at several points and comes out smooth.
pub const SAMPLE_SPREAD: f32 = 0.5;

/// Where frame `frame`'s sample lies in each pixel of a target lit at `lit`
/// pixels for an output of `out`, from the lit pixel's centre, in lit
/// pixels: the [`jitter`] point, folded onto the output pixels the lit one
/// covers and drawn in to the middle [`SAMPLE_SPREAD`] of the one it falls
/// in, where each side of the output is a whole multiple of the lit one;
/// the point as it is otherwise (the output's pixels do not line up).
pub fn sample_offset(frame: u64, lit: Vec2, out: Vec2) -> Vec2 {
    let point = jitter(frame);
    let ratio = out / lit;
    let whole = (ratio - ratio.round()).abs().max_element() < 1e-4;
    if !whole {
        return point;
    }
    // In the output pixels the lit one covers, from its top left corner.
    let at = (point + 0.5) * ratio;
    let centre = at.floor() + 0.5;
    (centre + SAMPLE_SPREAD * (at - centre)) / ratio - 0.5
}

/// `view_proj` moved so that each pixel of a target of `size` pixels is
/// sampled `offset` pixels from its centre (see [`jitter`]).
pub fn jittered(view_proj: Mat4, offset: Vec2, size: Vec2) -> Mat4 {
    // A point's clip x and y shift by the offset times w: in normalized
    // device coordinates, two units a target's width; y points up there.
    let shift = Vec3::new(-2.0 * offset.x / size.x, 2.0 * offset.y / size.y, 0.0);
    Mat4::from_translation(shift) * view_proj
}

/// What the temporal path remembers from one frame to the next.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct TemporalState {
    /// Frames drawn so far: the jitter's phase.
    pub frame: u64,
    /// The last frame's view-projection, without its jitter: motion is
    /// measured between unjittered frames.
    pub previous_view_proj: Option<Mat4>,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn halton_mirrors_the_digits() {
        assert_eq!(halton(1, 2), 0.5);
        assert_eq!(halton(2, 2), 0.25);
        assert_eq!(halton(3, 2), 0.75);
        assert!((halton(1, 3) - 1.0 / 3.0).abs() < 1e-7);
        assert!((halton(5, 3) - 7.0 / 9.0).abs() < 1e-7);
    }

    /// A turn of the jitter covers the pixel evenly: its mean is near the
    /// centre, and each quarter of the pixel holds about a quarter of the
    /// points.
    #[test]
    fn a_turn_of_the_jitter_covers_the_pixel() {
        let points: Vec<Vec2> = (0..JITTER_PHASES).map(jitter).collect();
        let mean = points.iter().sum::<Vec2>() / points.len() as f32;
        assert!(mean.length() < 0.06, "mean {mean}");
        for quarter in 0..4 {
            let (right, down) = (quarter & 1 == 1, quarter & 2 == 2);
            let inside = points
                .iter()
                .filter(|p| (p.x >= 0.0) == right && (p.y >= 0.0) == down)
                .count();
            assert!((3..=5).contains(&inside), "quarter {quarter}: {inside}");
        }
        assert!(points.iter().all(|p| p.abs().max_element() <= 0.5));
        assert_eq!(jitter(0), jitter(JITTER_PHASES));
    }

    /// Where the output's pixels tile the lit ones, each output pixel is
    /// sampled within the middle of itself in every turn of the jitter;
    /// else the samples are the jitter's own.
    #[test]
    fn samples_fall_in_the_middle_of_the_output_pixels() {
        for ratio in [1.0f32, 2.0, 3.0] {
            let lit = Vec2::new(320.0, 180.0);
            let mut hits = vec![0; (ratio * ratio) as usize];
            for frame in 0..JITTER_PHASES {
                let offset = sample_offset(frame, lit, lit * ratio);
                assert!(offset.abs().max_element() < 0.5, "{offset}");
                let at = (offset + 0.5) * ratio;
                let from_centre = at - at.floor() - 0.5;
                assert!(from_centre.abs().max_element() <= SAMPLE_SPREAD * 0.5 + 1e-5);
                let cell = at.floor();
                hits[(cell.y * ratio + cell.x) as usize] += 1;
            }
            assert!(hits.iter().all(|&n| n > 0), "ratio {ratio}: {hits:?}");
        }
        let lit = Vec2::new(422.0, 238.0);
        assert_eq!(sample_offset(5, lit, Vec2::new(1280.0, 720.0)), jitter(5));
    }

    /// The jittered projection moves every point by the offset, in pixels.
    #[test]
    fn jittering_moves_every_point_by_the_offset() {
        let size = Vec2::new(640.0, 360.0);
        let view_proj = crate::camera::Camera::overview(Vec3::new(4.0, 3.0, 4.0))
            .view_projection(size.x / size.y);
        let pixel = |m: Mat4, p: Vec3| {
            let ndc = m.project_point3(p);
            Vec2::new((ndc.x + 1.0) * 0.5 * size.x, (1.0 - ndc.y) * 0.5 * size.y)
        };
        let offset = Vec2::new(0.3, -0.2);
        for p in [
            Vec3::ZERO,
            Vec3::new(1.0, 0.5, -2.0),
            Vec3::new(-0.7, 2.0, 1.0),
        ] {
            let moved = pixel(jittered(view_proj, offset, size), p) - pixel(view_proj, p);
            // A point seen at the texel's centre plus the offset now lands on
            // the centre: the picture moves against the offset.
            assert!((moved + offset).length() < 1e-3, "{p}: moved {moved}");
        }
    }
}
