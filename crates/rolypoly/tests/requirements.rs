//! Every requirement tag a comment in the code names is defined in
//! docs/requirements.md.

use std::collections::BTreeSet;
use std::path::Path;

const ROOT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../..");

/// The requirement groups: the capitals the page's tags start with.
fn groups(page: &str) -> String {
    let mut groups: Vec<char> = defined(page)
        .iter()
        .filter_map(|tag| tag.chars().next())
        .collect();
    groups.dedup();
    groups.into_iter().collect()
}

/// The tags the requirements page defines: the first word of each table row.
fn defined(page: &str) -> BTreeSet<String> {
    page.lines()
        .filter_map(|l| l.strip_prefix("| "))
        .filter_map(|l| l.split(' ').next())
        .filter(|w| w.len() > 1 && w.starts_with(|c: char| c.is_ascii_uppercase()))
        .map(str::to_owned)
        .collect()
}

/// The tags a line's comment names: a capital of the requirement `groups`
/// and a number, standing alone (`P10`, the ends of `X1-X5`).
fn tags_in_comment(line: &str, groups: &str) -> Vec<String> {
    let Some(at) = line.find("//") else {
        return Vec::new();
    };
    let words: Vec<&str> = line[at + 2..]
        .split(|c: char| !c.is_ascii_alphanumeric())
        .filter(|w| !w.is_empty())
        .collect();
    // A function key (`the F3 key`, `key F12`) is no tag of group F.
    let is_key = |k: usize| {
        let key = |w: Option<&&str>| w.is_some_and(|w| w.eq_ignore_ascii_case("key"));
        key(k.checked_sub(1).and_then(|j| words.get(j))) || key(words.get(k + 1))
    };
    words
        .iter()
        .enumerate()
        .filter(|&(k, _)| !is_key(k))
        .map(|(_, w)| *w)
        .filter(|w| {
            let mut chars = w.chars();
            let group = chars.next().is_some_and(|c| groups.contains(c));
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
    let defined = defined(&page);
    let groups = groups(&page);
    let mut files = Vec::new();
    sources(&Path::new(ROOT).join("crates"), &mut files);
    let mut used = BTreeSet::new();
    let mut undefined = Vec::new();
    for file in &files {
        let text = std::fs::read_to_string(file).unwrap();
        for (n, line) in text.lines().enumerate() {
            for tag in tags_in_comment(line, &groups) {
                if !defined.contains(&tag) {
                    let place = file.strip_prefix(ROOT).unwrap_or(file).display();
                    undefined.push(format!("{place}:{}: `{tag}`", n + 1));
                }
                used.insert(tag);
            }
        }
    }
    assert!(
        undefined.is_empty(),
        "tags not in docs/requirements.md:\n{}",
        undefined.join("\n")
    );
    assert!(used.len() > 30, "only {used:?} found: the scan is broken");
    // Every group is read: a group no comment names is a scan that skips it.
    for group in groups.chars() {
        assert!(
            used.iter().any(|tag| tag.starts_with(group)),
            "no comment names a tag of group {group}: is the scan missing it?"
        );
    }
}

#[test]
fn tags_are_read_from_comments_only() {
    let page = std::fs::read_to_string(format!("{ROOT}/docs/requirements.md")).unwrap();
    let groups = groups(&page);
    for group in "SIPXRAELTFGJ".chars() {
        assert!(
            groups.contains(group),
            "group {group} is read from the page"
        );
    }
    assert_eq!(
        tags_in_comment("//! Trails (X2) and rings (X3-X5).", &groups),
        ["X2", "X3", "X5"]
    );
    assert!(tags_in_comment("let d = TextureDimension::D2; // no tag, Q12", &groups).is_empty());
    assert!(tags_in_comment("// the F12 key writes a screenshot", &groups).is_empty());
    assert!(tags_in_comment("// The profiler (key F3).", &groups).is_empty());
    assert!(tags_in_comment("format!(\"/tmp/.X11-unix\")", &groups).is_empty());
    assert_eq!(
        tags_in_comment("    /// Bit-identical (P10).", &groups),
        ["P10"]
    );
    assert_eq!(tags_in_comment("// The sound (J1).", &groups), ["J1"]);
}
