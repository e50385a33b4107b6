//! A perspective camera.

use glam::{Mat4, Vec3};

/// The overview's vertical field of view, in degrees.
const OVERVIEW_FOV_DEG: f32 = 50.0;
/// How far the overview looks down, in degrees.
const OVERVIEW_TILT_DEG: f32 = 8.0;

/// A pinhole camera: where it stands, what it looks at, how wide it sees.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// Where it stands (m).
    pub eye: Vec3,
    /// The point it looks at (m).
    pub target: Vec3,
    /// Vertical field of view in degrees.
    pub fov_y_deg: f32,
}

impl Camera {
    /// A view of the whole room through its front wall, as a Cornell box
    /// is shown: from outside the room, where the front wall (drawn only
    /// from inside) hides nothing, looking slightly down, far enough back
    /// that the room's full height fills the picture. The field of view is
    /// narrow enough (50 degrees, about 80 across a 16:9 frame) that balls
    /// at the frame's edge stay round: a wider one seen from inside the
    /// room stretches them into eggs.
    pub fn overview(room_size: Vec3) -> Camera {
        let half_fov = (OVERVIEW_FOV_DEG / 2.0).to_radians();
        let tilt = OVERVIEW_TILT_DEG.to_radians();
        // The frame's top and bottom edges pass through the top and the
        // bottom of the front wall's opening.
        let (above, below) = ((half_fov - tilt).tan(), (half_fov + tilt).tan());
        let back = room_size.y / (above + below);
        let eye = Vec3::new(0.0, below * back, 0.5 * room_size.z + back);
        Camera {
            eye,
            target: eye + Vec3::new(0.0, -tilt.tan(), -1.0),
            fov_y_deg: OVERVIEW_FOV_DEG,
        }
    }

    /// World to camera space.
    pub fn view(&self) -> Mat4 {
        glam::camera::rh::view::look_at_mat4(self.eye, self.target, self.up())
    }

    /// The world direction the top of the picture leans towards: +Y, but
    /// for a camera looking straight down or up, where +Y is the line of
    /// sight itself and gives no picture at all, the far wall (-Z) looking
    /// down and the near one looking up: where +Y tends to as a camera
    /// facing the far wall tilts that way.
    fn up(&self) -> Vec3 {
        let sight = self.target - self.eye;
        if sight.cross(Vec3::Y).length_squared() > 1e-12 * sight.length_squared() {
            Vec3::Y
        } else if sight.y < 0.0 {
            Vec3::NEG_Z
        } else {
            Vec3::Z
        }
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

    /// World to clip space for a picture `aspect` wide per unit of height.
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

    #[test]
    fn a_camera_looking_straight_down_or_up_still_sees() {
        let size = glam::Vec2::new(640.0, 480.0);
        for (eye_y, far_wall_at_top) in [(4.0, true), (-4.0, false)] {
            let cam = Camera {
                eye: Vec3::new(0.0, eye_y, 0.0),
                target: Vec3::ZERO,
                fov_y_deg: 70.0,
            };
            let matrix = cam.view_projection(size.x / size.y);
            assert!(matrix.is_finite(), "{matrix}");
            // The target in the middle of the picture, and a point towards
            // the far wall above it looking down (clip y up), below it
            // looking up.
            let centre = matrix.project_point3(cam.target);
            assert!(centre.truncate().length() < 1e-5, "{centre}");
            let far = matrix.project_point3(Vec3::new(0.0, 0.0, -1.0));
            assert_eq!(far.y > 0.0, far_wall_at_top, "{far}");
            assert!(far.x.abs() < 1e-5, "{far}");
        }
    }
}
