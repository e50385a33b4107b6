//! Edits of a file's text that the fuzz tests make to real files: lines
//! dropped, doubled or swapped, a number replaced, a character replaced,
//! the text cut, something inserted. Shared by the scene, recording and
//! OBJ fuzzers, each of which finds the numbers of its own format.

/// One edit of a text.
#[derive(Clone, Debug)]
pub enum TextEdit {
    DeleteLine(usize),
    DuplicateLine(usize),
    /// Two lines swap places.
    SwapLines(usize, usize),
    /// The `k`-th number in the text becomes this.
    Number(usize, String),
    /// A character replaced at a place in the text.
    Char(usize, char),
    Truncate(usize),
    Insert(usize, String),
}

/// The char boundary at or before `at % (len + 1)`.
pub fn boundary(text: &str, at: usize) -> usize {
    let mut at = at % (text.len() + 1);
    while !text.is_char_boundary(at) {
        at -= 1;
    }
    at
}

/// `span` of `text` replaced by `with`.
pub fn splice(text: &str, (start, end): (usize, usize), with: &str) -> String {
    format!("{}{with}{}", &text[..start], &text[end..])
}

/// Lines joined back into a text, each ended by a newline.
pub fn joined(lines: &[&str]) -> String {
    lines.iter().map(|l| format!("{l}\n")).collect()
}

/// `text` with `edit` made; `numbers` are the byte spans of the numbers in
/// it, as its format writes them.
pub fn apply(text: &str, edit: &TextEdit, numbers: &[(usize, usize)]) -> String {
    let mut lines: Vec<&str> = text.lines().collect();
    let n = lines.len().max(1);
    match edit {
        TextEdit::DeleteLine(k) if !lines.is_empty() => {
            lines.remove(k % n);
            joined(&lines)
        }
        TextEdit::DuplicateLine(k) if !lines.is_empty() => {
            let k = k % n;
            lines.insert(k, lines[k]);
            joined(&lines)
        }
        TextEdit::SwapLines(a, b) if !lines.is_empty() => {
            lines.swap(a % n, b % n);
            joined(&lines)
        }
        TextEdit::Number(k, with) => match numbers.get(k % numbers.len().max(1)) {
            Some(&span) => splice(text, span, with),
            None => text.to_owned(),
        },
        TextEdit::Char(at, c) => {
            let at = boundary(text, *at);
            let end = text[at..]
                .chars()
                .next()
                .map_or(at, |old| at + old.len_utf8());
            splice(text, (at, end), &c.to_string())
        }
        TextEdit::Truncate(at) => text[..boundary(text, *at)].to_owned(),
        TextEdit::Insert(at, with) => {
            let at = boundary(text, *at);
            splice(text, (at, at), with)
        }
        _ => text.to_owned(),
    }
}
