//! The table against what it describes: the panel's spans lie in the
//! allowed ranges, every key has a change, and the table names each key
//! once. (That the sandbox takes each key when the table says is the
//! program's test.)

use super::*;

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
fn every_key_but_the_lists_has_a_valid_change() {
    let default = Scene::default();
    for key in KEYS {
        let list = matches!(key.slot, Slot::List(_));
        assert_eq!(nearby_change(key, &default).is_none(), list, "{}", key.name);
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
