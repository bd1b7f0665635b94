//! From a parsed scene to a world: load and place meshes, set materials, resolve regions and
//! events, and check what the file format alone cannot, naming the line of the table at fault.

use super::events::Event;
use super::spec::{BodySpec, GroundSpec, ObstacleSpec, RegionSpec, RotateSpec, SceneSpec, WorldSpec};
use super::{line_of, SceneError};
use crate::body::{moles, GasReference, Material, SoftBody, VolumeMode, DEFAULT_TEMPERATURE};
use crate::params::{self as table, Param, ParamId, Range};
use crate::geometry::rotate;
use crate::world::{ContactSettings, Ground, Integrator, Obstacle, WorldSettings};
use crate::mesh::{builtin, load, load_obj, LoadedMesh, MeshFormat};
use crate::vec3::{add, dot, normalize, scale, V3};

/// Reads a mesh file named in the scene (a path relative to the scene file) as bytes.
pub type Resolver<'a> = &'a mut dyn FnMut(&str) -> Result<Vec<u8>, String>;

/// A body ready to run, with what output needs.
pub struct BuiltBody {
    pub name: String,
    pub body: SoftBody,
    /// The mesh as loaded (its source polygons and vertex order, for writing OBJ files).
    pub mesh: LoadedMesh,
}

pub struct Built {
    pub bodies: Vec<BuiltBody>,
    pub events: Vec<Event>,
    /// The world's settings: `[world]` and the obstacles.
    pub settings: WorldSettings,
    /// Length of the run (s).
    pub duration: f64,
}

/// A table of the scene being checked: its text from byte `from` on (its header), its 1-based
/// line, and its path (`body[0]`) for errors.
pub(super) struct Ctx<'a> {
    text: &'a str,
    from: usize,
    pub(super) line: usize,
    table: String,
}

impl<'a> Ctx<'a> {
    pub(super) fn new(text: &'a str, from: usize, table: String) -> Self {
        Ctx { text, from, line: line_of(text, from), table }
    }
    /// An error about `key` of this table, at the line that sets the key if the table's text
    /// has it (else at the table's header: a value a preset or a default gave).
    pub(super) fn err(&self, key: &str, message: impl Into<String>) -> SceneError {
        let line = key_line(self.text, self.from, &self.table, key).unwrap_or(self.line);
        let key = if key.is_empty() { self.table.clone() } else { format!("{}.{key}", self.table) };
        SceneError { line: Some(line), key: Some(key), message: message.into() }
    }
    pub(super) fn finite(&self, key: &str, v: f64) -> Result<f64, SceneError> {
        if v.is_finite() { Ok(v) } else { Err(self.err(key, format!("must be a finite number, got {v}"))) }
    }
    pub(super) fn positive(&self, key: &str, v: f64) -> Result<f64, SceneError> {
        if v.is_finite() && v > 0.0 { Ok(v) } else { Err(self.err(key, format!("must be greater than 0, got {v}"))) }
    }
    pub(super) fn vec(&self, key: &str, v: [f64; 3]) -> Result<V3, SceneError> {
        if v.iter().all(|x| x.is_finite()) { Ok(v) } else { Err(self.err(key, format!("must be finite, got {v:?}"))) }
    }
    /// Number `v` of table parameter `p` under `key`, checked against the table's range (in the
    /// scene format's words: "must be 0 or more", "must be greater than 0", …).
    pub(super) fn param(&self, key: &str, p: &Param, v: f64) -> Result<f64, SceneError> {
        if p.range.contains(v) { Ok(v) } else { Err(self.err(key, format!("{}, got {v}", must(&p.range)))) }
    }
}

/// What a value outside `r` must be, as the scene format says it.
fn must(r: &Range) -> String {
    let unbounded_above = r.max == f64::INFINITY;
    if unbounded_above && r.min == f64::NEG_INFINITY {
        "must be a finite number".into()
    } else if unbounded_above && r.min == 0.0 {
        if r.min_open { "must be greater than 0".into() } else { "must be 0 or more".into() }
    } else {
        format!("must be {}", r.describe())
    }
}

