//! OBJ files fuzzed: arbitrary text and mutated meshes never make the
//! reader panic. Each gives a clean one-line error naming the file, or a
//! mesh the renderer can draw: whole triangles, every index a vertex,
//! every number finite, every normal of some length.

#[path = "../../../tests/text_edits.rs"]
mod text_edits;

use proptest::prelude::*;
use rolypoly_render::{DEFAULT_TUMBLER_OBJ, MeshData, from_obj};
use text_edits::TextEdit;

/// Cases per property.
const CASES: u32 = 600;

/// Cases for the shipped mesh, whose every case reads 31,000 lines.
const SHIPPED_CASES: u32 = 300;

/// The file name the reader is given.
const ORIGIN: &str = "fuzz.obj";

/// The shipped tumbler, as the program reads it.
const SHIPPED: &str = include_str!("../../../assets/tumbler.obj");

/// A small mesh with what the shipped one lacks: a quad, two objects,
/// negative indices, a shared normal, material and group lines.
const SMALL: &str = "# a square and a triangle
mtllib none.mtl
o square
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
vt 0 0
vt 1 0
vt 1 1
vt 0 1
vn 0 0 1
usemtl paint
s off
f 1/1/1 2/2/1 3/3/1 4/4/1
o triangle
g side
v 0 0 1
v 1 0 1
v 0 1 1
vt 0.5 0.5
vn 0 1 0
f -3/-1/-1 -2/-1/-1 -1/-1/-1
";

/// The properties every mesh read must have.
fn drawable(mesh: &MeshData) -> Result<(), TestCaseError> {
    prop_assert!(!mesh.indices.is_empty());
    prop_assert_eq!(mesh.indices.len() % 3, 0, "whole triangles");
    let n = mesh.vertices.len();
    prop_assert!(
        mesh.indices.iter().all(|&i| (i as usize) < n),
        "an index past the {n} vertices"
    );
    for v in &mesh.vertices {
        let numbers = v.position.iter().chain(&v.normal).chain(&v.uv);
        prop_assert!(numbers.clone().all(|x| x.is_finite()), "{v:?}");
        prop_assert!(v.normal.iter().any(|&x| x != 0.0), "{v:?}");
    }
    Ok(())
}

/// What every outcome of reading must satisfy.
fn check(text: &str) -> Result<(), TestCaseError> {
    match from_obj(text, ORIGIN) {
        Err(e) => {
            let message = e.to_string();
            prop_assert!(message.contains("`fuzz.obj`"), "{message}");
            prop_assert!(!message.contains(['\n', '\r']), "one line: {message:?}");
            Ok(())
        }
        Ok(mesh) => drawable(&mesh),
    }
}

