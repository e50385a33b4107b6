//! A perspective camera.

use glam::{Mat4, Vec3};

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    pub eye: Vec3,
    pub target: Vec3,
    /// Vertical field of view in degrees.
    pub fov_y_deg: f32,
}

impl Camera {
    /// A view of the whole room from just inside the front wall, above the
    /// tumblers' heads: the floor, the three far walls and the light.
    pub fn overview(room_size: Vec3) -> Camera {
        let half = room_size * 0.5;
        Camera {
            eye: Vec3::new(0.0, room_size.y * 0.6, half.z - 0.1),
            target: Vec3::new(0.0, room_size.y * 0.29, -half.z * 0.25),
            fov_y_deg: 70.0,
        }
    }

    pub fn view(&self) -> Mat4 {
        glam::camera::rh::view::look_at_mat4(self.eye, self.target, Vec3::Y)
    }

    /// Projection to wgpu's clip space (depth 0..1).
    pub fn projection(&self, aspect: f32) -> Mat4 {
        glam::camera::rh::proj::directx::perspective(
            self.fov_y_deg.to_radians(),
            aspect,
            0.02,
            100.0,
        )
    }

    pub fn view_projection(&self, aspect: f32) -> Mat4 {
        self.projection(aspect) * self.view()
    }

    /// The world-space ray through a pixel (x right, y down, in pixels).
    pub fn ray(&self, pixel: glam::Vec2, size: glam::Vec2) -> (Vec3, Vec3) {
        let ndc = glam::Vec2::new(2.0 * pixel.x / size.x - 1.0, 1.0 - 2.0 * pixel.y / size.y);
        let inverse = self.view_projection(size.x / size.y).inverse();
        let near = inverse.project_point3(ndc.extend(0.0));
        let far = inverse.project_point3(ndc.extend(1.0));
        (near, (far - near).normalize())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_centre_ray_looks_at_the_target() {
        let cam = Camera::overview(Vec3::new(8.0, 4.0, 8.0));
        let (origin, dir) = cam.ray(glam::Vec2::new(320.0, 240.0), glam::Vec2::new(640.0, 480.0));
        let expected = (cam.target - cam.eye).normalize();
        assert!(dir.dot(expected) > 0.9999, "{dir} vs {expected}");
        assert!(origin.distance(cam.eye) < 0.05);
    }
}
