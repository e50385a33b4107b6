//! Rays and where they meet the shapes of the room: spheres, the room's
//! one-sided rectangles, triangles and boxes.

use glam::Vec3;

/// A half-line: from `origin` along the unit vector `dir`.
#[derive(Clone, Copy, Debug)]
pub struct Ray {
    /// Where it starts.
    pub origin: Vec3,
    /// Its direction, of unit length.
    pub dir: Vec3,
}

/// How far a ray leaves a surface before it may meet anything (m): far
/// enough to clear the rounding of the point it left from.
pub const SURFACE_OFFSET: f32 = 1e-4;

/// The nearest distance beyond `SURFACE_OFFSET` at which `ray` meets the
/// sphere, if any before `t_max`.
pub fn hit_sphere(ray: &Ray, centre: Vec3, radius: f32, t_max: f32) -> Option<f32> {
    let from_centre = ray.origin - centre;
    let along = from_centre.dot(ray.dir);
    // As in scene.wgsl: the nearest approach as a vector, not as the
    // difference of two large squares.
    let across = from_centre - along * ray.dir;
    let gap = radius * radius - across.length_squared();
    if gap < 0.0 {
        return None;
    }
    let root = gap.sqrt();
    [-along - root, -along + root]
        .into_iter()
        .find(|&t| t > SURFACE_OFFSET && t < t_max)
}

/// Where `ray` meets the rectangle `corner + s u + t v` (s, t in 0..1)
/// from its front (the side `u x v` points to): the distance, s and t.
pub fn hit_rectangle(
    ray: &Ray,
    corner: Vec3,
    u: Vec3,
    v: Vec3,
    t_max: f32,
) -> Option<(f32, f32, f32)> {
    let normal = u.cross(v);
    let facing = ray.dir.dot(normal);
    if facing >= 0.0 {
        return None;
    }
    let t = (corner - ray.origin).dot(normal) / facing;
    if !(t > SURFACE_OFFSET && t < t_max) {
        return None;
    }
    let rel = ray.origin + ray.dir * t - corner;
    let (s, w) = (
        rel.dot(u) / u.length_squared(),
        rel.dot(v) / v.length_squared(),
    );
    ((0.0..=1.0).contains(&s) && (0.0..=1.0).contains(&w)).then_some((t, s, w))
}

/// Where `ray` meets triangle `a b c` from either side (Moller and
/// Trumbore): the distance and the barycentric weights of `b` and `c`.
pub fn hit_triangle(ray: &Ray, a: Vec3, b: Vec3, c: Vec3, t_max: f32) -> Option<(f32, f32, f32)> {
    let (e1, e2) = (b - a, c - a);
    let p = ray.dir.cross(e2);
    let det = e1.dot(p);
    if det.abs() < 1e-12 {
        return None;
    }
    let inv = 1.0 / det;
    let s = ray.origin - a;
    let u = s.dot(p) * inv;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let q = s.cross(e1);
    let v = ray.dir.dot(q) * inv;
    if v < 0.0 || u + v > 1.0 {
        return None;
    }
    let t = e2.dot(q) * inv;
    (t > SURFACE_OFFSET && t < t_max).then_some((t, u, v))
}

/// An axis-aligned box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    /// Its least corner.
    pub min: Vec3,
    /// Its greatest corner.
    pub max: Vec3,
}

impl Aabb {
    /// Holds nothing; the union with it is the other box.
    pub const EMPTY: Aabb = Aabb {
        min: Vec3::splat(f32::INFINITY),
        max: Vec3::splat(f32::NEG_INFINITY),
    };

    /// The box around a sphere.
    pub fn of_sphere(centre: Vec3, radius: f32) -> Aabb {
        Aabb {
            min: centre - Vec3::splat(radius),
            max: centre + Vec3::splat(radius),
        }
    }

    /// The box that holds both.
    pub fn union(self, other: Aabb) -> Aabb {
        Aabb {
            min: self.min.min(other.min),
            max: self.max.max(other.max),
        }
    }

    /// The box that also holds `point`.
    pub fn with(self, point: Vec3) -> Aabb {
        Aabb {
            min: self.min.min(point),
            max: self.max.max(point),
        }
    }

    /// Its middle.
    pub fn centre(&self) -> Vec3 {
        0.5 * (self.min + self.max)
    }

    /// Whether the ray, given as its origin and its direction's inverse,
    /// enters the box before `t_max` (the slab test).
    pub fn hit(&self, origin: Vec3, inv_dir: Vec3, t_max: f32) -> bool {
        let a = (self.min - origin) * inv_dir;
        let b = (self.max - origin) * inv_dir;
        let near = a.min(b).max_element().max(0.0);
        let far = a.max(b).min_element().min(t_max);
        near <= far
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shapes_are_met_where_they_are() {
        let ray = Ray {
            origin: Vec3::new(0.0, 0.0, 5.0),
            dir: Vec3::NEG_Z,
        };
        let t = hit_sphere(&ray, Vec3::ZERO, 1.0, f32::INFINITY).unwrap();
        assert!((t - 4.0).abs() < 1e-5);
        // From inside, the far side.
        let inside = Ray {
            origin: Vec3::ZERO,
            dir: Vec3::X,
        };
        assert!((hit_sphere(&inside, Vec3::ZERO, 1.0, 9.0).unwrap() - 1.0).abs() < 1e-6);
        // A rectangle facing the ray, and the same seen from behind.
        let (t, s, w) = hit_rectangle(
            &ray,
            Vec3::new(-1.0, -1.0, 0.0),
            Vec3::X * 2.0,
            Vec3::Y * 2.0,
            99.0,
        )
        .unwrap();
        assert!((t - 5.0).abs() < 1e-6 && (s - 0.5).abs() < 1e-6 && (w - 0.5).abs() < 1e-6);
        assert!(
            hit_rectangle(
                &ray,
                Vec3::new(-1.0, -1.0, 0.0),
                Vec3::Y * 2.0,
                Vec3::X * 2.0,
                99.0
            )
            .is_none()
        );
        let (t, u, v) = hit_triangle(
            &ray,
            Vec3::new(-1.0, -1.0, 1.0),
            Vec3::new(3.0, -1.0, 1.0),
            Vec3::new(-1.0, 3.0, 1.0),
            99.0,
        )
        .unwrap();
        assert!((t - 4.0).abs() < 1e-6 && (u - 0.25).abs() < 1e-6 && (v - 0.25).abs() < 1e-6);
        let b = Aabb::of_sphere(Vec3::new(0.0, 0.0, -3.0), 0.5);
        assert!(b.hit(ray.origin, ray.dir.recip(), 99.0));
        assert!(!b.hit(ray.origin, ray.dir.recip(), 7.0));
        assert!(!b.hit(ray.origin + Vec3::X, ray.dir.recip(), 99.0));
    }
}
