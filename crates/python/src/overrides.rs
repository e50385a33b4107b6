//! Scene overrides given as a dict of dotted keys
//! (`{"balls.count": 2000, "balls.friction": 0.5}`), read by the program's
//! own scene reader so that the same checks and messages apply.
//!
//! The program's own overrides cover three command-line options only, so
//! the dict is laid over the scene file's text instead: the file and the
//! overrides are merged as TOML and the merged text is read and checked as
//! one scene. A message that points at a line of the merged text is then
//! pointed back at where the value came from: the file's own line, or the
//! override (`overrides["balls.count"]`). Each override is first read on
//! its own, so that an unknown key or a value of the wrong type is named
//! as the override's fault before the file is looked at.

use std::collections::HashMap;
use std::ops::Range;

use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};
use rolypoly_core::scene::{BUILTIN_ORIGIN, Location, Scene, SceneError, line_of, parse_scene};
use toml::de::{DeTable, DeValue};
use toml::{Table, Value};

use crate::errors::value_error;

/// One override: its dotted key and its value as TOML.
pub struct Override {
    key: String,
    value: Value,
}

/// Reads a Python dict of dotted keys into overrides, in the dict's order.
pub fn from_dict(dict: Option<&Bound<'_, PyDict>>) -> PyResult<Vec<Override>> {
    let Some(dict) = dict else {
        return Ok(Vec::new());
    };
    let mut out = Vec::with_capacity(dict.len());
    for (key, value) in dict.iter() {
        let key: String = key.extract().map_err(|_| {
            value_error(format!(
                "overrides: the key {} is not a string; write keys as in a scene file, \
                 such as \"balls.count\"",
                key.repr().map_or_else(|_| "?".into(), |r| r.to_string())
            ))
        })?;
        if key.is_empty() || key.split('.').any(str::is_empty) {
            return Err(value_error(format!(
                "{}: not a dotted key such as \"balls.count\"",
                origin_of(&key)
            )));
        }
        let value =
            toml_value(&value).map_err(|why| value_error(format!("{}: {why}", origin_of(&key))))?;
        out.push(Override { key, value });
    }
    Ok(out)
}

/// How messages name the override of `key`.
pub fn origin_of(key: &str) -> String {
    format!("overrides[\"{key}\"]")
}

/// A Python value as TOML: booleans, numbers, strings, lists (tuples,
/// NumPy arrays) and dicts. Whether it suits its key is the reader's call.
fn toml_value(value: &Bound<'_, PyAny>) -> Result<Value, String> {
    if value.is_instance_of::<PyBool>() {
        return value
            .extract::<bool>()
            .map(Value::Boolean)
            .map_err(|e| e.to_string());
    }
    if value.is_instance_of::<PyFloat>() {
        return value
            .extract::<f64>()
            .map(Value::Float)
            .map_err(|e| e.to_string());
    }
    if value.is_instance_of::<PyInt>() {
        return value
            .extract::<i64>()
            .map(Value::Integer)
            .map_err(|_| format!("the whole number {value} does not fit in 64 bits"));
    }
    if let Ok(text) = value.cast::<PyString>() {
        return Ok(Value::String(text.to_string()));
    }
    if let Ok(dict) = value.cast::<PyDict>() {
        let mut table = Table::new();
        for (k, v) in dict.iter() {
            let k: String = k
                .extract()
                .map_err(|_| format!("the key {k} of a table is not a string"))?;
            table.insert(k, toml_value(&v)?);
        }
        return Ok(Value::Table(table));
    }
    if value.is_instance_of::<PyList>() || value.is_instance_of::<PyTuple>() {
        let items: Vec<Bound<'_, PyAny>> = value.extract().map_err(|e: PyErr| e.to_string())?;
        return items
            .iter()
            .map(toml_value)
            .collect::<Result<_, _>>()
            .map(Value::Array);
    }
    // NumPy arrays and scalars say what they are through `tolist`.
    if let Ok(plain) = value.call_method0("tolist")
        && !plain.is(value)
    {
        return toml_value(&plain);
    }
    let kind = value
        .get_type()
        .name()
        .map_or_else(|_| "?".into(), |n| n.to_string());
    Err(format!(
        "a value of type `{kind}` has no place in a scene file: give a number, a string, \
         a boolean, a list or a dict"
    ))
}

