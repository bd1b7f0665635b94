//! Presets: named sets of parameter values, defined once here beside the table. Applying one
//! sets each listed parameter (in order) through [`World::set_param`], so every value is checked
//! against the table's range like any other.
//!
//! - `modeler`: the world and material the modeler opens a model with — stiff enough bending to
//!   carry a mushroom's cap, damped to settle within a second or two, 30 J of gas, on the ground,
//!   stepped implicitly at one 1/60 s step per frame with a residual tolerance of 1e-3 (measured in
//!   Chromium: the resting shape is the same to four digits as at 1e-6, at twice the speed; see
//!   BENCHMARKS.md). Every value is a material or world property, not one of the mesh's: the
//!   reasons each stays the same when the mesh is subdivided are in `web/src/engine/models.ts`.

use super::{find, ParamError, Value};
use crate::world::World;

/// A named set of parameter values.
#[derive(Debug, Clone, Copy)]
pub struct Preset {
    pub name: &'static str,
    pub help: &'static str,
    /// (parameter id, value), applied in this order.
    pub values: &'static [(&'static str, Value)],
}

pub const MODELER: Preset = Preset {
    name: "modeler",
    help: "what the modeler opens a model with: bending as stiff as the edges, damped, 30 J of gas, on the ground, implicit at 1/60 s",
    values: &[
        ("stiffness", Value::Number(100.0)),
        ("spring_damping", Value::Number(0.1)),
        ("bending", Value::Number(100.0)),
        ("damping", Value::Number(1.5)),
        ("gravity", Value::Number(9.81)),
        ("ground", Value::Flag(true)),
        ("ground.height", Value::Number(0.0)),
        ("ground.friction", Value::Number(0.5)),
        ("gas.temperature", Value::Number(300.0)),
        ("gas.nrt", Value::Number(30.0)),
        ("integrator", Value::Choice("implicit")),
        ("tolerance", Value::Number(1e-3)),
        ("dt", Value::Number(1.0 / 60.0)),
    ],
};

/// Every preset.
pub const PRESETS: &[Preset] = &[MODELER];

/// The preset called `name`.
pub fn preset(name: &str) -> Result<&'static Preset, ParamError> {
    PRESETS.iter().find(|p| p.name == name).ok_or_else(|| ParamError {
        id: "preset".into(),
        message: format!("unknown preset '{name}' (one of: {})", PRESETS.iter().map(|p| p.name).collect::<Vec<_>>().join(", ")),
    })
}

impl World {
    /// Set every value of preset `name` (body parameters on body `body`). Checked first, so a
    /// preset either applies whole or not at all.
    pub fn apply_preset(&mut self, body: usize, name: &str) -> Result<(), ParamError> {
        let p = preset(name)?;
        for (id, v) in p.values {
            find(id)?.check(v)?;
        }
        for (id, v) in p.values {
            self.set_param(body, id, *v)?;
        }
        Ok(())
    }
}
