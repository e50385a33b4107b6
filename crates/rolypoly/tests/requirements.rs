//! Every requirement tag a comment in the code names is defined in
//! docs/requirements.md.

use std::collections::BTreeSet;
use std::path::Path;

const ROOT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../..");

/// The tags a line's comment names: a capital of the requirement groups and
/// a number, standing alone (`P10`, the ends of `X1-X5`).
fn tags_in_comment(line: &str) -> Vec<String> {
    let Some(at) = line.find("//") else {
        return Vec::new();
    };
    let words = line[at + 2..].split(|c: char| !c.is_ascii_alphanumeric());
    words
        .filter(|w| {
            let mut chars = w.chars();
            let group = chars.next().is_some_and(|c| "SIPXRAELT".contains(c));
            let number = chars.as_str();
            group && (1..=2).contains(&number.len()) && number.bytes().all(|b| b.is_ascii_digit())
        })
        .map(str::to_owned)
        .collect()
}

fn sources(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap().map(Result::unwrap) {
        let path = entry.path();
        if path.is_dir() {
            sources(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs" || e == "wgsl") {
            out.push(path);
        }
    }
}

#[test]
fn every_tag_in_the_code_is_defined_in_the_requirements_page() {
    let page = std::fs::read_to_string(format!("{ROOT}/docs/requirements.md")).unwrap();
    let defined: BTreeSet<String> = page
        .lines()
        .filter_map(|l| l.strip_prefix("| "))
        .filter_map(|l| l.split(' ').next())
        .map(str::to_owned)
        .collect();
    let mut files = Vec::new();
    sources(&Path::new(ROOT).join("crates"), &mut files);
    let mut used = BTreeSet::new();
    for file in &files {
        let text = std::fs::read_to_string(file).unwrap();
        for (n, line) in text.lines().enumerate() {
            for tag in tags_in_comment(line) {
                assert!(
                    defined.contains(&tag),
                    "{}:{}: `{tag}` is not in docs/requirements.md",
                    file.display(),
                    n + 1
                );
                used.insert(tag);
            }
        }
    }
    assert!(used.len() > 30, "only {used:?} found: the scan is broken");
}

#[test]
fn tags_are_read_from_comments_only() {
    assert_eq!(
        tags_in_comment("//! Trails (X2) and rings (X3-X5)."),
        ["X2", "X3", "X5"]
    );
    assert!(tags_in_comment("let d = TextureDimension::D2; // no tag, F12").is_empty());
    assert!(tags_in_comment("format!(\"/tmp/.X11-unix\")").is_empty());
    assert_eq!(tags_in_comment("    /// Bit-identical (P10)."), ["P10"]);
}
