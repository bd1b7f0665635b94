//! Get and set parameters by id (the table, `crate::params`): body parameters on a body of a
//! world, world parameters on its settings; and presets, named sets of them
//! (`crate::params::presets`), applied through the same checks, as they are or scaled by
//! similarity to the model's size (`crate::params::similarity`). Every value is checked against
//! the table's range first.

use crate::body::{GasReference, SoftBody, VolumeMode};
use crate::params::presets::preset;
use crate::params::similarity::{scaled, SIZED_DEFAULTS};
use crate::params::{find, ParamError, Scope, Value};
use crate::world::{Ground, Integrator, World, WorldSettings};

fn err(id: &str, message: impl Into<String>) -> ParamError {
    ParamError { id: id.to_string(), message: message.into() }
}

impl World {
    /// Every parameter of the `scopes` by its table id, in table order, with its current value
    /// (body parameters body `body`'s); None where it has none (the ground's without a ground).
    pub fn param_values(&self, body: usize, scopes: &[Scope]) -> Vec<(&'static str, Option<Value>)> {
        crate::params::TABLE.iter().filter(|p| scopes.contains(&p.scope)).map(|p| (p.id, self.param(body, p.id).ok())).collect()
    }

    /// The current value of parameter `id`; body parameters are body `body`'s.
    pub fn param(&self, body: usize, id: &str) -> Result<Value, ParamError> {
        let p = find(id)?;
        match p.scope {
            Scope::Body => body_param(self.bodies.get(body).ok_or_else(|| no_body(id, body, self.bodies.len()))?, id),
            Scope::World => world_param(&self.settings, id),
            Scope::Scene | Scope::Obstacle => Err(not_here(id)),
        }
    }

    /// Set parameter `id` (checked against its range; a message naming it and its unit if it
    /// does not fit). Body parameters go to body `body`, world parameters to the settings.
    pub fn set_param(&mut self, body: usize, id: &str, value: Value) -> Result<(), ParamError> {
        let p = find(id)?;
        p.check(&value)?;
        match p.scope {
            Scope::Body => {
                let n = self.bodies.len();
                set_body_param(self.bodies.get_mut(body).ok_or_else(|| no_body(id, body, n))?, id, value)
            }
            Scope::World => set_world_param(&mut self.settings, id, value),
            Scope::Scene | Scope::Obstacle => Err(not_here(id)),
        }
    }
}

fn no_body(id: &str, body: usize, n: usize) -> ParamError {
    err(id, format!("there is no body {body} (the world has {n})"))
}

fn not_here(id: &str) -> ParamError {
    err(id, "is set in a scene file, not on a world")
}

fn body_param(b: &SoftBody, id: &str) -> Result<Value, ParamError> {
    let m = &b.material;
    Ok(match id {
        "mass" => Value::Number(b.masses().iter().sum()),
        "stiffness" => Value::Number(m.stiffness),
        "spring_damping" => Value::Number(m.spring_damping),
        "bending" => Value::Number(m.bending_stiffness),
        "rigidity" => Value::Number(m.rigidity),
        "damping" => Value::Number(m.damping),
        "gas.amount" => Value::Number(m.gas_amount),
        "gas.temperature" => Value::Number(m.temperature),
        "gas.nrt" => Value::Number(m.nrt()),
        "gas.volume" => Value::Choice(m.volume_mode.name()),
        "gas.ambient" => Value::Number(b.gas_reference().ambient_pressure),
        "self_collision" => Value::Flag(m.self_collision),
        "yield" => Value::Number(m.yield_strain),
        "flow" => Value::Number(m.flow_rate),
        _ => return Err(err(id, "not a body parameter")),
    })
}

