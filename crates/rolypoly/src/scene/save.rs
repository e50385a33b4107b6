//! Writing a scene back as a file: only the keys whose values differ from
//! the default scene, under a header comment, so that loading the file
//! gives the identical scene.

use glam::DVec3;
use rolypoly_physics::Rgb;
use toml::{Table, Value};

use super::{SURFACE_NAMES, Scene};

/// The text of a scene file for `scene`: `header` as comment lines, then
/// the keys that differ from the default scene.
pub fn scene_file_text(scene: &Scene, header: &str) -> String {
    let differ = differences(&every_key(scene), &every_key(&Scene::default()));
    let mut text: String = header
        .lines()
        .map(|line| format!("# {line}").trim_end().to_owned() + "\n")
        .collect();
    if differ.is_empty() {
        text.push_str("#\n# Every key as in the default scene (see scenes/default.toml).\n");
        return text;
    }
    text.push_str(
        "#\n# Only the keys that differ from the default scene (see scenes/default.toml).\n\n",
    );
    // A table of plain values cannot fail to serialise.
    text + &toml::to_string(&differ).unwrap_or_default()
}

/// The entries of `table` that `default` does not have alike, table by
/// table; a list is kept or left whole.
fn differences(table: &Table, default: &Table) -> Table {
    let mut out = Table::new();
    for (key, value) in table {
        match (value, default.get(key)) {
            (Value::Table(inner), Some(Value::Table(base))) => {
                let inner = differences(inner, base);
                if !inner.is_empty() {
                    out.insert(key.clone(), Value::Table(inner));
                }
            }
            (value, Some(base)) if value == base => {}
            (value, _) => {
                out.insert(key.clone(), value.clone());
            }
        }
    }
    out
}

fn real(x: f64) -> Value {
    Value::Float(x)
}

/// A single-precision value as the decimal it was written as, so that
/// `0.9` is saved as `0.9`, not `0.8999999761581421`.
fn short(x: f32) -> Value {
    Value::Float(x.to_string().parse().unwrap_or(f64::from(x)))
}

fn vec3(v: DVec3) -> Value {
    Value::Array(v.to_array().map(real).to_vec())
}

fn rgb(c: Rgb) -> Value {
    Value::Array(c.map(short).to_vec())
}

fn count(n: usize) -> Value {
    Value::Integer(i64::try_from(n).unwrap_or(i64::MAX))
}

fn entries<const N: usize>(keys: [(&str, Value); N]) -> Table {
    keys.into_iter().map(|(k, v)| (k.to_owned(), v)).collect()
}

fn table<const N: usize>(keys: [(&str, Value); N]) -> Value {
    Value::Table(entries(keys))
}