/// The 1-based line at which the table starting at byte `from` of `text` sets `key` (its last
/// dotted part: `nrt` of `gas.nrt`, as `nrt = …` under `[body.gas]` or inside `gas = { nrt = … }`),
/// searched up to the next table that is not one of its own sub-tables; None if it does not.
fn key_line(text: &str, from: usize, table: &str, key: &str) -> Option<usize> {
    let base = table.split('[').next().unwrap_or(table);
    // An entry of a list (`masses[0].mass`): its own key names recur in the table (the body's
    // `mass`), so the table's header is cited instead.
    if key.contains('[') {
        return None;
    }
    let last = key.rsplit('.').next().filter(|k| !k.is_empty())?;
    let mut offset = from.min(text.len());
    for (i, line) in text[offset..].split_inclusive('\n').enumerate() {
        let t = line.trim_start();
        if i > 0 && t.starts_with('[') {
            let name = t.trim_start_matches('[').split([']', '.']).next().unwrap_or("").trim();
            if name != base || t.starts_with("[[") {
                return None;
            }
        }
        let code = t.split('#').next().unwrap_or("");
        let at = code.match_indices(last).find(|&(p, _)| {
            let before = code[..p].trim_end();
            let after = code[p + last.len()..].trim_start();
            (before.is_empty() || before.ends_with('{') || before.ends_with(',')) && after.starts_with('=')
        });
        if let Some((p, _)) = at {
            return Some(line_of(text, offset + (line.len() - t.len()) + p));
        }
        offset += line.len();
    }
    None
}

/// Build every body, obstacle and event of `spec` (parsed from `text`): the world's settings
/// (with the obstacles), then the bodies, then the events that act on them, each checked as
/// it is read (the first error stops the build).
pub fn build(spec: &SceneSpec, text: &str, resolve: Resolver) -> Result<Built, SceneError> {
    let settings = world_settings(spec, text, resolve)?;
    let bodies = built_bodies(spec, text, settings.ground, resolve)?;
    let events = super::events::resolve(spec, text, &bodies)?;
    Ok(Built { bodies, events, settings, duration: spec.world.duration })
}

/// `[world]` checked, then the obstacles, into the world's settings.
fn world_settings(spec: &SceneSpec, text: &str, resolve: Resolver) -> Result<WorldSettings, SceneError> {
    let w = &spec.world;
    let cx = Ctx::new(text, text.find("[world]").unwrap_or(0), "world".into());
    let integrator = check_world(&cx, w)?;
    let ground = match &w.ground {
        Some(g) => Some(check_ground(&cx, g)?),
        None => None,
    };

    let mut obstacles = Vec::new();
    for (k, o) in spec.obstacles.iter().enumerate() {
        let cx = Ctx::new(text, o.span().start, format!("obstacle[{k}]"));
        obstacles.push(obstacle(&cx, o.get_ref(), resolve)?);
    }

    Ok(WorldSettings {
        gravity: w.gravity,
        wind: w.wind,
        wind_drag: w.wind_drag,
        ground,
        obstacles,
        integrator,
        dt: w.dt,
        tolerance: w.tolerance,
        newton_iterations: w.newton_iterations,
        give_up: None,
        relax: false,
        deadline: None,
        interrupt: None,
        contact: ContactSettings { thickness: w.contact_thickness, friction: w.contact_friction, ..ContactSettings::default() },
    })
}

/// The `[world]` table's numbers checked, and its integrator.
fn check_world(cx: &Ctx, w: &WorldSpec) -> Result<Integrator, SceneError> {
    cx.param("dt", &table::DT, w.dt)?;
    cx.param("duration", &table::DURATION, w.duration)?;
    if w.duration / w.dt > 1e9 {
        return Err(cx.err("dt", format!("{} s in steps of {} s is more than 10⁹ steps", w.duration, w.dt)));
    }
    let integrator = Integrator::from_name(&w.integrator)
        .ok_or_else(|| cx.err("integrator", format!("unknown integrator '{}' (euler, midpoint, rk4, symplectic, implicit)", w.integrator)))?;
    cx.param("tolerance", &table::TOLERANCE, w.tolerance)?;
    // (A whole number already: the file's integer.)
    cx.param("newton_iterations", &table::NEWTON_ITERATIONS, w.newton_iterations as f64)?;
    cx.param("gravity", &table::GRAVITY, w.gravity)?;
    cx.vec("wind", w.wind)?;
    cx.param("wind_drag", &table::WIND_DRAG, w.wind_drag)?;
    cx.param("contact_thickness", &table::CONTACT_THICKNESS, w.contact_thickness)?;
    cx.param("contact_friction", &table::CONTACT_FRICTION, w.contact_friction)?;
    Ok(integrator)
}

