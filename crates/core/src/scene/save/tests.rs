//! Saved scenes load back as the identical scene, for every key.

use toml::{Table, Value};

use super::*;
use crate::scene::SHIPPED_SCENES;
use crate::scene::parse_scene;

/// Where a value sits in a scene file: table keys and list indices.
#[derive(Clone, Debug)]
enum Step {
    Key(String),
    Index(usize),
}

/// Every single value (number, flag, or a number inside a vector) of
/// `value`, by its path.
fn leaves(value: &Value, path: &mut Vec<Step>, out: &mut Vec<Vec<Step>>) {
    match value {
        Value::Table(t) => {
            for (k, v) in t {
                path.push(Step::Key(k.clone()));
                leaves(v, path, out);
                path.pop();
            }
        }
        Value::Array(items) => {
            for (i, v) in items.iter().enumerate() {
                path.push(Step::Index(i));
                leaves(v, path, out);
                path.pop();
            }
        }
        _ => out.push(path.clone()),
    }
}

fn at<'a>(value: &'a mut Value, path: &[Step]) -> &'a mut Value {
    path.iter().fold(value, |v, step| match (step, v) {
        (Step::Key(k), Value::Table(t)) => t.get_mut(k).unwrap(),
        (Step::Index(i), Value::Array(a)) => &mut a[*i],
        (step, v) => panic!("{step:?} does not lead into {v:?}"),
    })
}

/// Other values a key could take, nearest first.
fn changes(value: &Value) -> Vec<Value> {
    match value {
        Value::Float(x) => [0.9 * x, 1.1 * x, x + 0.05, x - 0.05, 0.5, 0.01]
            .map(Value::Float)
            .to_vec(),
        Value::Integer(n) => [n + 1, n - 1, n / 2].map(Value::Integer).to_vec(),
        Value::Boolean(b) => vec![Value::Boolean(!b)],
        // A word key: the other names of the key it is one of.
        Value::String(word) => crate::scene::keys::KEYS
            .iter()
            .find_map(|key| match &key.slot {
                crate::scene::keys::Slot::Word(place) if place.names.contains(&word.as_str()) => {
                    Some(place.names)
                }
                _ => None,
            })
            .unwrap_or_else(|| panic!("`{word}` is no key's name"))
            .iter()
            .filter(|name| *name != word)
            .map(|name| Value::String((*name).to_owned()))
            .collect(),
        other => panic!("no change for {other:?}"),
    }
}

fn name(path: &[Step]) -> String {
    path.iter()
        .map(|s| match s {
            Step::Key(k) => format!(".{k}"),
            Step::Index(i) => format!("[{i}]"),
        })
        .collect::<String>()
        .trim_start_matches('.')
        .to_owned()
}

fn round_trip(scene: &Scene, what: &str) -> String {
    let text = scene_file_text(scene, &format!("{what}\nsaved by a test"));
    let loaded = parse_scene(&text, "saved.toml")
        .unwrap_or_else(|e| panic!("{what}: the saved file does not load: {e}\n{text}"));
    assert_eq!(&loaded, scene, "{what}: saved as\n{text}");
    text
}

/// Lines that set a key.
fn key_lines(text: &str) -> usize {
    text.lines()
        .filter(|l| !l.starts_with('#') && l.contains(" = "))
        .count()
}

#[test]
fn every_key_changed_alone_is_saved_alone_and_loads_back() {
    let default = Value::Table(every_key(&Scene::default()));
    let mut paths = Vec::new();
    leaves(&default, &mut Vec::new(), &mut paths);
    assert!(paths.len() > 80, "{} values", paths.len());
    for path in &paths {
        let mut file = default.clone();
        let original = at(&mut file, path).clone();
        // The first change the scene's rules accept.
        let accepted = changes(&original)
            .into_iter()
            .filter(|c| *c != original)
            .find_map(|change| {
                *at(&mut file, path) = change;
                let text = toml::to_string(&file).unwrap();
                parse_scene(&text, "changed.toml").ok()
            });
        let scene = accepted.unwrap_or_else(|| panic!("{}: no change accepted", name(path)));
        assert_ne!(scene, Scene::default(), "{} changed nothing", name(path));
        let text = round_trip(&scene, &name(path));
        let in_list = path.iter().any(|s| matches!(s, Step::Index(_)));
        if !in_list {
            assert_eq!(key_lines(&text), 1, "{}:\n{text}", name(path));
        }
    }
}

#[test]
fn the_default_scene_saves_no_keys() {
    let text = round_trip(&Scene::default(), "default");
    assert_eq!(key_lines(&text), 0, "{text}");
    assert!(text.starts_with("# default\n# saved by a test\n"), "{text}");
}

#[test]
fn every_shipped_scene_loads_back_from_its_saved_file() {
    for shipped in SHIPPED_SCENES {
        let scene = parse_scene(shipped.text, shipped.name).unwrap();
        let text = round_trip(&scene, shipped.name);
        assert!(
            key_lines(&text) <= key_lines(shipped.text),
            "{}",
            shipped.name
        );
    }
}

#[test]
fn colours_are_saved_as_they_were_written() {
    let scene = parse_scene("[balls]\ncolor = [0.9, 0.1, 0.3]\n", "x.toml").unwrap();
    let text = round_trip(&scene, "colour");
    assert!(text.contains("color = [0.9, 0.1, 0.3]"), "{text}");
}

#[test]
fn the_key_table_matches_what_a_file_may_hold() {
    // Each table of the saved shape is a table a file may hold: a file of
    // every key, written in full, loads as the scene it came from.
    let mut scene = Scene::default();
    scene.world.gravity = 3.0;
    let text = toml::to_string(&Table::from(every_key(&scene))).unwrap();
    assert_eq!(parse_scene(&text, "full.toml").unwrap(), scene);
}
