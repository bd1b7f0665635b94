//! Scenes: a TOML file that describes a world (gravity, ground, wind, integrator, dt), its soft
//! bodies, rigid obstacles and timed events, and the runner that plays it.
//!
//! - [`spec`]: the file format (serde structs; unknown keys are errors), with [`actions`]: the
//!   timed actions and the keys each takes;
//! - [`build`]: turns a parsed file into bodies, obstacles and events, checking everything serde
//!   cannot (exactly one mesh source, regions, events in time order, …) with the line at fault;
//! - [`events`]: each event's values checked and resolved into what it does to a body;
//! - [`run`]: [`SceneRun`], which steps the world and fires the events on time.
//!
//! The core reads no files: mesh paths in a scene go through a resolver the caller provides
//! (the CLI reads them relative to the scene file; the modeler asks the user).
//! `docs/scenes.md` documents the format for users.

pub mod actions;
pub mod build;
pub mod events;
pub mod run;
pub mod save;
pub mod spec;

pub use run::SceneRun;
pub use spec::SceneSpec;

use std::fmt;

/// What is wrong with a scene, with the line (1-based) and key when known.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneError {
    pub line: Option<usize>,
    pub key: Option<String>,
    pub message: String,
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if let Some(l) = self.line {
            write!(f, "line {l}: ")?;
        }
        if let Some(k) = &self.key {
            write!(f, "{k}: ")?;
        }
        write!(f, "{}", self.message)
    }
}

impl std::error::Error for SceneError {}

impl SceneError {
    pub fn at(text: &str, span: Option<std::ops::Range<usize>>, key: Option<String>, message: impl Into<String>) -> Self {
        SceneError { line: span.map(|s| line_of(text, s.start)), key, message: message.into() }
    }
}

/// 1-based line of byte `offset` in `text`.
pub fn line_of(text: &str, offset: usize) -> usize {
    text.as_bytes()[..offset.min(text.len())].iter().filter(|&&b| b == b'\n').count() + 1
}

/// Parse scene text. Syntax errors, unknown keys and wrong types come back with the line and the
/// key's path (`body[0].stiffness`).
pub fn parse(text: &str) -> Result<SceneSpec, SceneError> {
    let de = toml::Deserializer::parse(text).map_err(|e| SceneError::at(text, e.span(), None, clean(e.message())))?;
    serde_path_to_error::deserialize(de).map_err(|e| {
        let path = e
            .path()
            .to_string()
            .split('.')
            .filter(|s| !s.contains("$__serde_spanned"))
            .collect::<Vec<_>>()
            .join(".");
        let key = if path.is_empty() || path == "?" { None } else { Some(path) };
        let message = clean(e.inner().message());
        // An event's action refused by serde (`actions::read`): said at its `action` key, as the
        // checks after parsing say theirs.
        if let (Some(k), Some(span)) = (&key, e.inner().span()) {
            if is_event(k) && !message.starts_with("missing field") {
                return build::Ctx::new(text, span.start, k.clone()).err("action", message);
            }
        }
        SceneError::at(text, e.inner().span(), key, message)
    })
}

/// Whether `path` is an event's table itself (`event[2]`), not one of its keys.
fn is_event(path: &str) -> bool {
    path.strip_prefix("event[").and_then(|r| r.strip_suffix(']')).is_some_and(|n| n.parse::<usize>().is_ok())
}

/// toml's messages end with a newline and name Rust types: say it in the file's terms.
fn clean(message: &str) -> String {
    message.trim().replace("expected f64", "expected a number").replace("expected u32", "expected a whole number ≥ 0")
}

/// Serialize a scene back to TOML (what the modeler saves).
pub fn to_toml(spec: &SceneSpec) -> Result<String, String> {
    toml::to_string_pretty(spec).map_err(|e| e.to_string())
}
