//! Every wait on the GPU is bounded (G4): a frame or an engine step
//! that takes longer than `--gpu-timeout` ends the program with one line
//! naming what was waited for, the adapter and the bound, and a way out.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn rolypoly(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rolypoly"))
        .args(args)
        .output()
        .expect("the rolypoly binary runs")
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8(bytes.to_vec()).expect("UTF-8")
}

fn scratch(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("gpu-timeout");
    std::fs::create_dir_all(&dir).expect("scratch folder");
    let path = dir.join(name);
    let _ = std::fs::remove_file(&path);
    path
}

fn scene(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../scenes")
        .join(name)
        .display()
        .to_string()
}

/// The adapter `render` draws with, as it names it ("name (backend)").
fn adapter() -> String {
    let out = scratch("probe.png");
    let output = rolypoly(&[
        "render",
        "--size",
        "16x9",
        "--out",
        out.to_str().expect("UTF-8 path"),
    ]);
    assert!(output.status.success(), "{}", text(&output.stderr));
    let said = text(&output.stdout);
    said.rsplit_once(", on ")
        .map(|(_, adapter)| adapter.trim().trim_end_matches(')').to_string())
        .unwrap_or_else(|| panic!("no adapter named in {said:?}"))
}

/// Asserts one clean line of error that names `what`, the adapter, the
/// bound and the ways out, with exit status 1.
fn assert_timed_out(output: &Output, what: &str, bound: &str) {
    let err = text(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "stderr: {err}");
    assert!(output.stdout.is_empty(), "nothing on stdout: {err}");
    assert!(!err.contains("panicked"), "{err}");
    assert_eq!(err.lines().count(), 1, "one line: {err}");
    let adapter = adapter();
    for part in [
        "error: ",
        what,
        &adapter,
        bound,
        "--quality low",
        "WGPU_BACKEND=gl",
    ] {
        assert!(err.contains(part), "{part:?} missing from {err:?}");
    }
}

#[test]
fn a_heavy_frame_past_a_tiny_bound_is_named_and_nothing_is_written() {
    let out = scratch("heavy.png");
    let output = rolypoly(&[
        "--scene",
        &scene("ballpit-100k.toml"),
        "render",
        "--time",
        "0",
        "--size",
        "1280x720",
        "--gpu-timeout",
        "0.001",
        "--out",
        out.to_str().expect("UTF-8 path"),
    ]);
    assert_timed_out(&output, "the frame at t = 0.000 s (1280x720)", "0.001 s");
    assert!(!out.exists(), "no picture is written for a frame not drawn");
}

#[test]
fn the_gpu_engine_past_a_tiny_bound_names_its_stage() {
    let output = rolypoly(&[
        "--scene",
        &scene("ballpit-100k.toml"),
        "--engine",
        "gpu",
        "simulate",
        "--steps",
        "3",
        "--gpu-timeout",
        "0.001",
    ]);
    assert_timed_out(&output, "the gpu engine's step", "0.001 s");
}

#[test]
fn a_generous_bound_changes_nothing() {
    let (a, b) = (scratch("bounded.png"), scratch("unbounded.png"));
    for (out, extra) in [(&a, &["--gpu-timeout", "120"][..]), (&b, &[][..])] {
        let mut args = vec![
            "render",
            "--time",
            "0.5",
            "--size",
            "160x90",
            "--out",
            out.to_str().expect("UTF-8 path"),
        ];
        args.extend_from_slice(extra);
        let output = rolypoly(&args);
        assert!(output.status.success(), "{}", text(&output.stderr));
    }
    let (a, b) = (image::open(&a).expect("png"), image::open(&b).expect("png"));
    assert_eq!(a.as_bytes(), b.as_bytes());
}

#[test]
fn a_bound_that_is_not_a_positive_number_of_seconds_is_refused() {
    for bad in ["0", "-1", "abc", "inf", "NaN", "1e9", ""] {
        let output = rolypoly(&["simulate", "--steps", "1", "--gpu-timeout", bad]);
        let err = text(&output.stderr);
        assert_eq!(output.status.code(), Some(2), "{bad:?}: {err}");
        assert!(err.contains("--gpu-timeout"), "{bad:?}: {err}");
        assert!(!err.contains("panicked"), "{bad:?}: {err}");
    }
    let output = rolypoly(&["simulate", "--steps", "1", "--gpu-timeout", "0.25"]);
    assert!(output.status.success(), "{}", text(&output.stderr));
}
