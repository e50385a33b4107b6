//! The table of keys written out for people: as the Markdown reference in
//! `docs/scenes.md`, and as `scenes/default.toml`, the default scene with
//! every key and its comment. Tests fail when either file and the table
//! disagree.

use std::fmt::Write as _;

use toml::Value;

use super::Scene;
use super::bounds::{number_text, widen};
use super::keys::{Allowed, Control, KEYS, Key, List, Slot, Takes};
use super::save::value_of;

/// The lines that open and close the reference in `docs/scenes.md`.
pub const BEGIN_MARK: &str =
    "<!-- The key reference, written from the table of keys (crates/core/src/scene/keys.rs). -->";
/// See [`BEGIN_MARK`].
pub const END_MARK: &str = "<!-- End of the key reference. -->";

/// The reference: a row per key, in the order of the table, with its type,
/// its default, the values it allows, when a running sandbox takes a
/// change and the panel's control for it.
pub fn key_reference() -> String {
    let scene = Scene::default();
    let mut text = String::from(
        "| key | type | default | allowed | a change takes effect | what it is for |\n\
         | --- | --- | --- | --- | --- | --- |\n",
    );
    for key in KEYS {
        let takes = match key.takes {
            Takes::NextStep => "next step",
            Takes::NextFrame => "next frame",
            Takes::Restart => "restart (I)",
        };
        let shown = match key.control {
            Control::Hidden => String::new(),
            Control::Slider(label, ..) | Control::Checkbox(label) | Control::Choice(label) => {
                format!("; panel: \"{label}\"")
            }
        };
        let _ = writeln!(
            text,
            "| `{}` | {} | {} | {} | {takes}{shown} | {} |",
            key.name,
            type_name(key),
            default_text(key, &scene),
            allowed_text(key, &scene),
            key.doc
        );
    }
    text
}

/// What `scenes/default.toml` says before its keys.
const DEFAULT_SCENE_HEADER: &str = "\
The default rolypoly scene, written out in full.

This file is the documented example of the scene format: the program has
the same scene built in, and it is written from the program's table of
scene keys (docs/scenes.md has the same as a table). Run with your own
scene file:

    cargo run --release -- --scene my-scene.toml
    cargo run --release -- simulate --scene my-scene.toml --seconds 10

A scene file only needs the keys it changes; every key left out keeps the
value shown here. Unknown keys are an error, and every value is checked
against what its comment allows.

Units are SI (metres, kilograms, seconds). +y is up, the floor is y = 0 and
the room is centred on x = z = 0. Colours are linear [r, g, b].";

/// The default scene as a file: every key under its table, each with its
/// doc line and what it allows as a comment.
pub fn default_scene_file() -> String {
    let scene = Scene::default();
    let mut text = comment(DEFAULT_SCENE_HEADER);
    let mut table = "";
    for key in KEYS {
        let (in_table, leaf) = key.table_and_leaf();
        if in_table != table {
            table = in_table;
            let _ = write!(text, "\n[{table}]\n");
        } else {
            text.push('\n');
        }
        text += &comment(key.doc);
        if !matches!(key.allowed, Allowed::ListRules) {
            text += &comment(&format!("Allowed: {}.", allowed_text(key, &scene)));
        }
        let value = value_of(key, &scene);
        let _ = writeln!(text, "{leaf} = {}", multi_line(&value));
    }
    text
}

/// `text` as comment lines of at most 78 characters, never breaking a
/// range such as `0 ..= 1` or `> 0`.
fn comment(text: &str) -> String {
    const KEEP: char = '\u{1}';
    let kept = text
        .replace(" ..= ", &format!("{KEEP}..={KEEP}"))
        .replace("> ", &format!(">{KEEP}"))
        .replace("< ", &format!("<{KEEP}"))
        .replace("<= ", &format!("<={KEEP}"));
    let mut out = String::new();
    for paragraph in kept.split('\n') {
        if paragraph.starts_with("    ") || paragraph.is_empty() {
            out += format!("# {paragraph}").trim_end();
            out.push('\n');
            continue;
        }
        let mut line = String::from("#");
        for word in paragraph.split(' ') {
            if line.len() + 1 + word.len() > 78 && line.len() > 1 {
                out += &line;
                out.push('\n');
                line = String::from("#");
            }
            line.push(' ');
            line += word;
        }
        out += &line;
        out.push('\n');
    }
    out.replace(KEEP, " ")
}

/// A value as a file writes it; a list of entries one entry a line.
fn multi_line(value: &Value) -> String {
    match value {
        Value::Array(items) if items.iter().any(|v| v.is_table() || v.is_array()) => {
            let mut text = String::from("[\n");
            for item in items {
                let _ = writeln!(text, "    {item},");
            }
            text + "]"
        }
        _ => value.to_string(),
    }
}

fn type_name(key: &Key) -> &'static str {
    match key.slot {
        Slot::Real(_) | Slot::Single(_) => "number",
        Slot::Count(_) => "whole number",
        Slot::Switch(_) => "true or false",
        Slot::Vector(_) => "[x, y, z]",
        Slot::Color(_) => "[r, g, b]",
        Slot::Word(_) => "string",
        Slot::List(List::TumblerColors) => "array of [r, g, b]",
        Slot::List(_) => "array of tables",
    }
}