/// `[world.ground]` checked.
fn check_ground(cx: &Ctx, g: &GroundSpec) -> Result<Ground, SceneError> {
    cx.param("ground.height", &table::GROUND_HEIGHT, g.height)?;
    cx.param("ground.friction", &table::GROUND_FRICTION, g.friction)?;
    cx.param("ground.restitution", &table::GROUND_RESTITUTION, g.restitution)?;
    Ok(Ground { height: g.height, friction: g.friction, restitution: g.restitution })
}

/// Every `[[body]]`, with its preset (if any) under the keys it gives itself; names unique,
/// at least one body.
fn built_bodies(spec: &SceneSpec, text: &str, ground: Option<Ground>, resolve: Resolver) -> Result<Vec<BuiltBody>, SceneError> {
    let mut bodies: Vec<BuiltBody> = Vec::new();
    // The keys each body gives itself (a preset fills the others); the text parsed already.
    let tables = text.parse::<toml::Table>().ok();
    let given = |k: usize| tables.as_ref().and_then(|t| t.get("body")?.as_array()?.get(k)?.as_table().cloned()).unwrap_or_default();
    for (k, b) in spec.bodies.iter().enumerate() {
        let cx = Ctx::new(text, b.span().start, format!("body[{k}]"));
        let mut built = body(&cx, b.get_ref(), ground, k, resolve)?;
        if let Some(name) = &b.get_ref().preset {
            apply_preset(&cx, &mut built.body, name, &given(k))?;
        }
        if bodies.iter().any(|o| o.name == built.name) {
            return Err(cx.err("name", format!("two bodies are named '{}'", built.name)));
        }
        bodies.push(built);
    }
    if bodies.is_empty() {
        return Err(SceneError { line: None, key: Some("body".into()), message: "the scene has no [[body]]".into() });
    }
    Ok(bodies)
}

