//! Get and set parameters by id (the table, `crate::params`): body parameters on a body of a
//! world, world parameters on its settings; and presets, named sets of them
//! (`crate::params::presets`), applied through the same checks, as they are or scaled by
//! similarity to the model's size (`crate::params::similarity`). Every value is checked against
//! the table's range first.

use crate::body::{moles, GasReference, Material, SoftBody};
use crate::params::field::field;
use crate::params::presets::preset;
use crate::params::similarity::{scaled, SIZED_DEFAULTS};
use crate::params::{ParamError, ParamId, Scope, Value, GROUND_HEIGHT};
use crate::world::{Ground, World, WorldSettings};

fn err(id: ParamId, message: impl Into<String>) -> ParamError {
    ParamError { id: id.id().to_string(), message: message.into() }
}

impl World {
    /// Every parameter of the `scopes` by its table id, in table order, with its current value
    /// (body parameters body `body`'s); None where it has none (the ground's without a ground).
    pub fn param_values(&self, body: usize, scopes: &[Scope]) -> Vec<(&'static str, Option<Value>)> {
        ParamId::ALL.iter().filter(|p| scopes.contains(&p.param().scope)).map(|&p| (p.id(), self.param_of(body, p).ok())).collect()
    }

    /// The current value of parameter `id`; body parameters are body `body`'s.
    pub fn param(&self, body: usize, id: &str) -> Result<Value, ParamError> {
        self.param_of(body, ParamId::find(id)?)
    }

    /// [`World::param`] by typed id.
    pub fn param_of(&self, body: usize, id: ParamId) -> Result<Value, ParamError> {
        match id.param().scope {
            Scope::Body => body_param(self.bodies.get(body).ok_or_else(|| no_body(id, body, self.bodies.len()))?, id),
            Scope::World => world_param(&self.settings, id),
            Scope::Scene | Scope::Obstacle => Err(not_here(id)),
        }
    }

    /// Set parameter `id` (checked against its range; a message naming it and its unit if it
    /// does not fit). Body parameters go to body `body`, world parameters to the settings.
    pub fn set_param(&mut self, body: usize, id: &str, value: Value) -> Result<(), ParamError> {
        self.set_param_of(body, ParamId::find(id)?, value)
    }

    /// [`World::set_param`] by typed id.
    pub fn set_param_of(&mut self, body: usize, id: ParamId, value: Value) -> Result<(), ParamError> {
        id.param().check(&value)?;
        match id.param().scope {
            Scope::Body => {
                let n = self.bodies.len();
                set_body_param(self.bodies.get_mut(body).ok_or_else(|| no_body(id, body, n))?, id, value)
            }
            Scope::World => set_world_param(&mut self.settings, id, value),
            Scope::Scene | Scope::Obstacle => Err(not_here(id)),
        }
    }
}

fn no_body(id: ParamId, body: usize, n: usize) -> ParamError {
    err(id, format!("there is no body {body} (the world has {n})"))
}

fn not_here(id: ParamId) -> ParamError {
    err(id, "is set in a scene file, not on a world")
}

/// Body parameter `id` of `b`: a field of its material ([`Material::FIELDS`]), or one of the
/// few that are not (the mass, nRT, the ambient pressure).
fn body_param(b: &SoftBody, id: ParamId) -> Result<Value, ParamError> {
    if let Some(f) = field(Material::FIELDS, id.id()) {
        return Ok((f.get)(&b.material));
    }
    Ok(match id {
        ParamId::Mass => Value::Number(b.masses().iter().sum()),
        ParamId::GasNrt => Value::Number(b.material.nrt()),
        ParamId::GasAmbient => Value::Number(b.gas_reference().ambient_pressure),
        _ => return Err(err(id, "not a body parameter")),
    })
}

/// Set body parameter `id` of `b` (not range-checked: [`World::set_param`] checks first). The
/// gas's amount and temperature go through the body (`SoftBody::set_gas`, which re-derives its
/// pressure), nRT through [`moles`] at the current temperature; every other material field
/// through [`Material::FIELDS`].
pub(crate) fn set_body_param(b: &mut SoftBody, id: ParamId, value: Value) -> Result<(), ParamError> {
    let sim = |e: crate::SimError| err(id, e.to_string());
    let (n, t) = (b.material.gas_amount, b.material.temperature);
    match (id, value) {
        (ParamId::Mass, Value::Number(x)) => b.set_total_mass(x).map_err(sim)?,
        (ParamId::GasAmount, Value::Number(x)) => b.set_gas(x, t).map_err(sim)?,
        (ParamId::GasTemperature, Value::Number(x)) => b.set_gas(n, x).map_err(sim)?,
        (ParamId::GasNrt, Value::Number(x)) => b.set_gas(moles(x, t), t).map_err(sim)?,
        (ParamId::GasAmbient, Value::Number(x)) => b.set_gas_reference(GasReference { ambient_pressure: x, ..b.gas_reference() }).map_err(sim)?,
        _ => match field(Material::FIELDS, id.id()) {
            Some(f) => (f.set)(&mut b.material, value).map_err(|m| err(id, m))?,
            None => return Err(err(id, "not a body parameter")),
        },
    }
    Ok(())
}

