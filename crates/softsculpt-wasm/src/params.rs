//! The calls on parameters: every parameter of a body and its world as JSON, a preset applied,
//! one parameter set from a JSON value (checked by the core's table), and the ground moved.

use crate::abi::exports;
use crate::fails::param_fail;
use crate::handle::{with_body, with_world};
use crate::{bytes, set_result, status, text};
use softsculpt::params::{self, ParamError, Scope, Value};

/// A JSON value as the parameter `id` takes it: a number, `[x, y, z]`, a choice's name, or a flag.
fn value_of(id: &str, v: &serde_json::Value) -> Result<Value, ParamError> {
    let refuse = || ParamError {
        id: id.to_string(),
        message: format!("cannot take the value {v}"),
    };
    Ok(match v {
        serde_json::Value::Number(n) => Value::Number(n.as_f64().ok_or_else(refuse)?),
        serde_json::Value::Bool(f) => Value::Flag(*f),
        serde_json::Value::String(s) => params::choice(params::find(id)?.id, s)?,
        serde_json::Value::Array(a) if a.len() == 3 => {
            let c = |k: usize| a[k].as_f64().ok_or_else(refuse);
            Value::Vector([c(0)?, c(1)?, c(2)?])
        }
        _ => return Err(refuse()),
    })
}

exports! {
    /// Every body and world parameter of body `b` and its world, as a JSON object in the result
    /// (`null` for the ground's when there is no ground).
    pub fn ss_params(w: u32, b: u32) -> i32 {
        status(|| {
            with_body(w, b, |h, i| {
                let out: serde_json::Map<String, serde_json::Value> = h
                    .world
                    .param_values(i, &[Scope::Body, Scope::World])
                    .into_iter()
                    .map(|(id, v)| (id.to_string(), v.and_then(|v| serde_json::to_value(v).ok()).unwrap_or(serde_json::Value::Null)))
                    .collect();
                set_result(serde_json::Value::Object(out).to_string().into_bytes());
                Ok(())
            })
        })
    }

    /// Apply preset `name` (`softsculpt::params::presets`): its body parameters on body `b`, its
    /// world parameters on the world; all or nothing.
    ///
    /// # Safety
    /// `name` must point to `len` bytes.
    pub unsafe fn ss_apply_preset(w: u32, b: u32, name: *const u8, len: usize) -> i32 {
        status(|| {
            let name = text(name, len, "the preset name")?;
            with_world(w, |h| h.world.apply_preset(b as usize, name).map_err(param_fail))
        })
    }

    /// Set parameter `id` (body parameters on body `b`, world parameters on the world) from a JSON
    /// value; refused with an error naming the parameter and its unit.
    ///
    /// # Safety
    /// `id` must point to `id_len` bytes and `json` to `json_len` bytes.
    pub unsafe fn ss_set_param(
        w: u32,
        b: u32,
        id: *const u8,
        id_len: usize,
        json: *const u8,
        json_len: usize,
    ) -> i32 {
        status(|| {
            let id = text(id, id_len, "the parameter id")?;
            let v: serde_json::Value = serde_json::from_slice(bytes(json, json_len)).map_err(|e| {
                param_fail(ParamError {
                    id: id.to_string(),
                    message: format!("the value is not JSON ({e})"),
                })
            })?;
            let value = value_of(id, &v).map_err(param_fail)?;
            with_world(w, |h| {
                h.world.set_param(b as usize, id, value).map_err(param_fail)
            })
        })
    }

    /// `World::move_ground`: the ground to `height` m, carrying the bodies standing on it; result
    /// `{"moved": n}` (bodies moved). Refused like `ss_set_param("ground.height")`.
    pub fn ss_move_ground(w: u32, height: f64) -> i32 {
        status(|| {
            with_world(w, |h| {
                let moved = h.world.move_ground(height).map_err(param_fail)?;
                set_result(serde_json::json!({ "moved": moved }).to_string().into_bytes());
                Ok(())
            })
        })
    }
}
