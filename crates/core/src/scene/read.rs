//! Reads a scene file over a scene: walks the file's tables against the
//! table of keys, writes each value it finds where its key says, and notes
//! the line of every key it sets, so that a later range error can point at
//! it. A key the table does not know, or a value of the wrong type, is an
//! error that names the key's full path.

use std::collections::HashMap;
use std::ops::Range;

use glam::DVec3;
use serde::de::{Error as _, Unexpected};
use toml::Spanned;
use toml::de::{DeTable, DeValue};

use super::keys::{Allowed, KEYS, Key, Place, Slot, key};
use super::{Location, Scene, SceneError, line_of};

/// What a value should have been, in the words of a scene file.
pub(super) const A_NUMBER: &str = "a number";
const A_WHOLE_NUMBER: &str = "a whole number";
const A_TABLE: &str = "a table of keys";
const THREE_NUMBERS: &str = "an array of length 3";

/// A file being read: its text, its name for messages, and what was noted
/// of the keys set so far.
pub(super) struct Reader<'a> {
    pub(super) source: &'a str,
    pub(super) origin: &'a str,
    /// Key path -> the line that set it.
    pub(super) lines: HashMap<String, usize>,
    /// Key path -> its value as written, for the keys set one value each.
    pub(super) written: HashMap<String, String>,
}

impl<'a> Reader<'a> {
    pub(super) fn new(source: &'a str, origin: &'a str) -> Self {
        Reader {
            source,
            origin,
            lines: HashMap::new(),
            written: HashMap::new(),
        }
    }

    /// Parses the whole file and lays every key it sets over `scene`.
    pub(super) fn read(&mut self, scene: &mut Scene) -> Result<(), SceneError> {
        let root = DeTable::parse(self.source).map_err(|e| self.syntax(&e, None))?;
        self.table(root.get_ref(), "", scene)
    }

    pub(super) fn note(&mut self, key: &str, span: Range<usize>) {
        self.lines
            .insert(key.to_owned(), line_of(self.source, span.start));
    }

    /// [`Self::note`], keeping the text of the value as well: a number too
    /// large for its key's type is shown as written, not as `inf`.
    pub(super) fn note_written(&mut self, key: &str, span: Range<usize>) {
        if let Some(text) = self.source.get(span.clone()) {
            self.written.insert(key.to_owned(), text.trim().to_owned());
        }
        self.note(key, span);
    }

    /// The error for a problem of the file's shape at `span`.
    pub(super) fn shape_error(&self, span: Range<usize>, message: String) -> SceneError {
        SceneError::Syntax {
            at: Location {
                origin: self.origin.to_owned(),
                line: Some(line_of(self.source, span.start)),
            },
            message,
        }
    }

    /// A TOML error as a scene error; `list` names the list key whose entry
    /// it came from, to give an unknown key its full path.
    pub(super) fn syntax(&self, error: &toml::de::Error, list: Option<&str>) -> SceneError {
        let line = error.span().map(|span| line_of(self.source, span.start));
        // toml's messages are one line per fact; keep them on one line.
        let message = error
            .message()
            .lines()
            .map(str::trim)
            .filter(|l| !l.is_empty())
            .collect::<Vec<_>>()
            .join("; ")
            .replacen("missing field", "missing key", 1);
        let message = match (list, message.strip_prefix("unknown field `")) {
            (Some(list), Some(rest)) => format!("unknown key `{list}.{rest}"),
            _ => message,
        };
        SceneError::Syntax {
            at: Location {
                origin: self.origin.to_owned(),
                line,
            },
            message: in_scene_words(&message),
        }
    }

    /// Every entry of the table at `path` (`""` for the top level).
    fn table(&mut self, table: &DeTable, path: &str, scene: &mut Scene) -> Result<(), SceneError> {
        for (name, value) in table {
            let full = if path.is_empty() {
                name.get_ref().to_string()
            } else {
                format!("{path}.{}", name.get_ref())
            };
            if let Some(key) = key(&full) {
                self.value(key, value, scene)?;
            } else if is_table(&full) {
                match value.get_ref() {
                    DeValue::Table(inner) => self.table(inner, &full, scene)?,
                    other => return Err(self.wrong_type(value.span(), other, A_TABLE)),
                }
            } else {
                let known = names_in(path)
                    .map(|n| format!("`{n}`"))
                    .collect::<Vec<_>>()
                    .join(", ");
                return Err(self.shape_error(
                    name.span(),
                    format!("unknown key `{full}`, expected one of {known}"),
                ));
            }
        }
        Ok(())
    }

    /// Writes `value` where `key` says, converted to the key's type.
    fn value(
        &mut self,
        key: &Key,
        value: &Spanned<DeValue>,
        scene: &mut Scene,
    ) -> Result<(), SceneError> {
        let span = value.span();
        match &key.slot {
            Slot::Real(place) => put(place, scene, self.number(value)?),
            Slot::Single(place) => put(place, scene, self.number(value)? as f32),
            Slot::Count(place) => put(place, scene, self.count(key, value)?),
            Slot::Switch(place) => match value.get_ref() {
                DeValue::Boolean(b) => put(place, scene, *b),
                other => return Err(self.wrong_type(span, other, "a boolean")),
            },
            Slot::Vector(place) => put(place, scene, DVec3::from_array(self.three(value)?)),
            Slot::Color(place) => put(place, scene, self.three(value)?.map(|x| x as f32)),
            Slot::Word(place) => match value.get_ref() {
                DeValue::String(name) if place.names.contains(&name.as_ref()) => {
                    (place.write)(scene, name);
                }
                DeValue::String(name) => {
                    let problem = format!(
                        "`{name}` is not allowed: expected one of {}",
                        place.names.join(", ")
                    );
                    return Err(self.shape_error(span, format!("{}: {problem}", key.name)));
                }
                other => return Err(self.wrong_type(span, other, "a string")),
            },
            Slot::List(list) => return self.list(*list, key.name, value, scene),
        }
        self.note_written(key.name, span);
        Ok(())
    }

