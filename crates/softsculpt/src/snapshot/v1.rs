//! Snapshot format versions 1 and 2 (`super` holds the header and the policy): the version-1
//! payload, a whole world in plain types, and the version-2 extension (each body's targets);
//! written from a world and read back into one. Every later version starts with this payload.

use crate::body::{Faces, Frozen, GasReference, Material, Model, SoftBody, Springs, State, VolumeMode, Work};
use crate::mesh::{topology, TriMesh};
use crate::world::{Action, ContactSettings, Event, Events, Ground, Integrator, Load, Obstacle, Shape, World, WorldSettings};
use serde::{Deserialize, Serialize};

// ----- the payload, version 1 --------------------------------------------------------------------

/// A whole world.
#[derive(Clone, Serialize, Deserialize)]
pub struct WorldV1 {
    pub settings: SettingsV1,
    /// Steps taken; time = t_base + since · clock_dt (s).
    pub steps: u64,
    pub t_base: f64,
    pub since: u64,
    pub clock_dt: f64,
    pub bodies: Vec<BodyV1>,
    /// The events not fired yet, in time order.
    pub events: Vec<EventV1>,
    /// Index of the next event to fire (0 as written: only pending events are kept).
    pub next_event: u64,
    pub loads: Vec<LoadV1>,
}

/// `WorldSettings`; units as there (m/s², m/s, N·s/m³, s, m).
#[derive(Clone, Serialize, Deserialize)]
pub struct SettingsV1 {
    pub gravity: f64,
    pub wind: [f64; 3],
    pub wind_drag: f64,
    /// Height (m), friction, restitution.
    pub ground: Option<[f64; 3]>,
    pub obstacles: Vec<ObstacleV1>,
    pub integrator: IntegratorV1,
    pub dt: f64,
    pub contact_thickness: f64,
    pub contact_friction: f64,
    pub edge_contact: bool,
}

#[derive(Clone, Serialize, Deserialize)]
pub enum IntegratorV1 {
    Euler,
    Midpoint,
    Rk4,
    Symplectic,
}

#[derive(Clone, Serialize, Deserialize)]
pub struct ObstacleV1 {
    pub shape: ShapeV1,
    pub friction: f64,
}

/// Obstacle shapes (m); a mesh as positions (flat xyz) and triangles.
#[derive(Clone, Serialize, Deserialize)]
pub enum ShapeV1 {
    Sphere { center: [f64; 3], radius: f64 },
    Box { center: [f64; 3], half: [f64; 3], axes: [[f64; 3]; 3] },
    Capsule { a: [f64; 3], b: [f64; 3], radius: f64 },
    Mesh { positions: Vec<f64>, triangles: Vec<[u32; 3]> },
}

/// `Material`; units as there (N/m, N·s/m, N/m, 1/s, mol, K).
#[derive(Clone, Serialize, Deserialize)]
pub struct MaterialV1 {
    pub stiffness: f64,
    pub spring_damping: f64,
    pub bending_stiffness: f64,
    pub damping: f64,
    pub gas_amount: f64,
    pub temperature: f64,
    pub volume_mode: VolumeModeV1,
    pub self_collision: bool,
}

#[derive(Clone, Serialize, Deserialize)]
pub enum VolumeModeV1 {
    Exact,
    Box,
    Sphere,
}

/// One body. Per-vertex arrays are flat xyz (3 values per vertex) unless said otherwise; rest
/// lengths follow the springs' order, which the triangles determine (edges sorted by (i, j)).
#[derive(Clone, Serialize, Deserialize)]
pub struct BodyV1 {
    pub material: MaterialV1,
    pub triangles: Vec<[u32; 3]>,
    /// Positions (m) and velocities (m/s).
    pub x: Vec<f64>,
    pub v: Vec<f64>,
    /// Rest lengths of the edge springs and of the bending springs (m).
    pub rest: Vec<f64>,
    pub bending_rest: Vec<f64>,
    /// Vertex masses (kg), one per vertex, and the pinned vertices.
    pub mass: Vec<f64>,
    pub pinned: Vec<u32>,
    /// User forces (N), the load kept by a freeze under load (N), face pressures (Pa, one per
    /// face).
    pub user_force: Vec<f64>,
    pub prestress: Vec<f64>,
    pub face_pressure: Vec<f64>,
    /// Gas reference: surroundings' pressure (Pa), reference volume (m³).
    pub gas: [f64; 2],
    /// The frozen state `reset` returns to.
    pub frozen_x: Vec<f64>,
    pub frozen_rest: Vec<f64>,
    pub frozen_bending_rest: Vec<f64>,
    pub frozen_gas: [f64; 2],
    pub frozen_prestress: Vec<f64>,
}

