//! The window, used as a person uses it: the real binary under a virtual X
//! display (Xvfb), driven by xdotool, each step checked from the program's
//! own log of state changes (`--log-events`) and from a screenshot.
//!
//! Needs `Xvfb` and `xdotool` (Debian: `apt-get install xvfb xdotool`);
//! without them the test fails and says so.

use serde_json::Value;
use std::io::{BufRead, BufReader};
use std::path::PathBuf;
use std::process::{Command, Stdio};
use std::sync::mpsc::{Receiver, channel};
use std::time::{Duration, Instant};

mod display;
use display::{Guard, start_display, tool};

struct Session {
    display: String,
    window: String,
    lines: Receiver<Value>,
    seen: Vec<Value>,
}

impl Session {
    fn xdotool(&self, args: &[&str]) {
        let status = Command::new(tool("xdotool"))
            .args(args)
            .env("DISPLAY", &self.display)
            .status()
            .expect("xdotool runs");
        assert!(status.success(), "xdotool {args:?} failed");
    }

    /// Waits (software rendering is slow) for a logged event matching `want`.
    fn expect(&mut self, what: &str, want: impl Fn(&Value) -> bool) -> Value {
        let deadline = Instant::now() + Duration::from_secs(60);
        while Instant::now() < deadline {
            if let Ok(v) = self.lines.recv_timeout(Duration::from_millis(200)) {
                self.seen.push(v.clone());
                if want(&v) {
                    return v;
                }
            }
        }
        panic!("never saw {what}; the log so far: {:#?}", self.seen);
    }

    fn settle(&self) {
        std::thread::sleep(Duration::from_millis(600));
    }
}

fn number(v: &Value, key: &str) -> f64 {
    v[key]
        .as_f64()
        .unwrap_or_else(|| panic!("{key} missing in {v}"))
}

/// One window at a time: two would race for a display, and each test's
/// keys must reach its own window.
static ONE_WINDOW: std::sync::Mutex<()> = std::sync::Mutex::new(());

/// Opens the window with `args` (and the event log) on a display of its
/// own, focused, once it said it is ready; and what it said. The window is
/// the only one open while the returned guard lives.
fn open_window(
    args: &[&str],
    shots: &std::path::Path,
) -> (
    Session,
    Guard,
    display::XServer,
    Value,
    std::sync::MutexGuard<'static, ()>,
) {
    let alone = ONE_WINDOW
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    let (display, xvfb) = start_display();
    let runtime = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("xdg-runtime");
    std::fs::create_dir_all(&runtime).expect("runtime folder");
    let mut child = Command::new(env!("CARGO_BIN_EXE_rolypoly"))
        .args(["--log-events", "--window-size", "480x270"])
        .args(args)
        .arg("--screenshot-dir")
        .arg(shots)
        .env("DISPLAY", &display)
        .env_remove("WAYLAND_DISPLAY")
        .env("XDG_RUNTIME_DIR", &runtime)
        .stdout(Stdio::piped())
        .stderr(Stdio::inherit())
        .spawn()
        .expect("rolypoly starts");
    let stdout = child.stdout.take().expect("stdout");
    let app = Guard(child);
    let (send, lines) = channel();
    std::thread::spawn(move || {
        for line in BufReader::new(stdout).lines().map_while(Result::ok) {
            if let Ok(v) = serde_json::from_str::<Value>(&line) {
                let _ = send.send(v);
            }
        }
    });
    let mut s = Session {
        display,
        window: String::new(),
        lines,
        seen: Vec::new(),
    };
    let ready = s.expect("the window to open", |v| v["event"] == "ready");
    let found = Command::new(tool("xdotool"))
        .args(["search", "--sync", "--name", "^rolypoly$"])
        .env("DISPLAY", &s.display)
        .output()
        .expect("xdotool search");
    s.window = String::from_utf8_lossy(&found.stdout)
        .lines()
        .next()
        .expect("the window exists")
        .to_owned();
    let w = s.window.clone();
    s.xdotool(&["windowfocus", "--sync", &w]);
    s.settle();
    (s, app, xvfb, ready, alone)
}

