//! The shape all tumblers share: six spheres on one axis, and the mass
//! properties they give (parallel-axis theorem).

use crate::config::SphereSpec;
use glam::{DMat3, DVec3};

/// The shape and mass properties shared by all tumblers, derived from the six
/// spheres with the parallel-axis theorem.
#[derive(Clone, Debug, PartialEq)]
pub struct TumblerShape {
    /// The six spheres it is made of.
    pub spheres: Vec<SphereSpec>,
    /// Total mass (kg).
    pub mass: f64,
    /// Centre of mass in the body frame: `(0, -a, 0)`.
    pub center_of_mass: DVec3,
    /// Radius `R` of the round bottom (sphere 0).
    pub bottom_radius: f64,
    /// Distance `a` of the centre of mass below the bottom sphere's centre.
    pub com_offset: f64,
    /// Inertia tensor about the centre of mass, in the body frame.
    pub inertia: DMat3,
    /// A sphere around all six spheres (centre on the axis, body frame) for
    /// cheap rejection before the six sphere tests (P7).
    pub bound_height: f64,
    /// Radius of that sphere (m).
    pub bound_radius: f64,
}

impl TumblerShape {
    /// The shape made of `spheres`, sphere 0 its round bottom.
    pub fn new(spheres: &[SphereSpec]) -> TumblerShape {
        let mass: f64 = spheres.iter().map(|s| s.mass).sum();
        let com_y = spheres.iter().map(|s| s.mass * s.height).sum::<f64>() / mass;
        // Each sphere is a uniform solid sphere: 2/5 m r^2 about its own centre,
        // shifted to the common centre of mass. Offsets lie on the axis, so the
        // shift adds only to the two transverse moments.
        let axial: f64 = spheres
            .iter()
            .map(|s| 0.4 * s.mass * s.radius * s.radius)
            .sum();
        let transverse: f64 = axial
            + spheres
                .iter()
                .map(|s| s.mass * (s.height - com_y).powi(2))
                .sum::<f64>();
        let (lo, hi) = axis_extent(spheres);
        let bound_height = 0.5 * (lo + hi);
        let bound_radius = spheres
            .iter()
            .map(|s| (s.height - bound_height).abs() + s.radius)
            .fold(0.0, f64::max);
        TumblerShape {
            spheres: spheres.to_vec(),
            mass,
            center_of_mass: DVec3::new(0.0, com_y, 0.0),
            bottom_radius: spheres[0].radius,
            com_offset: -com_y,
            inertia: DMat3::from_diagonal(DVec3::new(transverse, axial, transverse)),
            bound_height,
            bound_radius,
        }
    }

    /// Radius of gyration about a transverse axis through the centre of mass.
    pub fn transverse_gyration_radius(&self) -> f64 {
        (self.inertia.x_axis.x / self.mass).sqrt()
    }

    /// Small-amplitude rocking frequency of a rolling pendulum (rad/s):
    /// `w0^2 = g a / (k^2 + (R - a)^2)`.
    pub fn rocking_frequency(&self, gravity: f64) -> f64 {
        let k = self.transverse_gyration_radius();
        let (r, a) = (self.bottom_radius, self.com_offset);
        (gravity * a / (k * k + (r - a) * (r - a))).sqrt()
    }
}

/// The lowest and highest points of a compound of spheres on its axis
/// (body frame heights).
pub fn axis_extent(spheres: &[SphereSpec]) -> (f64, f64) {
    let lo = spheres
        .iter()
        .map(|s| s.height - s.radius)
        .fold(f64::INFINITY, f64::min);
    let hi = spheres
        .iter()
        .map(|s| s.height + s.radius)
        .fold(f64::NEG_INFINITY, f64::max);
    (lo, hi)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::WorldConfig;

    #[test]
    fn default_shape_has_centre_of_mass_below_bottom_centre() {
        let cfg = WorldConfig::default();
        let shape = TumblerShape::new(&cfg.tumblers.spheres);
        assert!(shape.com_offset > 0.0);
        assert!(shape.com_offset < shape.bottom_radius);
        assert_eq!(shape.spheres.len(), 6);
    }

    #[test]
    fn parallel_axis_inertia_matches_hand_computation() {
        let spheres = [
            SphereSpec {
                height: 0.0,
                radius: 1.0,
                mass: 2.0,
            },
            SphereSpec {
                height: 2.0,
                radius: 0.5,
                mass: 2.0,
            },
        ];
        let shape = TumblerShape::new(&spheres);
        // centre of mass at 1.0; each sphere 1.0 away from it
        let axial = 0.4 * 2.0 * 1.0 + 0.4 * 2.0 * 0.25;
        assert!((shape.inertia.y_axis.y - axial).abs() < 1e-12);
        assert!((shape.inertia.x_axis.x - (axial + 2.0 + 2.0)).abs() < 1e-12);
        assert!((shape.com_offset + 1.0).abs() < 1e-12);
    }
}