/// A timed event: time (s), body index, scene line, action.
#[derive(Clone, Serialize, Deserialize)]
pub struct EventV1 {
    pub time: f64,
    pub body: u32,
    pub line: u32,
    pub action: ActionV1,
}

/// `world::Action`, indices as u32.
#[derive(Clone, Serialize, Deserialize)]
pub enum ActionV1 {
    Freeze { under_load: bool },
    Reset,
    SetGas { amount: Option<f64>, temperature: Option<f64>, nrt: Option<f64> },
    SetWind([f64; 3]),
    Force { vertices: Vec<u32>, per_vertex: [f64; 3], until: f64 },
    Pressure { faces: Vec<u32>, pressure: f64, until: f64 },
    Pin(Vec<u32>),
    Unpin(Vec<u32>),
    Inflate(Vec<f64>),
    SetMass { vertices: Vec<u32>, mass: f64 },
}

/// A load in force until `until` (s): forces (N per listed vertex) or pressures (Pa per listed
/// face) on body `body`.
#[derive(Clone, Serialize, Deserialize)]
pub struct LoadV1 {
    pub body: u32,
    pub until: f64,
    pub forces: Option<(Vec<u32>, [f64; 3])>,
    pub pressures: Option<(Vec<u32>, f64)>,
}

// ----- the payload, version 2 --------------------------------------------------------------------

/// Version 2: the version-1 payload and what version 2 added.
#[derive(Clone, Serialize, Deserialize)]
pub struct WorldV2 {
    pub base: WorldV1,
    pub ext: ExtensionV2,
}

/// What version 2 added: the implicit integrator and its settings, target springs.
#[derive(Clone, Serialize, Deserialize)]
pub struct ExtensionV2 {
    /// The integrator is `implicit` (the version-1 part then says `Symplectic`).
    pub implicit: bool,
    /// Relative residual tolerance (dimensionless) and Newton iteration cap.
    pub tolerance: f64,
    pub newton_iterations: u32,
    /// Every body's target springs, in body order.
    pub targets: Vec<Vec<TargetV2>>,
}

/// A target spring: vertex, anchor (m), stiffness (N/m), damping (N·s/m).
#[derive(Clone, Serialize, Deserialize)]
pub struct TargetV2 {
    pub vertex: u32,
    pub anchor: [f64; 3],
    pub stiffness: f64,
    pub damping: f64,
}

/// The version-2 additions of `w`.
pub(crate) fn extension(w: &World) -> ExtensionV2 {
    ExtensionV2 {
        implicit: w.settings.integrator == Integrator::Implicit,
        tolerance: w.settings.tolerance,
        newton_iterations: w.settings.newton_iterations,
        targets: w
            .bodies
            .iter()
            .map(|b| b.targets().iter().map(|t| TargetV2 { vertex: t.vertex as u32, anchor: t.anchor, stiffness: t.stiffness, damping: t.damping }).collect())
            .collect(),
    }
}

/// Apply version-2 additions to a world read from a version-1 payload.
pub(crate) fn apply_extension(w: &mut World, ext: &ExtensionV2) -> Result<(), String> {
    if ext.implicit {
        w.settings.integrator = Integrator::Implicit;
    }
    w.settings.tolerance = ext.tolerance;
    w.settings.newton_iterations = ext.newton_iterations;
    w.settings.validate().map_err(|e| e.to_string())?;
    if ext.targets.len() != w.bodies.len() {
        return Err(format!("targets for {} bodies, the world has {}", ext.targets.len(), w.bodies.len()));
    }
    for (k, (b, list)) in w.bodies.iter_mut().zip(&ext.targets).enumerate() {
        let list: Vec<crate::body::Target> = list.iter().map(|t| crate::body::Target { vertex: t.vertex as usize, anchor: t.anchor, stiffness: t.stiffness, damping: t.damping }).collect();
        b.set_targets(&list).map_err(|e| format!("body {k}: {e}"))?;
    }
    Ok(())
}

