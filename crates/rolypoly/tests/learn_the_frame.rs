//! docs/learn-the-frame.md stays true: each WGSL line it quotes is a line
//! of the shader file it names, in the order the file has them, and its
//! exercises do what it says: a larger specular exponent narrows the
//! highlight, one shadow tap hardens the penumbra.

use std::path::{Path, PathBuf};
use std::process::Command;

mod pages;

use pages::{ROOT, pages};

/// docs/learn-the-frame.md, one of the pages.
fn page() -> String {
    let path = pages()
        .into_iter()
        .find(|p| p.ends_with("docs/learn-the-frame.md"))
        .expect("docs/learn-the-frame.md is a page");
    std::fs::read_to_string(path).expect("docs/learn-the-frame.md is readable")
}

/// Each ```wgsl block of the page: the file its first line names, and its
/// other lines.
fn quoted_blocks(page: &str) -> Vec<(String, Vec<String>)> {
    let mut blocks = Vec::new();
    let mut lines = page.lines();
    while let Some(line) = lines.next() {
        if line.trim() != "```wgsl" {
            continue;
        }
        let body: Vec<String> = lines
            .by_ref()
            .take_while(|l| l.trim() != "```")
            .map(|l| l.trim().to_string())
            .collect();
        let (first, rest) = body.split_first().expect("a quoted block is not empty");
        let file = first
            .strip_prefix("// ")
            .unwrap_or_else(|| panic!("a quoted block starts by naming its file: {first}"));
        blocks.push((file.to_string(), rest.to_vec()));
    }
    blocks
}

#[test]
fn every_quoted_wgsl_line_is_a_line_of_the_file_it_names() {
    let blocks = quoted_blocks(&page());
    assert!(blocks.len() >= 12, "only {} quoted blocks", blocks.len());
    for (file, quoted) in blocks {
        let source = std::fs::read_to_string(Path::new(ROOT).join(&file))
            .unwrap_or_else(|e| panic!("the page quotes {file}, which cannot be read: {e}"));
        let lines: Vec<&str> = source.lines().map(str::trim).collect();
        let mut from = 0;
        for line in quoted.iter().filter(|l| !l.is_empty()) {
            let at = lines[from..]
                .iter()
                .position(|l| l == line)
                .unwrap_or_else(|| {
                    panic!("the page quotes `{line}` from {file}, which has no such line after line {from}")
                });
            from += at + 1;
        }
    }
}

fn scratch(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

/// The shipped shaders exported to `dir`, with `from` replaced by `to` in
/// scene.wgsl, as the page's exercise says (it quotes both).
fn exported_with(dir: &Path, edit: Option<(&str, &str)>) {
    let output = Command::new(env!("CARGO_BIN_EXE_rolypoly"))
        .args(["shaders", "--export"])
        .arg(dir)
        .output()
        .expect("rolypoly runs");
    assert!(output.status.success(), "{output:?}");
    if let Some((from, to)) = edit {
        let page = page();
        assert!(
            page.contains(&format!("`{from}`")) && page.contains(&format!("`{to}`")),
            "the page's exercise no longer says to change `{from}` to `{to}`"
        );
        let scene = dir.join("scene.wgsl");
        let source = std::fs::read_to_string(&scene).expect("scene.wgsl");
        assert_eq!(source.matches(from).count(), 1, "`{from}` in scene.wgsl");
        std::fs::write(&scene, source.replace(from, to)).expect("the edit saved");
    }
}

/// `view` of the default scene at t = 1.5 s (seed `seed`), drawn with the
/// shaders of `dir`: each pixel's brightest channel, 0 ..= 1.
fn view_with(dir: &Path, view: &str, seed: u64) -> Vec<f32> {
    let out = dir.join(format!("{view}.png"));
    let output = Command::new(env!("CARGO_BIN_EXE_rolypoly"))
        .args(["--seed", &seed.to_string(), "render", "--time", "1.5"])
        .args(["--size", "320x180", "--view", view, "--shaders"])
        .arg(dir)
        .arg("--out")
        .arg(&out)
        .output()
        .expect("rolypoly runs");
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    image::open(&out)
        .expect("a PNG")
        .to_rgb8()
        .pixels()
        .map(|p| *p.0.iter().max().expect("three channels") as f32 / 255.0)
        .collect()
}

fn count(values: &[f32], keep: impl Fn(f32) -> bool) -> usize {
    values.iter().filter(|&&v| keep(v)).count()
}

#[test]
fn a_larger_specular_exponent_narrows_the_highlight() {
    let exponent = "pow(max(dot(n, h), 0.0), material.z)";
    let eightfold = "pow(max(dot(n, h), 0.0), material.z * 8.0)";
    for seed in [1, 6] {
        let shipped = scratch(&format!("exercise-shipped-{seed}"));
        exported_with(&shipped, None);
        let edited = scratch(&format!("exercise-exponent-{seed}"));
        exported_with(&edited, Some((exponent, eightfold)));
        let bright = |v: f32| v > 0.1;
        let before = count(&view_with(&shipped, "specular", seed), bright);
        let after = count(&view_with(&edited, "specular", seed), bright);
        println!(
            "seed {seed}: highlight pixels {before} with the shipped exponent, {after} with eight times it"
        );
        assert!(
            before > 200,
            "seed {seed}: no highlight to narrow ({before})"
        );
        assert!(
            (after as f64) < 0.7 * before as f64,
            "seed {seed}: the highlight did not narrow: {before} -> {after} pixels"
        );
    }
}

#[test]
fn one_shadow_tap_hardens_the_penumbra() {
    let taps = "let taps = max(SHADOW_TAPS, 1);";
    let one = "let taps = 1;";
    for seed in [2, 5] {
        let shipped = scratch(&format!("exercise-soft-{seed}"));
        exported_with(&shipped, None);
        let edited = scratch(&format!("exercise-hard-{seed}"));
        exported_with(&edited, Some((taps, one)));
        let grey = |v: f32| v > 0.1 && v < 0.9;
        let soft = view_with(&shipped, "shadow", seed);
        let hard = view_with(&edited, "shadow", seed);
        let (before, after) = (count(&soft, grey), count(&hard, grey));
        println!("seed {seed}: penumbra pixels {before} with the shipped taps, {after} with one");
        // The same shadows, with narrower edges.
        let dark = |v: f32| v <= 0.1;
        assert!(
            count(&soft, dark) > 100 && count(&hard, dark) > 100,
            "seed {seed}: no shadows"
        );
        assert!(
            (after as f64) < 0.8 * before as f64,
            "seed {seed}: the penumbra did not harden: {before} -> {after} pixels"
        );
    }
}