/// Escape releases the mouse, a second Escape quits, cleanly.
fn quit(s: &mut Session, mut app: Guard) {
    s.xdotool(&["key", "Escape"]);
    s.expect("the mouse released", |v| {
        v["event"] == "mouse" && v["captured"] == false
    });
    s.xdotool(&["key", "Escape"]);
    let deadline = Instant::now() + Duration::from_secs(30);
    loop {
        if let Some(status) = app.0.try_wait().expect("wait") {
            assert!(status.success(), "rolypoly exited with {status}");
            break;
        }
        assert!(
            Instant::now() < deadline,
            "rolypoly did not quit on the second Escape"
        );
        std::thread::sleep(Duration::from_millis(100));
    }
}

fn scratch_folder(name: &str) -> PathBuf {
    let folder = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&folder);
    std::fs::create_dir_all(&folder).expect("scratch folder");
    folder
}

#[test]
fn the_gpu_engine_plays_in_the_window_throws_and_restarts() {
    let shots = scratch_folder("window-gpu-shots");
    let (mut s, app, _xvfb, ready, _alone) =
        open_window(&["--engine", "gpu", "--seed", "2"], &shots);
    assert_eq!(
        (ready["engine"].as_str(), ready["balls"].as_u64()),
        (Some("gpu"), Some(30))
    );
    let rate = s.expect("the frame rate", |v| v["event"] == "frame_rate");
    assert!(number(&rate, "fps") > 0.0, "{rate}");
    s.xdotool(&["key", "b"]);
    let thrown = s.expect("a ball thrown", |v| v["event"] == "throw");
    assert_eq!(thrown["balls"].as_u64(), Some(31), "{thrown}");
    s.xdotool(&["key", "i"]);
    let reset = s.expect("the balls anew", |v| v["event"] == "reset");
    assert_eq!(reset["balls"].as_u64(), Some(30), "{reset}");
    quit(&mut s, app);
}

