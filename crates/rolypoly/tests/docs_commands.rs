//! Every command README.md and docs/*.md show is one that works.
//!
//! - Each `cargo run --release -- ...` line of a fenced shell block runs
//!   with the built binary, in a scratch folder, in the block's order, made
//!   short by the overrides of [`shortened`] (docs/testing.md lists them).
//! - A block after a line `<!-- flags only: REASON -->` (it needs a GPU,
//!   opens a window or takes minutes) is parsed by the command line only,
//!   as are the commands in inline code spans.
//! - Every shown command is written one way, `cargo run --release -- ...`,
//!   and a `cargo bench` that passes flags names its bench target (else
//!   the library's own test harness is handed them and refuses).

use std::path::{Path, PathBuf};
use std::process::Command as Process;

mod pages;

use clap::Parser;
use clap::error::ErrorKind;
use glam::DVec3;
use pages::{ROOT, pages};
use rolypoly::cli::{Cli, Command};
use rolypoly::sandbox::{SHIPPED_SCENES, Sandbox};
use rolypoly::scene::parse_scene;

/// How the program is run in every shown command.
const RUN: &str = "cargo run --release --";

/// The marker of a block that is parsed, not run.
const FLAGS_ONLY: &str = "<!-- flags only:";

/// The most a shown command is asked for when the test runs it.
const MOST_WIDTH: u32 = 160;
const MOST_SECONDS: f64 = 1.0;
const MOST_TIME: f64 = 3.0;
const MOST_SPP: u32 = 4;

/// The flags whose value is a file the command writes.
const OUTPUT_FLAGS: [&str; 5] = ["--out", "--trace", "--hdr", "--series", "--audio"];

/// A command shown on a page.
#[derive(Debug)]
struct Shown {
    /// `page:line`, for messages.
    place: String,
    /// What follows `cargo run --release --`.
    args: Vec<String>,
    /// Why it is only parsed, or None when it runs.
    flags_only: Option<String>,
    /// The fenced block it is in (commands of one block share a folder).
    block: usize,
}

/// A command line split into words as a POSIX shell would: quotes kept
/// together, a `#` word and what follows it dropped. `$PWD` stands for
/// the folder the command is run in.
fn words(line: &str) -> Vec<String> {
    let mut words = Vec::new();
    let mut word: Option<String> = None;
    let mut quote: Option<char> = None;
    for c in line.chars() {
        match (quote, c) {
            (Some(q), c) if c == q => quote = None,
            (Some(_), c) => word.get_or_insert_default().push(c),
            (None, '"' | '\'') => {
                quote = Some(c);
                word.get_or_insert_default();
            }
            (None, '#') if word.is_none() => break,
            (None, c) if c.is_whitespace() => words.extend(word.take()),
            (None, c) => word.get_or_insert_default().push(c),
        }
    }
    words.extend(word);
    words
}

/// The program's arguments if `line` is a shown command, else None.
fn run_args(line: &str) -> Option<Vec<String>> {
    let line = line.trim();
    if line == RUN.trim_end_matches(" --") {
        return Some(Vec::new());
    }
    line.strip_prefix(RUN)
        .filter(|rest| rest.is_empty() || rest.starts_with(' '))
        .map(words)
}

/// The commands of the page's fenced shell blocks, and of its inline code
/// spans, in order.
fn shown_in(page: &Path) -> Vec<Shown> {
    let text = std::fs::read_to_string(page).expect("a page is readable");
    let name = page
        .strip_prefix(ROOT)
        .unwrap_or(page)
        .display()
        .to_string();
    let mut shown = Vec::new();
    let mut prose = String::new();
    let mut fence: Option<String> = None;
    let mut marker: Option<String> = None;
    let mut pending = String::new();
    let mut block = 0;
    for (n, line) in text.lines().enumerate() {
        let place = format!("{name}:{}", n + 1);
        if let Some(lang) = line.trim_start().strip_prefix("```") {
            if fence.take().is_none() {
                fence = Some(lang.trim().to_owned());
                block += 1;
            } else {
                marker = None;
            }
            prose.push('\n');
            continue;
        }
        let Some(lang) = &fence else {
            if let Some(reason) = line.trim().strip_prefix(FLAGS_ONLY) {
                marker = Some(reason.trim_end_matches("-->").trim().to_owned());
            } else if !line.trim().is_empty() {
                marker = None;
            }
            prose.push_str(line);
            prose.push('\n');
            continue;
        };
        if !matches!(lang.as_str(), "sh" | "bash" | "shell" | "console") {
            continue;
        }
        // A line ended by `\` goes on on the next.
        if let Some(head) = line.strip_suffix('\\') {
            pending.push_str(head);
            pending.push(' ');
            continue;
        }
        let full = std::mem::take(&mut pending) + line;
        if let Some(args) = run_args(&full) {
            shown.push(Shown {
                place,
                args,
                flags_only: marker.clone(),
                block,
            });
        }
    }
    for (k, span) in prose.split('`').enumerate() {
        let span = span.replace('\n', " ");
        if k % 2 == 1
            && let Some(args) = run_args(&span)
        {
            shown.push(Shown {
                place: format!("{name} (`{}`)", span.trim()),
                args,
                flags_only: Some("shown in the text".to_owned()),
                block: 0,
            });
        }
    }
    shown
}

