//! Files of earlier SoftSculpt versions, read into today's world.
//!
//! **Modeler project files, version 1** (JSON, `"format": "softsculpt-project"`, `"version": 1`):
//! one body as arrays (`positions`, `velocities`, `restLengths`, `masses`, `pinned` 0/1 per
//! vertex, `frozenPositions`, `frozenRestLengths`, `prestress`, `frozenPrestress`,
//! `bendingRestLengths`, `frozenBendingRestLengths`, `triangles`, the gas references `gas` and
//! `frozenGas` as [surroundings' pressure Pa, reference volume m³]) and its parameters by the
//! page's old names (`stiffness`, `springDamping`, `gravity`, `groundOn`, `volumeMode` as an
//! index into exact/box/sphere, `integrator` as an index into euler/midpoint/rk4/symplectic, …),
//! with the page's state in `ui` (`dt` among it). Such a file becomes a one-body world whose
//! springs follow the triangles exactly as they did (the mesh is taken as it is, never welded),
//! so it continues where it was saved.

use crate::snapshot::{self, BodyV1, IntegratorV1, MaterialV1, SettingsV1, VolumeModeV1, WorldV1};
use crate::world::{World, WorldSettings};
use crate::Material;
use serde::Deserialize;
use std::collections::BTreeMap;

#[derive(Deserialize)]
#[serde(rename_all = "camelCase")]
struct BodyFileV1 {
    triangles: Vec<f64>,
    pinned: Vec<f64>,
    gas: [f64; 2],
    frozen_gas: [f64; 2],
    #[serde(default)]
    params: BTreeMap<String, serde_json::Value>,
    positions: Vec<f64>,
    velocities: Vec<f64>,
    rest_lengths: Vec<f64>,
    masses: Vec<f64>,
    frozen_positions: Vec<f64>,
    frozen_rest_lengths: Vec<f64>,
    prestress: Vec<f64>,
    frozen_prestress: Vec<f64>,
    bending_rest_lengths: Vec<f64>,
    frozen_bending_rest_lengths: Vec<f64>,
}

/// A project's name and the page's state (`ui`) as the file had them.
pub struct ProjectMeta {
    pub name: String,
    pub ui: serde_json::Value,
}

const VOLUME_MODES: [VolumeModeV1; 3] = [VolumeModeV1::Exact, VolumeModeV1::Box, VolumeModeV1::Sphere];
const INTEGRATORS: [IntegratorV1; 4] = [IntegratorV1::Euler, IntegratorV1::Midpoint, IntegratorV1::Rk4, IntegratorV1::Symplectic];

