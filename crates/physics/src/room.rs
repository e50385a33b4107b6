//! The closed room: six axis-aligned planes facing inwards.

use glam::DVec3;
use serde::{Deserialize, Serialize};

/// One of the room's six surfaces. Each has its own colour (S1), which a ball
/// takes on when it hits it (P5).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Surface {
    /// The floor, at the room's lowest y.
    Floor,
    /// The ceiling, at its highest y.
    Ceiling,
    /// The wall at -x.
    Left,
    /// The wall at +x.
    Right,
    /// The wall at -z.
    Back,
    /// The wall at +z.
    Front,
}

impl Surface {
    /// All six, in the order of `RoomConfig::colors`.
    pub const ALL: [Surface; 6] = [
        Surface::Floor,
        Surface::Ceiling,
        Surface::Left,
        Surface::Right,
        Surface::Back,
        Surface::Front,
    ];

    /// Its place in [`Surface::ALL`].
    pub fn index(self) -> usize {
        self as usize
    }

    /// Its name in scene files: `floor`, `left`...
    pub fn name(self) -> &'static str {
        match self {
            Surface::Floor => "floor",
            Surface::Ceiling => "ceiling",
            Surface::Left => "left",
            Surface::Right => "right",
            Surface::Back => "back",
            Surface::Front => "front",
        }
    }

    /// The unit normal pointing into the room.
    pub fn inward_normal(self) -> DVec3 {
        match self {
            Surface::Floor => DVec3::Y,
            Surface::Ceiling => DVec3::NEG_Y,
            Surface::Left => DVec3::X,
            Surface::Right => DVec3::NEG_X,
            Surface::Back => DVec3::Z,
            Surface::Front => DVec3::NEG_Z,
        }
    }
}

/// The room's inner box: floor at y = 0, centred on x = z = 0.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Room {
    /// The corner with the smallest coordinates (m).
    pub min: DVec3,
    /// The corner with the largest (m).
    pub max: DVec3,
}

impl Room {
    /// A room of `size`, centred on x and z, its floor at y = 0.
    pub fn new(size: DVec3) -> Room {
        Room {
            min: DVec3::new(-0.5 * size.x, 0.0, -0.5 * size.z),
            max: DVec3::new(0.5 * size.x, size.y, 0.5 * size.z),
        }
    }

    /// Its width, height and depth (m).
    pub fn size(&self) -> DVec3 {
        self.max - self.min
    }

    /// Signed distance from `p` to a surface's plane, positive inside the room.
    pub fn distance(&self, surface: Surface, p: DVec3) -> f64 {
        match surface {
            Surface::Floor => p.y - self.min.y,
            Surface::Ceiling => self.max.y - p.y,
            Surface::Left => p.x - self.min.x,
            Surface::Right => self.max.x - p.x,
            Surface::Back => p.z - self.min.z,
            Surface::Front => self.max.z - p.z,
        }
    }

    /// The distance from `p` to the nearest surface's plane: the least of
    /// [`Room::distance`] over all of them.
    pub fn nearest_distance(&self, p: DVec3) -> f64 {
        (p - self.min).min(self.max - p).min_element()
    }

    /// The point of a surface's plane nearest to `p`.
    pub fn foot(&self, surface: Surface, p: DVec3) -> DVec3 {
        p - surface.inward_normal() * self.distance(surface, p)
    }

    /// Moves a sphere's centre so that the sphere lies inside the room.
    pub fn clamp_sphere(&self, p: DVec3, radius: f64) -> DVec3 {
        let lo = self.min + DVec3::splat(radius);
        let hi = self.max - DVec3::splat(radius);
        p.max(lo).min(hi)
    }

    /// Whether a sphere lies inside the room (allowing `tolerance` of overlap).
    pub fn contains_sphere(&self, p: DVec3, radius: f64, tolerance: f64) -> bool {
        Surface::ALL
            .iter()
            .all(|&s| self.distance(s, p) >= radius - tolerance)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inward_normals_point_into_the_room() {
        let room = Room::new(DVec3::new(4.0, 3.0, 5.0));
        let centre = DVec3::new(0.0, 1.5, 0.0);
        for s in Surface::ALL {
            let d = room.distance(s, centre);
            let moved = room.distance(s, centre + 0.1 * s.inward_normal());
            assert!(moved > d, "{s:?}");
        }
    }

    #[test]
    fn the_nearest_distance_is_the_least_of_every_surface() {
        let room = Room::new(DVec3::new(4.0, 3.0, 5.0));
        let mut rng = crate::rng::Rng::new(5);
        for _ in 0..200 {
            let p = DVec3::new(
                rng.range(-2.5, 2.5),
                rng.range(-0.5, 3.5),
                rng.range(-3.0, 3.0),
            );
            let least = Surface::ALL
                .iter()
                .map(|&s| room.distance(s, p))
                .fold(f64::INFINITY, f64::min);
            assert_eq!(room.nearest_distance(p), least, "{p}");
        }
    }

    #[test]
    fn clamp_keeps_spheres_inside() {
        let room = Room::new(DVec3::new(2.0, 2.0, 2.0));
        let p = room.clamp_sphere(DVec3::new(5.0, -1.0, 0.0), 0.25);
        assert!(room.contains_sphere(p, 0.25, 1e-12));
        assert_eq!(p, DVec3::new(0.75, 0.25, 0.0));
    }
}
