//! Timed events in a scene file: each event checked and resolved for the bodies it acts on
//! ([`resolve`]). What each action takes is its [`ActionSpec`] variant (`super::actions`, read
//! and checked by serde); the resolved events ([`Action`], [`Event`]) and how they act are the
//! world's (`crate::world::events`).
//!
//! Regions select vertices (and, for pressures, the faces whose three vertices are all selected)
//! by where they are when the scene starts, after placement: an event always acts on the same
//! material points, however the body has moved since.

use super::actions::ActionSpec;
use super::build::{select_in, BuiltBody, Ctx};
use super::spec::{RegionSpec, SceneSpec};
use super::SceneError;
pub use crate::world::{Action, Event};
use crate::params as table;
use crate::vec3::scale;

/// Every `[[event]]` checked (time order, values) and resolved, one per body it targets (the
/// named one, else every body).
pub(super) fn resolve(spec: &SceneSpec, text: &str, bodies: &[BuiltBody]) -> Result<Vec<Event>, SceneError> {
    let mut events = Vec::new();
    let mut last = 0.0;
    for (k, e) in spec.events.iter().enumerate() {
        let cx = Ctx::new(text, e.span().start, format!("event[{k}]"));
        let e = e.get_ref();
        if !(e.time.is_finite() && e.time >= 0.0) {
            return Err(cx.err("time", format!("must be 0 or more, got {}", e.time)));
        }
        if e.time < last {
            return Err(cx.err("time", format!("events must be in time order: {} s comes after an event at {last} s", e.time)));
        }
        last = e.time;
        if let ActionSpec::SetGas { amount, temperature, nrt } = &e.action {
            if amount.is_none() && temperature.is_none() && nrt.is_none() {
                return Err(cx.err("action", "action 'set_gas' needs `amount`, `nrt` or `temperature`"));
            }
            if amount.is_some() && nrt.is_some() {
                return Err(cx.err("action", "give the gas as `amount` (mol) or as `nrt` (J), not both"));
            }
        }
        let targets: Vec<usize> = match &e.body {
            Some(name) => vec![bodies
                .iter()
                .position(|b| &b.name == name)
                .ok_or_else(|| cx.err("body", format!("no body is named '{name}'")))?],
            None => (0..bodies.len()).collect(),
        };
        let until = match e.action.duration() {
            Some(d) => e.time + cx.positive("duration", d)?,
            None => f64::INFINITY,
        };
        for bi in targets {
            let action = event_action(&cx, &e.action, &bodies[bi], spec.world.gravity, until)?;
            events.push(Event { time: e.time, body: bi, action, line: cx.line });
        }
    }
    Ok(events)
}

/// Action `a` on body `b`, its values checked (`until`: when a force or pressure ends, s;
/// `gravity`: the world's, which decides a freeze's default `under_load`).
fn event_action(cx: &Ctx, a: &ActionSpec, b: &BuiltBody, gravity: f64, until: f64) -> Result<Action, SceneError> {
    let region = |r: &RegionSpec| select_in(cx, "region", r, &b.body, &b.mesh);
    Ok(match a {
        ActionSpec::Freeze { under_load, keep_tension } => {
            Action::Freeze { under_load: under_load.unwrap_or(gravity != 0.0), keep_tension: keep_tension.unwrap_or(false) }
        }
        ActionSpec::Reset {} => Action::Reset,
        &ActionSpec::SetGas { amount, temperature, nrt } => set_gas(cx, b, amount, temperature, nrt)?,
        ActionSpec::SetWind { wind } => Action::SetWind(cx.vec("wind", *wind)?),
        ActionSpec::Force { region: r, force, .. } => {
            let vertices = region(r)?;
            let f = cx.vec("force", *force)?;
            Action::Force { per_vertex: scale(f, 1.0 / vertices.len() as f64), vertices, until }
        }
        ActionSpec::Pressure { region: r, pressure, .. } => {
            let p = cx.finite("pressure", *pressure)?;
            let sel = vertex_mask(b.body.vertex_count(), &region(r)?);
            let faces: Vec<usize> = (0..b.body.face_count())
                .filter(|&f| b.body.triangles()[f].iter().all(|&v| sel[v as usize]))
                .collect();
            if faces.is_empty() {
                return Err(cx.err("region", "selects no whole face (a face needs all three vertices inside)"));
            }
            Action::Pressure { faces, pressure: p, until }
        }
        ActionSpec::Pin { region: r } => Action::Pin(region(r)?),
        ActionSpec::Unpin { region: r } => Action::Unpin(region(r)?),
        ActionSpec::Inflate { region: r, factor } => {
            let f = cx.positive("factor", *factor)?;
            let mut factors = vec![1.0; b.body.vertex_count()];
            let vertices = match r {
                Some(r) => region(r)?,
                None => (0..b.body.vertex_count()).collect(),
            };
            for v in vertices {
                factors[v] = f;
            }
            Action::Inflate(factors)
        }
        ActionSpec::SetMass { region: r, mass } => {
            let vertices = region(r)?;
            Action::SetMass { vertices, mass: cx.positive("mass", *mass)? }
        }
    })
}

/// A `set_gas` event's values checked: gas only in a closed body.
fn set_gas(cx: &Ctx, b: &BuiltBody, amount: Option<f64>, temperature: Option<f64>, nrt: Option<f64>) -> Result<Action, SceneError> {
    if let Some(a) = amount {
        cx.param("amount", &table::GAS_AMOUNT, a)?;
    }
    if let Some(t) = temperature {
        cx.param("temperature", &table::TEMPERATURE, t)?;
    }
    if let Some(n) = nrt {
        cx.param("nrt", &table::GAS_NRT, n)?;
    }
    if (amount.unwrap_or(0.0) > 0.0 || nrt.unwrap_or(0.0) > 0.0) && !b.body.is_closed() {
        return Err(cx.err("amount", format!("body '{}' is open: gas needs a closed surface", b.name)));
    }
    Ok(Action::SetGas { amount, temperature, nrt })
}

fn vertex_mask(n: usize, vertices: &[usize]) -> Vec<bool> {
    let mut m = vec![false; n];
    for &v in vertices {
        m[v] = true;
    }
    m
}
