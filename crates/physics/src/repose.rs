//! The angle of repose of a heap of balls: how steep a poured pile stands.
//!
//! A heap poured from a point is a cone. Its surface is read ring by ring
//! around the pour's axis (the highest ball top in each ring, two radii
//! wide), and a straight line is fitted to the flank, the rings whose
//! surface lies between a fifth and four fifths of the peak's height: the
//! rounded top and the scattered foot are left out, as in the image
//! measurements of Zhou, Xu, Yu and Zulli (Powder Technology 2002).

use glam::DVec3;

/// The angle of repose in degrees of the heap that `positions` (ball
/// centres, every ball of radius `radius`) form around the vertical line
/// through `axis` (x, z), or `None` when the balls form no flank to fit
/// (fewer than three rings on it, or a surface that does not fall away).
pub fn angle_of_repose(positions: &[DVec3], radius: f64, axis: [f64; 2]) -> Option<f64> {
    let ring_width = 2.0 * radius;
    if ring_width.is_nan() || ring_width <= 0.0 {
        return None;
    }
    let ring_of = |p: &DVec3| {
        let across = ((p.x - axis[0]).powi(2) + (p.z - axis[1]).powi(2)).sqrt();
        (across / ring_width) as usize
    };
    let rings = positions.iter().map(ring_of).max()? + 1;
    let mut surface = vec![f64::NEG_INFINITY; rings];
    for p in positions {
        let top = &mut surface[ring_of(p)];
        *top = top.max(p.y + radius);
    }
    let peak = surface.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let on_flank = |h: f64| h >= 0.2 * peak && h <= 0.8 * peak;
    let flank: Vec<(f64, f64)> = surface
        .iter()
        .enumerate()
        .filter(|&(_, &h)| on_flank(h))
        .map(|(k, &h)| ((k as f64 + 0.5) * ring_width, h))
        .collect();
    if flank.len() < 3 {
        return None;
    }
    let slope = least_squares_slope(&flank);
    (slope < 0.0).then(|| (-slope).atan().to_degrees())
}

/// The slope of the straight line that fits `points` (x, y) best.
fn least_squares_slope(points: &[(f64, f64)]) -> f64 {
    let n = points.len() as f64;
    let (mx, my) = points
        .iter()
        .fold((0.0, 0.0), |(sx, sy), &(x, y)| (sx + x / n, sy + y / n));
    let (sxy, sxx) = points.iter().fold((0.0, 0.0), |(sxy, sxx), &(x, y)| {
        (sxy + (x - mx) * (y - my), sxx + (x - mx) * (x - mx))
    });
    sxy / sxx
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Balls of radius `r` packed under a cone of slope angle `degrees`,
    /// its apex `height` above the floor at (x, z) = `axis`.
    fn cone(degrees: f64, height: f64, r: f64, axis: [f64; 2]) -> Vec<DVec3> {
        let slope = degrees.to_radians().tan();
        let foot = height / slope;
        let step = 2.0 * r;
        let n = (foot / step).ceil() as i64;
        let mut balls = Vec::new();
        for i in -n..=n {
            for k in -n..=n {
                let (x, z) = (i as f64 * step, k as f64 * step);
                let top = height - slope * (x * x + z * z).sqrt();
                let mut y = r;
                while y + r <= top {
                    balls.push(DVec3::new(x + axis[0], y, z + axis[1]));
                    y += step;
                }
            }
        }
        balls
    }

    #[test]
    fn a_cone_of_balls_reads_as_its_slope() {
        for (degrees, axis) in [(20.0, [0.0, 0.0]), (30.0, [1.0, -0.5]), (40.0, [-2.0, 3.0])] {
            let balls = cone(degrees, 1.0, 0.01, axis);
            let angle = angle_of_repose(&balls, 0.01, axis).unwrap();
            assert!((angle - degrees).abs() < 1.5, "{degrees}: read {angle}");
        }
    }

    #[test]
    fn a_flat_layer_has_no_flank() {
        let layer: Vec<DVec3> = (0..400)
            .map(|k| DVec3::new((k % 20) as f64 * 0.02, 0.01, (k / 20) as f64 * 0.02))
            .collect();
        assert_eq!(angle_of_repose(&layer, 0.01, [0.2, 0.2]), None);
        assert_eq!(angle_of_repose(&[], 0.01, [0.0, 0.0]), None);
    }
}
