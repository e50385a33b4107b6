//! The reference of every scene key, written from the table of keys as a
//! Markdown table: `docs/scenes.md` holds it, and a test fails when the
//! page and the table disagree.

use std::fmt::Write as _;

use super::Scene;
use super::bounds::{number_text, widen};
use super::keys::{Allowed, Control, KEYS, Key, List, Slot, Takes};

/// The lines that open and close the reference in `docs/scenes.md`.
pub const BEGIN_MARK: &str = "<!-- The key reference, written from the table of keys (crates/rolypoly/src/scene/keys.rs). -->";
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
            Control::Slider(label, ..) | Control::Checkbox(label) => {
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

fn type_name(key: &Key) -> &'static str {
    match key.slot {
        Slot::Real(_) | Slot::Single(_) => "number",
        Slot::Count(_) => "whole number",
        Slot::Switch(_) => "true or false",
        Slot::Vector(_) => "[x, y, z]",
        Slot::Color(_) => "[r, g, b]",
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
        Slot::List(list) => {
            let n = match list {
                List::BallPlacements => world.balls.placements.len(),
                List::TumblerColors => world.tumblers.colors.len(),
                List::TumblerSpheres => world.tumblers.spheres.len(),
                List::TumblerPlacements => world.tumblers.placements.len(),
            };
            format!("{n} entries (scenes/default.toml)")
        }
    }
}

fn allowed_text(key: &Key, scene: &Scene) -> String {
    match key.allowed {
        Allowed::Any => "either".into(),
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
             ROLYPOLY_BLESS=1 cargo test -p rolypoly --lib reference"
        );
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