/// One edit of an OBJ file's text.
fn edit() -> impl Strategy<Value = TextEdit> {
    let number = prop_oneof![
        any::<f32>().prop_map(|x| x.to_string()),
        any::<i64>().prop_map(|x| x.to_string()),
        (-12..12i32).prop_map(|x| x.to_string()),
        Just("0".to_owned()),
        Just("4294967295".to_owned()),
        Just("4294967296".to_owned()),
        Just("18446744073709551616".to_owned()),
        Just("-99999999".to_owned()),
        Just("nan".to_owned()),
        Just("inf".to_owned()),
        Just("1e39".to_owned()),
        Just("1e-45".to_owned()),
        Just(String::new()),
        Just("x".to_owned()),
        Just("1//1".to_owned()),
        Just("//".to_owned()),
    ];
    let token = prop_oneof![
        Just("\nf 1 2 3\n".to_owned()),
        Just("\nf 1/1/1 2/2/2\n".to_owned()),
        Just("\nf 1\n".to_owned()),
        Just("\nf\n".to_owned()),
        Just("\nf 0/0/0 0/0/0 0/0/0\n".to_owned()),
        Just("\nf -1/-1/-1 -2/-2/-2 -3/-3/-3\n".to_owned()),
        Just("\nf 1//1 2//1 3//1\n".to_owned()),
        Just("\nf 1/1 2/1 3/1 4/1 5/1\n".to_owned()),
        Just("\nv 1 2\n".to_owned()),
        Just("\nv 1 2 3 4 5 6 7\n".to_owned()),
        Just("\nvn 0 0 0\n".to_owned()),
        Just("\nvt\n".to_owned()),
        Just("\nvt 0.5 0.5 0.5\n".to_owned()),
        Just("\no\n".to_owned()),
        Just("\ng a b\n".to_owned()),
        Just("\nl 1 2\n".to_owned()),
        Just("\np 1\n".to_owned()),
        Just("\nmtllib x.mtl\nusemtl x\n".to_owned()),
        Just("\\\n".to_owned()),
        Just("/".to_owned()),
        Just("#".to_owned()),
        Just("\r".to_owned()),
        Just("\t".to_owned()),
        "[a-z0-9 ./\\-\n]{1,12}",
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
    let numbers: Vec<(usize, usize)> = number_spans(text).collect();
    text_edits::apply(text, edit, &numbers)
}

/// Byte spans of the numbers in `text`: coordinates, and the indices
/// between a face's slashes.
fn number_spans(text: &str) -> impl Iterator<Item = (usize, usize)> + '_ {
    let bytes = text.as_bytes();
    let mut i = 0;
    std::iter::from_fn(move || {
        while i < bytes.len() {
            let starts = bytes[i].is_ascii_digit()
                || (bytes[i] == b'-' && bytes.get(i + 1).is_some_and(u8::is_ascii_digit));
            let inside_word =
                i > 0 && (bytes[i - 1].is_ascii_alphanumeric() || bytes[i - 1] == b'.');
            if starts && !inside_word {
                let start = i;
                i += 1;
                while i < bytes.len()
                    && (bytes[i].is_ascii_alphanumeric() || matches!(bytes[i], b'.' | b'-' | b'+'))
                {
                    i += 1;
                }
                return Some((start, i));
            }
            i += 1;
        }
        None
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: CASES, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn arbitrary_text_is_an_error_or_a_mesh(text in "\\PC{0,300}") {
        check(&text)?;
    }

    #[test]
    fn obj_shaped_lines_are_an_error_or_a_mesh(
        text in "((v|vn) -?[0-9]{1,2}(\\.[0-9])? -?[0-9](\\.[0-9])? -?[0-9]\n|vt [0-9](\\.[0-9])? [0-9]\n|f( -?[0-9]{1,2}(/(-?[0-9]{1,2})?(/-?[0-9]{1,2})?)?){0,5}\n|(o|g) [a-z]{0,3}\n|s (1|off)\n|l 1 2\n|# x\n){0,16}"
    ) {
        check(&text)?;
    }

    #[test]
    fn edited_small_meshes_are_an_error_or_a_mesh(edits in proptest::collection::vec(edit(), 1..6)) {
        let text = edits.iter().fold(SMALL.to_owned(), |t, e| apply(&t, e));
        check(&text)?;
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: SHIPPED_CASES, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn edited_shipped_meshes_are_an_error_or_a_mesh(edits in proptest::collection::vec(edit(), 1..4)) {
        let text = edits.iter().fold(SHIPPED.to_owned(), |t, e| apply(&t, e));
        check(&text)?;
    }
}

#[test]
fn the_seeds_read_as_drawable_meshes() {
    assert_eq!(SHIPPED, DEFAULT_TUMBLER_OBJ);
    let shipped = from_obj(SHIPPED, ORIGIN).expect("the shipped mesh reads");
    drawable(&shipped).expect("drawable");
    let small = from_obj(SMALL, ORIGIN).expect("the small mesh reads");
    drawable(&small).expect("drawable");
    // A square in two triangles and a triangle; corners one per (v, vt, vn).
    assert_eq!((small.vertices.len(), small.indices.len()), (7, 9));
}

#[test]
fn a_number_edit_lands_on_a_number() {
    let text = "# 3 sides\nv 1.5 -2e3 0\nvt2 0.5 1\nf 1/2/3 4//-5\n";
    let spans: Vec<&str> = number_spans(text).map(|(a, b)| &text[a..b]).collect();
    assert_eq!(
        spans,
        [
            "3", "1.5", "-2e3", "0", "0.5", "1", "1", "2", "3", "4", "-5"
        ]
    );
}

fn refusal(text: &str) -> String {
    from_obj(text, ORIGIN)
        .expect_err("must be refused")
        .to_string()
}

// Found by the fuzzing: a relative index reaching back past the first
// texture coordinate overflowed inside tobj (a panic in debug builds).
#[test]
fn a_relative_index_before_the_first_is_refused() {
    let corner = "-3/-1/-1 ";
    assert!(SMALL.contains(corner));
    // Five texture coordinates come before the triangle: -5 is the first.
    let first = SMALL.replacen(corner, "-3/-5/-1 ", 1);
    drawable(&from_obj(&first, ORIGIN).expect("-5 names the first")).expect("drawable");
    let message = refusal(&SMALL.replacen(corner, "-3/-99999999/-1 ", 1));
    assert_eq!(
        message,
        "tumbler mesh `fuzz.obj`: not a valid OBJ file: line 23: face corner `-3/-99999999/-1` names no texture coordinate -99999999"
    );
    assert!(
        refusal(&SMALL.replacen(corner, "-3/-6/-1 ", 1)).contains("names no texture coordinate -6")
    );
    // A huge index overflowed the same way for normals.
    let huge = SMALL.replacen(corner, "-3/-1/4611686018427387904 ", 1);
    assert!(refusal(&huge).contains("names no normal 4611686018427387904"));
    assert!(refusal(&SMALL.replacen(corner, "0/-1/-1 ", 1)).contains("names no position 0"));
}

// Found by the fuzzing: an object's name came out in the message with the
// `\r` (or any control character) it held.
#[test]
fn control_characters_in_a_name_are_escaped() {
    let text = SMALL
        .replacen("o square", "o s\rq\u{1b}uare", 1)
        .replacen("vn 0 0 1\n", "", 1);
    let message = refusal(&text);
    assert!(message.contains("object `s\\rq\\u{1b}uare`"), "{message}");
}
