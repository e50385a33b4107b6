//! The viewer's camera: mouse look (yaw and pitch, pitch clamped) and
//! W/A/S/D movement relative to where it looks (I1, I2).

use glam::{Vec2, Vec3};
use rolypoly_render::Camera;

use crate::sandbox::CameraPose;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FlyCamera {
    pub position: Vec3,
    /// Radians about +y; 0 looks along -z.
    pub yaw: f32,
    /// Radians above the horizon.
    pub pitch: f32,
    pub fov_y_deg: f32,
}

/// Looking straight up or down makes "forward" meaningless; stop short.
const PITCH_LIMIT: f32 = 1.5;

impl FlyCamera {
    /// Starts where the renderer's overview camera stands, looking the same way.
    pub fn from_camera(camera: &Camera) -> FlyCamera {
        let d = (camera.target - camera.eye).normalize();
        FlyCamera {
            position: camera.eye,
            yaw: (-d.x).atan2(-d.z),
            pitch: d.y.asin(),
            fov_y_deg: camera.fov_y_deg,
        }
    }

    /// Standing and looking as `pose` says, with the field of view of `like`.
    pub fn posed(pose: &CameraPose, like: &Camera) -> FlyCamera {
        FlyCamera {
            position: pose.position,
            yaw: pose.yaw,
            pitch: pose.pitch,
            fov_y_deg: like.fov_y_deg,
        }
    }

    pub fn forward(&self) -> Vec3 {
        Vec3::new(
            -self.yaw.sin() * self.pitch.cos(),
            self.pitch.sin(),
            -self.yaw.cos() * self.pitch.cos(),
        )
    }

    /// Turns by a mouse movement of `delta` pixels.
    pub fn turn(&mut self, delta: Vec2, radians_per_pixel: f32) {
        self.yaw -= delta.x * radians_per_pixel;
        self.pitch = (self.pitch - delta.y * radians_per_pixel).clamp(-PITCH_LIMIT, PITCH_LIMIT);
    }

    /// Moves by `forward` and `right` (each -1, 0 or 1) at `speed` for `dt`,
    /// along the view direction and its right, and stays inside `lo..hi`.
    pub fn walk(&mut self, forward: f32, right: f32, speed: f32, dt: f32, lo: Vec3, hi: Vec3) {
        let ahead = self.forward();
        let side = ahead.cross(Vec3::Y).normalize_or_zero();
        let step = (ahead * forward + side * right).normalize_or_zero() * speed * dt;
        self.position = (self.position + step).clamp(lo, hi);
    }

    pub fn camera(&self) -> Camera {
        Camera {
            eye: self.position,
            target: self.position + self.forward(),
            fov_y_deg: self.fov_y_deg,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trips_the_overview_camera() {
        let overview = Camera::overview(Vec3::new(8.0, 4.0, 8.0));
        let fly = FlyCamera::from_camera(&overview);
        let back = fly.camera();
        let want = (overview.target - overview.eye).normalize();
        assert!((back.target - back.eye).normalize().dot(want) > 0.9999);
    }

    #[test]
    fn pitch_is_clamped_and_walking_follows_the_view() {
        let mut c = FlyCamera {
            position: Vec3::ZERO,
            yaw: 0.0,
            pitch: 0.0,
            fov_y_deg: 60.0,
        };
        c.turn(Vec2::new(0.0, -10_000.0), 0.01);
        assert!((c.pitch - PITCH_LIMIT).abs() < 1e-6);
        c.pitch = 0.0;
        let big = Vec3::splat(100.0);
        c.walk(1.0, 0.0, 2.0, 0.5, -big, big);
        assert!((c.position - Vec3::new(0.0, 0.0, -1.0)).length() < 1e-5);
        c.walk(0.0, 1.0, 2.0, 0.5, -big, big);
        assert!((c.position - Vec3::new(1.0, 0.0, -1.0)).length() < 1e-5);
        c.walk(1.0, 0.0, 100.0, 1.0, Vec3::splat(-2.0), Vec3::splat(2.0));
        assert!(c.position.z >= -2.0);
    }
}
