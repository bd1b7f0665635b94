//! The timed actions of a scene file, typed: one variant per `action = "…"`, with the keys that
//! action takes. Serde reads them (the `action` key is the tag; a key an action does not take is
//! refused), and [`read`] words serde's complaints in the scene format's terms: an unknown
//! action lists the valid ones, a missing key is one the action needs, a stray key one it does
//! not take. `docs/scenes.md` lists the actions for users; keep the two in step.
//!
//! A new action, or a new key of one, is written here (the variant and its fields) and acted on
//! in `super::events` (what it does to a body).

use super::spec::RegionSpec;
use serde::de::value::{MapDeserializer, SeqDeserializer};
use serde::de::{self, Deserialize, Deserializer, IntoDeserializer, Visitor};
use serde::Serialize;
use std::fmt;

/// What an `[[event]]` does (besides `time` and `body`, which every event has).
#[derive(Debug, Clone, PartialEq, serde::Deserialize, Serialize)]
#[serde(tag = "action", rename_all = "snake_case", deny_unknown_fields)]
pub enum ActionSpec {
    /// Rest shape := current shape.
    Freeze {
        /// Keep the current loads balanced (default: when gravity is on).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        under_load: Option<bool>,
        /// Keep the gas pressing and solve rest lengths so the shape is an equilibrium
        /// (default: false, a plain or under-load freeze).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        keep_tension: Option<bool>,
    },
    /// Back to the last frozen state.
    Reset {},
    /// Gas amount (mol), temperature (K) or product nRT (J): at least one; absent ones kept.
    SetGas {
        #[serde(default, skip_serializing_if = "Option::is_none")]
        amount: Option<f64>,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        temperature: Option<f64>,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        nrt: Option<f64>,
    },
    /// Wind velocity (m/s).
    SetWind { wind: [f64; 3] },
    /// Total force over the region (N), shared equally by its vertices, for `duration` (s;
    /// absent: to the end).
    Force {
        #[serde(default, skip_serializing_if = "Option::is_none")]
        duration: Option<f64>,
        region: RegionSpec,
        force: [f64; 3],
    },
    /// Pressure on the region's faces (Pa), positive pushing inward, for `duration` (s; absent:
    /// to the end).
    Pressure {
        #[serde(default, skip_serializing_if = "Option::is_none")]
        duration: Option<f64>,
        region: RegionSpec,
        pressure: f64,
    },
    Pin { region: RegionSpec },
    Unpin { region: RegionSpec },
    /// Rest-length factor (dimensionless; > 1 grows) over the region (absent: the whole body).
    Inflate {
        #[serde(default, skip_serializing_if = "Option::is_none")]
        region: Option<RegionSpec>,
        factor: f64,
    },
    /// Vertex mass (kg) over the region.
    SetMass { region: RegionSpec, mass: f64 },
}

impl ActionSpec {
    /// How long a force or pressure lasts (s), if the event says.
    pub fn duration(&self) -> Option<f64> {
        match self {
            ActionSpec::Force { duration, .. } | ActionSpec::Pressure { duration, .. } => *duration,
            _ => None,
        }
    }
}

/// An event's action from the event's keys other than `time` and `body` (serde's
/// `deserialize_with` for the flattened field), refused in the scene format's words.
pub(super) fn read<'de, D: Deserializer<'de>>(d: D) -> Result<ActionSpec, D::Error> {
    let table = toml::Table::deserialize(d)?;
    let name = table.get("action").and_then(|a| a.as_str()).map(str::to_string);
    let keys: Vec<String> = table.keys().cloned().collect();
    ActionSpec::deserialize(Value(toml::Value::Table(table))).map_err(|e| {
        let name = name.as_deref().unwrap_or("");
        de::Error::custom(match e {
            KeyError::Unknown(a, valid) => format!("unknown action '{a}' (one of: {})", valid.join(", ")),
            KeyError::Missing("action") => "missing field `action`".to_string(),
            KeyError::Missing(k) => format!("action '{name}' needs `{k}`"),
            KeyError::Stray(k, _) if keys.contains(&k) => format!("action '{name}' does not take `{k}`"),
            // A key inside one of the event's tables (`region = { al = … }`).
            KeyError::Stray(k, valid) => format!("unknown field `{k}`, expected one of `{}`", valid.join("`, `")),
            KeyError::Other(m) if name.is_empty() => m,
            KeyError::Other(m) => format!("action '{name}': {m}"),
        })
    })
}

/// Why serde refused an event's keys, kept apart so [`read`] can say it in the format's terms.
#[derive(Debug)]
enum KeyError {
    /// An action that does not exist, and the ones that do.
    Unknown(String, &'static [&'static str]),
    /// A key the action needs.
    Missing(&'static str),
    /// A key the action (or one of its tables) does not take, and the ones it does.
    Stray(String, &'static [&'static str]),
    /// Anything else (a wrong type).
    Other(String),
}

impl de::Error for KeyError {
    fn custom<T: fmt::Display>(msg: T) -> Self {
        KeyError::Other(msg.to_string())
    }
    fn unknown_variant(variant: &str, expected: &'static [&'static str]) -> Self {
        KeyError::Unknown(variant.to_string(), expected)
    }
    fn unknown_field(field: &str, expected: &'static [&'static str]) -> Self {
        KeyError::Stray(field.to_string(), expected)
    }
    fn missing_field(field: &'static str) -> Self {
        KeyError::Missing(field)
    }
}

impl fmt::Display for KeyError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{self:?}")
    }
}

impl std::error::Error for KeyError {}

/// A TOML value read back through serde with [`KeyError`] as the error type (toml's own
/// deserializer flattens every complaint into a message).
struct Value(toml::Value);

impl<'de> IntoDeserializer<'de, KeyError> for Value {
    type Deserializer = Value;
    fn into_deserializer(self) -> Value {
        self
    }
}

impl<'de> Deserializer<'de> for Value {
    type Error = KeyError;
    fn deserialize_any<V: Visitor<'de>>(self, v: V) -> Result<V::Value, KeyError> {
        match self.0 {
            toml::Value::String(s) => v.visit_string(s),
            toml::Value::Integer(i) => v.visit_i64(i),
            toml::Value::Float(x) => v.visit_f64(x),
            toml::Value::Boolean(b) => v.visit_bool(b),
            toml::Value::Datetime(t) => v.visit_string(t.to_string()),
            toml::Value::Array(a) => v.visit_seq(SeqDeserializer::new(a.into_iter().map(Value))),
            toml::Value::Table(t) => v.visit_map(MapDeserializer::new(t.into_iter().map(|(k, x)| (k, Value(x))))),
        }
    }
    fn deserialize_option<V: Visitor<'de>>(self, v: V) -> Result<V::Value, KeyError> {
        v.visit_some(self)
    }
    serde::forward_to_deserialize_any! {
        bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 f32 f64 char str string bytes byte_buf unit
        unit_struct newtype_struct seq tuple tuple_struct map struct enum identifier ignored_any
    }
}
