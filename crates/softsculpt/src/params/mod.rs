//! Every user-visible parameter, defined once: id (the scene-file key), scope, unit, default,
//! valid range and a one-line help text ([`table`]). The CLI's flags and help, the scene
//! format's defaults, `Material::default()` and `WorldSettings::default()` read it; the binding
//! can hand it to the page as JSON ([`table_json`]); `docs/parameters.md` and the page's
//! `web/src/engine/params.ts` are generated from it ([`markdown`], [`typescript::typescript`],
//! checked by a test). Inside the core a parameter is named by its typed [`ParamId`].
//!
//! Get and set by id: [`crate::world::World::param`] and [`crate::world::World::set_param`]
//! (`world/params.rs`) route body parameters to a body's material and world parameters to the
//! world's settings, checking the range with a message that names the parameter and its unit.
//! The parameters that are plain fields are listed once beside their struct ([`field::Field`]:
//! `Material::FIELDS`, `WorldSettings::FIELDS`, `Ground::FIELDS`), which get, set and
//! validation all read.
//! This module is plain data and pure functions: it imports nothing of bodies or worlds, which
//! read it for their defaults (`tests/layers.rs`).

pub mod field;
pub mod presets;
pub mod similarity;
pub mod table;
pub mod typescript;

pub use table::*;

use serde::Serialize;

/// Whose parameter it is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Scope {
    /// A body's material (or mass, or gas reference): each body has its own.
    Body,
    /// The world's settings: every body shares them.
    World,
    /// A scene file's run (not part of a world).
    Scene,
    /// Each rigid obstacle of a scene file.
    Obstacle,
}

/// A parameter's value.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(untagged)]
pub enum Value {
    Number(f64),
    Vector([f64; 3]),
    /// One of a fixed set of names (the integrator, the volume mode).
    Choice(&'static str),
    Flag(bool),
}

/// Valid values of a number (or of each component of a vector): `min ≤ v ≤ max`, or
/// `min < v` when `min_open`; always finite.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Range {
    pub min: f64,
    pub max: f64,
    pub min_open: bool,
}

impl Range {
    pub fn contains(&self, v: f64) -> bool {
        v.is_finite() && v <= self.max && if self.min_open { v > self.min } else { v >= self.min }
    }
    /// "≥ 0", "> 0", "between 0 and 1", "finite".
    pub fn describe(&self) -> String {
        match (self.min.is_finite(), self.max.is_finite()) {
            (true, true) => format!("between {} and {}", self.min, self.max),
            (true, false) => format!("{} {}", if self.min_open { ">" } else { "≥" }, self.min),
            (false, true) => format!("≤ {}", self.max),
            (false, false) => "finite".into(),
        }
    }
}

/// One user-visible parameter.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Param {
    /// snake_case, the scene-file key (`gas.amount` is `amount` in a body's `gas` table).
    pub id: &'static str,
    pub scope: Scope,
    /// SI unit ("" for dimensionless, flags and choices).
    pub unit: &'static str,
    pub default: Value,
    pub range: Range,
    pub help: &'static str,
}

impl Param {
    /// The default of a number parameter (a compile-time error in a const if it is not one).
    pub const fn number(&self) -> f64 {
        match self.default {
            Value::Number(x) => x,
            _ => panic!("not a number parameter"),
        }
    }
    pub const fn flag(&self) -> bool {
        match self.default {
            Value::Flag(x) => x,
            _ => panic!("not a flag parameter"),
        }
    }
    pub const fn vector(&self) -> [f64; 3] {
        match self.default {
            Value::Vector(x) => x,
            _ => panic!("not a vector parameter"),
        }
    }
    pub const fn choice(&self) -> &'static str {
        match self.default {
            Value::Choice(x) => x,
            _ => panic!("not a choice parameter"),
        }
    }
    /// The valid names of a choice parameter.
    pub fn choices(&self) -> &'static [&'static str] {
        if self.id == INTEGRATOR.id {
            INTEGRATOR_CHOICES
        } else if self.id == VOLUME.id {
            VOLUME_CHOICES
        } else {
            &[]
        }
    }
    /// "N/m" or "" → " N/m" / "" for messages.
    fn unit_suffix(&self) -> String {
        if self.unit.is_empty() { String::new() } else { format!(" {}", self.unit) }
    }
    /// The default as the CLI shows it.
    pub fn default_text(&self) -> String {
        match self.default {
            Value::Number(x) => format!("{x}"),
            Value::Vector(v) => format!("{},{},{}", v[0], v[1], v[2]),
            Value::Choice(c) => c.to_string(),
            Value::Flag(b) => b.to_string(),
        }
    }
    /// Check `value` against the parameter's kind and range: a message naming the parameter
    /// and its unit if it does not fit.
    pub fn check(&self, value: &Value) -> Result<(), ParamError> {
        let fail = |message: String| Err(ParamError { id: self.id.to_string(), message });
        match (self.default, value) {
            (Value::Number(_), Value::Number(x)) if !self.range.contains(*x) => {
                fail(format!("must be {}{}, got {x}", self.range.describe(), self.unit_suffix()))
            }
            (Value::Vector(_), Value::Vector(v)) if !v.iter().all(|x| self.range.contains(*x)) => {
                fail(format!("every component must be {}{}, got {v:?}", self.range.describe(), self.unit_suffix()))
            }
            (Value::Choice(_), Value::Choice(c)) if !self.choices().contains(c) => {
                fail(format!("unknown choice '{c}' (one of: {})", self.choices().join(", ")))
            }
            (Value::Number(_), Value::Number(_))
            | (Value::Vector(_), Value::Vector(_))
            | (Value::Choice(_), Value::Choice(_))
            | (Value::Flag(_), Value::Flag(_)) => Ok(()),
            _ => fail(format!("expected {}, got {value:?}", kind(&self.default))),
        }
    }
}

