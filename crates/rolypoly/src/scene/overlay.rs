//! Copies what the file gives onto the default, remembering the line of
//! every key it sets.

use std::collections::HashMap;
use std::ops::Range;

use glam::DVec3;
use rolypoly_fx::EffectsConfig;
use rolypoly_physics::{BallPlacement, SphereSpec, TumblerPlacement};
use rolypoly_render::LightConfig;
use toml::Spanned;

use super::checks::ITERATIONS;
use super::file::{FileBallPlacement, FileEffects, FileLight, FileScene, rgb};
use super::{Location, MAX_BALLS, PARTICLE_CAPACITY, SURFACE_NAMES, Scene, SceneError, line_of};

pub(super) struct Overlay<'a> {
    pub(super) source: &'a str,
    pub(super) origin: &'a str,
    pub(super) lines: HashMap<String, usize>,
    /// Key path -> its value as written, for the keys set one value each.
    pub(super) written: HashMap<String, String>,
}

impl Overlay<'_> {
    fn note(&mut self, key: &str, span: Range<usize>) {
        self.lines
            .insert(key.to_owned(), line_of(self.source, span.start));
    }

    /// [`Self::note`], keeping the text of the value as well: a number
    /// too large for its key's type is shown as written, not as `inf`.
    fn note_written(&mut self, key: &str, span: Range<usize>) {
        if let Some(text) = self.source.get(span.clone()) {
            self.written.insert(key.to_owned(), text.trim().to_owned());
        }
        self.note(key, span);
    }

    /// Copies `value` into `dst` (converted) and records its line.
    fn set<T, U>(
        &mut self,
        key: &str,
        dst: &mut U,
        value: Option<Spanned<T>>,
        convert: impl FnOnce(T) -> U,
    ) {
        if let Some(value) = value {
            self.note_written(key, value.span());
            *dst = convert(value.into_inner());
        }
    }

    /// Integer keys are read signed; a value that does not fit `usize` is
    /// reported here because it cannot be stored for the later check.
    fn set_count(
        &mut self,
        key: &str,
        dst: &mut usize,
        value: Option<Spanned<i64>>,
        range: (usize, usize),
    ) -> Result<(), SceneError> {
        let Some(value) = value else { return Ok(()) };
        let span = value.span();
        let raw = value.into_inner();
        self.note_written(key, span.clone());
        match usize::try_from(raw) {
            Ok(n) => {
                *dst = n;
                Ok(())
            }
            Err(_) => Err(SceneError::OutOfRange {
                at: Location {
                    origin: self.origin.to_owned(),
                    line: Some(line_of(self.source, span.start)),
                },
                key: key.to_owned(),
                value: raw.to_string(),
                allowed: format!("{} ..= {}", range.0, range.1),
            }),
        }
    }

    /// One `[[balls.placement]]`, its keys noted as `balls.placement[i].key`.
    fn ball_placement(&mut self, i: usize, p: FileBallPlacement) -> BallPlacement {
        let key = format!("balls.placement[{i}]");
        self.note(&key, p.position.span());
        let mut placement = BallPlacement::new(DVec3::ZERO, DVec3::ZERO);
        let at = |name: &str| format!("{key}.{name}");
        self.set(
            &at("position"),
            &mut placement.position,
            Some(p.position),
            DVec3::from_array,
        );
        self.set(
            &at("velocity"),
            &mut placement.velocity,
            p.velocity,
            DVec3::from_array,
        );
        self.set(&at("spin"), &mut placement.spin, p.spin, DVec3::from_array);
        self.set(&at("color"), &mut placement.color, p.color, |c| {
            Some(rgb(c))
        });
        self.set(&at("radius"), &mut placement.radius, p.radius, Some);
        self.set(&at("mass"), &mut placement.mass, p.mass, Some);
        placement
    }

    pub(super) fn apply(&mut self, file: FileScene, scene: &mut Scene) -> Result<(), SceneError> {
        let c = &mut scene.world;
        self.set("gravity", &mut c.gravity, file.gravity, |v| v);

        if let Some(room) = file.room {
            self.set("room.size", &mut c.room.size, room.size, DVec3::from_array);
            self.set(
                "room.restitution",
                &mut c.room.restitution,
                room.restitution,
                |v| v,
            );
            self.set("room.friction", &mut c.room.friction, room.friction, |v| v);
            self.set(
                "room.rolling_resistance",
                &mut c.room.rolling_resistance,
                room.rolling_resistance,
                |v| v,
            );
            if let Some(colors) = room.colors {
                let given = [
                    colors.floor,
                    colors.ceiling,
                    colors.left,
                    colors.right,
                    colors.back,
                    colors.front,
                ];
                for ((name, dst), value) in SURFACE_NAMES.iter().zip(&mut c.room.colors).zip(given)
                {
                    self.set(&format!("room.colors.{name}"), dst, value, rgb);
                }
            }
        }

        if let Some(light) = file.light {
            self.apply_light(light, &mut scene.light);
        }

        if let Some(balls) = file.balls {
            self.set_count(
                "balls.count",
                &mut c.balls.count,
                balls.count,
                (0, MAX_BALLS),
            )?;
            self.set("balls.radius", &mut c.balls.radius, balls.radius, |v| v);
            self.set("balls.mass", &mut c.balls.mass, balls.mass, |v| v);
            self.set(
                "balls.restitution",
                &mut c.balls.restitution,
                balls.restitution,
                |v| v,
            );
            self.set(
                "balls.speed_min",
                &mut c.balls.speed_min,
                balls.speed_min,
                |v| v,
            );
            self.set(
                "balls.speed_max",
                &mut c.balls.speed_max,
                balls.speed_max,
                |v| v,
            );
            self.set(
                "balls.start_fill",
                &mut c.balls.start_fill,
                balls.start_fill,
                |v| v,
            );
            self.set("balls.color", &mut c.balls.color, balls.color, rgb);
            if let Some(placements) = balls.placement {
                c.balls.placements = placements
                    .into_iter()
                    .enumerate()
                    .map(|(i, p)| self.ball_placement(i, p))
                    .collect();
            }
        }

        if let Some(t) = file.tumblers {
            let dst = &mut c.tumblers;
            self.set(
                "tumblers.restitution",
                &mut dst.restitution,
                t.restitution,
                |v| v,
            );
            self.set(
                "tumblers.floor_friction",
                &mut dst.floor_friction,
                t.floor_friction,
                |v| v,
            );
            self.set("tumblers.damping", &mut dst.damping, t.damping, |v| v);
            if let Some(colors) = t.colors {
                self.note("tumblers.colors", colors.span());
                dst.colors = colors
                    .into_inner()
                    .into_iter()
                    .enumerate()
                    .map(|(i, color)| {
                        self.note(&format!("tumblers.colors[{i}]"), color.span());
                        rgb(color.into_inner())
                    })
                    .collect();
            }
            if let Some(spheres) = t.spheres {
                self.note("tumblers.spheres", spheres.span());
                dst.spheres = spheres
                    .into_inner()
                    .into_iter()
                    .enumerate()
                    .map(|(i, s)| {
                        let key = format!("tumblers.spheres[{i}]");
                        self.note(&key, s.height.span());
                        self.note_written(&format!("{key}.height"), s.height.span());
                        self.note_written(&format!("{key}.radius"), s.radius.span());
                        self.note_written(&format!("{key}.mass"), s.mass.span());
                        SphereSpec {
                            height: s.height.into_inner(),
                            radius: s.radius.into_inner(),
                            mass: s.mass.into_inner(),
                        }
                    })
                    .collect();
            }
            if let Some(placements) = t.placement {
                dst.placements = placements
                    .into_iter()
                    .enumerate()
                    .map(|(i, p)| {
                        let key = format!("tumblers.placement[{i}]");
                        self.note(&key, p.x.span());
                        let mut placement = TumblerPlacement {
                            x: 0.0,
                            z: 0.0,
                            tilt_axis: DVec3::X,
                            tilt_deg: 0.0,
                        };
                        self.set(&format!("{key}.x"), &mut placement.x, Some(p.x), |v| v);
                        self.set(&format!("{key}.z"), &mut placement.z, Some(p.z), |v| v);
                        self.set(
                            &format!("{key}.tilt_axis"),
                            &mut placement.tilt_axis,
                            p.tilt_axis,
                            DVec3::from_array,
                        );
                        self.set(
                            &format!("{key}.tilt_deg"),
                            &mut placement.tilt_deg,
                            p.tilt_deg,
                            |v| v,
                        );
                        placement
                    })
                    .collect();
            }
        }

        if let Some(f) = file.fireball {
            let dst = &mut c.fireball;
            self.set("fireball.radius", &mut dst.radius, f.radius, |v| v);
            self.set("fireball.speed", &mut dst.speed, f.speed, |v| v);
            self.set("fireball.spawn", &mut dst.spawn, f.spawn, DVec3::from_array);
            self.set(
                "fireball.direction",
                &mut dst.direction,
                f.direction,
                DVec3::from_array,
            );
            self.set(
                "fireball.consumes_balls",
                &mut dst.consumes_balls,
                f.consumes_balls,
                |v| v,
            );
            self.set(
                "fireball.starts_active",
                &mut dst.starts_active,
                f.starts_active,
                |v| v,
            );
        }

        if let Some(g) = file.grab {
            self.set("grab.stiffness", &mut c.grab.stiffness, g.stiffness, |v| v);
            self.set("grab.damping", &mut c.grab.damping, g.damping, |v| v);
            self.set("grab.max_force", &mut c.grab.max_force, g.max_force, |v| v);
        }

        if let Some(s) = file.solver {
            self.set("solver.dt", &mut c.solver.dt, s.dt, |v| v);
            self.set_count(
                "solver.iterations",
                &mut c.solver.iterations,
                s.iterations,
                ITERATIONS,
            )?;
            self.set(
                "solver.bounce_threshold",
                &mut c.solver.bounce_threshold,
                s.bounce_threshold,
                |v| v,
            );
            self.set(
                "solver.event_threshold",
                &mut c.solver.event_threshold,
                s.event_threshold,
                |v| v,
            );
        }

        if let Some(e) = file.effects {
            self.apply_effects(e, &mut scene.effects)?;
        }
        Ok(())
    }

    fn apply_light(&mut self, l: FileLight, c: &mut LightConfig) {
        self.set("light.color", &mut c.color, l.color, rgb);
        self.set("light.intensity", &mut c.intensity, l.intensity, |v| {
            v as f32
        });
        self.set("light.ambient", &mut c.ambient, l.ambient, |v| v as f32);
        self.set(
            "light.bulb_radius",
            &mut c.bulb_radius,
            l.bulb_radius,
            |v| v as f32,
        );
        self.set("light.drop", &mut c.drop, l.drop, |v| v as f32);
        self.set("light.bloom", &mut c.bloom, l.bloom, |v| v);
        self.set(
            "light.bloom_strength",
            &mut c.bloom_strength,
            l.bloom_strength,
            |v| v as f32,
        );
        self.set(
            "light.bloom_threshold",
            &mut c.bloom_threshold,
            l.bloom_threshold,
            |v| v as f32,
        );
        self.set(
            "light.fireball_light",
            &mut c.fireball_light,
            l.fireball_light,
            |v| v,
        );
        self.set("light.indirect", &mut c.indirect, l.indirect, |v| v);
        self.set("light.occlusion", &mut c.occlusion, l.occlusion, |v| v);
    }

    fn apply_effects(&mut self, e: FileEffects, c: &mut EffectsConfig) -> Result<(), SceneError> {
        self.set_count(
            "effects.capacity",
            &mut c.capacity,
            e.capacity,
            PARTICLE_CAPACITY,
        )?;

        if let Some(t) = e.trail {
            let dst = &mut c.trail;
            self.set(
                "effects.trail.interval_min",
                &mut dst.interval_min,
                t.interval_min,
                |v| v,
            );
            self.set(
                "effects.trail.interval_max",
                &mut dst.interval_max,
                t.interval_max,
                |v| v,
            );
            self.set("effects.trail.life", &mut dst.life, t.life, |v| v);
            self.set("effects.trail.size", &mut dst.size, t.size, |v| v);
        }

        if let Some(w) = e.wall_hit {
            let dst = &mut c.wall_hit;
            self.set(
                "effects.wall_hit.duration",
                &mut dst.duration,
                w.duration,
                |v| v,
            );
            self.set("effects.wall_hit.rate", &mut dst.rate, w.rate, |v| v);
            self.set("effects.wall_hit.radius", &mut dst.radius, w.radius, |v| v);
            self.set("effects.wall_hit.life", &mut dst.life, w.life, |v| v);
            self.set("effects.wall_hit.size", &mut dst.size, w.size, |v| v);
        }

        if let Some(b) = e.ball_hit {
            let dst = &mut c.ball_hit;
            self.set(
                "effects.ball_hit.duration",
                &mut dst.duration,
                b.duration,
                |v| v,
            );
            self.set("effects.ball_hit.rate", &mut dst.rate, b.rate, |v| v);
            self.set("effects.ball_hit.radius", &mut dst.radius, b.radius, |v| v);
            self.set("effects.ball_hit.life", &mut dst.life, b.life, |v| v);
            self.set("effects.ball_hit.size", &mut dst.size, b.size, |v| v);
            self.set(
                "effects.ball_hit.burst_life",
                &mut dst.burst_life,
                b.burst_life,
                |v| v,
            );
            self.set(
                "effects.ball_hit.burst_size",
                &mut dst.burst_size,
                b.burst_size,
                |v| v,
            );
        }
        Ok(())
    }
}
