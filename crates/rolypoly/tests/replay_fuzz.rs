//! Recordings fuzzed: arbitrary text and mutated real recordings never make
//! the reader panic. Each gives a clean one-line error naming the file, or
//! a log that is well formed, writes back to the same log, and (when short)
//! replays to its end tick or is refused, without a panic.

use std::sync::LazyLock;

use glam::DVec3;
#[path = "../../../tests/text_edits.rs"]
mod text_edits;

use proptest::prelude::*;
use rolypoly::sandbox::{Input, REPLAY_FORMAT, ReplayLog, SHIPPED_SCENES, Sandbox};
use rolypoly::scene::{Scene, parse_scene};
use text_edits::{TextEdit, joined, splice};

/// Cases per property.
const CASES: u32 = 600;

/// The file name the reader is given.
const ORIGIN: &str = "fuzz.replay";

/// Longest log replayed, in ticks: longer ones prove nothing more.
const REPLAY_TICKS: u64 = 400;

/// Most balls a replayed scene may hold, for the same reason.
const REPLAY_BALLS: usize = 2000;

fn shipped(name: &str) -> Scene {
    let s = SHIPPED_SCENES
        .iter()
        .find(|s| s.name == name)
        .expect("a shipped scene");
    parse_scene(s.text, s.name).expect("a shipped scene parses")
}

/// A session with every kind of input a recording holds.
fn session() -> ReplayLog {
    let mut s = Sandbox::new(shipped("default.toml"), "default.toml", 3).expect("builds");
    let ticks = |s: &mut Sandbox, n: usize| (0..n).for_each(|_| s.tick());
    ticks(&mut s, 10);
    s.start_recording();
    s.throw(DVec3::new(0.0, 2.0, 3.0), DVec3::new(0.1, -0.2, -1.0))
        .expect("a throw");
    ticks(&mut s, 8);
    s.apply(Input::Fireball {
        from: [0.0, 1.5, 3.0],
        direction: [0.1, -0.1, -1.0],
    })
    .expect("a fireball");
    ticks(&mut s, 8);
    let t = s.world().tumblers()[0].center_of_mass();
    s.apply(Input::Grab {
        tumbler: 0,
        point: t.to_array(),
    })
    .expect("a grab");
    for k in 0..5 {
        let to = t + DVec3::new(0.03 * f64::from(k), 0.0, 0.01 * f64::from(k));
        s.apply(Input::Drag { to: to.to_array() }).expect("a drag");
        ticks(&mut s, 2);
    }
    s.apply(Input::Release).expect("a release");
    s.apply(Input::GrabBall { ball: 0 }).expect("a ball held");
    s.apply(Input::Drag {
        to: [0.0, 1.5, 0.0],
    })
    .expect("a drag");
    ticks(&mut s, 3);
    s.apply(Input::Release).expect("a release");
    s.apply(Input::Camera {
        position: [0.1, 1.0, 3.0],
        yaw: 0.2,
        pitch: -0.1,
    })
    .expect("a camera");
    let mut scene = s.scene().clone();
    scene.world.gravity = 4.0;
    s.set_scene(scene).expect("settings");
    ticks(&mut s, 6);
    s.apply(Input::FireballOff).expect("fireball off");
    s.restart().expect("a restart");
    ticks(&mut s, 10);
    s.stop_recording().expect("a recording")
}

/// A short session on another scene, recorded from its start.
fn cradle() -> ReplayLog {
    let mut s =
        Sandbox::new(shipped("newtons-cradle.toml"), "newtons-cradle.toml", 9).expect("builds");
    s.start_recording();
    s.throw(DVec3::new(0.5, 1.0, 1.0), DVec3::NEG_Z)
        .expect("a throw");
    (0..30).for_each(|_| s.tick());
    s.stop_recording().expect("a recording")
}

/// A recording with no input.
fn quiet() -> ReplayLog {
    let mut s = Sandbox::new(shipped("default.toml"), "default.toml", 1).expect("builds");
    (0..4).for_each(|_| s.tick());
    s.start_recording();
    (0..6).for_each(|_| s.tick());
    s.stop_recording().expect("a recording")
}

/// The real recordings mutated, as their files' text.
static RECORDINGS: LazyLock<Vec<String>> = LazyLock::new(|| {
    [session(), cradle(), quiet()]
        .map(|log| log.to_text())
        .into()
});

