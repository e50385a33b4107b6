//! What a newcomer finds first: the licences, the changelog and the guide
//! for contributors are there, and no text in the repository points at
//! something outside it (a document it does not hold, a machine's folders,
//! the circumstances of one measurement).

use std::path::{Path, PathBuf};

mod pages;

use pages::{ROOT, pages};

/// Words that point outside the repository, each with what to write
/// instead. Built from pieces so that this file does not match itself.
fn outside_words() -> Vec<(String, &'static str)> {
    vec![
        (
            ["SP", "EC"].concat(),
            "the requirement tags live in docs/requirements.md: name the tag alone",
        ),
        (
            ["the re", "port"].concat(),
            "there is no report in the repository: say what the thing is",
        ),
        (
            ["at ", "hand"].concat(),
            "say what was measured and on what, not what was missing",
        ),
        (
            ["this ", "machine"].concat(),
            "name the machine a figure was measured on (cores, adapter)",
        ),
        (
            ["virtual ", "machine"].concat(),
            "name the machine a figure was measured on (cores, adapter)",
        ),
        (["/wo", "rk/"].concat(), "a folder of one machine"),
        (["/ho", "me/"].concat(), "a folder of one machine"),
        (["/tmp/", "g"].concat(), "a folder of one machine"),
    ]
}

/// True when `word` stands in `line` as a word of its own (so that
/// `BALL_SPECULAR` is not `SPEC`), case-insensitively for lower-case words.
fn stands_in(line: &str, word: &str) -> bool {
    let (line, word) = if word.chars().any(char::is_uppercase) {
        (line.to_owned(), word.to_owned())
    } else {
        (line.to_lowercase(), word.to_lowercase())
    };
    let is_word = |c: char| c.is_alphanumeric() || c == '_';
    line.match_indices(&word).any(|(at, _)| {
        let before = line[..at].chars().next_back();
        let after = line[at + word.len()..].chars().next();
        let starts = word.starts_with(is_word);
        let ends = word.ends_with(is_word);
        let joined_before = starts && before.is_some_and(is_word);
        let joined_after = ends && after.is_some_and(is_word);
        !(joined_before || joined_after)
    })
}

/// The repository's text files: its sources, pages, scenes and scripts.
fn text_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).expect("a readable folder") {
        let path = entry.expect("a folder entry").path();
        let name = path.file_name().unwrap_or_default().to_string_lossy();
        if path.is_dir() {
            if !(name.starts_with('.') && name != ".ci")
                && name != "target"
                && name != "__pycache__"
            {
                text_files(&path, out);
            }
            continue;
        }
        let text_kind = path.extension().is_none_or(|e| {
            [
                "rs", "wgsl", "md", "toml", "py", "pyi", "txt", "sh", "yml", "ipynb", "csv",
            ]
            .contains(&e.to_string_lossy().as_ref())
        });
        // This file holds the words it looks for, as examples of its scan.
        let this_test = path.ends_with("crates/rolypoly/tests/front_door.rs");
        if text_kind && name != "Cargo.lock" && !this_test {
            out.push(path);
        }
    }
}

#[test]
fn no_text_points_outside_the_repository() {
    let mut files = Vec::new();
    text_files(Path::new(ROOT), &mut files);
    assert!(
        files.len() > 100,
        "only {} files: the scan is broken",
        files.len()
    );
    let words = outside_words();
    let mut found = Vec::new();
    for file in &files {
        // Text files only: a binary without an extension is skipped.
        let Ok(text) = std::fs::read_to_string(file) else {
            continue;
        };
        for (n, line) in text.lines().enumerate() {
            for (word, instead) in &words {
                if stands_in(line, word) {
                    let place = file
                        .strip_prefix(ROOT)
                        .unwrap_or(file)
                        .display()
                        .to_string();
                    found.push(format!("{place}:{}: \"{word}\": {instead}", n + 1));
                }
            }
        }
    }
    assert!(found.is_empty(), "{}", found.join("\n"));
}

#[test]
fn the_scan_finds_words_not_parts_of_words() {
    let spec = ["SP", "EC"].concat();
    assert!(stands_in(&format!("(as {spec} A4 says)"), &spec));
    assert!(!stands_in("override BALL_SPECULAR: f32;", &spec));
    assert!(stands_in(
        "As The Report says",
        &["the re", "port"].concat()
    ));
    assert!(!stands_in(
        "the reporting of events",
        &["the re", "port"].concat()
    ));
    assert!(stands_in("cd /work/main", &["/wo", "rk/"].concat()));
    assert!(!stands_in("/tmp/.X11-unix/X9", &["/tmp/", "g"].concat()));
}

#[test]
fn the_licences_changelog_and_contributing_guide_are_there() {
    let read = |name: &str| {
        std::fs::read_to_string(Path::new(ROOT).join(name))
            .unwrap_or_else(|e| panic!("{name} is missing ({e})"))
    };
    assert!(read("LICENSE-MIT").contains("Permission is hereby granted"));
    assert!(read("LICENSE-APACHE").contains("Apache License"));
    let changelog = read("CHANGELOG.md");
    assert!(
        changelog.contains("## [Unreleased]"),
        "Keep a Changelog's form"
    );
    assert!(read("CONTRIBUTING.md").contains(".ci/run"));
    let manifest = read("Cargo.toml");
    assert!(manifest.contains("license = \"MIT OR Apache-2.0\""));
}

#[test]
fn every_page_is_linked_from_the_readme() {
    let readme = std::fs::read_to_string(Path::new(ROOT).join("README.md")).expect("README.md");
    for page in pages().iter().skip(1) {
        let name = page.file_name().unwrap_or_default().to_string_lossy();
        assert!(
            readme.contains(&format!("(docs/{name}")),
            "README.md links no docs/{name}"
        );
    }
}