fn body(cx: &Ctx, b: &BodySpec, ground: Option<Ground>, index: usize, resolve: Resolver) -> Result<BuiltBody, SceneError> {
    let mut material = Material::default();
    let name = b.name.clone().unwrap_or_else(|| format!("body{}", index + 1));
    if name.is_empty() || !name.chars().all(|c| c.is_alphanumeric() || c == '_' || c == '-') {
        return Err(cx.err("name", format!("'{name}' must be letters, digits, '_' or '-' (it names output files)")));
    }
    let mut mesh = match (&b.model, &b.mesh, &b.obj) {
        (Some(m), None, None) => LoadedMesh::from_trimesh(builtin::builtin(m).map_err(|e| cx.err("model", e.to_string()))?),
        (None, Some(path), None) => {
            load_file(cx, path, resolve)?
        }
        (None, None, Some(text)) => load_obj(text.as_bytes()).map_err(|e| cx.err("obj", e.to_string()))?,
        (None, None, None) => return Err(cx.err("", "needs a surface: `model`, `mesh` or `obj`")),
        _ => return Err(cx.err("", "give exactly one of `model`, `mesh` and `obj`")),
    };
    let s = cx.positive("scale", b.scale)?;
    let rot = match &b.rotate {
        Some(r) => Some(rotation(cx, "rotate", r)?),
        None => None,
    };
    let t = cx.vec("translate", b.translate)?;
    let place = |p: V3| add(rot.as_ref().map_or(scale(p, s), |r| r(scale(p, s))), t);
    for x in [&mut mesh.mesh.positions, &mut mesh.source.positions] {
        for c in x.chunks_exact_mut(3) {
            c.copy_from_slice(&place([c[0], c[1], c[2]]));
        }
    }
    if b.on_ground {
        let Some(g) = ground else {
            return Err(cx.err("on_ground", "needs a ground: add [world.ground]"));
        };
        let lowest = mesh.mesh.positions.chunks_exact(3).map(|c| c[1]).fold(f64::INFINITY, f64::min);
        for x in [&mut mesh.mesh.positions, &mut mesh.source.positions] {
            for c in x.chunks_exact_mut(3) {
                c[1] += g.height - lowest;
            }
        }
    }
    material.stiffness = cx.param("stiffness", &table::STIFFNESS, b.stiffness)?;
    material.spring_damping = cx.param("spring_damping", &table::SPRING_DAMPING, b.spring_damping)?;
    material.bending_stiffness = cx.param("bending", &table::BENDING, b.bending)?;
    material.rigidity = cx.param("rigidity", &table::RIGIDITY, b.rigidity)?;
    material.damping = cx.param("damping", &table::DAMPING, b.damping)?;
    material.yield_strain = cx.param("yield", &table::YIELD, b.yield_strain)?;
    material.flow_rate = cx.param("flow", &table::FLOW, b.flow)?;
    material.self_collision = b.self_collision;
    if let Some(g) = &b.gas {
        material.temperature = cx.param("gas.temperature", &table::TEMPERATURE, g.temperature.unwrap_or(DEFAULT_TEMPERATURE))?;
        material.gas_amount = match (g.amount, g.nrt) {
            (Some(_), Some(_)) => return Err(cx.err("gas", "give `amount` (mol) or `nrt` (J), not both")),
            (Some(a), None) => cx.param("gas.amount", &table::GAS_AMOUNT, a)?,
            (None, Some(n)) => moles(cx.param("gas.nrt", &table::GAS_NRT, n)?, material.temperature),
            (None, None) => return Err(cx.err("gas", "needs `amount` (mol) or `nrt` (J)")),
        };
        if let Some(v) = &g.volume {
            material.volume_mode = VolumeMode::from_name(v)
                .ok_or_else(|| cx.err("gas.volume", format!("unknown volume mode '{v}' ({})", VolumeMode::NAMES.join(", "))))?;
        }
    }
    let mass = cx.param("mass", &table::MASS, b.mass)?;
    let mut body = SoftBody::new(&mesh.mesh, mass, material).map_err(|e| cx.err(if b.gas.is_some() { "gas" } else { "" }, e.to_string()))?;
    if let Some(ambient) = b.gas.as_ref().and_then(|g| g.ambient) {
        let gas = GasReference { ambient_pressure: cx.param("gas.ambient", &table::AMBIENT, ambient)?, reference_volume: body.gas_reference().reference_volume };
        let (x, rest) = (body.positions().to_vec(), body.rest_lengths().to_vec());
        body.set_gas_reference(gas).and_then(|_| body.set_frozen(&x, &rest, gas)).map_err(|e| cx.err("gas.ambient", e.to_string()))?;
    }
    for (k, m) in b.masses.iter().enumerate() {
        let key = format!("masses[{k}]");
        let mass = cx.positive(&format!("{key}.mass"), m.mass)?;
        for v in select_in(cx, &format!("{key}.region"), &m.region, &body, &mesh)? {
            body.set_vertex_mass(v, mass).map_err(|e| cx.err(&key, e.to_string()))?;
        }
    }
    for (k, r) in b.pins.iter().enumerate() {
        for v in select_in(cx, &format!("pins[{k}]"), r, &body, &mesh)? {
            body.set_pinned(v, true).map_err(|e| cx.err("pins", e.to_string()))?;
        }
    }
    body.set_uniform_velocity(cx.vec("velocity", b.velocity)?).map_err(|e| cx.err("velocity", e.to_string()))?;
    Ok(BuiltBody { name, body, mesh })
}

