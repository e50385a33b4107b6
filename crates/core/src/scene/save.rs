//! Writing a scene back as a file: only the keys whose values differ from
//! the default scene, under a header comment, so that loading the file
//! gives the identical scene.

use glam::DVec3;
use rolypoly_physics::Rgb;
use toml::{Table, Value};

use super::Scene;
use super::keys::{KEYS, Key, List, Slot};

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

/// `table` with `value` at the dotted `path`, making the tables on the way.
fn insert_at(table: &mut Table, path: &str, value: Value) {
    match path.split_once('.') {
        None => {
            table.insert(path.to_owned(), value);
        }
        Some((head, rest)) => {
            let inner = table
                .entry(head)
                .or_insert_with(|| Value::Table(Table::new()));
            if let Value::Table(inner) = inner {
                insert_at(inner, rest, value);
            }
        }
    }
}

/// Every key of `scene`, in the shape of a scene file.
fn every_key(scene: &Scene) -> Table {
    let mut file = Table::new();
    for key in KEYS {
        insert_at(&mut file, key.name, value_of(key, scene));
    }
    file
}

/// The value of `key` in `scene`, as a file writes it.
pub(super) fn value_of(key: &Key, scene: &Scene) -> Value {
    match &key.slot {
        Slot::Real(place) => real(*(place.read)(scene)),
        Slot::Single(place) => short(*(place.read)(scene)),
        Slot::Count(place) => count(*(place.read)(scene)),
        Slot::Switch(place) => Value::Boolean(*(place.read)(scene)),
        Slot::Vector(place) => vec3(*(place.read)(scene)),
        Slot::Color(place) => rgb(*(place.read)(scene)),
        Slot::Word(place) => Value::String((place.read)(scene).to_owned()),
        Slot::List(list) => Value::Array(list_entries(*list, scene)),
    }
}

/// The entries of `list` as a file writes them.
fn list_entries(list: List, scene: &Scene) -> Vec<Value> {
    let tumblers = &scene.world.tumblers;
    match list {
        List::BallPlacements => scene
            .world
            .balls
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
            .collect(),
        List::TumblerColors => tumblers.colors.iter().copied().map(rgb).collect(),
        List::TumblerSpheres => tumblers
            .spheres
            .iter()
            .map(|s| {
                let mut t = Table::new();
                t.insert("height".into(), real(s.height));
                t.insert("radius".into(), real(s.radius));
                t.insert("mass".into(), real(s.mass));
                Value::Table(t)
            })
            .collect(),
        List::TumblerPlacements => tumblers
            .placements
            .iter()
            .map(|p| {
                let mut t = Table::new();
                t.insert("x".into(), real(p.x));
                t.insert("z".into(), real(p.z));
                // Upright about x unless said otherwise, as a file reads.
                if p.tilt_axis != DVec3::X {
                    t.insert("tilt_axis".into(), vec3(p.tilt_axis));
                }
                if p.tilt_deg != 0.0 {
                    t.insert("tilt_deg".into(), real(p.tilt_deg));
                }
                Value::Table(t)
            })
            .collect(),
    }
}

#[cfg(test)]
mod tests;