/// Whether replaying `log` is cheap enough for a fuzz case.
fn cheap(log: &ReplayLog) -> bool {
    let small =
        |text: &str| parse_scene(text, "x").map_or(true, |s| s.world.balls.total() <= REPLAY_BALLS);
    log.to_tick <= REPLAY_TICKS
        && small(&log.scene)
        && log.inputs.iter().all(|t| match &t.input {
            Input::Settings { scene } => small(scene),
            _ => true,
        })
}

/// What every outcome of reading must satisfy.
fn check(text: &str) -> Result<(), TestCaseError> {
    let log = match ReplayLog::parse(text, ORIGIN) {
        Err(e) => {
            // As `main` prints it.
            let message = format!("{e:#}");
            prop_assert!(message.starts_with(ORIGIN), "{message}");
            prop_assert!(!message.contains(['\n', '\r']), "one line: {message:?}");
            return Ok(());
        }
        Ok(log) => log,
    };
    prop_assert_eq!(log.format, REPLAY_FORMAT);
    prop_assert!(log.from_tick <= log.to_tick);
    prop_assert!(
        log.inputs.windows(2).all(|w| w[0].tick <= w[1].tick)
            && log.inputs.iter().all(|t| t.tick <= log.to_tick),
        "ticks out of order or past the end"
    );
    // What was read is what would be written again (as R after a replay does).
    let again = ReplayLog::parse(&log.to_text(), "again.replay")
        .map_err(|e| TestCaseError::fail(format!("{e:#}\n{}", log.to_text())))?;
    prop_assert_eq!(&again, &log);
    if cheap(&log) {
        match Sandbox::for_replay(&log) {
            // A refusal is a clean message, as `rolypoly replay` prints it.
            Err(e) => prop_assert!(!e.to_string().is_empty()),
            Ok(mut s) => {
                s.replay_until(log.from_tick);
                prop_assert_eq!(s.ticks(), log.from_tick);
                s.replay_until(u64::MAX);
                prop_assert!(!s.replaying());
                prop_assert_eq!(s.ticks(), log.to_tick);
                // As the end-state check reads the state.
                let _ = s.digest();
            }
        }
    }
    Ok(())
}