// ----- writing -----------------------------------------------------------------------------------

fn u32s(v: &[usize]) -> Vec<u32> {
    v.iter().map(|&i| i as u32).collect()
}

fn body_v1(b: &SoftBody) -> BodyV1 {
    let (m, s, f) = (&b.model, &b.state, &b.frozen);
    let p = &b.material;
    BodyV1 {
        material: MaterialV1 {
            stiffness: p.stiffness,
            spring_damping: p.spring_damping,
            bending_stiffness: p.bending_stiffness,
            damping: p.damping,
            gas_amount: p.gas_amount,
            temperature: p.temperature,
            volume_mode: match p.volume_mode {
                // Version 3 says `ellipsoid` in its extension; this is the placeholder.
                VolumeMode::Exact | VolumeMode::Ellipsoid => VolumeModeV1::Exact,
                VolumeMode::Box => VolumeModeV1::Box,
                VolumeMode::Sphere => VolumeModeV1::Sphere,
            },
            self_collision: p.self_collision,
        },
        triangles: m.faces.triangles().to_vec(),
        x: s.x.clone(),
        v: s.v.clone(),
        rest: m.springs.rest.clone(),
        bending_rest: m.bending.rest.clone(),
        mass: m.mass.clone(),
        pinned: (0..m.inv_mass.len()).filter(|&i| m.inv_mass[i] == 0.0).map(|i| i as u32).collect(),
        user_force: m.user_force.clone(),
        prestress: m.prestress.clone(),
        face_pressure: m.face_pressure.clone(),
        gas: [m.gas.ambient_pressure, m.gas.reference_volume],
        frozen_x: f.x.clone(),
        frozen_rest: f.rest.clone(),
        frozen_bending_rest: f.bending_rest.clone(),
        frozen_gas: [f.gas.ambient_pressure, f.gas.reference_volume],
        frozen_prestress: f.prestress.clone(),
    }
}

fn settings_v1(w: &WorldSettings) -> SettingsV1 {
    SettingsV1 {
        gravity: w.gravity,
        wind: w.wind,
        wind_drag: w.wind_drag,
        ground: w.ground.map(|g| [g.height, g.friction, g.restitution]),
        obstacles: w
            .obstacles
            .iter()
            .map(|o| ObstacleV1 {
                friction: o.friction,
                shape: match &o.shape {
                    Shape::Sphere { center, radius } => ShapeV1::Sphere { center: *center, radius: *radius },
                    Shape::Box { center, half, axes } => ShapeV1::Box { center: *center, half: *half, axes: *axes },
                    Shape::Capsule { a, b, radius } => ShapeV1::Capsule { a: *a, b: *b, radius: *radius },
                    Shape::Mesh(m) => ShapeV1::Mesh { positions: m.positions().to_vec(), triangles: m.triangles().to_vec() },
                },
            })
            .collect(),
        integrator: match w.integrator {
            Integrator::Euler => IntegratorV1::Euler,
            Integrator::Midpoint => IntegratorV1::Midpoint,
            Integrator::Rk4 => IntegratorV1::Rk4,
            // Version 2 says `implicit` in its extension; this is the placeholder.
            Integrator::Symplectic | Integrator::Implicit => IntegratorV1::Symplectic,
        },
        dt: w.dt,
        contact_thickness: w.contact.thickness,
        contact_friction: w.contact.friction,
        edge_contact: w.contact.edge_contact,
    }
}

