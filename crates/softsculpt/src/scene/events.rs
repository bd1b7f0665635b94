//! Timed events in a scene file: what each action takes, and each event checked and resolved
//! for the bodies it acts on ([`resolve`]). The resolved events ([`Action`],
//! [`Event`]) and how they act are the world's (`crate::world::events`).
//!
//! Regions select vertices (and, for pressures, the faces whose three vertices are all selected)
//! by where they are when the scene starts, after placement: an event always acts on the same
//! material points, however the body has moved since.

use super::build::{select_in, BuiltBody, Ctx};
use super::spec::{EventSpec, SceneSpec};
use super::SceneError;
pub use crate::world::{Action, Event};
use crate::params as table;
use crate::vec3::scale;

/// Every action, with the keys it requires and the keys it may take (besides `time`, `action`
/// and `body`, which every event may have).
pub const ACTIONS: &[(&str, &[&str], &[&str])] = &[
    ("freeze", &[], &["under_load", "keep_tension"]),
    ("reset", &[], &[]),
    ("set_gas", &[], &["amount", "temperature", "nrt"]),
    ("set_wind", &["wind"], &[]),
    ("force", &["region", "force"], &["duration"]),
    ("pressure", &["region", "pressure"], &["duration"]),
    ("pin", &["region"], &[]),
    ("unpin", &["region"], &[]),
    ("inflate", &["factor"], &["region"]),
    ("set_mass", &["region", "mass"], &[]),
];

/// Keys of `e` that are set, besides `time`, `action` and `body`.
pub fn present_keys(e: &EventSpec) -> Vec<&'static str> {
    let mut keys = Vec::new();
    let mut add = |set: bool, k: &'static str| {
        if set {
            keys.push(k)
        }
    };
    add(e.duration.is_some(), "duration");
    add(e.region.is_some(), "region");
    add(e.force.is_some(), "force");
    add(e.pressure.is_some(), "pressure");
    add(e.amount.is_some(), "amount");
    add(e.temperature.is_some(), "temperature");
    add(e.nrt.is_some(), "nrt");
    add(e.wind.is_some(), "wind");
    add(e.factor.is_some(), "factor");
    add(e.mass.is_some(), "mass");
    add(e.under_load.is_some(), "under_load");
    add(e.keep_tension.is_some(), "keep_tension");
    keys
}

/// Check an event's keys against its action: unknown action, missing or stray keys.
pub fn check_keys(e: &EventSpec) -> Result<(), String> {
    let Some((_, required, optional)) = ACTIONS.iter().find(|(name, _, _)| *name == e.action) else {
        let names: Vec<&str> = ACTIONS.iter().map(|a| a.0).collect();
        return Err(format!("unknown action '{}' (one of: {})", e.action, names.join(", ")));
    };
    let present = present_keys(e);
    for r in *required {
        if !present.contains(r) {
            return Err(format!("action '{}' needs `{r}`", e.action));
        }
    }
    for p in &present {
        if !required.contains(p) && !optional.contains(p) {
            return Err(format!("action '{}' does not take `{p}`", e.action));
        }
    }
    if e.action == "set_gas" && present.is_empty() {
        return Err("action 'set_gas' needs `amount`, `nrt` or `temperature`".into());
    }
    if e.amount.is_some() && e.nrt.is_some() {
        return Err("give the gas as `amount` (mol) or as `nrt` (J), not both".into());
    }
    Ok(())
}

/// Every `[[event]]` checked (time order, keys) and resolved, one per body it targets (the
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
        check_keys(e).map_err(|m| cx.err("action", m))?;
        let targets: Vec<usize> = match &e.body {
            Some(name) => vec![bodies
                .iter()
                .position(|b| &b.name == name)
                .ok_or_else(|| cx.err("body", format!("no body is named '{name}'")))?],
            None => (0..bodies.len()).collect(),
        };
        let until = match e.duration {
            Some(d) => e.time + cx.positive("duration", d)?,
            None => f64::INFINITY,
        };
        for bi in targets {
            let action = event_action(&cx, e, &bodies[bi], spec.world.gravity, until)?;
            events.push(Event { time: e.time, body: bi, action, line: cx.line });
        }
    }
    Ok(events)
}

/// Event `e`'s action on body `b`, its values checked (`until`: when a force or pressure
/// ends, s; `gravity`: the world's, which decides a freeze's default `under_load`).
fn event_action(cx: &Ctx, e: &EventSpec, b: &BuiltBody, gravity: f64, until: f64) -> Result<Action, SceneError> {
    let region = |cx: &Ctx| -> Result<Vec<usize>, SceneError> {
        match &e.region {
            Some(r) => select_in(cx, "region", r, &b.body, &b.mesh),
            None => Ok((0..b.body.vertex_count()).collect()),
        }
    };
    Ok(match e.action.as_str() {
        "freeze" => Action::Freeze { under_load: e.under_load.unwrap_or(gravity != 0.0), keep_tension: e.keep_tension.unwrap_or(false) },
        "reset" => Action::Reset,
        "set_gas" => set_gas(cx, e, b)?,
        "set_wind" => Action::SetWind(cx.vec("wind", e.wind.unwrap_or_default())?),
        "force" => {
            let vertices = region(cx)?;
            let f = cx.vec("force", e.force.unwrap_or_default())?;
            Action::Force { per_vertex: scale(f, 1.0 / vertices.len() as f64), vertices, until }
        }
        "pressure" => {
            let p = cx.finite("pressure", e.pressure.unwrap_or(0.0))?;
            let sel = vertex_mask(b.body.vertex_count(), &region(cx)?);
            let faces: Vec<usize> = (0..b.body.face_count())
                .filter(|&f| b.body.triangles()[f].iter().all(|&v| sel[v as usize]))
                .collect();
            if faces.is_empty() {
                return Err(cx.err("region", "selects no whole face (a face needs all three vertices inside)"));
            }
            Action::Pressure { faces, pressure: p, until }
        }
        "pin" => Action::Pin(region(cx)?),
        "unpin" => Action::Unpin(region(cx)?),
        "inflate" => {
            let f = cx.positive("factor", e.factor.unwrap_or(1.0))?;
            let mut factors = vec![1.0; b.body.vertex_count()];
            for v in region(cx)? {
                factors[v] = f;
            }
            Action::Inflate(factors)
        }
        "set_mass" => Action::SetMass { vertices: region(cx)?, mass: cx.positive("mass", e.mass.unwrap_or(0.0))? },
        other => unreachable!("check_keys accepted unknown action {other}"),
    })
}

/// A `set_gas` event's values checked: gas only in a closed body.
fn set_gas(cx: &Ctx, e: &EventSpec, b: &BuiltBody) -> Result<Action, SceneError> {
    if let Some(a) = e.amount {
        cx.param("amount", &table::GAS_AMOUNT, a)?;
    }
    if let Some(t) = e.temperature {
        cx.param("temperature", &table::TEMPERATURE, t)?;
    }
    if let Some(n) = e.nrt {
        cx.param("nrt", &table::GAS_NRT, n)?;
    }
    if (e.amount.unwrap_or(0.0) > 0.0 || e.nrt.unwrap_or(0.0) > 0.0) && !b.body.is_closed() {
        return Err(cx.err("amount", format!("body '{}' is open: gas needs a closed surface", b.name)));
    }
    Ok(Action::SetGas { amount: e.amount, temperature: e.temperature, nrt: e.nrt })
}

fn vertex_mask(n: usize, vertices: &[usize]) -> Vec<bool> {
    let mut m = vec![false; n];
    for &v in vertices {
        m[v] = true;
    }
    m
}
