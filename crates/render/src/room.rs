//! The room's six surfaces, one list for everything that needs them: the
//! quads drawn for them and the panels that bounce light.

use glam::Vec3;

/// One surface of the room: the corner its two edges `u` and `v` run from,
/// with `u x v` pointing into the room.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Surface {
    /// The corner both edges start from (m).
    pub corner: Vec3,
    /// The first edge.
    pub u: Vec3,
    /// The second edge.
    pub v: Vec3,
}

impl Surface {
    /// The unit normal pointing into the room.
    pub fn normal(&self) -> Vec3 {
        self.u.cross(self.v).normalize()
    }

    /// Its area (m^2).
    pub fn area(&self) -> f32 {
        self.u.cross(self.v).length()
    }

    /// The four corners, in order around the surface.
    pub fn corners(&self) -> [Vec3; 4] {
        [
            self.corner,
            self.corner + self.u,
            self.corner + self.u + self.v,
            self.corner + self.v,
        ]
    }

    /// The point at `(s, t)` (each 0 ..= 1) along the two edges.
    pub fn at(&self, s: f32, t: f32) -> Vec3 {
        self.corner + self.u * s + self.v * t
    }
}

/// The surfaces of a room of `size` (floor at y = 0, centred on x and z) in
/// the order of `SceneView::room_colors`: floor, ceiling, left, right,
/// back, front.
pub fn surfaces(size: Vec3) -> [Surface; 6] {
    let (hx, hz) = (0.5 * size.x, 0.5 * size.z);
    let surface = |u: Vec3, v: Vec3, corner: Vec3| Surface { corner, u, v };
    [
        surface(
            Vec3::X * size.x,
            Vec3::NEG_Z * size.z,
            Vec3::new(-hx, 0.0, hz),
        ),
        surface(
            Vec3::X * size.x,
            Vec3::Z * size.z,
            Vec3::new(-hx, size.y, -hz),
        ),
        surface(Vec3::Y * size.y, Vec3::Z * size.z, Vec3::new(-hx, 0.0, -hz)),
        surface(Vec3::Z * size.z, Vec3::Y * size.y, Vec3::new(hx, 0.0, -hz)),
        surface(Vec3::X * size.x, Vec3::Y * size.y, Vec3::new(-hx, 0.0, -hz)),
        surface(Vec3::Y * size.y, Vec3::X * size.x, Vec3::new(-hx, 0.0, hz)),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn surfaces_face_into_the_room_and_close_it() {
        let size = Vec3::new(8.0, 4.0, 6.0);
        let centre = Vec3::new(0.0, 2.0, 0.0);
        let expected = [
            Vec3::Y,
            Vec3::NEG_Y,
            Vec3::X,
            Vec3::NEG_X,
            Vec3::Z,
            Vec3::NEG_Z,
        ];
        let mut area = 0.0;
        for (surface, normal) in surfaces(size).iter().zip(expected) {
            assert!((surface.normal() - normal).length() < 1e-6);
            // The centre lies in front of every surface, at half the room's
            // extent along the normal.
            let reach = (centre - surface.corner).dot(normal);
            assert!((reach - (size * normal.abs()).element_sum() / 2.0).abs() < 1e-6);
            for corner in surface.corners() {
                assert!(corner.abs().cmple(Vec3::new(4.0, 4.0, 3.0)).all() && corner.y >= 0.0);
            }
            area += surface.area();
        }
        assert!((area - 2.0 * (8.0 * 4.0 + 8.0 * 6.0 + 4.0 * 6.0)).abs() < 1e-4);
    }
}