/// A version-1 project file → a one-body world, and the file's name and `ui`. Errors say what
/// is wrong ("not JSON", "version 3 is newer…", "'masses' has 10 values, expected 12", …).
pub fn project_v1(bytes: &[u8]) -> Result<(World, ProjectMeta), String> {
    let j: serde_json::Value = serde_json::from_slice(bytes).map_err(|e| format!("not a SoftSculpt project (not JSON: {e})"))?;
    if j.get("format").and_then(|f| f.as_str()) != Some("softsculpt-project") {
        return Err("not a SoftSculpt project (no \"format\": \"softsculpt-project\")".into());
    }
    match j.get("version").and_then(|v| v.as_u64()) {
        Some(1) => {}
        Some(v) if v > 1 => return Err(format!("project version {v} is not a version-1 file")),
        _ => return Err("the project's \"version\" is missing or not a whole number".into()),
    }
    let b: BodyFileV1 = serde_path_to_error::deserialize(j.get("body").cloned().unwrap_or_default())
        .map_err(|e| format!("project: body.{}: {}", e.path(), e.inner()))?;
    let name = j.get("name").and_then(|n| n.as_str()).unwrap_or("project").to_string();
    let ui = j.get("ui").cloned().filter(|u| u.is_object()).unwrap_or_else(|| serde_json::json!({}));

    let n = b.masses.len();
    let whole = |v: &[f64], what: &str| -> Result<Vec<u32>, String> {
        v.iter().map(|&x| if x >= 0.0 && x.fract() == 0.0 && x < u32::MAX as f64 { Ok(x as u32) } else { Err(format!("project: '{what}' must hold whole numbers ≥ 0, got {x}")) }).collect()
    };
    let idx = whole(&b.triangles, "triangles")?;
    if idx.len() % 3 != 0 {
        return Err(format!("project: 'triangles' has {} indices, not a multiple of 3", idx.len()));
    }
    if b.pinned.len() != n {
        return Err(format!("project: 'pinned' has {} values, expected {n} (one per vertex)", b.pinned.len()));
    }
    let num = |k: &str| b.params.get(k).and_then(|v| v.as_f64());
    let mat = Material::default();
    let pick = |k: &str, d: f64| num(k).unwrap_or(d);
    let material = MaterialV1 {
        stiffness: pick("stiffness", mat.stiffness),
        spring_damping: pick("springDamping", mat.spring_damping),
        bending_stiffness: pick("bendingStiffness", mat.bending_stiffness),
        damping: pick("damping", mat.damping),
        gas_amount: pick("gasAmount", mat.gas_amount),
        temperature: pick("temperature", mat.temperature),
        volume_mode: VOLUME_MODES[choice(num("volumeMode"), 3, "volumeMode")?.unwrap_or(0)].clone(),
        self_collision: pick("selfCollision", 0.0) != 0.0,
    };
    let ws = WorldSettings::default();
    let ground_on = num("groundOn").map_or(ws.ground.is_some(), |g| g != 0.0);
    let default_ground = ws.ground.unwrap_or(crate::world::Ground::at(0.0));
    let dt = ui.get("dt").and_then(|d| d.as_f64()).filter(|d| d.is_finite() && *d > 0.0).unwrap_or(ws.dt);
    let settings = SettingsV1 {
        gravity: pick("gravity", ws.gravity),
        wind: [pick("windX", ws.wind[0]), pick("windY", ws.wind[1]), pick("windZ", ws.wind[2])],
        wind_drag: pick("windDrag", ws.wind_drag),
        ground: ground_on.then(|| [pick("groundHeight", default_ground.height), pick("friction", default_ground.friction), default_ground.restitution]),
        obstacles: Vec::new(),
        integrator: INTEGRATORS[choice(num("integrator"), 4, "integrator")?.unwrap_or(3)].clone(),
        dt,
        contact_thickness: ws.contact.thickness,
        contact_friction: ws.contact.friction,
        edge_contact: ws.contact.edge_contact,
    };
    let body = BodyV1 {
        material,
        triangles: idx.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect(),
        user_force: vec![0.0; b.positions.len()],
        face_pressure: vec![0.0; idx.len() / 3],
        x: b.positions,
        v: b.velocities,
        rest: b.rest_lengths,
        bending_rest: b.bending_rest_lengths,
        mass: b.masses,
        pinned: (0..n).filter(|&i| b.pinned[i] != 0.0).map(|i| i as u32).collect(),
        prestress: b.prestress,
        gas: b.gas,
        frozen_x: b.frozen_positions,
        frozen_rest: b.frozen_rest_lengths,
        frozen_bending_rest: b.frozen_bending_rest_lengths,
        frozen_gas: b.frozen_gas,
        frozen_prestress: b.frozen_prestress,
    };
    let payload = WorldV1 { settings, steps: 0, t_base: 0.0, since: 0, clock_dt: dt, bodies: vec![body], events: Vec::new(), next_event: 0, loads: Vec::new() };
    let world = snapshot::world_from_v1(payload).map_err(|e| format!("project: {}", e.trim_start_matches("body 0: ")))?;
    Ok((world, ProjectMeta { name, ui }))
}

/// An index into a list of `count` names, stored as a number.
fn choice(v: Option<f64>, count: usize, what: &str) -> Result<Option<usize>, String> {
    match v {
        None => Ok(None),
        Some(x) if x >= 0.0 && x.fract() == 0.0 && (x as usize) < count => Ok(Some(x as usize)),
        Some(x) => Err(format!("project: '{what}' must be 0 to {}, got {x}", count - 1)),
    }
}