/// One edit of a recording's text.
#[derive(Clone, Debug)]
enum Edit {
    /// An edit any text may take.
    Text(TextEdit),
    /// The `k`-th input's kind becomes this, its fields left as they were.
    Kind(usize, &'static str),
    /// An input line put before the `k`-th line, at that line's tick (so
    /// that the order holds and the log may be read and replayed).
    Line(usize, &'static str),
}

/// Inputs as a recording's lines hold them, less the tick: the odd ones a
/// player cannot make, and ones that rebuild the world.
const LINES: [&str; 20] = [
    r#""kind":"grab","tumbler":18446744073709551615,"point":[0,1,0]}"#,
    r#""kind":"grab","tumbler":0,"point":[1e300,-1e300,0]}"#,
    r#""kind":"grab_ball","ball":18446744073709551615}"#,
    r#""kind":"grab_ball","ball":0}"#,
    r#""kind":"drag","to":[1e300,-1e300,1e300]}"#,
    r#""kind":"drag","to":[-1e-300,5e-324,0]}"#,
    r#""kind":"throw","from":[1e300,0,-1e300],"direction":[0,0,0],"speed":40}"#,
    r#""kind":"throw","from":[0,1,0],"direction":[1e300,1e300,1e300],"speed":0.5}"#,
    r#""kind":"throw","from":[0,1,0],"direction":[0,0,-1],"speed":1e300}"#,
    r#""kind":"fireball","from":[0,1e300,0],"direction":[0,0,0]}"#,
    r#""kind":"fireball","from":[0,1,0],"direction":[1e308,-1e308,1e308]}"#,
    r#""kind":"fireball_off"}"#,
    r#""kind":"release"}"#,
    r#""kind":"restart"}"#,
    r#""kind":"load","name":"three.toml","scene":"[balls]\ncount = 3\n"}"#,
    r#""kind":"load","name":"bad.toml","scene":"[balls]\ncount = -3\n"}"#,
    r#""kind":"settings","scene":"gravity = 30\n[balls]\ncount = 60\n"}"#,
    r#""kind":"settings","scene":"gravity = -1e9\n"}"#,
    r#""kind":"camera","position":[3e38,-3e38,0],"yaw":3e38,"pitch":-3e38}"#,
    r#""kind":"camera","position":[0,0,0],"yaw":0,"pitch":0,"extra":1}"#,
];

const KINDS: [&str; 12] = [
    "fireball",
    "fireball_off",
    "throw",
    "grab",
    "grab_ball",
    "drag",
    "release",
    "restart",
    "settings",
    "load",
    "camera",
    "jump",
];

/// A number as JSON writes one, from the plain to the extreme.
fn json_number() -> impl Strategy<Value = String> {
    prop_oneof![
        (-10.0..10.0f64).prop_map(|x| format!("{x:.3}")),
        (0..500u64).prop_map(|x| x.to_string()),
        any::<u64>().prop_map(|x| x.to_string()),
        any::<i64>().prop_map(|x| x.to_string()),
        any::<f64>()
            .prop_filter("finite", |x| x.is_finite())
            .prop_map(|x| format!("{x:e}")),
        Just("1e300".to_owned()),
        Just("-1e39".to_owned()),
        Just("0".to_owned()),
        Just("-0.0".to_owned()),
    ]
}

fn line() -> impl Strategy<Value = Edit> {
    (any::<usize>(), proptest::sample::select(&LINES[..])).prop_map(|(k, l)| Edit::Line(k, l))
}

/// Edits that keep each line JSON: numbers changed, lines moved about.
fn json_edit() -> impl Strategy<Value = Edit> {
    prop_oneof![
        1 => any::<usize>().prop_map(|k| Edit::Text(TextEdit::DeleteLine(k))),
        1 => any::<usize>().prop_map(|k| Edit::Text(TextEdit::DuplicateLine(k))),
        1 => (any::<usize>(), any::<usize>()).prop_map(|(a, b)| Edit::Text(TextEdit::SwapLines(a, b))),
        4 => (any::<usize>(), json_number()).prop_map(|(k, n)| Edit::Text(TextEdit::Number(k, n))),
        2 => line(),
    ]
}

fn edit() -> impl Strategy<Value = Edit> {
    let number = prop_oneof![
        3 => json_number(),
        1 => any::<f64>().prop_map(|x| x.to_string()),
        1 => Just("1e400".to_owned()),
        1 => Just("18446744073709551616".to_owned()),
        1 => Just("-1".to_owned()),
        1 => Just("NaN".to_owned()),
        1 => Just("null".to_owned()),
        1 => Just("[]".to_owned()),
        1 => Just("true".to_owned()),
        1 => Just("\"x\"".to_owned()),
    ];
    let token = prop_oneof![
        Just("\n{\"tick\":0,\"kind\":\"restart\"}\n".to_owned()),
        Just("\n{\"tick\":3,\"kind\":\"grab\",\"tumbler\":18446744073709551615,\"point\":[1e300,0,0]}\n".to_owned()),
        Just("\n{\"tick\":4,\"kind\":\"drag\",\"to\":[1e300,-1e300,1e300]}\n".to_owned()),
        Just("\n{\"tick\":5,\"kind\":\"throw\",\"from\":[1e300,0,0],\"direction\":[0,0,0],\"speed\":40}\n".to_owned()),
        Just("\n{\"tick\":5,\"kind\":\"fireball\",\"from\":[0,1e300,0],\"direction\":[0,0,0]}\n".to_owned()),
        Just("\n{\"tick\":6,\"kind\":\"load\",\"name\":\"l.toml\",\"scene\":\"[balls]\\ncount = 3\\n\"}\n".to_owned()),
        Just("\n{\"tick\":7,\"kind\":\"settings\",\"scene\":\"gravity = -1e9\\n\"}\n".to_owned()),
        Just("\n{\"tick\":8,\"kind\":\"camera\",\"position\":[1e39,0,0],\"yaw\":1e39,\"pitch\":0}\n".to_owned()),
        Just("\"kind\":\"a\\nb\",".to_owned()),
        Just("\"x\\u001b\\n\":1,".to_owned()),
        Just("\\n".to_owned()),
        Just("\"".to_owned()),
        Just(",".to_owned()),
        Just("{".to_owned()),
        Just("}".to_owned()),
        Just("\r\n".to_owned()),
        "[a-z_\"{}\\[\\]:,0-9 .\\\\\n-]{1,12}",
    ];
    prop_oneof![
        1 => any::<usize>().prop_map(|k| Edit::Text(TextEdit::DeleteLine(k))),
        1 => any::<usize>().prop_map(|k| Edit::Text(TextEdit::DuplicateLine(k))),
        1 => (any::<usize>(), any::<usize>()).prop_map(|(a, b)| Edit::Text(TextEdit::SwapLines(a, b))),
        3 => (any::<usize>(), number).prop_map(|(k, n)| Edit::Text(TextEdit::Number(k, n))),
        1 => (any::<usize>(), proptest::sample::select(&KINDS[..])).prop_map(|(k, kind)| Edit::Kind(k, kind)),
        1 => line(),
        1 => (any::<usize>(), any::<char>()).prop_map(|(at, c)| Edit::Text(TextEdit::Char(at, c))),
        1 => any::<usize>().prop_map(|k| Edit::Text(TextEdit::Truncate(k))),
        2 => (any::<usize>(), token).prop_map(|(at, t)| Edit::Text(TextEdit::Insert(at, t))),
    ]
}

/// `text` with `edit` made.
fn apply(text: &str, edit: &Edit) -> String {
    let mut lines: Vec<&str> = text.lines().collect();
    let n = lines.len().max(1);
    match edit {
        Edit::Text(edit) => text_edits::apply(text, edit, &number_spans(text)),
        Edit::Line(k, body) if !lines.is_empty() => {
            // After the first line; at the end, at the last tick.
            let k = 1 + k % n;
            let (line, key) = match lines.get(k) {
                Some(line) => (line, "\"tick\":"),
                None => (&lines[0], "\"to_tick\":"),
            };
            let tick: String = line
                .find(key)
                .map(|at| {
                    line[at + key.len()..]
                        .chars()
                        .take_while(char::is_ascii_digit)
                        .collect()
                })
                .unwrap_or_default();
            let tick = if tick.is_empty() {
                "0".to_owned()
            } else {
                tick
            };
            let new = format!("{{\"tick\":{tick},{body}");
            lines.insert(k, &new);
            joined(&lines)
        }
        Edit::Kind(k, kind) => {
            let spans: Vec<(usize, usize)> = text
                .match_indices("\"kind\":\"")
                .filter_map(|(at, m)| {
                    let start = at + m.len();
                    text[start..].find('"').map(|len| (start, start + len))
                })
                .collect();
            match spans.get(k % spans.len().max(1)) {
                Some(&span) => splice(text, span, kind),
                None => text.to_owned(),
            }
        }
        _ => text.to_owned(),
    }
}

/// Byte spans of the numbers written in `text`, in JSON and in the scene
/// files inside its strings (where a line starts after a `\n` escape).
fn number_spans(text: &str) -> Vec<(usize, usize)> {
    let bytes = text.as_bytes();
    let mut spans = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        let starts = bytes[i].is_ascii_digit()
            || (bytes[i] == b'-' && bytes.get(i + 1).is_some_and(u8::is_ascii_digit));
        let escape = i >= 2 && &bytes[i - 2..i] == b"\\n";
        let inside_word = i > 0
            && !escape
            && (bytes[i - 1].is_ascii_alphanumeric() || matches!(bytes[i - 1], b'_' | b'.'));
        if starts && !inside_word {
            let mut j = i + 1;
            while j < bytes.len()
                && (bytes[j].is_ascii_alphanumeric()
                    || matches!(bytes[j], b'.' | b'_' | b'-' | b'+'))
            {
                j += 1;
            }
            spans.push((i, j));
            i = j;
        } else {
            i += 1;
        }
    }
    spans
}

proptest! {
    #![proptest_config(ProptestConfig { cases: CASES, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn arbitrary_text_is_an_error_or_a_valid_log(text in "\\PC{0,200}") {
        check(&text)?;
    }