/// Set body parameter `id` of `b` (not range-checked: [`World::set_param`] checks first).
pub(crate) fn set_body_param(b: &mut SoftBody, id: &str, value: Value) -> Result<(), ParamError> {
    let sim = |e: crate::SimError| err(id, e.to_string());
    let (n, t) = (b.material.gas_amount, b.material.temperature);
    match (id, value) {
        ("mass", Value::Number(x)) => b.set_total_mass(x).map_err(sim)?,
        ("stiffness", Value::Number(x)) => b.material.stiffness = x,
        ("spring_damping", Value::Number(x)) => b.material.spring_damping = x,
        ("bending", Value::Number(x)) => b.material.bending_stiffness = x,
        ("rigidity", Value::Number(x)) => b.material.rigidity = x,
        ("damping", Value::Number(x)) => b.material.damping = x,
        ("gas.amount", Value::Number(x)) => b.set_gas(x, t).map_err(sim)?,
        ("gas.temperature", Value::Number(x)) => b.set_gas(n, x).map_err(sim)?,
        ("gas.nrt", Value::Number(x)) => b.set_gas(crate::body::moles(x, t), t).map_err(sim)?,
        ("gas.volume", Value::Choice(c)) => b.material.volume_mode = VolumeMode::from_name(c).ok_or_else(|| err(id, "unknown volume mode"))?,
        ("gas.ambient", Value::Number(x)) => b.set_gas_reference(GasReference { ambient_pressure: x, ..b.gas_reference() }).map_err(sim)?,
        ("self_collision", Value::Flag(f)) => b.material.self_collision = f,
        ("yield", Value::Number(x)) => b.material.yield_strain = x,
        ("flow", Value::Number(x)) => b.material.flow_rate = x,
        _ => return Err(err(id, "not a body parameter")),
    }
    Ok(())
}

fn world_param(w: &WorldSettings, id: &str) -> Result<Value, ParamError> {
    let ground = |f: fn(&Ground) -> f64| w.ground.as_ref().map(f).map(Value::Number).ok_or_else(|| err(id, "there is no ground"));
    Ok(match id {
        "dt" => Value::Number(w.dt),
        "integrator" => Value::Choice(w.integrator.name()),
        "tolerance" => Value::Number(w.tolerance),
        "newton_iterations" => Value::Number(w.newton_iterations as f64),
        "gravity" => Value::Number(w.gravity),
        "wind" => Value::Vector(w.wind),
        "wind_drag" => Value::Number(w.wind_drag),
        "ground" => Value::Flag(w.ground.is_some()),
        "ground.height" => ground(|g| g.height)?,
        "ground.friction" => ground(|g| g.friction)?,
        "ground.restitution" => ground(|g| g.restitution)?,
        "contact_thickness" => Value::Number(w.contact.thickness),
        "contact_friction" => Value::Number(w.contact.friction),
        _ => return Err(err(id, "not a world parameter")),
    })
}

fn set_world_param(w: &mut WorldSettings, id: &str, value: Value) -> Result<(), ParamError> {
    let no_ground = || err(id, "there is no ground (set `ground` to true first)");
    match (id, value) {
        ("dt", Value::Number(x)) => w.dt = x,
        ("integrator", Value::Choice(c)) => w.integrator = Integrator::from_name(c).ok_or_else(|| err(id, "unknown integrator"))?,
        ("tolerance", Value::Number(x)) => w.tolerance = x,
        ("newton_iterations", Value::Number(x)) if x.fract() == 0.0 => w.newton_iterations = x as u32,
        ("newton_iterations", Value::Number(x)) => return Err(err(id, format!("must be a whole number, got {x}"))),
        ("gravity", Value::Number(x)) => w.gravity = x,
        ("wind", Value::Vector(v)) => w.wind = v,
        ("wind_drag", Value::Number(x)) => w.wind_drag = x,
        ("ground", Value::Flag(on)) => {
            if !on {
                w.ground = None;
            } else if w.ground.is_none() {
                w.ground = Some(Ground::at(crate::params::GROUND_HEIGHT.number()));
            }
        }
        ("ground.height", Value::Number(x)) => w.ground.as_mut().ok_or_else(no_ground)?.height = x,
        ("ground.friction", Value::Number(x)) => w.ground.as_mut().ok_or_else(no_ground)?.friction = x,
        ("ground.restitution", Value::Number(x)) => w.ground.as_mut().ok_or_else(no_ground)?.restitution = x,
        ("contact_thickness", Value::Number(x)) => w.contact.thickness = x,
        ("contact_friction", Value::Number(x)) => w.contact.friction = x,
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
            find(id)?.check(v)?;
        }
        for (id, v) in p.values {
            self.set_param(body, id, *v)?;
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
        let defaults = SIZED_DEFAULTS.iter().map(|id| find(id).map(|p| (p.id, p.default)));
        for entry in preset(name)?.values.iter().map(|&(id, v)| Ok((id, v))).chain(defaults) {
            let (id, v) = entry?;
            if open && matches!(id, "gas.nrt" | "gas.amount") {
                skipped.push(id);
                continue;
            }
            let v = match (id, v) {
                ("dt", Value::Number(dt)) => Value::Number(dt * size.sqrt().min(1.0)),
                _ => scaled(id, v, size)?,
            };
            find(id)?.check(&v)?;
            values.push((id, v));
        }
        for (id, v) in values {
            self.set_param(body, id, v)?;
        }
        Ok(skipped)
    }
}