/// Every key of `scene`, in the shape of a scene file.
fn every_key(scene: &Scene) -> Table {
    let c = &scene.world;
    let (room, balls, tumblers) = (&c.room, &c.balls, &c.tumblers);
    let light = &scene.light;
    let fx = &scene.effects;
    let colors = SURFACE_NAMES
        .iter()
        .zip(room.colors)
        .map(|(name, color)| ((*name).to_owned(), rgb(color)))
        .collect();
    let placed_balls = balls
        .placements
        .iter()
        .map(|p| {
            let mut t = Table::new();
            t.insert("position".into(), vec3(p.position));
            // At rest and without spin unless said otherwise, as a file reads.
            if p.velocity != DVec3::ZERO {
                t.insert("velocity".into(), vec3(p.velocity));
            }
            if p.spin != DVec3::ZERO {
                t.insert("spin".into(), vec3(p.spin));
            }
            if let Some(color) = p.color {
                t.insert("color".into(), rgb(color));
            }
            if let Some(radius) = p.radius {
                t.insert("radius".into(), real(radius));
            }
            if let Some(mass) = p.mass {
                t.insert("mass".into(), real(mass));
            }
            Value::Table(t)
        })
        .collect();
    let spheres = tumblers
        .spheres
        .iter()
        .map(|s| {
            table([
                ("height", real(s.height)),
                ("radius", real(s.radius)),
                ("mass", real(s.mass)),
            ])
        })
        .collect();
    let placed_tumblers = tumblers
        .placements
        .iter()
        .map(|p| {
            let mut t = entries([("x", real(p.x)), ("z", real(p.z))]);
            // Upright about x unless said otherwise, as a file reads.
            if p.tilt_axis != DVec3::X {
                t.insert("tilt_axis".into(), vec3(p.tilt_axis));
            }
            if p.tilt_deg != 0.0 {
                t.insert("tilt_deg".into(), real(p.tilt_deg));
            }
            Value::Table(t)
        })
        .collect();
    entries([
        ("gravity", real(c.gravity)),
        (
            "room",
            table([
                ("size", vec3(room.size)),
                ("restitution", real(room.restitution)),
                ("friction", real(room.friction)),
                ("rolling_resistance", real(room.rolling_resistance)),
                ("colors", Value::Table(colors)),
            ]),
        ),
        (
            "light",
            table([
                ("color", rgb(light.color)),
                ("intensity", short(light.intensity)),
                ("ambient", short(light.ambient)),
                ("bulb_radius", short(light.bulb_radius)),
                ("drop", short(light.drop)),
                ("bloom", Value::Boolean(light.bloom)),
                ("bloom_strength", short(light.bloom_strength)),
                ("bloom_threshold", short(light.bloom_threshold)),
                ("fireball_light", Value::Boolean(light.fireball_light)),
                ("indirect", Value::Boolean(light.indirect)),
                ("occlusion", Value::Boolean(light.occlusion)),
            ]),
        ),
        (
            "balls",
            table([
                ("count", count(balls.count)),
                ("radius", real(balls.radius)),
                ("mass", real(balls.mass)),
                ("restitution", real(balls.restitution)),
                ("speed_min", real(balls.speed_min)),
                ("speed_max", real(balls.speed_max)),
                ("start_fill", real(balls.start_fill)),
                ("color", rgb(balls.color)),
                ("placement", Value::Array(placed_balls)),
            ]),
        ),
        (
            "tumblers",
            table([
                ("restitution", real(tumblers.restitution)),
                ("floor_friction", real(tumblers.floor_friction)),
                ("damping", real(tumblers.damping)),
                (
                    "colors",
                    Value::Array(tumblers.colors.iter().copied().map(rgb).collect()),
                ),
                ("spheres", Value::Array(spheres)),
                ("placement", Value::Array(placed_tumblers)),
            ]),
        ),
        (
            "fireball",
            table([
                ("radius", real(c.fireball.radius)),
                ("speed", real(c.fireball.speed)),
                ("spawn", vec3(c.fireball.spawn)),
                ("direction", vec3(c.fireball.direction)),
                ("consumes_balls", Value::Boolean(c.fireball.consumes_balls)),
                ("starts_active", Value::Boolean(c.fireball.starts_active)),
            ]),
        ),
        (
            "grab",
            table([
                ("stiffness", real(c.grab.stiffness)),
                ("damping", real(c.grab.damping)),
                ("max_force", real(c.grab.max_force)),
            ]),
        ),
        (
            "solver",
            table([
                ("dt", real(c.solver.dt)),
                ("iterations", count(c.solver.iterations)),
                ("bounce_threshold", real(c.solver.bounce_threshold)),
                ("event_threshold", real(c.solver.event_threshold)),
            ]),
        ),
        (
            "effects",
            table([
                ("capacity", count(fx.capacity)),
                (
                    "trail",
                    table([
                        ("interval_min", real(fx.trail.interval_min)),
                        ("interval_max", real(fx.trail.interval_max)),
                        ("life", real(fx.trail.life)),
                        ("size", real(fx.trail.size)),
                    ]),
                ),
                (
                    "wall_hit",
                    table([
                        ("duration", real(fx.wall_hit.duration)),
                        ("rate", real(fx.wall_hit.rate)),
                        ("radius", real(fx.wall_hit.radius)),
                        ("life", real(fx.wall_hit.life)),
                        ("size", real(fx.wall_hit.size)),
                    ]),
                ),
                (
                    "ball_hit",
                    table([
                        ("duration", real(fx.ball_hit.duration)),
                        ("rate", real(fx.ball_hit.rate)),
                        ("radius", real(fx.ball_hit.radius)),
                        ("life", real(fx.ball_hit.life)),
                        ("size", real(fx.ball_hit.size)),
                        ("burst_life", real(fx.ball_hit.burst_life)),
                        ("burst_size", real(fx.ball_hit.burst_size)),
                    ]),
                ),
            ]),
        ),
    ])
}

#[cfg(test)]
mod tests;