    #[test]
    fn json_shaped_lines_are_an_error_or_a_valid_log(
        input in "(\\{\"tick\":[0-9]{1,3},\"kind\":\"(restart|release|fireball_off|drag|grab|grab_ball|throw|camera)\"(,\"(to|from|point|direction|position)\":\\[(-?[0-9]{1,3}(\\.[0-9])?,?){0,4}\\]|,\"(speed|yaw|pitch|tumbler|ball)\":-?[0-9]{1,4}(e[0-9]{1,3})?){0,3}\\}\n){0,6}",
        recording in 0..3usize,
    ) {
        // A real first line, then lines shaped like inputs.
        let first = RECORDINGS[recording].lines().next().unwrap_or_default();
        check(&format!("{first}\n{input}"))?;
    }

    #[test]
    fn renumbered_recordings_are_an_error_or_a_valid_log(
        recording in 0..3usize,
        edits in proptest::collection::vec(json_edit(), 1..4),
    ) {
        let text = edits.iter().fold(RECORDINGS[recording].clone(), |t, e| apply(&t, e));
        check(&text)?;
    }

    #[test]
    fn edited_recordings_are_an_error_or_a_valid_log(
        recording in 0..3usize,
        edits in proptest::collection::vec(edit(), 1..6),
    ) {
        let text = edits.iter().fold(RECORDINGS[recording].clone(), |t, e| apply(&t, e));
        check(&text)?;
    }
}