/// World parameter `id` of `w`: a field of the settings ([`WorldSettings::FIELDS`]) or of its
/// ground ([`Ground::FIELDS`], none without a ground), or whether there is a ground.
fn world_param(w: &WorldSettings, id: ParamId) -> Result<Value, ParamError> {
    if let Some(f) = field(WorldSettings::FIELDS, id.id()) {
        return Ok((f.get)(w));
    }
    if let Some(f) = field(Ground::FIELDS, id.id()) {
        return w.ground.as_ref().map(f.get).ok_or_else(|| err(id, "there is no ground"));
    }
    match id {
        ParamId::Ground => Ok(Value::Flag(w.ground.is_some())),
        _ => Err(err(id, "not a world parameter")),
    }
}

/// Set world parameter `id` of `w` (not range-checked: [`World::set_param`] checks first).
/// `ground` adds a ground at the table's default height (or removes it); `ground.*` need one.
fn set_world_param(w: &mut WorldSettings, id: ParamId, value: Value) -> Result<(), ParamError> {
    if let Some(f) = field(WorldSettings::FIELDS, id.id()) {
        return (f.set)(w, value).map_err(|m| err(id, m));
    }
    if let Some(f) = field(Ground::FIELDS, id.id()) {
        let g = w.ground.as_mut().ok_or_else(|| err(id, "there is no ground (set `ground` to true first)"))?;
        return (f.set)(g, value).map_err(|m| err(id, m));
    }
    match (id, value) {
        (ParamId::Ground, Value::Flag(on)) => {
            if !on {
                w.ground = None;
            } else if w.ground.is_none() {
                w.ground = Some(Ground::at(GROUND_HEIGHT.number()));
            }
        }
        _ => return Err(err(id, "not a world parameter")),
    }
    Ok(())
}

impl World {
    /// Set every value of preset `name` (body parameters on body `body`). Checked first, so a
    /// preset either applies whole or not at all.
    pub fn apply_preset(&mut self, body: usize, name: &str) -> Result<(), ParamError> {
        let p = preset(name)?;
        for (id, v) in p.values {
            id.param().check(v)?;
        }
        for &(id, v) in p.values {
            self.set_param_of(body, id, v)?;
        }
        Ok(())
    }

    /// Preset `name` for a model `size` times as large as the one it was tuned for: its values,
    /// and the [`SIZED_DEFAULTS`], scaled by similarity (the table of
    /// [`crate::params::similarity`]); `dt` × min(1, s^½). An open body (cloth-like) gets no
    /// gas — the gas law needs a closed surface — and the gas parameters skipped are returned.
    /// Checked whole first: all or nothing.
    pub fn apply_preset_scaled(&mut self, body: usize, name: &str, size: f64) -> Result<Vec<&'static str>, ParamError> {
        if !(size.is_finite() && size > 0.0) {
            return Err(ParamError { id: "preset".into(), message: format!("the model's size factor must be positive and finite (got {size})") });
        }
        let open = self.bodies.get(body).is_some_and(|b| !b.is_closed());
        let mut values = Vec::new();
        let mut skipped = Vec::new();
        let defaults = SIZED_DEFAULTS.iter().map(|&id| (id, id.param().default));
        for (id, v) in preset(name)?.values.iter().copied().chain(defaults) {
            if open && matches!(id, ParamId::GasNrt | ParamId::GasAmount) {
                skipped.push(id.id());
                continue;
            }
            let v = match (id, v) {
                (ParamId::Dt, Value::Number(dt)) => Value::Number(dt * size.sqrt().min(1.0)),
                _ => scaled(id, v, size)?,
            };
            id.param().check(&v)?;
            values.push((id, v));
        }
        for (id, v) in values {
            self.set_param_of(body, id, v)?;
        }
        Ok(skipped)
    }
}
