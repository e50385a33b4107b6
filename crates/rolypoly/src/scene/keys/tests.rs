//! The table against what it describes: the sandbox takes each key when
//! the table says, the panel's spans lie in the allowed ranges, and the
//! table names each key once.

use super::*;
use crate::sandbox::Sandbox;
use crate::scene::validate;

/// `scene` with the value of `key` changed to the nearest other value the
/// scene's rules accept, or `None` for a list.
fn changed(key: &Key, scene: &Scene) -> Option<Scene> {
    let near = |x: f64| [0.9 * x, 1.1 * x, x + 0.05, x - 0.05, 0.5, 0.01];
    let mut candidates: Vec<Scene> = Vec::new();
    let mut with = |edit: &dyn Fn(&mut Scene)| {
        let mut s = scene.clone();
        edit(&mut s);
        candidates.push(s);
    };
    match &key.slot {
        Slot::Real(p) => near(*(p.read)(scene)).map(|x| with(&|s| *(p.write)(s) = x)),
        Slot::Single(p) => {
            near(f64::from(*(p.read)(scene))).map(|x| with(&|s| *(p.write)(s) = x as f32))
        }
        Slot::Count(p) => {
            let n = *(p.read)(scene);
            [n + 1, n.saturating_sub(1), n, n, n, n].map(|n| with(&|s| *(p.write)(s) = n))
        }
        Slot::Switch(p) => {
            let b = *(p.read)(scene);
            [!b; 6].map(|b| with(&|s| *(p.write)(s) = b))
        }
        Slot::Vector(p) => {
            let v = *(p.read)(scene);
            near(1.0).map(|k| with(&|s| *(p.write)(s) = v * k))
        }
        Slot::Color(p) => {
            let c = *(p.read)(scene);
            near(1.0).map(|k| with(&|s| *(p.write)(s) = c.map(|x| (x * k as f32).min(1.0))))
        }
        Slot::Word(p) => {
            let now = (p.read)(scene);
            let other = p
                .names
                .iter()
                .find(|n| **n != now)
                .expect("two names or more");
            [other; 6].map(|name| with(&|s| (p.write)(s, name)))
        }
        Slot::List(_) => return None,
    };
    candidates
        .into_iter()
        .find(|s| s != scene && validate(s).is_ok())
}

#[test]
fn every_key_is_named_once_and_documented_in_one_line() {
    for (i, key) in KEYS.iter().enumerate() {
        assert!(
            KEYS[..i].iter().all(|k| k.name != key.name),
            "{} twice",
            key.name
        );
        assert!(
            !key.doc.is_empty() && !key.doc.contains('\n') && key.doc.ends_with('.'),
            "{}: {:?}",
            key.name,
            key.doc
        );
        assert!(std::ptr::eq(super::key(key.name).unwrap(), key));
    }
    assert!(KEYS.len() > 60, "{} keys", KEYS.len());
}

#[test]
fn a_change_waits_for_the_restart_exactly_when_the_table_says() {
    let default = Scene::default();
    for seed in [1, 7] {
        for key in KEYS {
            let Some(scene) = changed(key, &default) else {
                continue;
            };
            let mut sandbox = Sandbox::new(default.clone(), "default.toml", seed).unwrap();
            sandbox.set_scene(scene.clone()).unwrap();
            assert_eq!(
                sandbox.restart_pending(),
                key.takes == Takes::Restart,
                "{}: the table says {:?}",
                key.name,
                key.takes
            );
            if key.takes == Takes::NextStep {
                assert_eq!(sandbox.world().config(), &scene.world, "{}", key.name);
            }
        }
    }
}

#[test]
fn every_key_but_the_lists_has_a_valid_change() {
    let default = Scene::default();
    for key in KEYS {
        let list = matches!(key.slot, Slot::List(_));
        assert_eq!(changed(key, &default).is_none(), list, "{}", key.name);
    }
}

#[test]
fn the_panel_shows_switches_as_boxes_and_numbers_as_sliders_within_range() {
    let scene = Scene::default();
    let mut shown = 0;
    for key in KEYS {
        match key.control {
            Control::Hidden => continue,
            Control::Checkbox(_) => assert!(matches!(key.slot, Slot::Switch(_)), "{}", key.name),
            Control::Choice(_) => assert!(matches!(key.slot, Slot::Word(_)), "{}", key.name),
            Control::Slider(_, lo, hi) => {
                let default = match &key.slot {
                    Slot::Real(p) => *(p.read)(&scene),
                    Slot::Single(p) => f64::from(*(p.read)(&scene)),
                    Slot::Count(p) => *(p.read)(&scene) as f64,
                    _ => panic!("{}: a slider for a value that is not a number", key.name),
                };
                assert!(lo < hi && (lo..=hi).contains(&default), "{}", key.name);
                let bounds = match key.allowed {
                    Allowed::Within(b) => b,
                    Allowed::Derived(bounds, _) => bounds(&scene),
                    _ => panic!("{}: a slider for a range of another kind", key.name),
                };
                assert!(
                    bounds.contains(lo) && bounds.contains(hi),
                    "{}: {lo} ..= {hi} is not within {bounds}",
                    key.name
                );
            }
        }
        shown += 1;
    }
    assert!(shown >= 20, "{shown} keys in the panel");
}
