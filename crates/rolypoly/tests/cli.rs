//! Runs the built `rolypoly` binary the way a user does.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn rolypoly(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rolypoly"))
        .args(args)
        .output()
        .expect("the rolypoly binary runs")
}

/// Runs the binary as on a machine with no display to open a window on.
fn rolypoly_without_display(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rolypoly"))
        .args(args)
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .expect("the rolypoly binary runs")
}

fn stdout(output: &Output) -> String {
    String::from_utf8(output.stdout.clone()).expect("stdout is UTF-8")
}

fn stderr(output: &Output) -> String {
    String::from_utf8(output.stderr.clone()).expect("stderr is UTF-8")
}

/// Writes a scene file into this test target's scratch folder.
fn scene_file(name: &str, text: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("cli-scenes");
    std::fs::create_dir_all(&dir).expect("scratch folder");
    let path = dir.join(name);
    std::fs::write(&path, text).expect("scene file written");
    path
}

/// Asserts a failed run: non-zero exit, one `error:` message, no panic.
fn assert_clean_failure(output: &Output) -> String {
    let err = stderr(output);
    assert!(!output.status.success(), "expected failure, stderr: {err}");
    assert!(err.starts_with("error: "), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    assert!(output.stdout.is_empty(), "nothing on stdout on failure");
    err
}

/// Simulates one step of a scene file with `text` and returns the failure.
fn failure_for_scene(name: &str, text: &str) -> String {
    let path = scene_file(name, text);
    let path = path.to_str().expect("UTF-8 path");
    assert_clean_failure(&rolypoly(&["simulate", "--steps", "1", "--scene", path]))
}

fn json_lines(text: &str) -> Vec<serde_json::Value> {
    text.lines()
        .map(|line| serde_json::from_str(line).expect("each line is JSON"))
        .collect()
}

#[test]
fn trace_to_stdout_is_a_scene_line_then_state_lines() {
    let output = rolypoly(&["simulate", "--steps", "50", "--trace", "-"]);
    assert!(output.status.success(), "{}", stderr(&output));
    let lines = json_lines(&stdout(&output));
    assert_eq!(lines.len(), 1 + 51, "scene line + steps 0..=50");
    assert_eq!(lines[0]["kind"], "scene");
    assert_eq!(lines[0]["seed"], 1);
    for (i, line) in lines[1..].iter().enumerate() {
        assert_eq!(line["kind"], "state");
        assert_eq!(line["step"], i as u64);
        assert_eq!(line["balls"].as_array().map(Vec::len), Some(30));
        assert_eq!(line["tumblers"].as_array().map(Vec::len), Some(5));
        assert!(line["energy"]["total"].is_number());
        assert!(line["events"].is_array());
    }
}

#[test]
fn every_k_steps_and_the_last_step() {
    let output = rolypoly(&["simulate", "--steps", "50", "--every", "7", "--trace", "-"]);
    assert!(output.status.success(), "{}", stderr(&output));
    let steps: Vec<u64> = json_lines(&stdout(&output))[1..]
        .iter()
        .map(|line| line["step"].as_u64().expect("step"))
        .collect();
    assert_eq!(steps, [0, 7, 14, 21, 28, 35, 42, 49, 50]);
}

#[test]
fn same_seed_same_bytes_other_seed_differs() {
    let run = |seed: &str| {
        let output = rolypoly(&[
            "simulate",
            "--steps",
            "60",
            "--seed",
            seed,
            "--fireball",
            "--trace",
            "-",
        ]);
        assert!(output.status.success(), "{}", stderr(&output));
        output.stdout
    };
    let first = run("7");
    assert_eq!(first, run("7"));
    assert_ne!(first, run("8"));
}

#[test]
fn summary_without_trace() {
    let output = rolypoly(&["simulate", "--seconds", "0.5", "--balls", "4"]);
    assert!(output.status.success(), "{}", stderr(&output));
    let text = stdout(&output);
    assert!(text.contains("Simulated 60 steps"), "{text}");
    assert!(text.contains("4 balls"), "{text}");
    assert!(text.contains("energy"), "{text}");
}

#[test]
fn no_subcommand_without_a_display_is_a_clear_error() {
    let output = rolypoly_without_display(&["--balls", "5"]);
    let err = assert_clean_failure(&output);
    assert!(err.contains("display"), "{err}");
}

#[test]
fn a_screenshot_folder_that_does_not_exist_is_refused_before_the_window_opens() {
    let output = rolypoly_without_display(&["--screenshot-dir", "/no/such/folder"]);
    let err = assert_clean_failure(&output);
    assert!(
        err.contains("--screenshot-dir") && err.contains("/no/such/folder"),
        "{err}"
    );
}

#[test]
fn trace_to_a_file_and_summary_to_stdout() {
    let path = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("cli-trace.jsonl");
    let path_text = path.to_str().expect("UTF-8 path");
    let output = rolypoly(&[
        "simulate", "--steps", "10", "--every", "5", "--trace", path_text,
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    assert!(stdout(&output).contains("Simulated 10 steps"));
    let trace = std::fs::read_to_string(&path).expect("trace written");
    assert_eq!(json_lines(&trace).len(), 1 + 3);
}

/// The count in a summary's "N collision events".
fn events_counted(summary: &str) -> u64 {
    let words: Vec<&str> = summary.split_whitespace().collect();
    let at = words
        .windows(2)
        .position(|w| w == ["collision", "events"])
        .unwrap_or_else(|| panic!("no event count in {summary}"));
    words[at - 1].parse().expect("a count")
}

#[test]
fn a_trace_written_every_few_steps_counts_each_event_once() {
    for (seed, every) in [("1", "7"), ("3", "25")] {
        let plain = rolypoly(&["simulate", "--seconds", "3", "--seed", seed]);
        assert!(plain.status.success(), "{}", stderr(&plain));
        let counted = events_counted(&stdout(&plain));
        assert!(counted > 50, "seed {seed}: {counted}");
        let path = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("every-{seed}.jsonl"));
        let traced = rolypoly(&[
            "simulate",
            "--seconds",
            "3",
            "--seed",
            seed,
            "--every",
            every,
            "--trace",
            path.to_str().unwrap(),
        ]);
        assert!(traced.status.success(), "{}", stderr(&traced));
        assert_eq!(events_counted(&stdout(&traced)), counted, "seed {seed}");
        let trace = std::fs::read_to_string(&path).unwrap();
        let in_trace: usize = json_lines(&trace)
            .iter()
            .filter_map(|line| line["events"].as_array().map(Vec::len))
            .sum();
        assert_eq!(in_trace as u64, counted, "seed {seed}: the trace's events");
    }
}

#[test]
fn unwritable_trace_names_the_file() {
    let output = rolypoly(&[
        "simulate",
        "--steps",
        "1",
        "--trace",
        "/no/such/dir/t.jsonl",
    ]);
    let err = assert_clean_failure(&output);
    assert!(err.contains("/no/such/dir/t.jsonl"), "{err}");
    // Worded as for every other output in a missing folder.
    assert!(
        err.contains("the folder `/no/such/dir` does not exist"),
        "{err}"
    );
}

#[test]
fn unknown_key_names_file_line_and_key() {
    let err = failure_for_scene(
        "unknown-key.toml",
        "gravity = 9.81\n\n[balls]\ncount = 3\ncolour = [1, 0, 0]\n",
    );
    assert!(err.contains("unknown-key.toml:5:"), "{err}");
    assert!(err.contains("balls.colour"), "{err}");
}

#[test]
fn out_of_range_names_file_line_key_and_range() {
    let err = failure_for_scene(
        "out-of-range.toml",
        "[balls]\ncount = 3\nrestitution = 1.5\n",
    );
    assert!(
        err.contains(
            "out-of-range.toml:3: balls.restitution = 1.5 is out of range: allowed 0 ..= 1"
        ),
        "{err}"
    );
}

#[test]
fn malformed_toml_names_file_and_line() {
    let path = scene_file("malformed.toml", "gravity = 9.81\n[room\n");
    let output = rolypoly(&["--scene", path.to_str().unwrap()]);
    let err = assert_clean_failure(&output);
    assert!(err.contains("malformed.toml:2:"), "{err}");
}

#[test]
fn command_line_overrides_are_range_checked() {
    let output = rolypoly(&["simulate", "--steps", "1", "--gravity", "-3"]);
    let err = assert_clean_failure(&output);
    assert!(err.contains("--gravity"), "{err}");
    assert!(err.contains("allowed 0 ..= 100"), "{err}");

    let output = rolypoly(&["simulate", "--steps", "1", "--balls", "2000000"]);
    let err = assert_clean_failure(&output);
    assert!(err.contains("allowed 0 ..= 1000000"), "{err}");
}

#[test]
fn missing_scene_file_is_a_clear_error() {
    let output = rolypoly(&["simulate", "--steps", "1", "--scene", "no/such/scene.toml"]);
    let err = assert_clean_failure(&output);
    assert!(
        err.contains("cannot read scene file `no/such/scene.toml`"),
        "{err}"
    );
    assert!(err.contains("os error"), "{err}");
}

#[test]
fn help_documents_every_flag() {
    let output = rolypoly(&["simulate", "--help"]);
    assert!(output.status.success());
    let text = stdout(&output);
    for flag in [
        "--scene",
        "--seed",
        "--balls",
        "--gravity",
        "--steps",
        "--seconds",
        "--trace",
        "--every",
        "--fireball",
    ] {
        assert!(text.contains(flag), "simulate --help lacks {flag}:\n{text}");
    }

    let output = rolypoly(&["--help"]);
    assert!(output.status.success());
    let text = stdout(&output);
    for word in ["simulate", "--scene", "--seed", "--balls", "--gravity"] {
        assert!(text.contains(word), "--help lacks {word}:\n{text}");
    }
}

#[test]
fn usage_errors_exit_non_zero() {
    let output = rolypoly(&["simulate"]);
    assert!(!output.status.success());
    assert!(!stderr(&output).contains("panicked"));
    let output = rolypoly(&["simulate", "--steps", "1", "--every", "0"]);
    assert!(!output.status.success());
    let output = rolypoly(&["--no-such-flag"]);
    assert!(!output.status.success());
}

/// A scratch path for a file a test writes.
fn scratch(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("cli-out");
    std::fs::create_dir_all(&dir).expect("scratch folder");
    dir.join(name)
}

#[test]
fn render_writes_a_png_of_the_requested_size() {
    let out = scratch("frame.png");
    let _ = std::fs::remove_file(&out);
    let out_str = out.to_str().expect("UTF-8 path");
    let output = rolypoly(&[
        "render", "--time", "0.5", "--size", "96x54", "--out", out_str,
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let img = image::open(&out).expect("a PNG was written").to_rgba8();
    assert_eq!(img.dimensions(), (96, 54));
    // Not a blank frame: the room has light and dark parts.
    let lum: Vec<u32> = img
        .pixels()
        .map(|p| p.0[0] as u32 + p.0[1] as u32 + p.0[2] as u32)
        .collect();
    let (lo, hi) = (
        lum.iter().min().copied().unwrap_or(0),
        lum.iter().max().copied().unwrap_or(0),
    );
    assert!(hi > lo + 200, "frame is flat: {lo}..{hi}");
}

#[test]
fn render_without_a_graphics_adapter_is_a_clear_error_and_writes_nothing() {
    let out = scratch("no-adapter.png");
    let _ = std::fs::remove_file(&out);
    let out_str = out.to_str().expect("UTF-8 path");
    // Vulkan only, and its loader pointed at a driver list that does not
    // exist (the older and the newer name of the variable): no adapter.
    let output = Command::new(env!("CARGO_BIN_EXE_rolypoly"))
        .args(["render", "--out", out_str])
        .env("WGPU_BACKEND", "vulkan")
        .env("VK_ICD_FILENAMES", "/nonexistent/icd.json")
        .env("VK_DRIVER_FILES", "/nonexistent/icd.json")
        .output()
        .expect("the rolypoly binary runs");
    let err = assert_clean_failure(&output);
    assert!(
        err.contains("no usable graphics adapter was found (backends tried: Vulkan)"),
        "{err}"
    );
    assert!(
        err.contains("libvulkan1"),
        "the error names the loader: {err}"
    );
    assert_eq!(err.trim_end().lines().count(), 1, "one message: {err}");
    assert!(!out.exists(), "no PNG is written without an adapter");
}

#[test]
fn render_rejects_bad_sizes_and_meshes_cleanly() {
    let out = scratch("never.png");
    let out_str = out.to_str().expect("UTF-8 path");
    let err = assert_clean_failure(&rolypoly(&["render", "--size", "0x10", "--out", out_str]));
    assert!(err.contains("1 ..= 8192"), "{err}");

    let err = assert_clean_failure(&rolypoly(&[
        "render",
        "--tumbler-obj",
        "/no/such/mesh.obj",
        "--out",
        out_str,
    ]));
    assert!(err.contains("/no/such/mesh.obj"), "{err}");

    let broken = scratch("broken.obj");
    std::fs::write(&broken, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").expect("write");
    let broken_str = broken.to_str().expect("UTF-8 path");
    let err = assert_clean_failure(&rolypoly(&[
        "render",
        "--tumbler-obj",
        broken_str,
        "--out",
        out_str,
    ]));
    assert!(
        err.contains("broken.obj") && err.contains("normals"),
        "{err}"
    );
    assert!(!out.exists(), "no frame is written on failure");

    // Refused before the minute of simulation it asks for, not after.
    let err = assert_clean_failure(&rolypoly(&[
        "render",
        "--time",
        "60",
        "--out",
        "/no/such/folder/frame.png",
    ]));
    assert!(
        err.contains("the folder `/no/such/folder` does not exist"),
        "{err}"
    );
    // A frame is a PNG, whatever the name asks for.
    let jpeg = scratch("frame.jpg");
    let _ = std::fs::remove_file(&jpeg);
    let err = assert_clean_failure(&rolypoly(&[
        "render",
        "--out",
        jpeg.to_str().expect("UTF-8 path"),
    ]));
    assert!(
        err.contains("frame.jpg") && err.contains("frames are PNG images"),
        "{err}"
    );
    assert!(!jpeg.exists(), "nothing is written under a misleading name");
    let err = assert_clean_failure(&rolypoly(&["make-tumbler-obj", "--out", "t.png"]));
    assert!(err.contains("the mesh is a Wavefront OBJ file"), "{err}");
    let err = assert_clean_failure(&rolypoly(&[
        "make-tumbler-obj",
        "--out",
        "/no/such/folder/t.obj",
    ]));
    assert!(err.contains("/no/such/folder"), "{err}");
}

#[test]
fn make_tumbler_obj_writes_the_shipped_mesh_for_the_default_scene() {
    let out = scratch("tumbler.obj");
    let out_str = out.to_str().expect("UTF-8 path");
    let output = rolypoly(&["make-tumbler-obj", "--out", out_str]);
    assert!(output.status.success(), "{}", stderr(&output));
    let written = std::fs::read_to_string(&out).expect("written");
    let shipped = include_str!("../../../assets/tumbler.obj");
    assert!(
        written == shipped,
        "the command and assets/tumbler.obj disagree"
    );
}

#[test]
fn shaders_export_writes_the_shipped_files_and_never_loses_an_edit() {
    let dir = scratch("exported-shaders");
    let _ = std::fs::remove_dir_all(&dir);
    let dir_str = dir.to_str().expect("UTF-8 path");
    let output = rolypoly(&["shaders", "--export", dir_str]);
    assert!(output.status.success(), "{}", stderr(&output));
    assert!(
        stdout(&output).contains("scene.wgsl"),
        "{}",
        stdout(&output)
    );
    let shipped = Path::new(env!("CARGO_MANIFEST_DIR")).join("../render/shaders");
    let mut names = Vec::new();
    for entry in std::fs::read_dir(&shipped).expect("the renderer's shaders") {
        let name = entry.expect("an entry").file_name();
        let written = std::fs::read(dir.join(&name)).expect("exported");
        assert_eq!(
            written,
            std::fs::read(shipped.join(&name)).unwrap(),
            "{name:?}"
        );
        names.push(name.to_string_lossy().into_owned());
    }
    assert!(names.len() >= 9, "{names:?}");
    let readme = std::fs::read_to_string(dir.join("README.md")).expect("a README");
    assert!(
        names.iter().all(|n| readme.contains(n.as_str())),
        "{readme}"
    );
    // An edited file is refused by name and kept.
    std::fs::write(dir.join("tonemap.wgsl"), "// mine\n").unwrap();
    let err = assert_clean_failure(&rolypoly(&["shaders", "--export", dir_str]));
    assert!(err.contains("tonemap.wgsl"), "{err}");
    assert_eq!(
        std::fs::read_to_string(dir.join("tonemap.wgsl")).unwrap(),
        "// mine\n"
    );
    // Into a folder whose folder is not there.
    let err = assert_clean_failure(&rolypoly(&[
        "shaders",
        "--export",
        "/no/such/folder/shaders",
    ]));
    assert!(
        err.contains("/no/such/folder") && err.contains("does not exist"),
        "{err}"
    );
}

#[test]
fn render_draws_with_a_folders_shaders_and_names_a_broken_ones_line() {
    let dir = scratch("render-shaders");
    let _ = std::fs::remove_dir_all(&dir);
    let dir_str = dir.to_str().expect("UTF-8 path");
    assert!(rolypoly(&["shaders", "--export", dir_str]).status.success());
    let frame = |name: &str, with: Option<&str>| {
        let out = scratch(name);
        let _ = std::fs::remove_file(&out);
        let out_str = out.to_str().expect("UTF-8 path").to_owned();
        let mut args = vec![
            "render", "--time", "0.3", "--size", "64x36", "--out", &out_str,
        ];
        if let Some(dir) = with {
            args.extend(["--shaders", dir]);
        }
        let output = rolypoly(&args);
        (output, out)
    };
    // The exported files draw the shipped picture, byte for byte.
    let (output, shipped) = frame("shipped-shaders.png", None);
    assert!(output.status.success(), "{}", stderr(&output));
    let (output, exported) = frame("exported-shaders.png", Some(dir_str));
    assert!(output.status.success(), "{}", stderr(&output));
    assert_eq!(
        std::fs::read(&shipped).unwrap(),
        std::fs::read(&exported).unwrap()
    );
    // Tone mapping edited to give one colour: the picture is that colour.
    let tonemap = dir.join("tonemap.wgsl");
    let source = std::fs::read_to_string(&tonemap).unwrap();
    let entry = "fn fs_tonemap(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {";
    assert!(source.contains(entry));
    let magenta = source.replace(
        entry,
        &format!("{entry}\n    return vec4<f32>(1.0, 0.0, 1.0, 1.0);"),
    );
    std::fs::write(&tonemap, magenta).unwrap();
    let (output, edited) = frame("edited-shaders.png", Some(dir_str));
    assert!(output.status.success(), "{}", stderr(&output));
    let img = image::open(&edited).expect("a PNG").to_rgba8();
    assert!(
        img.pixels().all(|p| p.0 == [255, 0, 255, 255]),
        "{:?}",
        img.get_pixel(0, 0)
    );
    // A syntax error on line 3: one error naming the file, line and column,
    // and no picture.
    let mut lines: Vec<&str> = source.lines().collect();
    lines.insert(2, "fn (");
    std::fs::write(&tonemap, lines.join("\n")).unwrap();
    let (output, broken) = frame("broken-shaders.png", Some(dir_str));
    let err = assert_clean_failure(&output);
    assert!(err.contains("tonemap.wgsl:3:"), "{err}");
    assert!(!broken.exists());
    // A file missing, and a folder that is not there.
    std::fs::remove_file(&tonemap).unwrap();
    let err = assert_clean_failure(&frame("missing-shader.png", Some(dir_str)).0);
    assert!(err.contains("tonemap.wgsl"), "{err}");
    let err = assert_clean_failure(&frame("no-shaders.png", Some("/no/such/shaders")).0);
    assert!(err.contains("/no/such/shaders"), "{err}");
}

#[test]
fn a_scene_can_start_with_the_fireball_flying() {
    let path = scene_file("fireball-on.toml", "[fireball]\nstarts_active = true\n");
    let path = path.to_str().expect("UTF-8 path");
    let output = rolypoly(&["simulate", "--steps", "3", "--scene", path, "--trace", "-"]);
    assert!(output.status.success(), "{}", stderr(&output));
    let lines = json_lines(&stdout(&output));
    assert!(
        lines[1]["fireball"].is_object(),
        "no fireball at step 0: {}",
        lines[1]["fireball"]
    );
    let plain = rolypoly(&["simulate", "--steps", "3", "--trace", "-"]);
    assert!(json_lines(&stdout(&plain))[1]["fireball"].is_null());
}

/// Pixels of two frames whose colour differs by more than `threshold` (of
/// 255) in any channel.
fn pixels_differing(a: &Path, b: &Path, threshold: u8) -> usize {
    let (a, b) = (
        image::open(a).expect("png").to_rgba8(),
        image::open(b).expect("png").to_rgba8(),
    );
    a.pixels()
        .zip(b.pixels())
        .filter(|(p, q)| {
            p.0[..3]
                .iter()
                .zip(&q.0[..3])
                .any(|(x, y)| x.abs_diff(*y) > threshold)
        })
        .count()
}

/// The fireball is seen from the default camera: at t = 1.5 s (640 x 360)
/// it and its effects change at least 2 000 pixels by more than 24 of 255,
/// and its light alone (against `--no-fireball-light`) at least 3 000 by
/// more than 8, whatever the balls do (two seeds).
#[test]
fn the_fireball_is_seen_from_the_default_camera_and_lights_the_room() {
    for seed in ["1", "5"] {
        let frames = [
            ("without.png", vec![]),
            ("with.png", vec!["--fireball"]),
            ("unlit.png", vec!["--fireball", "--no-fireball-light"]),
        ]
        .map(|(name, extra)| {
            let out = scratch(&format!("fireball-seed{seed}-{name}"));
            let out_str = out.to_str().expect("UTF-8 path").to_owned();
            let mut args = vec![
                "render", "--time", "1.5", "--size", "640x360", "--seed", seed, "--out", &out_str,
            ];
            args.extend(extra);
            let output = rolypoly(&args);
            assert!(output.status.success(), "{}", stderr(&output));
            out
        });
        let [without, with, unlit] = &frames;
        let seen = pixels_differing(with, without, 24);
        assert!(
            seen >= 2000,
            "seed {seed}: the fireball changed only {seen} pixels"
        );
        let lit = pixels_differing(with, unlit, 8);
        assert!(
            lit >= 3000,
            "seed {seed}: its light changed only {lit} pixels"
        );
    }
}

#[test]
fn the_scene_files_light_lights_the_frame() {
    let dim = scene_file("dim.toml", "[light]\nintensity = 0.8\nambient = 0.05\n");
    let (bright_png, dim_png) = (scratch("bright.png"), scratch("dim.png"));
    let runs: [(&PathBuf, Option<&PathBuf>); 2] = [(&bright_png, None), (&dim_png, Some(&dim))];
    for (out, scene) in runs {
        let out_str = out.to_str().expect("UTF-8 path");
        let mut args = vec!["render", "--size", "96x54", "--out", out_str];
        if let Some(scene) = scene {
            args.extend(["--scene", scene.to_str().expect("UTF-8 path")]);
        }
        let output = rolypoly(&args);
        assert!(output.status.success(), "{}", stderr(&output));
    }
    let mean = |p: &PathBuf| {
        let img = image::open(p).expect("png").to_rgba8();
        img.pixels()
            .map(|p| p.0[..3].iter().map(|&c| c as f64).sum::<f64>())
            .sum::<f64>()
            / img.pixels().len() as f64
    };
    let (bright, dim) = (mean(&bright_png), mean(&dim_png));
    assert!(
        dim < 0.7 * bright,
        "a dimmer light gave {dim:.0} against {bright:.0}"
    );
}

#[test]
fn the_shipped_ball_pit_scene_loads_and_steps() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../scenes/ballpit-100k.toml"
    );
    let output = rolypoly(&["simulate", "--steps", "1", "--scene", path]);
    let out = stdout(&output);
    assert!(output.status.success(), "{}", stderr(&output));
    assert!(out.contains("100000 balls (100000 in play"), "{out}");
    assert!(out.contains("5 tumblers"), "{out}");
}

/// Decodes every frame of a GIF with its delay in milliseconds.
fn gif_frames(path: &std::path::Path) -> Vec<(image::RgbaImage, u32)> {
    use image::AnimationDecoder;
    let file = std::io::BufReader::new(std::fs::File::open(path).expect("the GIF was written"));
    let decoder = image::codecs::gif::GifDecoder::new(file).expect("a GIF");
    decoder
        .into_frames()
        .map(|frame| {
            let frame = frame.expect("a frame");
            let (numer, denom) = frame.delay().numer_denom_ms();
            (frame.into_buffer(), numer / denom)
        })
        .collect()
}

#[test]
fn record_writes_a_gif_with_a_frame_per_tick_that_loops_and_moves() {
    for (seconds, fps, frames, delay_ms) in [("0.4", "10", 4, 100), ("0.3", "20", 6, 50)] {
        let out = scratch(&format!("clip-{fps}.gif"));
        let _ = std::fs::remove_file(&out);
        let output = rolypoly(&[
            "record",
            "--seconds",
            seconds,
            "--fps",
            fps,
            "--size",
            "48x27",
            "--out",
            out.to_str().expect("UTF-8 path"),
        ]);
        assert!(output.status.success(), "{}", stderr(&output));
        assert!(stdout(&output).contains(&format!("{frames} frames of 48x27")));
        let decoded = gif_frames(&out);
        assert_eq!(
            decoded.len(),
            frames,
            "{seconds} s at {fps} frames a second"
        );
        for (image, delay) in &decoded {
            assert_eq!(image.dimensions(), (48, 27));
            assert_eq!(*delay, delay_ms);
        }
        // The balls fall: the last frame is not the first.
        assert_ne!(decoded[0].0, decoded[frames - 1].0);
        let bytes = std::fs::read(&out).expect("GIF");
        assert!(
            bytes.windows(11).any(|w| w == b"NETSCAPE2.0"),
            "the GIF loops"
        );
    }
}

#[test]
fn each_recorded_frame_is_the_frame_render_draws_at_its_time() {
    for (seconds, fps) in [("0.3", 10u32), ("0.5", 4)] {
        let folder = scratch(&format!("frames-{fps}"));
        let _ = std::fs::remove_dir_all(&folder);
        let folder_arg = format!("{}/", folder.to_str().expect("UTF-8 path"));
        let output = rolypoly(&[
            "record",
            "--seconds",
            seconds,
            "--fps",
            &fps.to_string(),
            "--size",
            "40x24",
            "--fireball",
            "--out",
            &folder_arg,
        ]);
        assert!(output.status.success(), "{}", stderr(&output));
        let mut names: Vec<_> = std::fs::read_dir(&folder)
            .expect("the folder was made")
            .map(|e| e.expect("entry").file_name().into_string().expect("name"))
            .collect();
        names.sort();
        let count = (seconds.parse::<f64>().expect("seconds") * f64::from(fps)).round() as u32;
        let expected: Vec<String> = (0..count).map(|k| format!("frame-{k:05}.png")).collect();
        assert_eq!(names, expected);
        for (k, name) in names.iter().enumerate() {
            let time = (k as f64 / f64::from(fps)).to_string();
            let single = scratch(&format!("frame-{fps}-{k}.png"));
            let output = rolypoly(&[
                "render",
                "--time",
                &time,
                "--size",
                "40x24",
                "--fireball",
                "--out",
                single.to_str().expect("UTF-8 path"),
            ]);
            assert!(output.status.success(), "{}", stderr(&output));
            let recorded = image::open(folder.join(name)).expect("PNG").to_rgba8();
            let rendered = image::open(&single).expect("PNG").to_rgba8();
            assert!(
                recorded == rendered,
                "{name} differs from render --time {time}"
            );
        }
    }
}

#[test]
fn record_to_mp4_goes_through_ffmpeg_and_says_so_when_it_is_missing() {
    let out = scratch("clip.mp4");
    let _ = std::fs::remove_file(&out);
    let out_str = out.to_str().expect("UTF-8 path");
    let args = [
        "record",
        "--seconds",
        "0.3",
        "--fps",
        "10",
        "--size",
        "33x19",
        "--out",
        out_str,
    ];
    // No program named ffmpeg anywhere on the search path.
    let output = Command::new(env!("CARGO_BIN_EXE_rolypoly"))
        .args(args)
        .env("PATH", scratch("no-programs-here"))
        .output()
        .expect("the rolypoly binary runs");
    let err = assert_clean_failure(&output);
    assert!(
        err.contains("`ffmpeg`") && err.contains("apt-get install ffmpeg"),
        "{err}"
    );
    assert!(!out.exists(), "nothing is written without ffmpeg");

    let ffmpeg_here = Command::new("ffmpeg").arg("-version").output().is_ok();
    if !ffmpeg_here {
        // `.ci/run` installs ffmpeg; a machine without it checks the error only.
        eprintln!("ffmpeg is not installed: the MP4 itself is not checked");
        return;
    }
    let output = rolypoly(&args);
    assert!(output.status.success(), "{}", stderr(&output));
    let bytes = std::fs::read(&out).expect("the MP4 was written");
    assert_eq!(&bytes[4..8], b"ftyp", "an MP4 file");
    // Odd sides are padded to even ones, as H.264 in 4:2:0 needs; three
    // frames at ten a second.
    let probe = Command::new("ffprobe")
        .args(["-v", "error", "-count_frames", "-select_streams", "v:0"])
        .args([
            "-show_entries",
            "stream=nb_read_frames,width,height,r_frame_rate",
        ])
        .args(["-of", "csv=p=0", out_str])
        .output()
        .expect("ffprobe comes with ffmpeg");
    assert_eq!(
        String::from_utf8_lossy(&probe.stdout).trim(),
        "34,20,10/1,3"
    );
}

#[test]
fn record_refuses_unknown_clip_kinds_and_lengths_cleanly() {
    let err = assert_clean_failure(&rolypoly(&["record", "--out", "clip.avi"]));
    assert!(
        err.contains("`clip.avi`") && err.contains(".gif") && err.contains(".mp4"),
        "{err}"
    );
    let err = assert_clean_failure(&rolypoly(&["record", "--out", "no-such-folder/clip.gif"]));
    assert!(
        err.contains("the folder `no-such-folder` does not exist"),
        "{err}"
    );
    for bad in [
        ["--seconds", "0"],
        ["--fps", "0"],
        ["--fps", "61"],
        ["--seconds", "nan"],
    ] {
        let output = rolypoly(&["record", bad[0], bad[1], "--out", "clip.gif"]);
        assert!(!output.status.success(), "{bad:?}");
        assert!(!stderr(&output).contains("panicked"), "{bad:?}");
    }
}

/// A recording of a short session, made through the sandbox as the window
/// makes one: some steps, a ball thrown, the recording from then on.
fn recording(name: &str) -> (PathBuf, rolypoly::sandbox::ReplayLog) {
    use rolypoly::sandbox::Sandbox;
    let scene = rolypoly::scene::Scene::default();
    let mut sandbox = Sandbox::new(scene, "default.toml", 5).expect("the default scene builds");
    (0..30).for_each(|_| sandbox.tick());
    sandbox.start_recording();
    sandbox
        .throw(glam::DVec3::new(0.0, 2.0, 3.0), glam::DVec3::NEG_Z)
        .expect("a throw");
    (0..36).for_each(|_| sandbox.tick());
    let log = sandbox.stop_recording().expect("a recording");
    let path = scratch(name);
    log.write(&path).expect("the recording is written");
    (path, log)
}

#[test]
fn replay_draws_a_recording_into_a_clip_and_checks_its_end_state() {
    let (log_path, log) = recording("session.replay");
    let out = scratch("replay.gif");
    let _ = std::fs::remove_file(&out);
    let output = rolypoly(&[
        "replay",
        log_path.to_str().expect("UTF-8 path"),
        "--size",
        "48x27",
        "--fps",
        "20",
        "--out",
        out.to_str().expect("UTF-8 path"),
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let said = stdout(&output);
    // 36 ticks of 1/120 s at 20 frames a second.
    assert!(said.contains("6 frames of 48x27, ticks 30 to 66"), "{said}");
    assert!(
        said.contains(&format!(
            "end state identical to the recording's (digest {})",
            log.end_digest
        )),
        "{said}"
    );
    let frames = gif_frames(&out);
    assert_eq!(frames.len(), 6);
    assert_ne!(frames[0].0, frames[5].0, "the balls move");
}

#[test]
fn replay_refuses_a_broken_or_tampered_recording_cleanly() {
    let (log_path, log) = recording("tampered.replay");
    let text = std::fs::read_to_string(&log_path).expect("the recording");
    let tampered = scratch("tampered-digest.replay");
    std::fs::write(
        &tampered,
        text.replacen(&log.end_digest, "0000000000000000", 1),
    )
    .expect("written");
    let out = scratch("tampered.gif");
    let err = assert_clean_failure_with_output(&rolypoly(&[
        "replay",
        tampered.to_str().expect("UTF-8 path"),
        "--size",
        "32x18",
        "--out",
        out.to_str().expect("UTF-8 path"),
    ]));
    assert!(
        err.contains("the replay ends in another state than the recording did"),
        "{err}"
    );

    let to_tick = format!("\"to_tick\":{}", log.to_tick);
    for (ticks, says) in [
        // 2.3 hours at 120 steps a second.
        ("1000000", "a clip is at most 3600 s"),
        (
            "99999999999",
            "hours of simulated time; a recording is at most 10",
        ),
    ] {
        let long = scratch(&format!("long-{ticks}.replay"));
        let text = text.replacen(&to_tick, &format!("\"to_tick\":{ticks}"), 1);
        std::fs::write(&long, text).expect("written");
        let err = assert_clean_failure(&rolypoly(&[
            "replay",
            long.to_str().expect("UTF-8 path"),
            "--out",
            out.to_str().expect("UTF-8 path"),
        ]));
        assert!(err.contains(says), "{err}");
    }

    let not_json = scene_file("not-a-recording.replay", "gravity = 3\n");
    let err = assert_clean_failure(&rolypoly(&[
        "replay",
        not_json.to_str().expect("UTF-8 path"),
        "--out",
        "x.gif",
    ]));
    assert!(
        err.contains("not-a-recording.replay:1: not a rolypoly recording"),
        "{err}"
    );

    let err = assert_clean_failure(&rolypoly(&["replay", "no/such.replay", "--out", "x.gif"]));
    assert!(
        err.contains("cannot read recording `no/such.replay`"),
        "{err}"
    );

    let err = assert_clean_failure(&rolypoly(&[
        "replay",
        log_path.to_str().expect("UTF-8 path"),
        "--fireball",
        "--out",
        "x.gif",
    ]));
    assert!(err.contains("--fireball does not apply"), "{err}");
}

/// A failed run that wrote to standard output before it failed (a clip's
/// summary before the end state's check): non-zero exit, one `error:`
/// message, no panic.
fn assert_clean_failure_with_output(output: &Output) -> String {
    let err = stderr(output);
    assert!(!output.status.success(), "expected failure, stderr: {err}");
    assert!(err.starts_with("error: "), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    err
}

#[test]
fn an_unknown_debug_view_is_a_clear_error_listing_the_views() {
    let output = rolypoly(&["render", "--show", "contacts,bogus", "--out", "never.png"]);
    assert!(!output.status.success());
    let text = stderr(&output);
    assert!(text.contains("`bogus` is not a debug view"), "{text}");
    assert!(
        text.contains("contacts, impulses, velocities, grid, rest, com"),
        "{text}"
    );
    assert!(!text.contains("panicked"), "{text}");
}

#[test]
fn render_show_draws_the_views_it_names() {
    let (plain, shown) = (scratch("no-views.png"), scratch("views.png"));
    for (out, extra) in [(&plain, None), (&shown, Some("velocities,grid"))] {
        let out_str = out.to_str().expect("UTF-8 path");
        let mut args = vec![
            "render", "--time", "0.5", "--size", "160x90", "--out", out_str,
        ];
        if let Some(views) = extra {
            args.extend(["--show", views]);
        }
        let output = rolypoly(&args);
        assert!(output.status.success(), "{}", stderr(&output));
    }
    let changed = pixels_differing(&plain, &shown, 12);
    assert!(changed > 30, "--show changed only {changed} pixels");
}

/// `--legend` draws what the views' marks mean into the frame's top left,
/// and nothing elsewhere; without `--show` it is refused.
#[test]
fn render_legend_names_the_views_marks_in_the_top_left() {
    let (bare, legend) = (scratch("views-bare.png"), scratch("views-legend.png"));
    for (out, extra) in [(&bare, None), (&legend, Some("--legend"))] {
        let out_str = out.to_str().expect("UTF-8 path");
        let mut args = vec![
            "render",
            "--time",
            "1",
            "--size",
            "640x360",
            "--show",
            "contacts,com",
            "--out",
            out_str,
        ];
        args.extend(extra);
        let output = rolypoly(&args);
        assert!(output.status.success(), "{}", stderr(&output));
    }
    let (a, b) = (
        image::open(&bare).expect("png").to_rgba8(),
        image::open(&legend).expect("png").to_rgba8(),
    );
    let (mut inside, mut outside) = (0, 0);
    for ((x, y, p), q) in a.enumerate_pixels().zip(b.pixels()) {
        if (0..3).any(|c| p.0[c].abs_diff(q.0[c]) > 16) {
            // The legend of two views (thirteen lines) stays in the left
            // 55 % and the top 80 % of a 640x360 frame.
            if x < 352 && y < 288 {
                inside += 1;
            } else {
                outside += 1;
            }
        }
    }
    assert!(inside > 5_000, "the legend changed only {inside} pixels");
    assert_eq!(outside, 0, "the legend reached beyond the top left");
    let output = rolypoly(&["render", "--legend", "--out", "never.png"]);
    let err = stderr(&output);
    assert_eq!(output.status.code(), Some(2), "{err}");
    assert!(err.contains("--show"), "{err}");
}

#[test]
fn the_gpu_engine_simulates_and_traces_the_balls_it_steps() {
    let args = [
        "simulate", "--engine", "gpu", "--steps", "120", "--every", "60", "--trace", "-",
    ];
    let output = rolypoly(&args);
    assert!(output.status.success(), "{}", stderr(&output));
    let lines = json_lines(&stdout(&output));
    let states: Vec<&serde_json::Value> = lines.iter().filter(|l| l["kind"] == "state").collect();
    assert_eq!(states.len(), 3, "steps 0, 60 and 120");
    let balls = |state: &serde_json::Value| state["balls"].as_array().expect("balls").clone();
    let (first, last) = (balls(states[0]), balls(states[2]));
    assert_eq!((first.len(), last.len()), (30, 30));
    // They fell: the GPU's state came back, not the start's.
    let height = |ball: &serde_json::Value| ball["p"][1].as_f64().expect("a height");
    let fallen = first
        .iter()
        .zip(&last)
        .filter(|(a, b)| height(b) < height(a))
        .count();
    assert!(fallen > 15, "only {fallen} of 30 fell");
    // A rerun gives the same bytes.
    assert_eq!(stdout(&rolypoly(&args)), stdout(&output));
}

/// A trace's scene line lists every ball's radius and mass as the scene
/// made them, the same bytes on either engine, for scenes of several sizes
/// and balls placed by hand.
#[test]
fn the_trace_header_is_the_same_on_both_engines() {
    let placed = scene_file(
        "header-placed.toml",
        "[balls]\ncount = 3\n[[balls.placement]]\nposition = [0.3, 0.5, 0.3]\n\
         velocity = [0.0, 0.0, 0.0]\nradius = 0.13\nmass = 0.3\n",
    );
    let placed = placed.to_str().expect("UTF-8 path");
    for extra in [
        &["--balls", "7"][..],
        &["--balls", "40", "--seed", "3"],
        &["--scene", placed],
    ] {
        let header = |engine: &str| {
            let mut args = vec![
                "simulate", "--engine", engine, "--steps", "1", "--trace", "-",
            ];
            args.extend_from_slice(extra);
            let output = rolypoly(&args);
            assert!(output.status.success(), "{engine}: {}", stderr(&output));
            stdout(&output)
                .lines()
                .next()
                .expect("a scene line")
                .to_string()
        };
        let (cpu, gpu) = (header("cpu"), header("gpu"));
        assert_eq!(cpu, gpu, "{extra:?}");
        let line: serde_json::Value = serde_json::from_str(&gpu).expect("JSON");
        let balls = line["balls"].as_array().expect("balls");
        assert!(!balls.is_empty(), "{extra:?}: {gpu}");
        assert!(
            balls.iter().all(|b| b["radius"].as_f64() > Some(0.0)),
            "{gpu}"
        );
    }
}

#[test]
fn the_gpu_engine_is_chosen_by_flag_or_scene_and_a_wrong_name_is_refused() {
    let output = rolypoly(&["simulate", "--engine", "quantum", "--steps", "1"]);
    let err = assert_clean_failure(&output);
    assert!(
        err.contains("`quantum` is not an engine: use one of cpu, gpu"),
        "{err}"
    );
    let err = failure_for_scene("engine.toml", "[solver]\nengine = \"quantum\"\n");
    assert!(
        err.contains("solver.engine") && err.contains("cpu") && err.contains("gpu"),
        "{err}"
    );
    let scene = scene_file("gpu-engine.toml", "[solver]\nengine = \"gpu\"\n");
    let by_scene = rolypoly(&[
        "simulate",
        "--scene",
        scene.to_str().expect("UTF-8"),
        "--steps",
        "60",
        "--trace",
        "-",
    ]);
    let by_flag = rolypoly(&[
        "simulate", "--engine", "gpu", "--steps", "60", "--trace", "-",
    ]);
    let on_cpu = rolypoly(&["simulate", "--steps", "60", "--trace", "-"]);
    let last = |out: &Output| json_lines(&stdout(out)).pop().expect("a state")["balls"].clone();
    assert_eq!(
        last(&by_scene),
        last(&by_flag),
        "the scene key and the flag choose alike"
    );
    assert_ne!(last(&by_flag), last(&on_cpu), "the engines differ");
}

#[test]
fn the_gpu_engine_without_an_adapter_is_one_clear_error_and_the_cpu_engine_still_runs() {
    let run = |engine: &str| {
        Command::new(env!("CARGO_BIN_EXE_rolypoly"))
            .args(["simulate", "--engine", engine, "--steps", "10"])
            .env("WGPU_BACKEND", "vulkan")
            .env("VK_ICD_FILENAMES", "/nonexistent/icd.json")
            .env("VK_DRIVER_FILES", "/nonexistent/icd.json")
            .output()
            .expect("the rolypoly binary runs")
    };
    let err = assert_clean_failure(&run("gpu"));
    assert!(
        err.contains("the gpu engine found no graphics adapter"),
        "{err}"
    );
    assert!(
        err.contains("--engine cpu"),
        "it says what else to do: {err}"
    );
    assert_eq!(err.trim_end().lines().count(), 1, "one message: {err}");
    assert!(
        run("cpu").status.success(),
        "no silent need of a GPU on the CPU engine"
    );
}

#[test]
fn render_draws_the_gpu_engines_balls_from_its_own_buffer() {
    let with = scratch("gpu-balls.png");
    let without = scratch("gpu-no-balls.png");
    for (out, balls) in [(&with, "300"), (&without, "0")] {
        let output = rolypoly(&[
            "render",
            "--engine",
            "gpu",
            "--balls",
            balls,
            "--time",
            "0.5",
            "--size",
            "160x90",
            "--out",
            out.to_str().expect("UTF-8"),
        ]);
        assert!(output.status.success(), "{}", stderr(&output));
    }
    let differing = pixels_differing(&with, &without, 24);
    assert!(differing > 1500, "the balls cover {differing} pixels");
}

/// The mean FLIP error `render` printed.
fn flip_mean(output: &Output) -> f32 {
    let out = stdout(output);
    out.lines()
        .find_map(|l| l.strip_prefix("mean FLIP error against the reference: "))
        .unwrap_or_else(|| panic!("no mean error in: {out}"))
        .parse()
        .expect("a number")
}

#[test]
fn render_reference_traces_on_the_cpu_alone_and_the_same_samples_give_the_same_bytes() {
    let path = |name: &str| scratch(name).to_str().expect("UTF-8 path").to_owned();
    let (a, b, c, hdr) = (
        path("ref-a.png"),
        path("ref-b.png"),
        path("ref-c.png"),
        path("ref-a.exr"),
    );
    // No graphics adapter: the reference needs none.
    let trace = |out: &str, seed: &str, extra: &[&str]| {
        let mut args = vec![
            "render",
            "--reference",
            "--time",
            "1",
            "--size",
            "64x36",
            "--spp",
            "4",
            "--reference-seed",
            seed,
            "--out",
            out,
        ];
        args.extend_from_slice(extra);
        let output = Command::new(env!("CARGO_BIN_EXE_rolypoly"))
            .args(&args)
            .env("WGPU_BACKEND", "vulkan")
            .env("VK_ICD_FILENAMES", "/nonexistent/icd.json")
            .env("VK_DRIVER_FILES", "/nonexistent/icd.json")
            .output()
            .expect("the rolypoly binary runs");
        assert!(output.status.success(), "{}", stderr(&output));
        assert!(
            stdout(&output).contains("path-traced reference, 4 samples a pixel"),
            "{}",
            stdout(&output)
        );
        std::fs::read(out).expect("a PNG was written")
    };
    let first = trace(&a, "7", &["--hdr", &hdr]);
    assert_eq!(first, trace(&b, "7", &[]), "the same seed, the same bytes");
    assert_ne!(first, trace(&c, "8", &[]), "another seed, other samples");
    let picture = image::load_from_memory(&first).expect("a PNG").to_rgba8();
    assert_eq!(picture.dimensions(), (64, 36));
    let exr = std::fs::read(&hdr).expect("the EXR was written");
    assert_eq!(
        &exr[..4],
        &[0x76, 0x2f, 0x31, 0x01],
        "OpenEXR's magic number"
    );
}

#[test]
fn render_against_itself_scores_no_error_and_compare_writes_the_three_pictures() {
    let path = |name: &str| scratch(name).to_str().expect("UTF-8 path").to_owned();
    let frame = path("truth-frame.png");
    let run = |args: &[&str]| {
        let output = rolypoly(args);
        assert!(output.status.success(), "{}", stderr(&output));
        output
    };
    run(&["render", "--time", "1", "--size", "80x45", "--out", &frame]);
    let same = path("truth-same.png");
    let output = run(&[
        "render",
        "--time",
        "1",
        "--size",
        "80x45",
        "--out",
        &same,
        "--against",
        &frame,
    ]);
    assert_eq!(flip_mean(&output), 0.0, "a frame against itself");
    let off = path("truth-off.png");
    let output = run(&[
        "render",
        "--time",
        "1",
        "--size",
        "80x45",
        "--no-indirect",
        "--out",
        &off,
        "--against",
        &frame,
    ]);
    assert!(flip_mean(&output) > 0.005, "another frame differs");

    let compared = scratch("truth-compare.png");
    let output = run(&[
        "render",
        "--compare",
        "--time",
        "1",
        "--size",
        "80x45",
        "--spp",
        "2",
        "--out",
        compared.to_str().expect("UTF-8 path"),
    ]);
    let mean = flip_mean(&output);
    assert!(mean > 0.0 && mean < 1.0, "{mean}");
    for name in [
        "truth-compare.png",
        "truth-compare-reference.png",
        "truth-compare-flip.png",
    ] {
        let picture = image::open(scratch(name)).expect("written").to_rgb8();
        assert_eq!(picture.dimensions(), (80, 45), "{name}");
    }
}

#[test]
fn the_references_noise_is_below_the_real_time_error_it_judges() {
    // Two references of other seeds differ by less than the real-time
    // frame differs from one, for two scenes (the default at 64 samples,
    // here at a quarter of 640x360 on each side).
    for seed in ["1", "2"] {
        let path = |name: &str| {
            scratch(&format!("noise-{seed}-{name}"))
                .to_str()
                .expect("UTF-8 path")
                .to_owned()
        };
        let common = ["--seed", seed, "--time", "2", "--size", "160x90"];
        let run = |extra: &[&str]| {
            let args: Vec<&str> = ["render"]
                .iter()
                .chain(&common)
                .chain(extra)
                .copied()
                .collect();
            let output = rolypoly(&args);
            assert!(output.status.success(), "{}", stderr(&output));
            output
        };
        let reference = path("a.png");
        run(&["--reference", "--spp", "64", "--out", &reference]);
        let noise = flip_mean(&run(&[
            "--reference",
            "--spp",
            "64",
            "--reference-seed",
            "2",
            "--out",
            &path("b.png"),
            "--against",
            &reference,
        ]));
        let error = flip_mean(&run(&["--out", &path("rt.png"), "--against", &reference]));
        assert!(
            noise < 0.8 * error,
            "scene seed {seed}: noise {noise}, real-time error {error}"
        );
    }
}

#[test]
fn render_reference_refuses_what_it_cannot_do() {
    let out = scratch("never-ref.png");
    let out_str = out.to_str().expect("UTF-8 path");
    let err = assert_clean_failure(&rolypoly(&["render", "--spp", "4", "--out", out_str]));
    assert!(
        err.contains("--spp, --reference-seed and --hdr go with --reference or --compare"),
        "{err}"
    );
    let err = assert_clean_failure(&rolypoly(&[
        "render",
        "--reference",
        "--spp",
        "0",
        "--out",
        out_str,
    ]));
    assert!(err.contains("--spp"), "{err}");
    let err = assert_clean_failure(&rolypoly(&[
        "render",
        "--reference",
        "--engine",
        "gpu",
        "--out",
        out_str,
    ]));
    assert!(err.contains("--engine cpu"), "{err}");
    let err = assert_clean_failure(&rolypoly(&[
        "render",
        "--size",
        "32x18",
        "--against",
        "/nonexistent/ref.png",
        "--out",
        out_str,
    ]));
    assert!(
        err.contains("cannot read the reference picture `/nonexistent/ref.png`"),
        "{err}"
    );
    let small = scratch("ref-small.png");
    let small_str = small.to_str().expect("UTF-8 path");
    let made = rolypoly(&[
        "render",
        "--reference",
        "--spp",
        "1",
        "--size",
        "16x9",
        "--out",
        small_str,
    ]);
    assert!(made.status.success(), "{}", stderr(&made));
    let err = assert_clean_failure_with_output(&rolypoly(&[
        "render",
        "--size",
        "32x18",
        "--against",
        small_str,
        "--out",
        out_str,
    ]));
    assert!(
        err.contains("the reference picture is 16x9 and the frame 32x18"),
        "{err}"
    );
    assert!(!out.exists() && !scratch("never-ref-flip.png").exists());
}

#[test]
fn frame_views_are_listed_and_an_unknown_one_is_refused_with_their_names() {
    let listed = rolypoly(&["render", "--view", "list"]);
    assert!(listed.status.success(), "{}", stderr(&listed));
    let text = stdout(&listed);
    for name in [
        "final",
        "albedo",
        "normals",
        "depth",
        "shadow-cube",
        "shadow",
        "ambient",
        "diffuse",
        "specular",
        "bounce",
        "occlusion",
        "bloom",
        "motion",
        "history",
        "msaa-edges",
    ] {
        assert!(
            text.lines()
                .any(|l| l.split_whitespace().next() == Some(name)),
            "{name} not listed:\n{text}"
        );
    }
    // From render, record and the window alike, before anything is drawn
    // or a display is looked for.
    for args in [
        vec!["render", "--view", "nosuch", "--out", "never.png"],
        vec!["record", "--view", "nosuch", "--out", "never.gif"],
        vec!["--view", "nosuch"],
    ] {
        let err = assert_clean_failure(&rolypoly_without_display(&args));
        assert!(
            err.contains("nosuch") && err.contains("shadow-cube") && err.contains("msaa-edges"),
            "{args:?}: {err}"
        );
    }
    assert!(!Path::new("never.png").exists() && !Path::new("never.gif").exists());
}

#[test]
fn the_window_names_a_missing_shader_folder_before_it_looks_for_a_display() {
    let err = assert_clean_failure(&rolypoly_without_display(&[
        "--shaders",
        "/no/such/shader-folder",
    ]));
    assert!(err.contains("/no/such/shader-folder"), "{err}");
    assert!(!err.contains("display"), "{err}");
}

#[test]
fn the_motion_view_of_a_moment_shows_what_moved_in_the_frame_before_it() {
    for seed in ["2", "9"] {
        let out = scratch(&format!("motion-{seed}.png"));
        let out_str = out.to_str().expect("UTF-8 path");
        let output = rolypoly(&[
            "--seed", seed, "render", "--time", "0.8", "--size", "160x90", "--view", "motion",
            "--out", out_str,
        ]);
        assert!(output.status.success(), "{}", stderr(&output));
        assert!(
            stdout(&output).contains("view motion:"),
            "{}",
            stdout(&output)
        );
        let img = image::open(&out).expect("a PNG").to_rgba8();
        let moving = img
            .pixels()
            .filter(|p| p.0[..3].iter().any(|&c| c > 8))
            .count();
        // The falling and rolling balls, not the still room.
        assert!(
            moving > 30 && moving < img.pixels().len() / 4,
            "seed {seed}: {moving} pixels moving"
        );
    }
}