/// `source` (a scene file's text, or none for the default scene) with
/// `overrides` laid over it, read and checked as the program reads a scene
/// file named `origin`.
pub fn scene_with(
    source: Option<&str>,
    origin: &str,
    overrides: &[Override],
) -> Result<Scene, SceneError> {
    // Each override alone: an unknown key or a value of the wrong type is
    // its own fault whatever the file says. Its range is checked below,
    // against the merged scene, where the ranges that depend on other keys
    // hold.
    for o in overrides {
        let mut alone = Table::new();
        insert_at(&mut alone, &o.key, o.value.clone()).map_err(|e| syntax(&o.key, e))?;
        let text = toml::to_string(&alone).map_err(|e| syntax(&o.key, e.to_string()))?;
        if let Err(error @ SceneError::Syntax { .. }) = parse_scene(&text, BUILTIN_ORIGIN) {
            return Err(blame(error, &o.key));
        }
    }
    // The file alone: its own malformed TOML or unknown key is reported as
    // the program reports it. A range error may be mended by an override,
    // so it waits for the merged scene.
    let (mut table, file) = match source {
        None => (Table::new(), HashMap::new()),
        Some(source) => {
            if let Err(error @ SceneError::Syntax { .. }) = parse_scene(source, origin) {
                return Err(error);
            }
            let root = DeTable::parse(source).map_err(|e| syntax_at(origin, e.message()))?;
            (plain_table(root.get_ref()), file_keys(source))
        }
    };
    for o in overrides {
        insert_at(&mut table, &o.key, o.value.clone()).map_err(|e| syntax(&o.key, e))?;
    }
    let merged = toml::to_string(&table).map_err(|e| syntax_at(origin, &e.to_string()))?;
    let origin_here = if source.is_some() {
        origin
    } else {
        BUILTIN_ORIGIN
    };
    parse_scene(&merged, origin_here).map_err(|error| {
        let merged_paths = paths_by_line(&merged);
        point_back(error, &merged_paths, &file, overrides)
    })
}

/// A problem of the override `key` itself.
fn syntax(key: &str, message: String) -> SceneError {
    SceneError::Syntax {
        at: Location {
            origin: origin_of(key),
            line: None,
        },
        message,
    }
}

fn syntax_at(origin: &str, message: &str) -> SceneError {
    SceneError::Syntax {
        at: Location {
            origin: origin.to_owned(),
            line: None,
        },
        message: message.to_owned(),
    }
}

/// `error` blamed on the override of `key`.
fn blame(mut error: SceneError, key: &str) -> SceneError {
    if let Some(at) = location(&mut error) {
        *at = Location {
            origin: origin_of(key),
            line: None,
        };
    }
    error
}

fn location(error: &mut SceneError) -> Option<&mut Location> {
    match error {
        SceneError::Syntax { at, .. }
        | SceneError::OutOfRange { at, .. }
        | SceneError::Invalid { at, .. } => Some(at),
        SceneError::Read { .. } => None,
    }
}

/// The key an error names, if it names one.
fn key_of(error: &SceneError) -> Option<String> {
    match error {
        SceneError::OutOfRange { key, .. } | SceneError::Invalid { key, .. } => Some(key.clone()),
        _ => None,
    }
}

/// Points an error about the merged text back at the file's line or at
/// the override the value came from.
fn point_back(
    mut error: SceneError,
    merged_paths: &HashMap<usize, Vec<String>>,
    file: &HashMap<String, Written>,
    overrides: &[Override],
) -> SceneError {
    let named = key_of(&error);
    let Some(line) = location(&mut error).and_then(|at| at.line) else {
        // A default the file did not give, or the scene as a whole.
        return error;
    };
    // Where to look, most precise first: the keys on the line that lie
    // under the key the message names (a list entry's own key), that key,
    // then whatever else the line holds.
    let on_line: &[String] = merged_paths.get(&line).map_or(&[], Vec::as_slice);
    let under = |p: &&String| named.as_deref().is_some_and(|key| within(p, key));
    let mut paths: Vec<&str> = on_line.iter().filter(under).map(String::as_str).collect();
    paths.extend(named.as_deref());
    paths.extend(on_line.iter().filter(|p| !under(p)).map(String::as_str));
    let overridden = overrides
        .iter()
        .rev()
        .find(|o| paths.iter().any(|p| within(p, &o.key)));
    let Some(o) = overridden else {
        let found = paths.iter().find_map(|p| file.get(*p));
        if let Some(at) = location(&mut error) {
            at.line = found.map(|w| w.line);
        }
        // A number as the file wrote it (`1e400`, `2_000_000`), as the
        // program shows it, not as TOML wrote it back.
        if let SceneError::OutOfRange { key, value, .. } = &mut error
            && let Some(text) = file.get(key.as_str()).and_then(|w| w.number.as_ref())
        {
            *value = text.clone();
        }
        return error;
    };
    // The value as the dict gave it, not as long as TOML spells it.
    if let SceneError::OutOfRange { key, value, .. } = &mut error
        && *key == o.key
    {
        *value = short_text(&o.value);
    }
    blame(error, &o.key)
}

/// A value as short as it reads: `1e308`, not its 309 digits.
fn short_text(value: &Value) -> String {
    match value {
        Value::Float(x) => format!("{x:?}"),
        Value::Array(items) => {
            let items: Vec<String> = items.iter().map(short_text).collect();
            format!("[{}]", items.join(", "))
        }
        other => other.to_string(),
    }
}

