//! Timed events in a scene file: what each action takes. The resolved events ([`Action`],
//! [`Event`]) and how they act are the world's (`crate::world::events`).
//!
//! Regions select vertices (and, for pressures, the faces whose three vertices are all selected)
//! by where they are when the scene starts, after placement: an event always acts on the same
//! material points, however the body has moved since.

use super::spec::EventSpec;
pub use crate::world::{Action, Event};

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