fn event_v1(e: &Event) -> EventV1 {
    let action = match &e.action {
        // A pending freeze's `keep_tension` has no place in `ActionV1::Freeze`: version 3 keeps
        // it beside (`ExtensionV3::keep_tension_events`).
        Action::Freeze { under_load, keep_tension: _ } => ActionV1::Freeze { under_load: *under_load },
        Action::Reset => ActionV1::Reset,
        Action::SetGas { amount, temperature, nrt } => ActionV1::SetGas { amount: *amount, temperature: *temperature, nrt: *nrt },
        Action::SetWind(w) => ActionV1::SetWind(*w),
        Action::Force { vertices, per_vertex, until } => ActionV1::Force { vertices: u32s(vertices), per_vertex: *per_vertex, until: *until },
        Action::Pressure { faces, pressure, until } => ActionV1::Pressure { faces: u32s(faces), pressure: *pressure, until: *until },
        Action::Pin(v) => ActionV1::Pin(u32s(v)),
        Action::Unpin(v) => ActionV1::Unpin(u32s(v)),
        Action::Inflate(f) => ActionV1::Inflate(f.clone()),
        Action::SetMass { vertices, mass } => ActionV1::SetMass { vertices: u32s(vertices), mass: *mass },
    };
    EventV1 { time: e.time, body: e.body as u32, line: e.line as u32, action }
}

fn load_v1(l: &Load) -> LoadV1 {
    LoadV1 {
        body: l.body as u32,
        until: l.until,
        forces: l.forces.as_ref().map(|(v, f)| (u32s(v), *f)),
        pressures: l.pressures.as_ref().map(|(v, p)| (u32s(v), *p)),
    }
}

/// The version-1 part of `w`'s snapshot (also what `crate::delta` compares).
pub(crate) fn payload(w: &World) -> WorldV1 {
    WorldV1 {
        settings: settings_v1(&w.settings),
        steps: w.clock.steps,
        t_base: w.clock.t_base,
        since: w.clock.since,
        clock_dt: w.clock.dt,
        bodies: w.bodies.iter().map(body_v1).collect(),
        // Fired events are history (they never fire again, and may no longer fit a body that
        // was replaced since): only the pending ones are kept.
        events: w.events.list[w.events.next..].iter().map(event_v1).collect(),
        next_event: 0,
        loads: w.events.loads.iter().map(load_v1).collect(),
    }
}


pub(crate) fn world_from_v1(w: WorldV1) -> Result<World, String> {
    let settings = settings_from_v1(w.settings)?;
    let bodies = w.bodies.into_iter().enumerate().map(|(k, b)| body_from_v1(b).map_err(|e| format!("body {k}: {e}"))).collect::<Result<Vec<_>, _>>()?;
    let sizes: Vec<(usize, usize)> = bodies.iter().map(|b| (b.vertex_count(), b.face_count())).collect();
    let events = w.events.into_iter().map(|e| event_from_v1(e, &sizes)).collect::<Result<Vec<_>, _>>()?;
    let loads = w.loads.into_iter().map(|l| load_from_v1(l, &sizes)).collect::<Result<Vec<_>, _>>()?;
    let next = usize::try_from(w.next_event).ok().filter(|&n| n <= events.len()).ok_or("the event cursor is past the events")?;
    if !(w.clock_dt.is_finite() && w.clock_dt > 0.0 && w.t_base.is_finite()) {
        return Err(format!("the clock is invalid (t_base {}, dt {})", w.t_base, w.clock_dt));
    }
    let mut world = World::new(bodies, settings);
    world.clock.steps = w.steps;
    world.clock.t_base = w.t_base;
    world.clock.since = w.since;
    world.clock.dt = w.clock_dt;
    world.events = Events { list: events, next, loads };
    Ok(world)
}