/// Whether `path` (`tumblers.placement[1].x`) lies at or under `key`.
fn within(path: &str, key: &str) -> bool {
    path.strip_prefix(key)
        .is_some_and(|rest| rest.is_empty() || rest.starts_with('.') || rest.starts_with('['))
}

/// `table` with `value` at the dotted `key`, making the tables on the way.
fn insert_at(table: &mut Table, key: &str, value: Value) -> Result<(), String> {
    let (head, leaf) = match key.rsplit_once('.') {
        Some((head, leaf)) => (Some(head), leaf),
        None => (None, key),
    };
    let mut here = table;
    let mut walked = String::new();
    for part in head.into_iter().flat_map(|h| h.split('.')) {
        if !walked.is_empty() {
            walked.push('.');
        }
        walked.push_str(part);
        let entry = here
            .entry(part.to_owned())
            .or_insert_with(|| Value::Table(Table::new()));
        here = match entry {
            Value::Table(inner) => inner,
            _ => return Err(format!("`{walked}` holds a value, not a table of keys")),
        };
    }
    here.insert(leaf.to_owned(), value);
    Ok(())
}

/// Where a key of a file is written: its line, and for a key of one
/// number, the number's text.
pub struct Written {
    line: usize,
    number: Option<String>,
}

/// Every key path of a TOML text (`balls.count`, `balls.placement[1]`,
/// `balls.placement[1].position`), where it is written.
fn key_paths(source: &str) -> Vec<(String, Written)> {
    let mut out = Vec::new();
    if let Ok(root) = DeTable::parse(source) {
        walk(root.get_ref(), "", source, &mut out);
    }
    out
}

fn walk(table: &DeTable<'_>, prefix: &str, source: &str, out: &mut Vec<(String, Written)>) {
    for (name, value) in table {
        let path = if prefix.is_empty() {
            name.get_ref().to_string()
        } else {
            format!("{prefix}.{}", name.get_ref())
        };
        let number = match value.get_ref() {
            DeValue::Integer(_) | DeValue::Float(_) => {
                source.get(value.span()).map(|t| t.trim().to_owned())
            }
            _ => None,
        };
        let line = line_of(source, name.span().start);
        out.push((path.clone(), Written { line, number }));
        match value.get_ref() {
            DeValue::Table(inner) => walk(inner, &path, source, out),
            DeValue::Array(items) => {
                for (i, item) in items.iter().enumerate() {
                    let entry = format!("{path}[{i}]");
                    if let Some(line) = line_at(source, item.span()) {
                        out.push((entry.clone(), Written { line, number: None }));
                    }
                    if let DeValue::Table(inner) = item.get_ref() {
                        walk(inner, &entry, source, out);
                    }
                }
            }
            _ => {}
        }
    }
}

fn line_at(source: &str, span: Range<usize>) -> Option<usize> {
    (span.end > span.start).then(|| line_of(source, span.start))
}

/// Key path -> where the file writes it (the first line, where a list's
/// entry is written over several).
fn file_keys(source: &str) -> HashMap<String, Written> {
    let mut keys = HashMap::new();
    for (path, written) in key_paths(source) {
        keys.entry(path).or_insert(written);
    }
    keys
}

/// Line -> the key paths written on it, the deepest first.
fn paths_by_line(source: &str) -> HashMap<usize, Vec<String>> {
    let mut by_line: HashMap<usize, Vec<String>> = HashMap::new();
    for (path, written) in key_paths(source) {
        by_line.entry(written.line).or_default().push(path);
    }
    for paths in by_line.values_mut() {
        paths.sort_by_key(|p| std::cmp::Reverse(p.len()));
    }
    by_line
}

/// A parsed file as plain TOML values, its numbers read as the scene reader
/// reads them: a float too large for 64 bits is infinite, not an error.
fn plain_table(table: &DeTable<'_>) -> Table {
    table
        .iter()
        .map(|(name, value)| (name.get_ref().to_string(), plain_value(value.get_ref())))
        .collect()
}

fn plain_value(value: &DeValue<'_>) -> Value {
    match value {
        DeValue::String(text) => Value::String(text.to_string()),
        DeValue::Integer(n) => match i64::from_str_radix(n.as_str(), n.radix()) {
            Ok(n) => Value::Integer(n),
            // Past 64 bits: the reader takes it as a real number, or
            // refuses it for a count either way.
            Err(_) => Value::Float(n.as_str().parse().unwrap_or(f64::INFINITY)),
        },
        DeValue::Float(x) => Value::Float(x.as_str().parse().unwrap_or(f64::NAN)),
        DeValue::Boolean(b) => Value::Boolean(*b),
        DeValue::Datetime(d) => Value::Datetime(*d),
        DeValue::Array(items) => {
            Value::Array(items.iter().map(|i| plain_value(i.get_ref())).collect())
        }
        DeValue::Table(inner) => Value::Table(plain_table(inner)),
    }
}