fn every_shown() -> Vec<Shown> {
    pages().iter().flat_map(|p| shown_in(p)).collect()
}

/// The shown command as the command line reads it; None for `--help`.
fn parsed(shown: &Shown) -> Option<Cli> {
    let argv = std::iter::once("rolypoly".to_owned()).chain(shown.args.iter().cloned());
    let parsed = Cli::try_parse_from(argv.clone());
    // `--help` and `--version` are shown as they are: clap answers them.
    if let Err(e) = &parsed
        && matches!(e.kind(), ErrorKind::DisplayHelp | ErrorKind::DisplayVersion)
    {
        return None;
    }
    Some(parsed.unwrap_or_else(|e| {
        panic!(
            "{}: `{RUN} {}` does not parse:\n{e}",
            shown.place,
            shown.args.join(" ")
        )
    }))
}

/// True when the command opens the window rather than finishing by itself.
fn opens_window(cli: &Cli) -> bool {
    match &cli.command {
        None => true,
        Some(Command::Replay(replay)) => replay.out.is_none(),
        Some(_) => false,
    }
}

/// `value` of a flag made no larger than the test runs.
fn shortened_value(flag: &str, value: &str) -> String {
    let number = |v: &str| v.parse::<f64>().ok();
    match flag {
        "--size" => match value
            .split_once('x')
            .map(|(w, h)| (w.parse::<u32>(), h.parse::<u32>()))
        {
            Some((Ok(w), Ok(h))) if w > MOST_WIDTH => {
                let h = (u64::from(h) * u64::from(MOST_WIDTH) / u64::from(w)).max(2) as u32;
                format!("{MOST_WIDTH}x{}", h + h % 2)
            }
            _ => value.to_owned(),
        },
        "--seconds" => match number(value) {
            Some(s) if s > MOST_SECONDS => MOST_SECONDS.to_string(),
            _ => value.to_owned(),
        },
        "--time" => match number(value) {
            Some(t) if t > MOST_TIME => MOST_TIME.to_string(),
            _ => value.to_owned(),
        },
        "--spp" => match value.parse::<u32>() {
            Ok(n) if n > MOST_SPP => MOST_SPP.to_string(),
            _ => value.to_owned(),
        },
        _ if OUTPUT_FLAGS.contains(&flag) => {
            // Into the scratch folder under its own name; a folder stays one.
            let name = Path::new(value)
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_else(|| value.to_owned());
            if value.ends_with('/') {
                format!("{name}/")
            } else {
                name
            }
        }
        _ => repository_input(value),
    }
}

/// A path into the repository (a shipped scene, an asset) read from there.
fn repository_input(value: &str) -> String {
    let path = Path::new(ROOT).join(value);
    let inside = ["scenes/", "assets/", "docs/", "examples/"]
        .iter()
        .any(|dir| value.starts_with(dir));
    if inside && path.exists() {
        path.display().to_string()
    } else {
        value.to_owned()
    }
}

/// The shown arguments made short: sizes, durations and samples capped,
/// outputs into the scratch folder, the repository's inputs read in place.
fn shortened(args: &[String]) -> Vec<String> {
    let mut out = Vec::new();
    // The flag the next word may be the value of.
    let mut flag: Option<&str> = None;
    for arg in args {
        if let Some((f, v)) = arg.split_once('=').filter(|_| arg.starts_with("--")) {
            out.push(format!("{f}={}", shortened_value(f, v)));
            flag = None;
        } else if arg.starts_with("--") {
            out.push(arg.clone());
            flag = Some(arg);
        } else if let Some(f) = flag.take() {
            out.push(shortened_value(f, arg));
        } else {
            out.push(repository_input(arg));
        }
    }
    out
}

/// A short recorded session of the default scene: the `.replay` file a
/// shown command plays (a user makes one with R in the window).
fn recorded_session() -> String {
    let shipped = &SHIPPED_SCENES[0];
    let scene = parse_scene(shipped.text, shipped.name).expect("the default scene parses");
    let mut sandbox = Sandbox::new(scene, shipped.name, 3).expect("the default scene builds");
    sandbox.start_recording();
    sandbox
        .throw(DVec3::new(0.0, 1.5, 3.0), DVec3::new(0.0, -0.1, -1.0))
        .expect("a throw");
    (0..30).for_each(|_| sandbox.tick());
    sandbox.stop_recording().expect("a recording").to_text()
}