#[test]
fn a_person_flies_shoots_pauses_grabs_resets_throws_steps_records_and_screenshots() {
    let shots = scratch_folder("window-shots");
    let (mut s, app, _xvfb, ready, _alone) = open_window(&["--seed", "3"], &shots);
    let runtime = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("xdg-runtime");
    assert_eq!(
        (ready["width"].as_u64(), ready["height"].as_u64()),
        (Some(480), Some(270))
    );
    let w = s.window.clone();

    // Once a second the frame rate, its frames' 95th percentile time, and
    // the quality level auto chose.
    let rate = s.expect("the frame rate", |v| v["event"] == "frame_rate");
    assert!(number(&rate, "fps") > 0.0, "{rate}");
    assert!(number(&rate, "p95_ms") > 0.0, "{rate}");
    assert!(number(&rate, "at") >= 1.0, "{rate}");
    assert!(
        ["high", "medium", "low"].contains(&rate["quality"].as_str().unwrap_or("")),
        "{rate}"
    );

    // The room sounds, on a device where there is one (CI has none: the
    // window said so once and plays on); M mutes, and M again plays.
    s.xdotool(&["key", "m"]);
    let muted = s.expect("the sound muted", |v| v["event"] == "sound");
    assert_eq!(muted["muted"], true, "{muted}");
    s.xdotool(&["key", "m"]);
    let playing = s.expect("the sound back", |v| {
        v["event"] == "sound" && v["muted"] == false
    });
    assert!(playing["device"].is_boolean(), "{playing}");

    // Mouse look: move right of the centre; the view turns.
    s.xdotool(&["mousemove", "--window", &w, "240", "135"]);
    s.settle();
    s.xdotool(&["mousemove", "--window", &w, "280", "135"]);
    let turned = s.expect("the camera to turn", |v| v["event"] == "camera");
    assert!(number(&turned, "yaw").abs() > 0.01, "{turned}");

    // W: the camera walks forwards.
    let before = turned["position"].clone();
    s.xdotool(&["keydown", "w"]);
    std::thread::sleep(Duration::from_millis(300));
    s.xdotool(&["keyup", "w"]);
    let walked = s.expect("the camera to move", |v| {
        v["event"] == "camera" && v["position"] != before
    });
    assert_ne!(walked["position"], before);

    // 1 shows the contacts, the F3 key opens the profiler, O takes the orbit
    // camera and gives the view back; the camera then stands where it was.
    s.xdotool(&["key", "1"]);
    s.expect("the contacts view", |v| {
        v["event"] == "debug_view" && v["view"] == "contacts" && v["on"] == true
    });
    s.xdotool(&["key", "F3"]);
    s.expect("the profiler", |v| {
        v["event"] == "profiler" && v["open"] == true
    });
    s.xdotool(&["key", "o"]);
    s.expect("the orbit camera", |v| {
        v["event"] == "orbit" && v["on"] == true
    });
    s.xdotool(&["key", "o"]);
    s.expect("the fly camera again", |v| {
        v["event"] == "orbit" && v["on"] == false
    });

    // F: the fireball appears.
    s.xdotool(&["key", "f"]);
    s.expect("the fireball", |v| {
        v["event"] == "fireball" && v["on"] == true
    });

    // Hold Left Shift: time stops while the camera still turns.
    s.xdotool(&["keydown", "Shift_L"]);
    let paused = s.expect("the pause", |v| {
        v["event"] == "pause" && v["paused"] == true
    });
    let frozen_at = number(&paused, "sim_time");
    s.settle();
    s.xdotool(&["mousemove", "--window", &w, "200", "135"]);
    let looked = s.expect("the camera to turn while paused", |v| {
        v["event"] == "camera"
    });
    assert_eq!(
        number(&looked, "sim_time"),
        frozen_at,
        "time moved while paused"
    );
    s.settle();
    s.xdotool(&["keyup", "Shift_L"]);
    let resumed = s.expect("the end of the pause", |v| {
        v["event"] == "pause" && v["paused"] == false
    });
    assert_eq!(
        number(&resumed, "sim_time"),
        frozen_at,
        "time moved while paused"
    );
    s.xdotool(&["key", "f"]);
    s.expect("the fireball gone", |v| {
        v["event"] == "fireball" && v["on"] == false
    });

    // G, then drag a tumbler that is in view.
    s.xdotool(&["key", "g"]);
    let grab = s.expect("grab mode", |v| {
        v["event"] == "grab_mode" && v["on"] == true
    });
    let on_screen: Vec<(f64, f64)> = grab["tumblers_on_screen"]
        .as_array()
        .expect("tumbler positions")
        .iter()
        .map(|p| (p[0].as_f64().unwrap_or(-1.0), p[1].as_f64().unwrap_or(-1.0)))
        .collect();
    let (x, y) = on_screen
        .iter()
        .copied()
        .find(|&(x, y)| (30.0..450.0).contains(&x) && (30.0..240.0).contains(&y))
        .unwrap_or_else(|| panic!("no tumbler in view: {on_screen:?}"));
    let (x, y) = (x.round() as i64, y.round() as i64);
    s.xdotool(&["mousemove", "--window", &w, &x.to_string(), &y.to_string()]);
    s.settle();
    s.xdotool(&["mousedown", "1"]);
    let grabbed = s.expect("a tumbler to be grabbed", |v| v["event"] == "grabbed");
    for k in 1..=6 {
        s.xdotool(&[
            "mousemove",
            "--window",
            &w,
            &(x + 12 * k).to_string(),
            &y.to_string(),
        ]);
        std::thread::sleep(Duration::from_millis(300));
    }
    std::thread::sleep(Duration::from_millis(1500));
    s.xdotool(&["mouseup", "1"]);
    let released = s.expect("the tumbler to be let go", |v| v["event"] == "released");
    let (a, b) = (&grabbed["at"], &released["at"]);
    let dx = b[0].as_f64().unwrap_or(0.0) - a[0].as_f64().unwrap_or(0.0);
    let dz = b[1].as_f64().unwrap_or(0.0) - a[1].as_f64().unwrap_or(0.0);
    assert!(
        (dx * dx + dz * dz).sqrt() > 0.05,
        "the dragged tumbler did not move: {a} -> {b}"
    );
    s.xdotool(&["key", "g"]);
    s.expect("grab mode off", |v| {
        v["event"] == "grab_mode" && v["on"] == false
    });

    // I: the balls start again.
    s.xdotool(&["key", "i"]);
    let reset = s.expect("the balls to re-initialise", |v| v["event"] == "reset");
    let balls = number(&reset, "balls");

    // Tab opens the sandbox panel; B throws a ball, then another.
    s.xdotool(&["key", "Tab"]);
    s.expect("the panel to open", |v| {
        v["event"] == "panel" && v["open"] == true
    });
    for thrown in 1..=2 {
        s.xdotool(&["key", "b"]);
        let throw = s.expect("a ball thrown", |v| v["event"] == "throw");
        assert_eq!(
            number(&throw, "balls"),
            balls + f64::from(thrown),
            "{throw}"
        );
    }

    // P pauses; each `.` runs one step and no more.
    s.xdotool(&["key", "p"]);
    s.expect("the pause", |v| {
        v["event"] == "pause" && v["paused"] == true
    });
    let mut counts = Vec::new();
    for _ in 0..2 {
        s.xdotool(&["key", "period"]);
        let stepped = s.expect("one step", |v| v["event"] == "stepped");
        assert_eq!(number(&stepped, "steps"), 1.0, "{stepped}");
        counts.push(number(&stepped, "step_count"));
        s.settle();
    }
    assert_eq!(counts[1], counts[0] + 1.0, "{counts:?}");
    s.xdotool(&["key", "p"]);
    s.expect("the end of the pause", |v| {
        v["event"] == "pause" && v["paused"] == false
    });
    s.xdotool(&["key", "Tab"]);
    s.expect("the panel to close", |v| {
        v["event"] == "panel" && v["open"] == false
    });

    // R records what is done until R again: a ball, the fireball, a turn
    // of the view; `rolypoly replay` plays it to the same end state.
    s.xdotool(&["key", "r"]);
    s.expect("the recording to start", |v| {
        v["event"] == "recording" && v["on"] == true
    });
    s.xdotool(&["key", "b"]);
    s.expect("a ball thrown", |v| v["event"] == "throw");
    s.settle();
    s.xdotool(&["key", "f"]);
    s.expect("the fireball", |v| {
        v["event"] == "fireball" && v["on"] == true
    });
    s.xdotool(&["mousemove", "--window", &w, "260", "125"]);
    s.settle();
    s.settle();
    s.xdotool(&["key", "r"]);
    let recorded = s.expect("the recording written", |v| v["event"] == "recorded");
    let replay_log = PathBuf::from(recorded["path"].as_str().expect("path"));
    assert!(replay_log.starts_with(&shots), "{}", replay_log.display());
    assert!(number(&recorded, "to_tick") > number(&recorded, "from_tick"));
    let clip = shots.join("replay-frames");
    let replayed = Command::new(env!("CARGO_BIN_EXE_rolypoly"))
        .arg("replay")
        .arg(&replay_log)
        .args(["--size", "96x54", "--fps", "10", "--out"])
        .arg(&clip)
        .env("XDG_RUNTIME_DIR", &runtime)
        .output()
        .expect("rolypoly replay runs");
    let said = String::from_utf8_lossy(&replayed.stdout);
    assert!(
        replayed.status.success(),
        "{said}{}",
        String::from_utf8_lossy(&replayed.stderr)
    );
    let digest = recorded["digest"].as_str().expect("digest");
    assert!(
        said.contains(&format!(
            "end state identical to the recording's (digest {digest})"
        )),
        "{said}"
    );
    assert!(clip.join("frame-00000.png").is_file());
    // In a window of its own, the replay ends in the recorded state too.
    let in_window = Command::new(env!("CARGO_BIN_EXE_rolypoly"))
        .args(["--log-events", "--window-size", "160x90", "replay"])
        .arg(&replay_log)
        .env("DISPLAY", &s.display)
        .env_remove("WAYLAND_DISPLAY")
        .env("XDG_RUNTIME_DIR", &runtime)
        .stdout(Stdio::piped())
        .stderr(Stdio::inherit())
        .spawn()
        .expect("rolypoly replay opens a window");
    let mut replay_window = Guard(in_window);
    let replay_stdout = replay_window.0.stdout.take().expect("stdout");
    let (send, ends) = channel();
    std::thread::spawn(move || {
        let end = BufReader::new(replay_stdout)
            .lines()
            .map_while(Result::ok)
            .filter_map(|line| serde_json::from_str::<Value>(&line).ok())
            .find(|v| v["event"] == "replay_end");
        let _ = send.send(end);
    });
    let ended = ends
        .recv_timeout(Duration::from_secs(90))
        .ok()
        .flatten()
        .expect("the replay in the window reaches its end");
    assert_eq!(ended["identical"], true, "{ended}");
    assert_eq!(ended["digest"].as_str(), Some(digest), "{ended}");
    assert_eq!(number(&ended, "tick"), number(&recorded, "to_tick"));
    drop(replay_window);
    s.xdotool(&["windowfocus", "--sync", &w]);
    s.xdotool(&["key", "f"]);
    s.expect("the fireball gone", |v| {
        v["event"] == "fireball" && v["on"] == false
    });

    // The F12 key: a PNG of the window's size appears where it says.
    s.xdotool(&["key", "F12"]);
    let shot = s.expect("a screenshot", |v| v["event"] == "screenshot");
    let path = PathBuf::from(shot["path"].as_str().expect("path"));
    assert!(path.starts_with(&shots), "{}", path.display());
    let image = image::open(&path)
        .expect("the screenshot is a PNG")
        .to_rgba8();
    assert_eq!(image.dimensions(), (480, 270));
    let lum: Vec<u32> = image
        .pixels()
        .map(|p| p.0[0] as u32 + p.0[1] as u32 + p.0[2] as u32)
        .collect();
    assert!(
        lum.iter().max() > lum.iter().min().map(|m| m + 200).as_ref(),
        "the screenshot is blank"
    );

    quit(&mut s, app);
}

