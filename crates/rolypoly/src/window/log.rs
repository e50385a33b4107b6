//! `--log-events`: one JSON object per line on standard output for every
//! change of state, so that a person's session (or a test driving the
//! window) can be followed and checked.

use serde_json::{Value, json};
use std::io::Write;

pub struct EventLog {
    enabled: bool,
}

impl EventLog {
    pub fn new(enabled: bool) -> EventLog {
        EventLog { enabled }
    }

    /// Writes `{"event": name, ...fields}`.
    pub fn say(&self, name: &str, fields: Value) {
        if !self.enabled {
            return;
        }
        let mut line = json!({ "event": name });
        if let (Some(line), Value::Object(fields)) = (line.as_object_mut(), fields) {
            line.extend(fields);
        }
        let mut out = std::io::stdout().lock();
        let _ = writeln!(out, "{line}");
        let _ = out.flush();
    }
}
