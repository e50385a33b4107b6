//! Scene files fuzzed: arbitrary text and mutated shipped scenes never
//! make the parser panic. Each gives a clean error naming where, or a
//! valid scene, which builds a world (or says why not) and saves to a
//! file that loads back as the identical scene.

#[path = "../../../tests/text_edits.rs"]
mod text_edits;

use proptest::prelude::*;
use rolypoly::sandbox::SHIPPED_SCENES;
use rolypoly::scene::{Scene, parse_scene, scene_file_text, validate};
use rolypoly_physics::World;
use text_edits::TextEdit;

/// Cases per property.
const CASES: u32 = 1500;

/// Most balls a fuzzed scene is built with: building a million takes long
/// and proves nothing more.
const BUILD_BALLS: usize = 5000;

/// What every outcome of parsing must satisfy.
fn check(text: &str) -> Result<(), TestCaseError> {
    match parse_scene(text, "fuzz.toml") {
        Err(e) => {
            let message = e.to_string();
            prop_assert!(message.starts_with("fuzz.toml"), "{message}");
            prop_assert!(!message.contains('\n'), "one line: {message}");
        }
        Ok(scene) => {
            prop_assert!(validate(&scene).is_ok());
            let saved = scene_file_text(&scene, "fuzzed");
            let loaded: Scene = parse_scene(&saved, "saved.toml")
                .map_err(|e| TestCaseError::fail(format!("{e}\n{saved}")))?;
            prop_assert_eq!(&loaded, &scene);
            if scene.world.balls.total() <= BUILD_BALLS {
                // A clean error or a world; never a panic.
                let _ = World::new(scene.world, 1);
            }
        }
    }
    Ok(())
}

/// One edit of a scene file's text.
fn edit() -> impl Strategy<Value = TextEdit> {
    let number = prop_oneof![
        any::<f64>().prop_map(|x| x.to_string()),
        any::<i64>().prop_map(|x| x.to_string()),
        (-10.0..10.0f64).prop_map(|x| format!("{x:.3}")),
        Just("nan".to_owned()),
        Just("-inf".to_owned()),
        Just("1e400".to_owned()),
        Just("0".to_owned()),
        Just("-0.0".to_owned()),
        Just("[]".to_owned()),
        Just("true".to_owned()),
        Just("\"x\"".to_owned()),
    ];
    let token = prop_oneof![
        Just("\n[balls]\n".to_owned()),
        Just("\n[[balls.placement]]\nposition = [0, 1, 0]\n".to_owned()),
        Just("\n[[tumblers.placement]]\nx = 0\nz = 0\n".to_owned()),
        Just("count = 3\n".to_owned()),
        Just("]".to_owned()),
        Just("=".to_owned()),
        Just("\"".to_owned()),
        Just("#".to_owned()),
        "[a-z_.\\[\\]=0-9 ,\n\"]{1,12}",
    ];
    prop_oneof![
        any::<usize>().prop_map(TextEdit::DeleteLine),
        any::<usize>().prop_map(TextEdit::DuplicateLine),
        (any::<usize>(), any::<usize>()).prop_map(|(a, b)| TextEdit::SwapLines(a, b)),
        (any::<usize>(), number).prop_map(|(k, n)| TextEdit::Number(k, n)),
        (any::<usize>(), any::<char>()).prop_map(|(at, c)| TextEdit::Char(at, c)),
        any::<usize>().prop_map(TextEdit::Truncate),
        (any::<usize>(), token).prop_map(|(at, t)| TextEdit::Insert(at, t)),
    ]
}

/// `text` with `edit` made.
fn apply(text: &str, edit: &TextEdit) -> String {
    text_edits::apply(text, edit, &number_spans(text))
}

/// Byte spans of the numbers written in `text` outside comments.
fn number_spans(text: &str) -> Vec<(usize, usize)> {
    let mut spans = Vec::new();
    let mut offset = 0;
    for line in text.split_inclusive('\n') {
        let code = line.split('#').next().unwrap_or("");
        let bytes = code.as_bytes();
        let mut i = 0;
        while i < bytes.len() {
            let starts = bytes[i].is_ascii_digit()
                || (bytes[i] == b'-' && bytes.get(i + 1).is_some_and(u8::is_ascii_digit));
            let inside_word = i > 0
                && (bytes[i - 1].is_ascii_alphanumeric()
                    || bytes[i - 1] == b'_'
                    || bytes[i - 1] == b'.');
            if starts && !inside_word {
                let mut j = i + 1;
                while j < bytes.len()
                    && (bytes[j].is_ascii_alphanumeric()
                        || matches!(bytes[j], b'.' | b'_' | b'-' | b'+'))
                {
                    j += 1;
                }
                spans.push((offset + i, offset + j));
                i = j;
            } else {
                i += 1;
            }
        }
        offset += line.len();
    }
    spans
}

proptest! {
    #![proptest_config(ProptestConfig { cases: CASES, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn arbitrary_text_is_an_error_or_a_valid_scene(text in "\\PC{0,200}") {
        check(&text)?;
    }

    #[test]
    fn toml_shaped_text_is_an_error_or_a_valid_scene(
        text in "(\\[{1,2}[a-z_.]{1,20}\\]{1,2}\n|[a-z_]{1,16} = (-?[0-9]{1,6}(\\.[0-9]{1,3})?|true|\\[[0-9, .]{0,12}\\])\n){0,12}"
    ) {
        check(&text)?;
    }

    #[test]
    fn edited_shipped_scenes_are_an_error_or_a_valid_scene(
        scene in 0..SHIPPED_SCENES.len(),
        edits in proptest::collection::vec(edit(), 1..6),
    ) {
        let text = edits.iter().fold(SHIPPED_SCENES[scene].text.to_owned(), |t, e| apply(&t, e));
        check(&text)?;
    }
}

#[test]
fn a_number_edit_lands_on_a_number() {
    let text = "# 12 in a comment\ngravity = 9.81\nsize = [1, -2.5e3, 3]\nname_2 = 4\n";
    let spans: Vec<&str> = number_spans(text)
        .iter()
        .map(|&(a, b)| &text[a..b])
        .collect();
    assert_eq!(spans, ["9.81", "1", "-2.5e3", "3", "4"]);
}