fn kind(v: &Value) -> &'static str {
    match v {
        Value::Number(_) => "a number",
        Value::Vector(_) => "three numbers [x, y, z]",
        Value::Choice(_) => "a name",
        Value::Flag(_) => "true or false",
    }
}

/// A parameter that does not exist, or a value it does not take.
#[derive(Debug, Clone, PartialEq)]
pub struct ParamError {
    pub id: String,
    pub message: String,
}

impl std::fmt::Display for ParamError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}: {}", self.id, self.message)
    }
}

impl std::error::Error for ParamError {}

/// The entry of `id`.
pub fn find(id: &str) -> Result<&'static Param, ParamError> {
    ParamId::find(id).map(ParamId::param)
}

impl ParamId {
    /// The typed id of string id `id` (the CLI's, a scene file's, the binding's).
    pub fn find(id: &str) -> Result<ParamId, ParamError> {
        ParamId::ALL.iter().copied().find(|p| p.param().id == id).ok_or_else(|| ParamError { id: id.to_string(), message: "no such parameter".into() })
    }
    /// The string id (the scene-file key).
    pub const fn id(self) -> &'static str {
        self.param().id
    }
}

impl std::fmt::Display for ParamId {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.id())
    }
}

/// The table's own spelling of choice `name` of parameter `id` (choices are `&'static str`).
pub fn choice(id: &str, name: &str) -> Result<Value, ParamError> {
    let p = find(id)?;
    p.choices()
        .iter()
        .find(|c| **c == name)
        .map(|c| Value::Choice(c))
        .ok_or_else(|| ParamError { id: id.to_string(), message: format!("unknown choice '{name}' (one of: {})", p.choices().join(", ")) })
}

/// The whole table as JSON: an array of `{id, scope, unit, default, min, max, min_open,
/// choices, help}` (min/max null when unbounded).
/// The material presets (`presets::PRESETS` that set only body parameters) as JSON: `[{"name",
/// "help"}]`, in table order: what the modeler's Material list offers.
pub fn material_presets_json() -> String {
    let rows: Vec<serde_json::Value> = presets::PRESETS
        .iter()
        .filter(|p| p.is_material())
        .map(|p| serde_json::json!({ "name": p.name, "help": p.help }))
        .collect();
    serde_json::Value::Array(rows).to_string()
}

pub fn table_json() -> String {
    let rows: Vec<serde_json::Value> = TABLE
        .iter()
        .map(|p| {
            let bound = |x: f64| if x.is_finite() { serde_json::json!(x) } else { serde_json::Value::Null };
            serde_json::json!({
                "id": p.id,
                "scope": p.scope,
                "unit": p.unit,
                "default": p.default,
                "min": bound(p.range.min),
                "max": bound(p.range.max),
                "min_open": p.range.min_open,
                "choices": p.choices(),
                "help": p.help,
            })
        })
        .collect();
    serde_json::Value::Array(rows).to_string()
}

/// The table as the Markdown of `docs/parameters.md`.
pub fn markdown() -> String {
    let mut out = String::from(
        "# Parameters\n\n\
         Every user-visible parameter of SoftSculpt, generated from the table in\n\
         `crates/softsculpt/src/params/table.rs` (a test fails if this page is stale; regenerate it\n\
         with `UPDATE_DOCS=1 cargo test -p softsculpt --test parameters`).\n\n\
         The id is the scene-file key (`gas.amount` is `amount` in a body's `gas` table,\n\
         `ground.height` is `height` in `[world.ground]`). *body* parameters belong to each body\n\
         (its material, mass and gas); *world* parameters are shared by every body of a world;\n\
         *scene* and *obstacle* ones exist only in scene files.\n\n\
         | id | scope | unit | default | valid | meaning |\n|---|---|---|---|---|---|\n",
    );
    for p in TABLE {
        let valid = match p.default {
            Value::Number(_) | Value::Vector(_) => p.range.describe(),
            Value::Choice(_) => p.choices().join(", "),
            Value::Flag(_) => "true, false".into(),
        };
        let scope = match p.scope {
            Scope::Body => "body",
            Scope::World => "world",
            Scope::Scene => "scene",
            Scope::Obstacle => "obstacle",
        };
        let unit = if p.unit.is_empty() { "–" } else { p.unit };
        out.push_str(&format!("| `{}` | {scope} | {unit} | {} | {valid} | {} |\n", p.id, p.default_text(), p.help));
    }
    out.push_str("\n## Presets\n\nNamed sets of values (`crates/softsculpt/src/params/presets.rs`), applied in order.\n\n| preset | values | meaning |\n|---|---|---|\n");
    for p in presets::PRESETS {
        let values: Vec<String> = p
            .values
            .iter()
            .map(|(id, v)| match v {
                Value::Number(x) => format!("`{id}` = {x}"),
                Value::Vector(x) => format!("`{id}` = {x:?}"),
                Value::Choice(c) => format!("`{id}` = {c}"),
                Value::Flag(f) => format!("`{id}` = {f}"),
            })
            .collect();
        out.push_str(&format!("| `{}` | {} | {} |\n", p.name, values.join(", "), p.help));
    }
    out
}