#[test]
fn the_recordings_read_back_and_replay_to_their_digest() {
    for text in RECORDINGS.iter() {
        let log = ReplayLog::parse(text, ORIGIN).expect("a real recording reads");
        assert_eq!(log.to_text(), *text);
        assert!(cheap(&log));
        let mut s = Sandbox::for_replay(&log).expect("replays");
        s.replay_until(u64::MAX);
        assert_eq!(s.digest(), log.end_digest);
    }
    // The session holds every kind the edits swap between, but for load.

    let kinds: usize = KINDS
        .iter()
        .filter(|k| RECORDINGS[0].contains(&format!("\"kind\":\"{k}\"")))
        .count();
    assert_eq!(kinds, KINDS.len() - 2);
}

#[test]
fn a_number_edit_lands_on_a_number() {
    let text = r##"{"tick":12,"to":[1.5,-2e3,0],"scene":"# 7 balls\ncount = 30\n[a]\n4 = 5"}"##;
    let spans: Vec<&str> = number_spans(text)
        .iter()
        .map(|&(a, b)| &text[a..b])
        .collect();
    assert_eq!(spans, ["12", "1.5", "-2e3", "0", "7", "30", "4", "5"]);
}

/// The first line of the quiet recording, then `input`.
fn with_input(input: &str) -> String {
    let first = RECORDINGS[2].lines().next().unwrap_or_default();
    format!("{first}\n{input}\n")
}

fn refusal(text: &str) -> String {
    format!(
        "{:#}",
        ReplayLog::parse(text, ORIGIN).expect_err("must be refused")
    )
}

// Found by the fuzzing: an f32 past 3.4e38 read as infinite; the log was
// taken and then written with `null`, which does not read back.
#[test]
fn a_camera_number_beyond_f32_is_refused() {
    let text =
        with_input(r#"{"tick":4,"kind":"camera","position":[-1e39,1,3],"yaw":0.2,"pitch":0}"#);
    let message = refusal(&text);
    assert_eq!(message, "fuzz.replay:2: a number out of range");
    // The largest f32 is still a camera.
    let text = text.replace("-1e39", "-3.4e38");
    assert!(ReplayLog::parse(&text, ORIGIN).is_ok());
}

// Found by the fuzzing: a name in the file came out in the message as it
// was, a newline or a terminal escape in it included.
#[test]
fn control_characters_in_a_message_are_escaped() {
    let first = RECORDINGS[2].lines().next().unwrap_or_default();
    let text = first.replacen('{', "{\"x\\u001b\\n\":1,", 1);
    let message = refusal(&text);
    assert!(
        message.starts_with("fuzz.replay:1: not a rolypoly recording: unknown field `x\\u{1b}\\n`"),
        "{message}"
    );
    let message = refusal(&with_input(r#"{"tick":4,"kind":"a\nb"}"#));
    assert!(
        message.starts_with("fuzz.replay:2: unknown variant `a\\nb`"),
        "{message}"
    );
}

// Found by the fuzzing: a load line (which no recording holds, as a load
// starts a new one) reset the replay to tick 0 short of where it said it
// started.
#[test]
fn a_scene_load_is_refused() {
    let message = refusal(&with_input(
        r#"{"tick":4,"kind":"load","name":"three.toml","scene":"[balls]\ncount = 3\n"}"#,
    ));
    assert!(
        message.starts_with("fuzz.replay:2: a recording holds no scene load"),
        "{message}"
    );
}
