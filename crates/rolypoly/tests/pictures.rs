//! The pictures the pages show are the program's pictures now.
//!
//! docs/pictures.txt lists each picture with the command that makes it
//! (`scripts/pictures` runs them). Here each program picture that is not
//! marked slow is drawn again at its own size and scored against the
//! committed one by FLIP's mean error (a GIF frame by frame): a picture
//! the renderer or the physics has left behind fails, and so does a page
//! that shows a picture the list does not make.

use std::path::{Path, PathBuf};
use std::process::Command;

mod pages;

use image::{AnimationDecoder, RgbaImage};
use pages::{ROOT, pages};
use rolypoly_reference::compare;

/// The most FLIP's mean error may be between a committed picture and the
/// program's picture now. The same program on the same adapter draws the
/// same pixels (0); another adapter's rounding stays near 0.01; a change
/// of the light, a camera or the physics' course gives several times this.
const MOST_FLIP: f32 = 0.03;

/// How a listed picture is made.
#[derive(Debug, PartialEq)]
enum Maker {
    /// A program command, run with `--out PICTURE`.
    Program,
    /// The same, too slow or too large to draw in the tests.
    Slow,
    /// A shell command (a plot by a Python example, the spectrogram).
    Script,
}

#[derive(Debug)]
struct Listed {
    picture: String,
    maker: Maker,
    command: String,
}

fn listed() -> Vec<Listed> {
    let text = std::fs::read_to_string(Path::new(ROOT).join("docs/pictures.txt"))
        .expect("docs/pictures.txt is readable");
    text.lines()
        .filter(|l| !l.trim().is_empty() && !l.starts_with('#'))
        .map(|line| {
            let (head, command) = line
                .split_once(": ")
                .unwrap_or_else(|| panic!("docs/pictures.txt: `{line}` is not `PICTURE: COMMAND`"));
            let (picture, maker) = match head.split_once(" (") {
                None => (head, Maker::Program),
                Some((p, "slow)")) => (p, Maker::Slow),
                Some((p, "script)")) => (p, Maker::Script),
                Some(_) => panic!("docs/pictures.txt: `{head}`: the mark is (slow) or (script)"),
            };
            Listed {
                picture: picture.to_owned(),
                maker,
                command: command.to_owned(),
            }
        })
        .collect()
}

/// The frames of a picture: one for a PNG, each frame of a GIF.
fn frames(path: &Path) -> Vec<RgbaImage> {
    if path.extension().is_some_and(|e| e == "gif") {
        let file = std::io::BufReader::new(std::fs::File::open(path).expect("a GIF"));
        let decoder = image::codecs::gif::GifDecoder::new(file).expect("a readable GIF");
        decoder
            .into_frames()
            .map(|f| f.expect("a GIF frame").into_buffer())
            .collect()
    } else {
        vec![
            image::open(path)
                .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
                .to_rgba8(),
        ]
    }
}

/// FLIP's mean error of `now` against `committed`, over their frames; 1,
/// the most, where their frame counts or sizes differ.
fn error(committed: &Path, now: &Path) -> f32 {
    let (a, b) = (frames(committed), frames(now));
    let alike = a.len() == b.len()
        && a.iter()
            .zip(&b)
            .all(|(a, b)| a.dimensions() == b.dimensions());
    if !alike {
        return 1.0;
    }
    let sum: f32 = a.iter().zip(&b).map(|(a, b)| compare(a, b).mean).sum();
    sum / a.len() as f32
}

fn scratch() -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("pictures");
    std::fs::create_dir_all(&dir).expect("a scratch folder");
    dir
}

#[test]
fn every_committed_picture_is_what_the_program_draws_now() {
    let dir = scratch();
    let mut stale = Vec::new();
    let mut drawn = 0;
    for entry in listed().iter().filter(|l| l.maker == Maker::Program) {
        let committed = Path::new(ROOT).join(&entry.picture);
        let name = entry.picture.replace('/', "-");
        let now = dir.join(&name);
        let output = Command::new(env!("CARGO_BIN_EXE_rolypoly"))
            .args(entry.command.split_whitespace())
            .arg("--out")
            .arg(&now)
            .current_dir(ROOT)
            .output()
            .expect("the rolypoly binary runs");
        assert!(
            output.status.success(),
            "{}: `{}` failed:\n{}",
            entry.picture,
            entry.command,
            String::from_utf8_lossy(&output.stderr)
        );
        let error = error(&committed, &now);
        println!("{}: FLIP {error:.4}", entry.picture);
        if error > MOST_FLIP {
            stale.push(format!(
                "{}: FLIP {error:.4} against the program's picture now ({}), allowed {MOST_FLIP}: run scripts/pictures {}",
                entry.picture,
                now.display(),
                entry.picture
            ));
        }
        drawn += 1;
    }
    assert!(
        drawn >= 10,
        "only {drawn} pictures drawn: the list is broken"
    );
    assert!(stale.is_empty(), "{}", stale.join("\n"));
}

/// The pictures (PNG, GIF) a page shows or links.
fn shown_by(page: &Path) -> Vec<String> {
    let text = std::fs::read_to_string(page).expect("a page");
    let base = page
        .parent()
        .expect("a folder")
        .strip_prefix(ROOT)
        .unwrap_or(Path::new(""));
    let mut shown = Vec::new();
    for piece in text.split("](").skip(1) {
        let target = piece.split([')', ' ', '#']).next().unwrap_or("");
        if target.ends_with(".png") || target.ends_with(".gif") {
            let path = base.join(target);
            shown.push(path.to_string_lossy().trim_start_matches("./").to_owned());
        }
    }
    shown
}

#[test]
fn every_picture_a_page_shows_is_listed_and_every_listed_one_exists() {
    let listed = listed();
    let names: Vec<&str> = listed.iter().map(|l| l.picture.as_str()).collect();
    let mut shown = Vec::new();
    for page in &pages() {
        for picture in shown_by(page) {
            let clean = Path::new(&picture)
                .components()
                .fold(PathBuf::new(), |mut p, c| {
                    match c {
                        std::path::Component::ParentDir => {
                            p.pop();
                        }
                        c => p.push(c),
                    }
                    p
                })
                .to_string_lossy()
                .into_owned();
            assert!(
                names.contains(&clean.as_str()),
                "{} shows {clean}, which docs/pictures.txt does not list with the command that makes it",
                page.display()
            );
            shown.push(clean);
        }
    }
    for name in &names {
        assert!(
            Path::new(ROOT).join(name).is_file(),
            "{name} is listed but missing"
        );
        assert!(
            shown.iter().any(|s| s == name),
            "{name} is listed but no page shows it"
        );
    }
}