/// Set the values of material preset `name` on `body`, except those the body's table `given`
/// sets itself (`gas.nrt` counts as given when the `gas` table has `nrt` or `amount`).
fn apply_preset(cx: &Ctx, body: &mut SoftBody, name: &str, given: &toml::Table) -> Result<(), SceneError> {
    let p = crate::params::presets::preset(name).map_err(|e| cx.err("preset", e.message))?;
    if !p.is_material() {
        let names: Vec<&str> = crate::params::presets::PRESETS.iter().filter(|p| p.is_material()).map(|p| p.name).collect();
        return Err(cx.err("preset", format!("'{name}' sets world parameters too; a body takes a material preset ({})", names.join(", "))));
    }
    let gas = given.get("gas").and_then(|g| g.as_table());
    let has = |id: ParamId| match id.id().split_once('.') {
        Some(("gas", "nrt" | "amount")) => gas.is_some_and(|g| g.contains_key("nrt") || g.contains_key("amount")),
        Some(("gas", key)) => gas.is_some_and(|g| g.contains_key(key)),
        _ => given.contains_key(id.id()),
    };
    for &(id, v) in p.values.iter().filter(|(id, _)| !has(*id)) {
        id.param().check(&v).map_err(|e| cx.err("preset", format!("'{name}': {e}")))?;
        crate::world::set_body_param(body, id, v).map_err(|e| cx.err("preset", format!("'{name}': {e}")))?;
    }
    Ok(())
}

/// A mesh file named in the scene, in the format its extension says, else its first bytes
/// say, else OBJ (as scenes always read).
fn load_file(cx: &Ctx, path: &str, resolve: Resolver) -> Result<LoadedMesh, SceneError> {
    let bytes = resolve(path).map_err(|e| cx.err("mesh", format!("cannot read '{path}': {e}")))?;
    let format = MeshFormat::from_path(path).or_else(|| MeshFormat::sniff(&bytes)).unwrap_or(MeshFormat::Obj);
    load(&bytes, Some(format)).map_err(|e| cx.err("mesh", format!("{path}: {e}")))
}

fn obstacle(cx: &Ctx, o: &ObstacleSpec, resolve: Resolver) -> Result<Obstacle, SceneError> {
    let need = |v: Option<[f64; 3]>, key: &str| -> Result<V3, SceneError> {
        cx.vec(key, v.ok_or_else(|| cx.err(key, format!("a {} obstacle needs `{key}`", o.shape)))?)
    };
    let radius = || cx.positive("radius", o.radius.ok_or_else(|| cx.err("radius", format!("a {} obstacle needs `radius`", o.shape)))?);
    let allowed: &[&str] = match o.shape.as_str() {
        "sphere" => &["center", "radius"],
        "box" => &["center", "half_extents", "rotate"],
        "capsule" => &["a", "b", "radius"],
        "mesh" => &["mesh", "model", "scale", "translate"],
        s => return Err(cx.err("shape", format!("unknown shape '{s}' (sphere, box, capsule, mesh)"))),
    };
    let set = [
        ("center", o.center.is_some()),
        ("radius", o.radius.is_some()),
        ("half_extents", o.half_extents.is_some()),
        ("rotate", o.rotate.is_some()),
        ("a", o.a.is_some()),
        ("b", o.b.is_some()),
        ("mesh", o.mesh.is_some()),
        ("model", o.model.is_some()),
        ("scale", o.scale.is_some()),
        ("translate", o.translate.is_some()),
    ];
    if let Some((k, _)) = set.iter().find(|(k, s)| *s && !allowed.contains(k)) {
        return Err(cx.err(k, format!("a {} obstacle does not take `{k}`", o.shape)));
    }
    let mut ob = match o.shape.as_str() {
        "sphere" => Obstacle::sphere(need(o.center, "center")?, radius()?),
        "box" => {
            let half = need(o.half_extents, "half_extents")?;
            for h in half {
                cx.positive("half_extents", h)?;
            }
            match &o.rotate {
                Some(r) => {
                    cx.vec("rotate.axis", r.axis)?;
                    if dot(r.axis, r.axis) == 0.0 {
                        return Err(cx.err("rotate.axis", "must not be zero"));
                    }
                    Obstacle::rotated_box(need(o.center, "center")?, half, r.axis, cx.finite("rotate.degrees", r.degrees)?.to_radians())
                }
                None => Obstacle::aabb(need(o.center, "center")?, half),
            }
        }
        "capsule" => Obstacle::capsule(need(o.a, "a")?, need(o.b, "b")?, radius()?),
        _ => {
            let mut mesh = match (&o.mesh, &o.model) {
                (Some(path), None) => {
                    load_file(cx, path, resolve)?.mesh
                }
                (None, Some(m)) => builtin::builtin(m).map_err(|e| cx.err("model", e.to_string()))?,
                _ => return Err(cx.err("mesh", "a mesh obstacle needs exactly one of `mesh` (a file) and `model`")),
            };
            let s = cx.positive("scale", o.scale.unwrap_or(1.0))?;
            let t = cx.vec("translate", o.translate.unwrap_or_default())?;
            for c in mesh.positions.chunks_exact_mut(3) {
                c.copy_from_slice(&add(scale([c[0], c[1], c[2]], s), t));
            }
            Obstacle::triangle_mesh(&mesh).map_err(|m| cx.err("mesh", m))?
        }
    };
    if let Some(f) = o.friction {
        ob.friction = cx.param("friction", &table::OBSTACLE_FRICTION, f)?;
    }
    ob.validate().map_err(|m| cx.err("", m))?;
    Ok(ob)
}