fn settings_from_v1(s: SettingsV1) -> Result<WorldSettings, String> {
    let mut obstacles = Vec::new();
    for o in s.obstacles {
        let mut ob = match o.shape {
            ShapeV1::Sphere { center, radius } => Obstacle::sphere(center, radius),
            ShapeV1::Box { center, half, axes } => Obstacle { shape: Shape::Box { center, half, axes }, friction: 0.0 },
            ShapeV1::Capsule { a, b, radius } => Obstacle::capsule(a, b, radius),
            ShapeV1::Mesh { positions, triangles } => Obstacle::triangle_mesh(&TriMesh { positions, triangles })?,
        };
        ob.friction = o.friction;
        obstacles.push(ob);
    }
    let settings = WorldSettings {
        gravity: s.gravity,
        wind: s.wind,
        wind_drag: s.wind_drag,
        ground: s.ground.map(|[height, friction, restitution]| Ground { height, friction, restitution }),
        obstacles,
        integrator: match s.integrator {
            IntegratorV1::Euler => Integrator::Euler,
            IntegratorV1::Midpoint => Integrator::Midpoint,
            IntegratorV1::Rk4 => Integrator::Rk4,
            IntegratorV1::Symplectic => Integrator::Symplectic,
        },
        dt: s.dt,
        tolerance: crate::params::TOLERANCE.number(),
        newton_iterations: crate::params::NEWTON_ITERATIONS.number() as u32,
        give_up: None,
        relax: false,
        deadline: None,
        interrupt: None,
        contact: ContactSettings { thickness: s.contact_thickness, friction: s.contact_friction, edge_contact: s.edge_contact },
    };
    settings.validate().map_err(|e| e.to_string())?;
    Ok(settings)
}

/// A V0 that is not positive was written by a Freeze of an open surface before V0 was kept
/// positive (`GasReference::volume_for`: 1 m³ there, as now); read the same way, so such a
/// project still opens. V0 enters only the gas energy (P = nRT/V does not depend on it), so
/// the body steps to the same bits as before.
fn gas(g: [f64; 2]) -> Result<GasReference, String> {
    if !g.iter().all(|v| v.is_finite()) {
        return Err(format!("gas reference {g:?} must be finite"));
    }
    Ok(GasReference { ambient_pressure: g[0], reference_volume: GasReference::volume_for(g[1]) })
}

fn body_from_v1(b: BodyV1) -> Result<SoftBody, String> {
    let m = b.material;
    let material = Material {
        stiffness: m.stiffness,
        spring_damping: m.spring_damping,
        bending_stiffness: m.bending_stiffness,
        damping: m.damping,
        gas_amount: m.gas_amount,
        temperature: m.temperature,
        volume_mode: match m.volume_mode {
            VolumeModeV1::Exact => VolumeMode::Exact,
            VolumeModeV1::Box => VolumeMode::Box,
            VolumeModeV1::Sphere => VolumeMode::Sphere,
        },
        self_collision: m.self_collision,
        ..Material::default()
    };
    material.validate().map_err(|e| e.to_string())?;
    let n = b.mass.len();
    if n == 0 || b.triangles.is_empty() {
        return Err("no vertices or no faces".into());
    }
    if let Some(t) = b.triangles.iter().flatten().find(|&&i| i as usize >= n) {
        return Err(format!("a face refers to vertex {t} of {n}"));
    }
    let faces = b.triangles.len();
    for (what, len, want) in [
        ("positions", b.x.len(), 3 * n),
        ("velocities", b.v.len(), 3 * n),
        ("user forces", b.user_force.len(), 3 * n),
        ("prestress", b.prestress.len(), 3 * n),
        ("face pressures", b.face_pressure.len(), faces),
        ("frozen positions", b.frozen_x.len(), 3 * n),
        ("frozen prestress", b.frozen_prestress.len(), 3 * n),
    ] {
        if len != want {
            return Err(format!("{what}: {len} values, expected {want}"));
        }
    }
    if let Some(m) = b.mass.iter().find(|m| !(m.is_finite() && **m > 0.0)) {
        return Err(format!("vertex mass {m} must be finite and > 0"));
    }
    let mut springs = Springs::new(&topology::edges(&b.triangles), &b.x);
    let mut bending = Springs::new(&topology::bending_pairs(&b.triangles), &b.x);
    for (what, len, want) in [
        ("rest lengths", b.rest.len(), springs.len()),
        ("frozen rest lengths", b.frozen_rest.len(), springs.len()),
        ("bending rest lengths", b.bending_rest.len(), bending.len()),
        ("frozen bending rest lengths", b.frozen_bending_rest.len(), bending.len()),
    ] {
        if len != want {
            return Err(format!("{what}: {len} values, expected {want}"));
        }
    }
    springs.rest = b.rest;
    bending.rest = b.bending_rest;
    let mut inv_mass: Vec<f64> = b.mass.iter().map(|m| 1.0 / m).collect();
    for &p in &b.pinned {
        *inv_mass.get_mut(p as usize).ok_or_else(|| format!("pinned vertex {p} of {n}"))? = 0.0;
    }
    let counts = topology::count_edges(&b.triangles);
    let external: Vec<f64> = b.user_force.iter().zip(&b.prestress).map(|(u, p)| u + p).collect();
    let hinges = crate::body::hinges::Hinges::new(&b.triangles);
    let model = Model {
        faces: Faces::new(b.triangles, n),
        springs,
        bending,
        hinges,
        closed: counts.boundary == 0 && counts.non_manifold == 0,
        mass: b.mass,
        inv_mass,
        external_active: external.iter().any(|&f| f != 0.0),
        external,
        user_force: b.user_force,
        prestress: b.prestress,
        face_pressure_active: b.face_pressure.iter().any(|&p| p != 0.0),
        face_pressure: b.face_pressure,
        gas: gas(b.gas)?,
        targets: Default::default(),
        self_contacts: Default::default(),
        plastic_dissipation: 0.0,
    };
    let frozen = Frozen { x: b.frozen_x, rest: b.frozen_rest, bending_rest: b.frozen_bending_rest, gas: gas(b.frozen_gas)?, prestress: b.frozen_prestress };
    let mut body = SoftBody { material, model, state: State { x: b.x, v: b.v, warm: Vec::new(), warm_dt: 0.0, kept: crate::body::implicit::Kept::default() }, work: Work::new(3 * n), frozen };
    // The hinges' rest angles are the frozen shape's, recomputed as the springs are.
    body.hinges_to_frozen();
    Ok(body)
}