fn three(values: [f64; 3]) -> String {
    let [x, y, z] = values.map(number_text);
    format!("[{x}, {y}, {z}]")
}

fn default_text(key: &Key, scene: &Scene) -> String {
    let world = &scene.world;
    match &key.slot {
        Slot::Real(p) => number_text(*(p.read)(scene)),
        Slot::Single(p) => number_text(widen(*(p.read)(scene))),
        Slot::Count(p) => (p.read)(scene).to_string(),
        Slot::Switch(p) => (p.read)(scene).to_string(),
        Slot::Vector(p) => three((p.read)(scene).to_array()),
        Slot::Color(p) => three((p.read)(scene).map(widen)),
        Slot::Word(p) => format!("\"{}\"", (p.read)(scene)),
        Slot::List(list) => {
            let n = match list {
                List::BallPlacements => world.balls.placements.len(),
                List::TumblerColors => world.tumblers.colors.len(),
                List::TumblerSpheres => world.tumblers.spheres.len(),
                List::TumblerPlacements => world.tumblers.placements.len(),
            };
            match n {
                0 => "none".into(),
                n => format!("{n} entries (scenes/default.toml)"),
            }
        }
    }
}

fn allowed_text(key: &Key, scene: &Scene) -> String {
    match key.allowed {
        Allowed::Any => match &key.slot {
            Slot::Word(place) => place
                .names
                .iter()
                .map(|name| format!("\"{name}\""))
                .collect::<Vec<_>>()
                .join(", "),
            _ => "true or false".into(),
        },
        Allowed::Within(bounds) => bounds.to_string(),
        Allowed::Derived(bounds, why) => {
            format!("{why}: {} in the default scene", bounds(scene))
        }
        Allowed::Each(bounds) => format!("each component {bounds}"),
        Allowed::EachDerived(bounds, why) => {
            let [x, y, z] = bounds(scene);
            format!("{why}: x {x}, y {y}, z {z} in the default scene")
        }
        Allowed::NonZero => "any finite non-zero vector".into(),
        Allowed::ListRules => "per entry: see what it is for".into(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const PAGE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../docs/scenes.md");

    /// The page with its reference replaced by `reference`.
    fn with_reference(page: &str, reference: &str) -> Option<String> {
        let (head, rest) = page.split_once(BEGIN_MARK)?;
        let (_, tail) = rest.split_once(END_MARK)?;
        Some(format!(
            "{head}{BEGIN_MARK}\n\n{reference}\n{END_MARK}{tail}"
        ))
    }

    /// Fails when docs/scenes.md's reference is not the table's; run with
    /// ROLYPOLY_BLESS=1 to write it anew.
    #[test]
    fn the_page_of_scene_keys_is_the_table_of_keys() {
        let page = std::fs::read_to_string(PAGE).unwrap();
        let expected = with_reference(&page, &key_reference())
            .expect("docs/scenes.md has lost the marks around its key reference");
        if std::env::var_os("ROLYPOLY_BLESS").is_some() {
            std::fs::write(PAGE, &expected).unwrap();
        }
        assert!(
            page == expected,
            "docs/scenes.md's key reference is stale: run \
             ROLYPOLY_BLESS=1 cargo test -p rolypoly-core --lib reference"
        );
    }

    const DEFAULT_SCENE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenes/default.toml");

    /// Fails when scenes/default.toml is not the table's; run with
    /// ROLYPOLY_BLESS=1 to write it anew.
    #[test]
    fn the_default_scene_file_is_the_table_of_keys() {
        let file = std::fs::read_to_string(DEFAULT_SCENE).unwrap();
        let expected = default_scene_file();
        if std::env::var_os("ROLYPOLY_BLESS").is_some() {
            std::fs::write(DEFAULT_SCENE, &expected).unwrap();
        }
        assert!(
            file == expected,
            "scenes/default.toml is stale: run \
             ROLYPOLY_BLESS=1 cargo test -p rolypoly-core --lib reference"
        );
        // And it is the default scene, every key written.
        assert_eq!(
            super::super::parse_scene(&expected, "default.toml").unwrap(),
            Scene::default()
        );
        for key in KEYS {
            let leaf = key.table_and_leaf().1;
            assert!(expected.contains(&format!("\n{leaf} = ")), "{}", key.name);
        }
    }

    #[test]
    fn the_reference_has_a_row_per_key_with_its_range() {
        let reference = key_reference();
        assert_eq!(reference.lines().count(), KEYS.len() + 2);
        for (key, row) in KEYS.iter().zip(reference.lines().skip(2)) {
            assert!(row.starts_with(&format!("| `{}` |", key.name)), "{row}");
            assert!(row.ends_with(&format!("| {} |", key.doc)), "{row}");
        }
        assert!(reference.contains("| `balls.restitution` | number | 0.85 | 0 ..= 1 | next step"));
        assert!(reference.contains("| `light.intensity` | number | 3.2 | 0 ..= 100 | next frame"));
    }
}