/// Rotation by `degrees` about `axis`.
fn rotation(cx: &Ctx, key: &str, r: &RotateSpec) -> Result<impl Fn(V3) -> V3, SceneError> {
    let axis = cx.vec(&format!("{key}.axis"), r.axis)?;
    if dot(axis, axis) == 0.0 {
        return Err(cx.err(&format!("{key}.axis"), "must not be zero"));
    }
    let k = normalize(axis);
    let (s, c) = cx.finite(&format!("{key}.degrees"), r.degrees)?.to_radians().sin_cos();
    Ok(move |v: V3| rotate(v, k, s, c))
}

/// The body's vertices in region `r` (positions at the start; `vertices` are indices into the
/// source file's vertex list, as a user sees them).
pub(super) fn select_in(cx: &Ctx, key: &str, r: &RegionSpec, body: &SoftBody, mesh: &LoadedMesh) -> Result<Vec<usize>, SceneError> {
    let forms = [r.center.is_some() || r.radius.is_some(), r.min.is_some() || r.max.is_some(), r.vertices.is_some(), r.all.is_some()];
    if forms.iter().filter(|&&f| f).count() != 1 {
        return Err(cx.err(key, "a region is exactly one of: `center` + `radius`, `min` + `max`, `vertices`, `all = true`"));
    }
    let x = body.positions();
    let n = body.vertex_count();
    let inside: Vec<usize> = if let Some(list) = &r.vertices {
        let mut out = Vec::new();
        for &s in list {
            let m = mesh.source_to_mesh.get(s as usize).copied().unwrap_or(u32::MAX);
            if m == u32::MAX {
                return Err(cx.err(&format!("{key}.vertices"), format!("vertex {s} is not a vertex of the mesh (it has {} vertices)", mesh.source_to_mesh.len())));
            }
            out.push(m as usize);
        }
        out
    } else if r.all.is_some() {
        if r.all != Some(true) {
            return Err(cx.err(&format!("{key}.all"), "only `all = true` makes sense"));
        }
        (0..n).collect()
    } else if r.center.is_some() || r.radius.is_some() {
        let (Some(c), Some(rad)) = (r.center, r.radius) else {
            return Err(cx.err(key, "a sphere region needs both `center` and `radius`"));
        };
        let c = cx.vec(&format!("{key}.center"), c)?;
        let rad = cx.positive(&format!("{key}.radius"), rad)?;
        (0..n).filter(|&i| {
            let d = [x[3 * i] - c[0], x[3 * i + 1] - c[1], x[3 * i + 2] - c[2]];
            dot(d, d) <= rad * rad
        })
        .collect()
    } else {
        let (Some(lo), Some(hi)) = (r.min, r.max) else {
            return Err(cx.err(key, "a box region needs both `min` and `max`"));
        };
        let lo = cx.vec(&format!("{key}.min"), lo)?;
        let hi = cx.vec(&format!("{key}.max"), hi)?;
        if (0..3).any(|d| lo[d] > hi[d]) {
            return Err(cx.err(key, format!("`min` {lo:?} must not exceed `max` {hi:?}")));
        }
        (0..n).filter(|&i| (0..3).all(|d| x[3 * i + d] >= lo[d] && x[3 * i + d] <= hi[d])).collect()
    };
    if inside.is_empty() {
        return Err(cx.err(key, "selects no vertex of the body"));
    }
    Ok(inside)
}
