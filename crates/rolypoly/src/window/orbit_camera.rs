//! The orbit camera (O): it circles a point, a picked body or the room's
//! centre, at a distance; moving the mouse turns it, the wheel zooms.
//!
//! It takes over from the fly camera without a jump: it starts where the
//! fly camera stands and looks the same way, circling the point on its
//! line of sight as far away as the body, and that point then glides to
//! the body and follows it. Handing back, the fly camera starts where the
//! orbit camera is and looks the same way.

use glam::{Vec2, Vec3};

use super::fly_camera::FlyCamera;

/// Nearest and farthest the orbit camera stands from its point (m).
const DISTANCES: (f32, f32) = (0.3, 40.0);
/// How long (s) the point takes to glide most of the way (1 - 1/e) to the
/// body it follows.
const GLIDE: f32 = 0.25;
/// Each notch of the wheel brings the camera this share nearer.
const ZOOM_PER_NOTCH: f32 = 0.9;
/// As the fly camera's: looking straight up or down is left out.
const PITCH_LIMIT: f32 = 1.5;

/// A camera circling a point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OrbitCamera {
    /// The point it circles now.
    pub pivot: Vec3,
    /// Its distance from the point (m).
    pub distance: f32,
    /// Radians about +y of its view direction; 0 looks along -z.
    pub yaw: f32,
    /// Radians above the horizon of its view direction.
    pub pitch: f32,
}

impl OrbitCamera {
    /// Takes over from `fly` to circle `target`: at first it circles the
    /// point of its line of sight nearest `target` (no nearer than the
    /// least distance), so that nothing moves at the handover.
    pub fn take_over(fly: &FlyCamera, target: Vec3) -> OrbitCamera {
        let forward = fly.forward();
        let distance = (target - fly.position)
            .dot(forward)
            .clamp(DISTANCES.0, DISTANCES.1);
        OrbitCamera {
            pivot: fly.position + forward * distance,
            distance,
            yaw: fly.yaw,
            pitch: fly.pitch,
        }
    }

    /// The fly camera that stands where this one does and looks the same
    /// way (for the hand back, and for everything that reads the camera).
    pub fn fly(&self, fov_y_deg: f32) -> FlyCamera {
        let looking = FlyCamera {
            position: Vec3::ZERO,
            yaw: self.yaw,
            pitch: self.pitch,
            fov_y_deg,
        };
        FlyCamera {
            position: self.pivot - looking.forward() * self.distance,
            ..looking
        }
    }

    /// Moves the point `elapsed` seconds of its glide towards `target`.
    pub fn follow(&mut self, target: Vec3, elapsed: f32) {
        let share = 1.0 - (-elapsed.max(0.0) / GLIDE).exp();
        self.pivot += (target - self.pivot) * share;
    }

    /// Circles the point by a mouse drag of `delta` pixels.
    pub fn turn(&mut self, delta: Vec2, radians_per_pixel: f32) {
        self.yaw -= delta.x * radians_per_pixel;
        self.pitch = (self.pitch - delta.y * radians_per_pixel).clamp(-PITCH_LIMIT, PITCH_LIMIT);
    }

    /// Comes nearer by `notches` of the wheel (farther where negative).
    pub fn zoom(&mut self, notches: f32) {
        self.distance =
            (self.distance * ZOOM_PER_NOTCH.powf(notches)).clamp(DISTANCES.0, DISTANCES.1);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fly(position: Vec3, yaw: f32, pitch: f32) -> FlyCamera {
        FlyCamera {
            position,
            yaw,
            pitch,
            fov_y_deg: 50.0,
        }
    }

    fn same_view(a: &FlyCamera, b: &FlyCamera) -> bool {
        (a.position - b.position).length() < 1e-4 && a.forward().dot(b.forward()) > 1.0 - 1e-6
    }

    #[test]
    fn it_takes_over_and_hands_back_without_a_jump() {
        let views = [
            fly(Vec3::new(0.0, 1.7, 6.0), 0.0, -0.2),
            fly(Vec3::new(-2.0, 0.5, 1.0), 1.1, 0.4),
            fly(Vec3::new(3.0, 3.0, -3.0), -2.5, -1.2),
        ];
        let targets = [
            Vec3::ZERO,
            Vec3::new(1.0, 0.2, -2.0),
            Vec3::new(-3.0, 2.0, 3.0),
        ];
        for before in views {
            for target in targets {
                let orbit = OrbitCamera::take_over(&before, target);
                assert!(
                    same_view(&orbit.fly(50.0), &before),
                    "{before:?} around {target}"
                );
                // Turned and zoomed, the fly camera takes over where it is.
                let mut moved = orbit;
                moved.turn(Vec2::new(40.0, -15.0), 0.01);
                moved.zoom(2.0);
                let after = moved.fly(50.0);
                assert!(((after.position - moved.pivot).length() - moved.distance).abs() < 1e-4);
                // Taking over again from there, around the same point, finds
                // the same point and changes nothing.
                let again = OrbitCamera::take_over(&after, moved.pivot);
                assert!(same_view(&again.fly(50.0), &after));
                assert!((again.pivot - moved.pivot).length() < 1e-4);
            }
        }
    }

    #[test]
    fn the_point_glides_to_the_body_frame_by_frame_and_then_follows_it() {
        let mut orbit =
            OrbitCamera::take_over(&fly(Vec3::new(0.0, 1.7, 6.0), 0.3, -0.2), Vec3::ZERO);
        let body = Vec3::new(0.5, 0.3, -0.5);
        let start = (orbit.pivot - body).length();
        let mut last = orbit.fly(50.0);
        // At 60 frames a second no frame moves the eye by more than a tenth
        // of the way, and after a second the point is on the body.
        for _ in 0..60 {
            orbit.follow(body, 1.0 / 60.0);
            let now = orbit.fly(50.0);
            assert!((now.position - last.position).length() < 0.1 * start);
            last = now;
        }
        assert!((orbit.pivot - body).length() < 0.02 * start);
        // A body that moves on is followed.
        for k in 0..120 {
            orbit.follow(body + Vec3::X * (k as f32 * 0.01), 1.0 / 60.0);
        }
        assert!((orbit.pivot - (body + Vec3::X * 1.19)).length() < 0.2);
    }

    #[test]
    fn turning_keeps_the_distance_and_zoom_stays_within_its_range() {
        let mut orbit =
            OrbitCamera::take_over(&fly(Vec3::new(0.0, 1.0, 4.0), 0.0, 0.0), Vec3::ZERO);
        for k in 0..20 {
            orbit.turn(Vec2::new(30.0 * k as f32, 7.0), 0.01);
            let eye = orbit.fly(50.0).position;
            assert!(((eye - orbit.pivot).length() - orbit.distance).abs() < 1e-4);
            assert!(orbit.pitch.abs() <= PITCH_LIMIT);
        }
        orbit.zoom(100.0);
        assert_eq!(orbit.distance, DISTANCES.0);
        orbit.zoom(-1000.0);
        assert_eq!(orbit.distance, DISTANCES.1);
    }
}