/// The screenshot the F12 key takes, once the window says where it wrote it.
fn shot(s: &mut Session) -> PathBuf {
    s.xdotool(&["key", "F12"]);
    let taken = s.expect("a screenshot", |v| v["event"] == "screenshot");
    PathBuf::from(taken["path"].as_str().expect("path"))
}

/// The share of a screenshot's pixels that are clearly green.
fn green_share(path: &std::path::Path) -> f64 {
    let image = image::open(path)
        .expect("the screenshot is a PNG")
        .to_rgba8();
    let green = image
        .pixels()
        .filter(|p| {
            let [r, g, b, _] = p.0.map(i32::from);
            g > 100 && g > 2 * r && g > 2 * b
        })
        .count();
    green as f64 / image.pixels().len() as f64
}

#[test]
fn a_student_steps_through_the_views_and_edits_a_shader_while_the_window_runs() {
    let shots = scratch_folder("window-shader-shots");
    let dir = scratch_folder("window-shaders");
    let exported = Command::new(env!("CARGO_BIN_EXE_rolypoly"))
        .args(["shaders", "--export"])
        .arg(&dir)
        .output()
        .expect("rolypoly runs");
    assert!(exported.status.success(), "{exported:?}");
    let (mut s, app, _xvfb, _ready, _alone) = open_window(
        &["--seed", "4", "--shaders", dir.to_str().expect("a path")],
        &shots,
    );

    // V shows the next view, Shift+V the previous; each change is named.
    s.xdotool(&["key", "v"]);
    let albedo = s.expect("the albedo view", |v| v["event"] == "frame_view");
    assert_eq!(albedo["view"], "albedo", "{albedo}");
    s.xdotool(&["key", "v"]);
    let normals = s.expect("the normals view", |v| v["event"] == "frame_view");
    assert_eq!(normals["view"], "normals", "{normals}");
    s.xdotool(&["key", "shift+v", "shift+v"]);
    s.expect("the albedo view again", |v| {
        v["event"] == "frame_view" && v["view"] == "albedo"
    });
    let last = s.expect("the final frame again", |v| v["event"] == "frame_view");
    assert_eq!(last["view"], "final", "{last}");
    let before = green_share(&shot(&mut s));
    assert!(before < 0.05, "the room is not green: {before}");

    // The lit surfaces' colour made a constant green, saved: the next
    // frames draw with it.
    let scene = dir.join("scene.wgsl");
    let source = std::fs::read_to_string(&scene).expect("the exported scene shader");
    let lit = "return terms.diffuse + terms.specular + indirect;";
    assert_eq!(
        source.matches(lit).count(),
        1,
        "Blinn-Phong's sum is where it was"
    );
    let saved = Instant::now();
    std::fs::write(
        &scene,
        source.replace(lit, "return vec3<f32>(0.0, 4.0, 0.0);"),
    )
    .expect("the edit saved");
    let reloaded = s.expect("the edit drawn", |v| v["event"] == "shader_reloaded");
    let fps = s
        .seen
        .iter()
        .rev()
        .find(|v| v["event"] == "frame_rate")
        .map_or(f64::NAN, |v| number(v, "fps"));
    println!(
        "save to the first frame drawn with it: {:.0} ms as the window measures it, {:.0} ms as this test does (seen {:.0} ms after the save, pipelines built in {:.0} ms; the window at {fps:.1} frames a second)",
        number(&reloaded, "save_to_picture_ms"),
        1e3 * saved.elapsed().as_secs_f64(),
        number(&reloaded, "seen_ms"),
        number(&reloaded, "build_ms"),
    );
    let green = green_share(&shot(&mut s));
    assert!(
        green > 0.5,
        "the lit surfaces are not the edit's green: {green}"
    );

    // A syntax error: named by file and line, and the window draws on
    // with the last good shaders.
    let mut lines: Vec<&str> = source.lines().collect();
    lines.insert(9, "fn oops( {");
    std::fs::write(&scene, lines.join("\n")).expect("the mistake saved");
    let error = s.expect("the shader error", |v| v["event"] == "shader_error");
    assert!(
        error["file"]
            .as_str()
            .is_some_and(|f| f.ends_with("scene.wgsl")),
        "{error}"
    );
    assert_eq!(error["line"].as_u64(), Some(10), "{error}");
    assert!(
        error["error"]
            .as_str()
            .is_some_and(|e| e.contains("scene.wgsl:10:")),
        "{error}"
    );
    s.expect("frames drawn after the error", |v| {
        v["event"] == "frame_rate" && v["fps"].as_f64().is_some_and(|f| f > 0.0)
    });
    let still = green_share(&shot(&mut s));
    assert!(
        still > 0.5,
        "the last good shaders stopped drawing: {still}"
    );

    // Fixed: the error clears and the shipped picture is back.
    std::fs::write(&scene, &source).expect("the fix saved");
    s.expect("the fix drawn", |v| v["event"] == "shader_reloaded");
    let after = green_share(&shot(&mut s));
    assert!(after < 0.05, "the fix did not take: {after}");
    quit(&mut s, app);
}
