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

/// Samples per side of a surface when summing a light's power on it.
const POWER_SAMPLES: usize = 32;

/// The intensity (W / sr, in the frame's units) of an even point source
/// with the power that `light` delivers to the six surfaces of a room of
/// `room_size`. The frame's lights fall off as `attenuated` says and have
/// no power as such; what they deliver is the integral of their `E` (what
/// the albedo is multiplied by) over the surfaces, times pi (the frame's
/// `E` is irradiance over pi), and an even source's power is `4 pi I`. So
/// `I` is a quarter of that integral. The path-traced reference's lights,
/// and the bounce light here, have this intensity.
pub fn power_of(light: &PointLight, room_size: Vec3) -> Vec3 {
    let mut total = Vec3::ZERO;
    for surface in room::surfaces(room_size) {
        let normal = surface.normal();
        let area = surface.area() / (POWER_SAMPLES * POWER_SAMPLES) as f32;
        for a in 0..POWER_SAMPLES {
            for b in 0..POWER_SAMPLES {
                let s = (a as f32 + 0.5) / POWER_SAMPLES as f32;
                let t = (b as f32 + 0.5) / POWER_SAMPLES as f32;
                let to_light = light.position - surface.at(s, t);
                let distance = to_light.length().max(1e-3);
                let cosine = normal.dot(to_light / distance).max(0.0);
                total += attenuated(light, distance) * cosine * area;
            }
        }
    }
    total / 4.0
}

/// The light each surface sends back in its own colour, over every
/// bounce: the first as `wall_light` works it out from `lights`, and on
/// top the light that goes on bouncing between the surfaces, taken as
/// spread evenly over them: the first bounce's mean, summed over every
/// further bounce (divided by one less the mean albedo). It is the light
/// the frame's own direct light sends back, energy for energy; a
/// path-traced reference (L6) showed the bounce of old, scaled to the
/// ambient strength, about half as bright as the truth in the shadows.
pub fn bounce(view: &SceneView, lights: &[PointLight]) -> [Vec3; 6] {
    let surfaces = room::surfaces(view.room_size);
    let albedo: [Vec3; 6] = std::array::from_fn(|i| {
        let shade = if i == 0 { FLOOR_MEAN_SHADE } else { 1.0 };
        view.room_colors[i] * shade
    });
    let first = wall_light(view, lights);
    let total_area: f32 = surfaces.iter().map(|s| s.area()).sum();
    let mean = |values: &[Vec3; 6]| {
        values
            .iter()
            .zip(&surfaces)
            .map(|(v, s)| *v * s.area())
            .sum::<Vec3>()
            / total_area
    };
    let kept = Vec3::ONE - mean(&albedo).min(Vec3::splat(0.99));
    let further = mean(&first) / kept;
    std::array::from_fn(|i| first[i] + albedo[i] * further)
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
    #[test]
    fn an_inverse_square_light_keeps_its_intensity() {
        // A light that falls off as 1 / d^2 in the frame's units has
        // intensity pi x its colour: its flux (pi E over the room) is a
        // point source's 4 pi I.
        let light = PointLight {
            position: Vec3::new(0.3, 1.7, -0.4),
            color: Vec3::new(1.0, 2.0, 3.0),
            falloff: [0.0, 0.0, 1.0],
            reach: None,
        };
        let i = power_of(&light, Vec3::new(8.0, 4.0, 6.0));
        let expected = light.color * std::f32::consts::PI;
        assert!(
            (i - expected).length() < 0.01 * expected.length(),
            "{i} {expected}"
        );
    }

    #[test]
    fn a_room_of_one_albedo_sends_back_the_sum_of_every_bounce() {
        // Over a closed room of albedo a, what the surfaces send back
        // averages (4 I / A) a / (1 - a), wherever the light hangs: the
        // light's power (see `power_of`) spread over the area A, reflected
        // a + a^2 + ...
        for albedo in [0.3f32, 0.7] {
            let mut view = room();
            view.room_colors = [Vec3::splat(albedo); 6];
            // The floor's mean shade darkens its colour.
            view.room_colors[0] = Vec3::splat(albedo / FLOOR_MEAN_SHADE);
            for position in [Vec3::new(0.0, 3.75, 0.0), Vec3::new(-2.0, 1.0, 3.0)] {
                let light = PointLight {
                    position,
                    color: Vec3::splat(2.0),
                    falloff: CEILING_FALLOFF,
                    reach: None,
                };
                let intensity = power_of(&light, view.room_size).x;
                let sent = bounce(&view, &[light]);
                let surfaces = room::surfaces(view.room_size);
                let area: f32 = surfaces.iter().map(|s| s.area()).sum();
                let mean = sent
                    .iter()
                    .zip(&surfaces)
                    .map(|(b, s)| b.x * s.area())
                    .sum::<f32>()
                    / area;
                let expected = 4.0 * intensity / area * albedo / (1.0 - albedo);
                assert!(
                    (mean / expected - 1.0).abs() < 0.01,
                    "{albedo} {position}: {mean} {expected}"
                );
            }
        }
    }
}
