//! The fireball's own look (X1): eight crystal cores turning inside, and
//! two outer energy shells that breathe (pulse in size and alpha).

use glam::{Quat, Vec3};

/// One crystal core turning inside the fireball.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Core {
    /// Its centre (m).
    pub position: Vec3,
    /// Its size (m).
    pub size: f32,
    /// How it is turned.
    pub rotation: Quat,
}

/// One energy shell around the fireball.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shell {
    /// Its radius now (m).
    pub radius: f32,
    /// Its opacity now.
    pub alpha: f32,
}

/// Linear HDR colour of the white-hot heart at the fireball's centre: far
/// brighter than white, so it glows through the bloom from across the room.
pub const HEART_COLOR: Vec3 = Vec3::new(16.0, 8.0, 2.0);
/// The heart's radius, as a share of the fireball's.
const HEART_SHARE: f32 = 0.6;

/// Linear HDR colour of the crystal cores (brighter than 1: they glow).
pub const CORE_COLOR: Vec3 = Vec3::new(4.0, 2.8, 1.2);
/// Linear HDR colours of the inner and the outer shell.
pub const SHELL_COLORS: [Vec3; 2] = [Vec3::new(3.0, 1.2, 0.15), Vec3::new(2.4, 0.36, 0.72)];
/// How brightly the fireball lights the room for each unit of its shells'
/// glow (colour times alpha): brighter than the ceiling light within a
/// metre, so that the floor and walls it flies past glow orange.
const LIGHT_PER_GLOW: f32 = 4.0;

/// How the fireball looks at one moment: heart, cores and shells.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FireballLook {
    /// The fireball's centre (m).
    pub centre: Vec3,
    /// Radius of the glowing heart.
    pub heart_radius: f32,
    /// The eight crystal cores.
    pub cores: [Core; 8],
    /// The inner and the outer shell.
    pub shells: [Shell; 2],
}

impl FireballLook {
    /// The look of a fireball of `radius` at `centre`, `time` seconds into
    /// the effects.
    pub fn at(centre: Vec3, radius: f32, time: f64) -> FireballLook {
        let t = time as f32;
        let turn = Quat::from_euler(glam::EulerRot::YXZ, 2.1 * t, 1.3 * t, 0.7 * t);
        let mut cores = [Core {
            position: centre,
            size: 0.0,
            rotation: Quat::IDENTITY,
        }; 8];
        for (i, core) in cores.iter_mut().enumerate() {
            // The corners of a cube, turning.
            let corner = Vec3::new(
                if i & 1 == 0 { -1.0 } else { 1.0 },
                if i & 2 == 0 { -1.0 } else { 1.0 },
                if i & 4 == 0 { -1.0 } else { 1.0 },
            ) / 3f32.sqrt();
            let pulse = 1.0 + 0.15 * (5.0 * t + i as f32).sin();
            core.position = centre + turn * corner * (0.38 * radius * pulse);
            core.size = 0.22 * radius;
            core.rotation = Quat::from_axis_angle(corner, 3.0 * t + i as f32);
        }
        let breathe = |rate: f32, phase: f32| (std::f32::consts::TAU * rate * t + phase).sin();
        let shells = [
            // The shells reach beyond the body that collides: a corona
            // that reads as fire from across the room.
            Shell {
                radius: radius * (1.3 + 0.1 * breathe(1.6, 0.0)),
                alpha: 0.45 + 0.15 * breathe(1.6, 0.0),
            },
            Shell {
                radius: radius * (2.0 + 0.18 * breathe(0.9, 1.3)),
                alpha: 0.22 + 0.1 * breathe(0.9, 1.3),
            },
        ];
        FireballLook {
            centre,
            heart_radius: HEART_SHARE * radius,
            cores,
            shells,
        }
    }

    /// The light the fireball casts from its centre, linear colour times
    /// intensity: its shells' colours, as strongly as they glow now.
    pub fn light(&self) -> Vec3 {
        self.shells
            .iter()
            .zip(SHELL_COLORS)
            .map(|(shell, color)| color * shell.alpha)
            .sum::<Vec3>()
            * LIGHT_PER_GLOW
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cores_stay_inside_and_shells_breathe() {
        let (radius, centre) = (0.15, Vec3::new(1.0, 2.0, 3.0));
        let mut sizes = Vec::new();
        for i in 0..200 {
            let look = FireballLook::at(centre, radius, i as f64 * 0.01);
            for c in look.cores {
                assert!(c.position.distance(centre) + 0.5 * c.size * 3f32.sqrt() < radius * 1.05);
            }
            sizes.push((
                look.shells[0].radius,
                look.shells[0].alpha,
                look.shells[1].radius,
            ));
        }
        let span = |f: fn(&(f32, f32, f32)) -> f32| {
            let v: Vec<f32> = sizes.iter().map(f).collect();
            v.iter().cloned().fold(f32::MIN, f32::max) - v.iter().cloned().fold(f32::MAX, f32::min)
        };
        assert!(
            span(|s| s.0) > 0.1 * radius,
            "the inner shell does not breathe"
        );
        assert!(span(|s| s.1) > 0.2, "its alpha does not pulse");
        assert!(
            span(|s| s.2) > 0.1 * radius,
            "the outer shell does not breathe"
        );
    }
}