/// Indices of `list` checked against `limit`.
fn indices(list: Vec<u32>, limit: usize, what: &str) -> Result<Vec<usize>, String> {
    match list.iter().find(|&&i| i as usize >= limit) {
        Some(i) => Err(format!("{what} {i} of {limit}")),
        None => Ok(list.into_iter().map(|i| i as usize).collect()),
    }
}

fn event_from_v1(e: EventV1, sizes: &[(usize, usize)]) -> Result<Event, String> {
    let body = e.body as usize;
    let &(nv, nf) = sizes.get(body).ok_or_else(|| format!("an event for body {body} of {}", sizes.len()))?;
    let action = match e.action {
        ActionV1::Freeze { under_load } => Action::Freeze { under_load, keep_tension: false },
        ActionV1::Reset => Action::Reset,
        ActionV1::SetGas { amount, temperature, nrt } => Action::SetGas { amount, temperature, nrt },
        ActionV1::SetWind(w) => Action::SetWind(w),
        ActionV1::Force { vertices, per_vertex, until } => Action::Force { vertices: indices(vertices, nv, "event vertex")?, per_vertex, until },
        ActionV1::Pressure { faces, pressure, until } => Action::Pressure { faces: indices(faces, nf, "event face")?, pressure, until },
        ActionV1::Pin(v) => Action::Pin(indices(v, nv, "event vertex")?),
        ActionV1::Unpin(v) => Action::Unpin(indices(v, nv, "event vertex")?),
        ActionV1::Inflate(f) if f.len() == nv => Action::Inflate(f),
        ActionV1::Inflate(f) => return Err(format!("an inflate event has {} factors for {nv} vertices", f.len())),
        ActionV1::SetMass { vertices, mass } => Action::SetMass { vertices: indices(vertices, nv, "event vertex")?, mass },
    };
    Ok(Event { time: e.time, body, action, line: e.line as usize })
}

fn load_from_v1(l: LoadV1, sizes: &[(usize, usize)]) -> Result<Load, String> {
    let body = l.body as usize;
    let &(nv, nf) = sizes.get(body).ok_or_else(|| format!("a load on body {body} of {}", sizes.len()))?;
    let forces = match l.forces {
        Some((v, f)) => Some((indices(v, nv, "load vertex")?, f)),
        None => None,
    };
    let pressures = match l.pressures {
        Some((v, p)) => Some((indices(v, nf, "load face")?, p)),
        None => None,
    };
    Ok(Load { body, until: l.until, forces, pressures })
}