    /// A number; a whole number is taken for a real one.
    pub(super) fn number(&self, value: &Spanned<DeValue>) -> Result<f64, SceneError> {
        let parsed = match value.get_ref() {
            DeValue::Float(x) => x.as_str().parse().ok(),
            DeValue::Integer(n) if n.radix() == 10 => n.as_str().parse().ok(),
            DeValue::Integer(n) => i64::from_str_radix(n.as_str(), n.radix())
                .ok()
                .map(|n| n as f64),
            other => return Err(self.wrong_type(value.span(), other, A_NUMBER)),
        };
        parsed.ok_or_else(|| self.shape_error(value.span(), "the number cannot be read".into()))
    }

    /// A whole number that fits the key's type; one that does not is out
    /// of the key's range.
    fn count(&self, key: &Key, value: &Spanned<DeValue>) -> Result<usize, SceneError> {
        let DeValue::Integer(n) = value.get_ref() else {
            return Err(self.wrong_type(value.span(), value.get_ref(), A_WHOLE_NUMBER));
        };
        i64::from_str_radix(n.as_str(), n.radix())
            .ok()
            .and_then(|n| usize::try_from(n).ok())
            .ok_or_else(|| {
                let written = self.source.get(value.span()).unwrap_or_default().trim();
                SceneError::OutOfRange {
                    at: Location {
                        origin: self.origin.to_owned(),
                        line: Some(line_of(self.source, value.span().start)),
                    },
                    key: key.name.to_owned(),
                    value: written.to_owned(),
                    allowed: match key.allowed {
                        Allowed::Within(bounds) => bounds.to_string(),
                        _ => "a whole number >= 0".into(),
                    },
                }
            })
    }

    /// Three numbers, `[x, y, z]`.
    pub(super) fn three(&self, value: &Spanned<DeValue>) -> Result<[f64; 3], SceneError> {
        let DeValue::Array(items) = value.get_ref() else {
            return Err(self.wrong_type(value.span(), value.get_ref(), THREE_NUMBERS));
        };
        if items.len() != 3 {
            let message = serde::de::value::Error::invalid_length(items.len(), &THREE_NUMBERS);
            return Err(self.shape_error(value.span(), message.to_string()));
        }
        let mut out = [0.0; 3];
        for (x, item) in out.iter_mut().zip(items.iter()) {
            *x = self.number(item)?;
        }
        Ok(out)
    }

    /// "invalid type: string "x", expected a number", at `span`.
    pub(super) fn wrong_type(
        &self,
        span: Range<usize>,
        found: &DeValue,
        expected: &str,
    ) -> SceneError {
        let unexpected = match found {
            DeValue::String(s) => Unexpected::Str(s),
            DeValue::Integer(n) => i64::from_str_radix(n.as_str(), n.radix())
                .map_or(Unexpected::Other("integer"), Unexpected::Signed),
            DeValue::Float(x) => x
                .as_str()
                .parse()
                .map_or(Unexpected::Other("floating point"), Unexpected::Float),
            DeValue::Boolean(b) => Unexpected::Bool(*b),
            DeValue::Datetime(_) => Unexpected::Other("date-time"),
            DeValue::Array(_) => Unexpected::Seq,
            DeValue::Table(_) => Unexpected::Map,
        };
        let message = serde::de::value::Error::invalid_type(unexpected, &expected);
        self.shape_error(span, in_scene_words(&message.to_string()))
    }
}

fn put<T>(place: &Place<T>, scene: &mut Scene, value: T) {
    *(place.write)(scene) = value;
}

/// Whether `path` names a table of keys (such as `room.colors`).
fn is_table(path: &str) -> bool {
    KEYS.iter().any(|k| {
        k.name.len() > path.len()
            && k.name.starts_with(path)
            && k.name[path.len()..].starts_with('.')
    })
}

/// The names a table at `path` may hold, in the order of the table of keys.
fn names_in(path: &str) -> impl Iterator<Item = &'static str> {
    let prefix = if path.is_empty() {
        String::new()
    } else {
        format!("{path}.")
    };
    let mut seen: Vec<&'static str> = Vec::new();
    for key in KEYS {
        if let Some(rest) = key.name.strip_prefix(prefix.as_str()) {
            let name = rest.split('.').next().unwrap_or(rest);
            if !seen.contains(&name) {
                seen.push(name);
            }
        }
    }
    seen.into_iter()
}

/// Says what a value should have been in the words of a TOML scene file,
/// not of the program that reads it: "expected f64" becomes "expected a
/// number", "expected struct FileSphere" "expected a table of keys".
fn in_scene_words(message: &str) -> String {
    let Some((head, expected)) = message.rsplit_once("expected ") else {
        return message.to_owned();
    };
    let plain = match expected {
        "f64" | "f32" => A_NUMBER,
        "i64" | "u64" | "u32" | "usize" => A_WHOLE_NUMBER,
        "a sequence" => "an array",
        "a map" => A_TABLE,
        struct_name if struct_name.starts_with("struct ") => A_TABLE,
        _ => return message.to_owned(),
    };
    format!("{head}expected {plain}")
}
