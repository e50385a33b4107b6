//! The CPU's half of the lighting model: how a point light falls off, and
//! the light the room's six surfaces send back each frame, which the
//! irradiance volume then gathers (see irradiance.rs).

use crate::room;
use crate::view::{PointLight, SceneView};
use glam::Vec3;

/// How much of `light`'s colour arrives at `distance`, before the cosine:
/// `1 / (c0 + c1 d + c2 d^2)` of it, for its falloff `[c0, c1, c2]`, times
/// `(1 - (d / reach)^4)^2` (0 beyond) where it has a reach. The same as
/// `point_light` in scene.wgsl.
pub fn attenuated(light: &PointLight, distance: f32) -> Vec3 {
    let [c0, c1, c2] = light.falloff;
    let window = light.reach.map_or(1.0, |reach| {
        let edge = (1.0 - (distance / reach).powi(4)).max(0.0);
        edge * edge
    });
    light.color * window / (c0 + c1 * distance + c2 * distance * distance)
}

/// The wood's grain, planks and seams darken its base colour by this
/// much on average (the mean of `wood` in scene.wgsl over a floor).
const FLOOR_MEAN_SHADE: f32 = 0.84;

/// Samples per side of a surface when averaging the light on it.
const SAMPLES: usize = 12;

/// The light each surface of the room sends back, in its own colour: the
/// direct light falling on it from `lights` (ceiling light and fireball),
/// averaged over the surface, times its colour. Shadows are left out: at
/// this scale a ball's shadow changes a wall's average by little.
pub fn wall_light(view: &SceneView, lights: &[PointLight]) -> [Vec3; 6] {
    let mut out = [Vec3::ZERO; 6];
    for (i, surface) in room::surfaces(view.room_size).iter().enumerate() {
        let normal = surface.normal();
        let mut sum = Vec3::ZERO;
        for a in 0..SAMPLES {
            for b in 0..SAMPLES {
                let s = (a as f32 + 0.5) / SAMPLES as f32;
                let t = (b as f32 + 0.5) / SAMPLES as f32;
                let point = surface.at(s, t);
                for light in lights {
                    let to_light = light.position - point;
                    let distance = to_light.length().max(1e-3);
                    let cosine = normal.dot(to_light / distance).max(0.0);
                    sum += attenuated(light, distance) * cosine;
                }
            }
        }
        let shade = if i == 0 { FLOOR_MEAN_SHADE } else { 1.0 };
        out[i] = sum / (SAMPLES * SAMPLES) as f32 * view.room_colors[i] * shade;
    }
    out
}

/// The light each surface sends back, scaled so that on average over the
/// room's surfaces, by area, it is as bright as `view.light.ambient`: the
/// ambient strength keeps its meaning (how much light reaches what the
/// lamp does not light), and the bounce only spreads it by colour and
/// place. The scale is set by the ceiling light alone, so that the
/// fireball's own bounce (`fireball`) comes on top of it.
pub fn bounce(view: &SceneView, ceiling: PointLight, fireball: Option<PointLight>) -> [Vec3; 6] {
    let from_ceiling = wall_light(view, &[ceiling]);
    let areas = room::surfaces(view.room_size).map(|s| s.area());
    let mean = from_ceiling
        .iter()
        .zip(areas)
        .map(|(light, area)| luminance(*light) * area)
        .sum::<f32>()
        / areas.iter().sum::<f32>();
    let scale = if mean > 0.0 {
        view.light.ambient / mean
    } else {
        0.0
    };
    let from_fireball = fireball.map_or([Vec3::ZERO; 6], |f| wall_light(view, &[f]));
    std::array::from_fn(|i| (from_ceiling[i] + from_fireball[i]) * scale)
}

/// Linear luminance (Rec. 709).
fn luminance(c: Vec3) -> f32 {
    c.dot(Vec3::new(0.2126, 0.7152, 0.0722))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::view::{CEILING_FALLOFF, Light, LightConfig};

    fn room() -> SceneView {
        let room_size = Vec3::new(8.0, 4.0, 8.0);
        SceneView {
            room_size,
            room_colors: [Vec3::ONE; 6],
            light: Light::ceiling_centre(room_size, &LightConfig::default()),
            balls: Vec::new(),
            tumblers: Vec::new(),
            particles: Vec::new(),
            fireball: None,
            fireball_light: None,
            debug_marks: Vec::new(),
            gpu_balls: None,
        }
    }

    #[test]
    fn surfaces_send_back_their_own_colour_in_proportion_to_the_light() {
        let mut view = room();
        view.room_colors[2] = Vec3::new(0.8, 0.1, 0.1);
        let light = PointLight {
            position: Vec3::new(0.0, 3.0, 0.0),
            color: Vec3::splat(2.0),
            falloff: CEILING_FALLOFF,
            reach: None,
        };
        let once = wall_light(&view, &[light]);
        let twice = wall_light(
            &view,
            &[PointLight {
                color: light.color * 2.0,
                ..light
            }],
        );
        for (a, b) in once.iter().zip(&twice) {
            assert!((*b - *a * 2.0).length() < 1e-5, "{a} {b}");
        }
        // The red wall sends back red; the left and right walls, mirror
        // images about the light, send back the same amount of light.
        let red = once[2];
        assert!(red.x > 5.0 * red.y && (red.y - red.z).abs() < 1e-6, "{red}");
        assert!(
            (once[3].x - red.x / 0.8).abs() < 1e-4,
            "{} {}",
            once[3],
            red
        );
        // Moved towards the left wall, the light falls more on it than on
        // the right wall.
        let nearer_left = PointLight {
            position: Vec3::new(-3.0, 2.0, 0.0),
            ..light
        };
        let moved = wall_light(&view, &[nearer_left]);
        assert!(
            moved[2].x / 0.8 > 1.1 * moved[3].x,
            "{} {}",
            moved[2],
            moved[3]
        );
    }

    #[test]
    fn a_surface_behind_the_light_gets_nothing() {
        let view = room();
        // A light pressed against the left wall, facing it from outside:
        // the wall's inward face is lit only from inside the room.
        let light = PointLight {
            position: Vec3::new(-4.5, 2.0, 0.0),
            color: Vec3::ONE,
            falloff: CEILING_FALLOFF,
            reach: None,
        };
        assert_eq!(wall_light(&view, &[light])[2], Vec3::ZERO);
    }
}