/// Files a shown command reads that a user would have made first: a
/// recording, a scene file of their own.
fn make_inputs(args: &[String], scratch: &Path) {
    let mut after_output = false;
    for arg in args {
        let output = std::mem::take(&mut after_output);
        after_output = OUTPUT_FLAGS.contains(&arg.as_str());
        let path = scratch.join(arg);
        if output || arg.starts_with('-') || Path::new(arg).is_absolute() || path.exists() {
            continue;
        }
        if arg.ends_with(".replay") {
            std::fs::write(&path, recorded_session()).expect("a recording written");
        } else if arg.ends_with(".toml") {
            let default = SHIPPED_SCENES[0].text;
            std::fs::write(&path, default).expect("a scene file written");
        }
    }
}

/// An empty scratch folder for one block's commands.
fn scratch(block: &str) {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join("docs-commands")
        .join(block);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("a scratch folder");
}

#[test]
fn every_shown_command_parses() {
    let shown = every_shown();
    assert!(
        shown.len() > 20,
        "only {} commands found: the scan is broken",
        shown.len()
    );
    for command in &shown {
        parsed(command);
    }
}

#[test]
fn every_shown_command_that_is_run_works() {
    let mut ran = 0;
    let mut folders = std::collections::BTreeSet::new();
    for command in every_shown().iter().filter(|c| c.flags_only.is_none()) {
        let Some(cli) = parsed(command) else {
            continue;
        };
        assert!(
            !opens_window(&cli),
            "{}: `{RUN} {}` opens the window: put `{FLAGS_ONLY} opens a window -->` before its block",
            command.place,
            command.args.join(" ")
        );
        // The block's earlier commands wrote what a later one may read: a
        // block's folder is made afresh for its first command only.
        let page = command.place.split(':').next().unwrap_or("page");
        let block = format!("{}-{}", page.replace('/', "-"), command.block);
        if !folders.contains(&block) {
            scratch(&block);
            folders.insert(block.clone());
        }
        let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
            .join("docs-commands")
            .join(&block);
        let args = shortened(&command.args);
        make_inputs(&args, &dir);
        let output = Process::new(env!("CARGO_BIN_EXE_rolypoly"))
            .args(&args)
            .current_dir(&dir)
            .output()
            .expect("the rolypoly binary runs");
        assert!(
            output.status.success(),
            "{}: `{RUN} {}` (run as `rolypoly {}`) failed:\n{}",
            command.place,
            command.args.join(" "),
            args.join(" "),
            String::from_utf8_lossy(&output.stderr)
        );
        ran += 1;
    }
    assert!(ran > 10, "only {ran} commands ran: the scan is broken");
}

#[test]
fn every_page_runs_the_program_one_way() {
    let subcommands = [
        "simulate",
        "render",
        "record",
        "replay",
        "sound",
        "make-tumbler-obj",
        "shaders",
        "--",
    ];
    for page in pages() {
        let text = std::fs::read_to_string(&page).expect("a page is readable");
        for (n, line) in text.lines().enumerate() {
            for piece in line.split('`').map(str::trim) {
                let bare = piece.strip_prefix("rolypoly ").is_some_and(|rest| {
                    subcommands.iter().any(|s| rest.starts_with(s)) && rest.contains(" --")
                });
                assert!(
                    !bare,
                    "{}:{}: `{piece}`: write the command as `{RUN} ...`, as every page does",
                    page.display(),
                    n + 1
                );
                let bench = piece.starts_with("cargo bench") && piece.contains(" -- ");
                assert!(
                    !bench || piece.contains("--bench "),
                    "{}:{}: `{piece}` hands its flags to every bench target, the library's test harness too (which refuses them): name one with --bench",
                    page.display(),
                    n + 1
                );
            }
        }
    }
}

#[test]
fn the_scan_reads_what_a_page_shows() {
    assert_eq!(
        words(r#"render --camera=-1,2,3 --out "my frame.png" # a comment"#),
        ["render", "--camera=-1,2,3", "--out", "my frame.png"]
    );
    assert_eq!(run_args("cargo run --release"), Some(vec![]));
    assert_eq!(
        run_args("cargo run --release -p rolypoly-bench --bin figures"),
        None
    );
    let args = |s: &str| s.split(' ').map(str::to_owned).collect::<Vec<_>>();
    assert_eq!(
        shortened(&args(
            "render --size 1280x720 --time 10 --out docs/screenshot.png"
        )),
        args("render --size 160x90 --time 3 --out screenshot.png")
    );
    assert_eq!(
        shortened(&args("record --seconds 2.5 --out frames/")),
        args("record --seconds 1 --out frames/")
    );
    // A flag without a value before an output: the output still lands in
    // the scratch folder, never on the repository's own file.
    assert_eq!(
        shortened(&args("record --fireball --out docs/clip.gif")),
        args("record --fireball --out clip.gif")
    );
    let scene = shortened(&args("simulate --scene scenes/heap.toml"));
    assert!(scene[2].ends_with("/scenes/heap.toml") && Path::new(&scene[2]).is_absolute());
}
