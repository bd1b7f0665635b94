//! Thin WebAssembly binding of the SoftSculpt engine: raw `extern "C"` exports, no physics here.
//!
//! Bodies live in a table and are named by a handle (> 0). Bulk data crosses as pointers into wasm
//! memory, which the JavaScript side views as typed arrays (never vertex by vertex): positions
//! for rendering (`ss_render_positions`, f32, refreshed by `ss_sync`), the engine's own f64
//! arrays, and staging arrays the page writes into (user forces, face pressures, per-vertex
//! weights) before calling the operation that reads them. A pointer stays valid until the body
//! is freed or replaced (`ss_subdivide`) — and views must be re-made if wasm memory grows.
//!
//! Every fallible call returns a status (0 = ok, 1 = failed) or a handle (0 = failed); the
//! message is then in `ss_message_ptr`/`ss_message_len`. Nothing here panics on bad input.

mod scene;
mod table;

use softsculpt::body::{GasReference, Material, SoftBody, VolumeMode};
use softsculpt::mesh::{self, builtin, ObjData, TriMesh};
use softsculpt::world::{Ground, Integrator, World, WorldSettings};
use table::{with, with_table, Entry};

/// Allocate `len` bytes in wasm memory for the page to fill (e.g. a file's bytes).
#[no_mangle]
pub extern "C" fn ss_alloc(len: usize) -> *mut u8 {
    let mut v = Vec::<u8>::with_capacity(len.max(1));
    let p = v.as_mut_ptr();
    std::mem::forget(v);
    p
}

/// Free memory from [`ss_alloc`].
///
/// # Safety
/// `ptr` and `len` must come from one call of `ss_alloc`.
#[no_mangle]
pub unsafe extern "C" fn ss_dealloc(ptr: *mut u8, len: usize) {
    if !ptr.is_null() {
        drop(Vec::from_raw_parts(ptr, 0, len.max(1)));
    }
}

/// The last message (error or warnings), UTF-8.
#[no_mangle]
pub extern "C" fn ss_message_ptr() -> *const u8 {
    table::message_ptr()
}
#[no_mangle]
pub extern "C" fn ss_message_len() -> usize {
    table::message_len()
}

pub(crate) unsafe fn bytes<'a>(ptr: *const u8, len: usize) -> &'a [u8] {
    if len == 0 || ptr.is_null() {
        &[]
    } else {
        std::slice::from_raw_parts(ptr, len)
    }
}

fn create(mesh: &TriMesh, mass: f64, warnings: &[String]) -> u32 {
    match SoftBody::new(mesh, mass, Material::default()) {
        Ok(body) => {
            table::set_message(&warnings.join("\n"));
            with_table(|t| t.insert(Entry::new(World::single(body, WorldSettings::default()))))
        }
        Err(e) => table::fail(e.to_string()),
    }
}

/// A built-in model by name (`sphere`, `mushroom`, `octopus`) of total mass `mass` (kg).
///
/// # Safety
/// `name` must point to `len` readable bytes.
#[no_mangle]
pub unsafe extern "C" fn ss_create_builtin(name: *const u8, len: usize, mass: f64) -> u32 {
    let name = String::from_utf8_lossy(bytes(name, len)).into_owned();
    match builtin::builtin(&name) {
        Ok(m) => create(&mesh::reorder::by_locality(&m).0, mass, &[]),
        Err(e) => table::fail(e.to_string()),
    }
}

/// A body from OBJ bytes (welded, checked, oriented); warnings go to the message.
///
/// # Safety
/// `ptr` must point to `len` readable bytes.
#[no_mangle]
pub unsafe extern "C" fn ss_create_obj(ptr: *const u8, len: usize, mass: f64) -> u32 {
    match mesh::load_obj(bytes(ptr, len)) {
        Ok(l) => create(&l.mesh, mass, &l.report.warnings),
        Err(e) => table::fail(e.to_string()),
    }
}

/// A body from an indexed triangle mesh (positions f64 xyz, `n_indices` u32 indices), prepared
/// like a file (`weld` = 1: welded, checked, oriented, reordered) or taken as it is (`weld` = 0,
/// for restoring a saved project whose indices must not change).
///
/// # Safety
/// The pointers must point to `3 n_vertices` f64 and `n_indices` u32.
#[no_mangle]
pub unsafe extern "C" fn ss_create_mesh(pos: *const f64, n_vertices: usize, idx: *const u32, n_indices: usize, mass: f64, weld: u32) -> u32 {
    if pos.is_null() || idx.is_null() || n_indices % 3 != 0 {
        return table::fail("a mesh needs positions and a multiple of 3 indices".into());
    }
    let positions = std::slice::from_raw_parts(pos, 3 * n_vertices).to_vec();
    let indices = std::slice::from_raw_parts(idx, n_indices).to_vec();
    if let Some(bad) = indices.iter().find(|&&i| i as usize >= n_vertices) {
        return table::fail(format!("index {bad} out of range ({n_vertices} vertices)"));
    }
    if positions.iter().any(|p| !p.is_finite()) {
        return table::fail("the mesh has non-finite coordinates (NaN or infinity)".into());
    }
    if weld == 0 {
        let triangles = indices.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect();
        return create(&TriMesh { positions, triangles }, mass, &[]);
    }
    let data = ObjData { positions, arities: vec![3; n_indices / 3], indices };
    match mesh::prepare(data) {
        Ok(l) => create(&l.mesh, mass, &l.report.warnings),
        Err(e) => table::fail(e.to_string()),
    }
}

/// The standard benchmark workload at an icosphere level (see `softsculpt::workload`), with its
/// parameters; step it with `ss_step(h, 1e-4, n)`.
#[no_mangle]
pub extern "C" fn ss_create_workload(level: u32) -> u32 {
    if level > 8 {
        return table::fail(format!("level {level} is too large (at most 8)"));
    }
    with_table(|t| t.insert(Entry::new(softsculpt::workload::world(level))))
}

#[no_mangle]
pub extern "C" fn ss_free(h: u32) {
    with_table(|t| t.remove(h));
}

// ----- sizes and arrays --------------------------------------------------------------------

#[no_mangle]
pub extern "C" fn ss_vertex_count(h: u32) -> u32 {
    with(h, 0, |e| e.world.bodies[0].vertex_count() as u32)
}
#[no_mangle]
pub extern "C" fn ss_face_count(h: u32) -> u32 {
    with(h, 0, |e| e.world.bodies[0].face_count() as u32)
}
#[no_mangle]
pub extern "C" fn ss_spring_count(h: u32) -> u32 {
    with(h, 0, |e| e.world.bodies[0].spring_count() as u32)
}
/// Copy positions into the f32 render array and return its pointer.
#[no_mangle]
pub extern "C" fn ss_sync(h: u32) -> *const f32 {
    with(h, std::ptr::null(), |e| {
        e.sync();
        e.render.as_ptr()
    })
}
#[no_mangle]
pub extern "C" fn ss_render_positions(h: u32) -> *const f32 {
    with(h, std::ptr::null(), |e| e.render.as_ptr())
}
/// Triangles, 3 u32 per face.
#[no_mangle]
pub extern "C" fn ss_triangles(h: u32) -> *const u32 {
    with(h, std::ptr::null(), |e| e.triangles.as_ptr())
}
/// Springs, 2 u32 per spring (for the wireframe).
#[no_mangle]
pub extern "C" fn ss_springs(h: u32) -> *const u32 {
    with(h, std::ptr::null(), |e| e.springs.as_ptr())
}
#[no_mangle]
pub extern "C" fn ss_positions(h: u32) -> *const f64 {
    with(h, std::ptr::null(), |e| e.world.bodies[0].positions().as_ptr())
}
#[no_mangle]
pub extern "C" fn ss_velocities(h: u32) -> *const f64 {
    with(h, std::ptr::null(), |e| e.world.bodies[0].velocities().as_ptr())
}
#[no_mangle]
pub extern "C" fn ss_masses(h: u32) -> *const f64 {
    with(h, std::ptr::null(), |e| e.world.bodies[0].masses().as_ptr())
}
#[no_mangle]
pub extern "C" fn ss_rest_lengths(h: u32) -> *const f64 {
    with(h, std::ptr::null(), |e| e.world.bodies[0].rest_lengths().as_ptr())
}
/// Bending springs: count and rest lengths (m), now and frozen.
#[no_mangle]
pub extern "C" fn ss_bending_count(h: u32) -> u32 {
    with(h, 0, |e| e.world.bodies[0].bending_rest_lengths().len() as u32)
}
#[no_mangle]
pub extern "C" fn ss_bending_rest_lengths(h: u32) -> *const f64 {
    with(h, std::ptr::null(), |e| e.world.bodies[0].bending_rest_lengths().as_ptr())
}
#[no_mangle]
pub extern "C" fn ss_frozen_bending_rest_lengths(h: u32) -> *const f64 {
    with(h, std::ptr::null(), |e| e.world.bodies[0].frozen_bending_rest_lengths().as_ptr())
}
/// Set the bending rest lengths now and frozen (`ss_bending_count` f64 each).
///
/// # Safety
/// Both pointers must point to `ss_bending_count(h)` f64.
#[no_mangle]
pub unsafe extern "C" fn ss_set_bending_rest(h: u32, now: *const f64, frozen: *const f64) -> u32 {
    table::status(h, |e| {
        let n = e.world.bodies[0].bending_rest_lengths().len();
        let a = std::slice::from_raw_parts(now, n).to_vec();
        let b = std::slice::from_raw_parts(frozen, n).to_vec();
        e.world.bodies[0].set_bending_rest_lengths(&a, &b).map_err(|e| e.to_string())
    })
}
#[no_mangle]
pub extern "C" fn ss_frozen_positions(h: u32) -> *const f64 {
    with(h, std::ptr::null(), |e| e.world.bodies[0].frozen_positions().as_ptr())
}
#[no_mangle]
pub extern "C" fn ss_frozen_rest_lengths(h: u32) -> *const f64 {
    with(h, std::ptr::null(), |e| e.world.bodies[0].frozen_rest_lengths().as_ptr())
}
/// 1 per pinned vertex, 0 otherwise (kept up to date by `ss_set_pinned`).
#[no_mangle]
pub extern "C" fn ss_pinned(h: u32) -> *const u8 {
    with(h, std::ptr::null(), |e| e.pinned.as_ptr())
}
/// Staging arrays the page writes: user forces (3 f64 per vertex, N), face pressures (1 f64 per
/// face, Pa), and a per-vertex f64 array for weights, masses, factors.
#[no_mangle]
pub extern "C" fn ss_user_forces(h: u32) -> *mut f64 {
    with(h, std::ptr::null_mut(), |e| e.user_forces.as_mut_ptr())
}
#[no_mangle]
pub extern "C" fn ss_face_pressures(h: u32) -> *mut f64 {
    with(h, std::ptr::null_mut(), |e| e.face_pressures.as_mut_ptr())
}
#[no_mangle]
pub extern "C" fn ss_vertex_scratch(h: u32) -> *mut f64 {
    with(h, std::ptr::null_mut(), |e| e.scratch.as_mut_ptr())
}
/// A second per-vertex-xyz staging array (3 f64 per vertex), e.g. velocities to restore.
#[no_mangle]
pub extern "C" fn ss_vector_scratch(h: u32) -> *mut f64 {
    with(h, std::ptr::null_mut(), |e| e.vectors.as_mut_ptr())
}

// ----- parameters ----------------------------------------------------------------------------

/// Parameter ids for `ss_get`/`ss_set` (the same table is in web/src/engine/params.ts).
pub mod param {
    pub const STIFFNESS: u32 = 0; // N/m
    pub const SPRING_DAMPING: u32 = 1; // N·s/m
    pub const DAMPING: u32 = 2; // 1/s
    pub const GRAVITY: u32 = 3; // m/s²
    pub const GAS_AMOUNT: u32 = 4; // mol
    pub const TEMPERATURE: u32 = 5; // K
    pub const VOLUME_MODE: u32 = 6; // 0 exact, 1 box, 2 sphere
    pub const WIND_X: u32 = 7; // m/s
    pub const WIND_Y: u32 = 8;
    pub const WIND_Z: u32 = 9;
    pub const WIND_DRAG: u32 = 10; // N·s/m³
    pub const GROUND_ON: u32 = 11; // 0/1
    pub const GROUND_HEIGHT: u32 = 12; // m
    pub const FRICTION: u32 = 13; // –
    pub const INTEGRATOR: u32 = 14; // 0 euler, 1 midpoint, 2 rk4, 3 symplectic
    pub const TOTAL_MASS: u32 = 15; // kg (set: split equally)
    pub const AMBIENT_PRESSURE: u32 = 16; // Pa (gas reference)
    pub const REFERENCE_VOLUME: u32 = 17; // m³
    pub const FROZEN_AMBIENT_PRESSURE: u32 = 18; // Pa (read only)
    pub const FROZEN_REFERENCE_VOLUME: u32 = 19; // m³ (read only)
    pub const BENDING_STIFFNESS: u32 = 20; // N/m
    pub const SELF_COLLISION: u32 = 21; // 0/1 (acts in a scene's world)
}

const INTEGRATORS: [Integrator; 4] = [Integrator::Euler, Integrator::Midpoint, Integrator::Rk4, Integrator::Symplectic];
const MODES: [VolumeMode; 3] = [VolumeMode::Exact, VolumeMode::Box, VolumeMode::Sphere];

/// Body parameters read the body's material (or masses, or gas reference); world parameters
/// read the entry's one-body world.
#[no_mangle]
pub extern "C" fn ss_get(h: u32, id: u32) -> f64 {
    with(h, f64::NAN, |e| {
        let (b, w) = (&e.world.bodies[0], &e.world.settings);
        let p = &b.material;
        match id {
            param::STIFFNESS => p.stiffness,
            param::SPRING_DAMPING => p.spring_damping,
            param::DAMPING => p.damping,
            param::GRAVITY => w.gravity,
            param::GAS_AMOUNT => p.gas_amount,
            param::TEMPERATURE => p.temperature,
            param::VOLUME_MODE => MODES.iter().position(|&m| m == p.volume_mode).unwrap_or(0) as f64,
            param::WIND_X => w.wind[0],
            param::WIND_Y => w.wind[1],
            param::WIND_Z => w.wind[2],
            param::WIND_DRAG => w.wind_drag,
            param::GROUND_ON => w.ground.is_some() as u8 as f64,
            param::GROUND_HEIGHT => e.ground.height,
            param::FRICTION => e.ground.friction,
            param::INTEGRATOR => INTEGRATORS.iter().position(|&m| m == w.integrator).unwrap_or(3) as f64,
            param::TOTAL_MASS => b.masses().iter().sum(),
            param::AMBIENT_PRESSURE => b.gas_reference().ambient_pressure,
            param::REFERENCE_VOLUME => b.gas_reference().reference_volume,
            param::FROZEN_AMBIENT_PRESSURE => b.frozen_gas_reference().ambient_pressure,
            param::FROZEN_REFERENCE_VOLUME => b.frozen_gas_reference().reference_volume,
            param::BENDING_STIFFNESS => p.bending_stiffness,
            param::SELF_COLLISION => p.self_collision as u8 as f64,
            _ => f64::NAN,
        }
    })
}

/// Set a parameter; refused (status 1, with a message) if the value is invalid. Body
/// parameters go to the body's material, world parameters to the entry's world.
#[no_mangle]
pub extern "C" fn ss_set(h: u32, id: u32, value: f64) -> u32 {
    table::status(h, |e| {
        let mut p = e.world.bodies[0].material.clone();
        let mut w = e.world.settings.clone();
        let index = |n: usize| if value.is_finite() && value >= 0.0 && (value as usize) < n { Ok(value as usize) } else { Err(format!("no choice {value}")) };
        let body = &mut e.world.bodies[0];
        match id {
            param::STIFFNESS => p.stiffness = value,
            param::SPRING_DAMPING => p.spring_damping = value,
            param::BENDING_STIFFNESS => p.bending_stiffness = value,
            param::SELF_COLLISION => p.self_collision = value != 0.0,
            param::DAMPING => p.damping = value,
            param::GRAVITY => w.gravity = value,
            param::GAS_AMOUNT => return body.set_gas(value, p.temperature).map_err(|e| e.to_string()),
            param::TEMPERATURE => return body.set_gas(p.gas_amount, value).map_err(|e| e.to_string()),
            param::VOLUME_MODE => p.volume_mode = MODES[index(3)?],
            param::WIND_X => w.wind[0] = value,
            param::WIND_Y => w.wind[1] = value,
            param::WIND_Z => w.wind[2] = value,
            param::WIND_DRAG => w.wind_drag = value,
            param::GROUND_ON => w.ground = (value != 0.0).then_some(e.ground),
            param::GROUND_HEIGHT => {
                e.ground.height = value;
                w.ground = w.ground.map(|_| e.ground);
            }
            param::FRICTION => {
                e.ground.friction = value;
                w.ground = w.ground.map(|_| e.ground);
            }
            param::INTEGRATOR => w.integrator = INTEGRATORS[index(4)?],
            param::TOTAL_MASS => return body.set_total_mass(value).map_err(|e| e.to_string()),
            param::AMBIENT_PRESSURE => {
                let g = GasReference { ambient_pressure: value, ..body.gas_reference() };
                return body.set_gas_reference(g).map_err(|e| e.to_string());
            }
            param::REFERENCE_VOLUME => {
                let g = GasReference { reference_volume: value, ..body.gas_reference() };
                return body.set_gas_reference(g).map_err(|e| e.to_string());
            }
            _ => return Err(format!("unknown parameter id {id}")),
        }
        p.validate().map_err(|e| e.to_string())?;
        w.validate().map_err(|e| e.to_string())?;
        if let Some(g) = w.ground {
            if !(g.height.is_finite() && g.friction.is_finite() && g.friction >= 0.0) {
                return Err("ground: height and friction must be finite, friction ≥ 0".into());
            }
        }
        e.world.bodies[0].material = p;
        e.world.settings = w;
        Ok(())
    })
}

// ----- stepping ------------------------------------------------------------------------------

/// `substeps` steps of `dt` s. On failure the body's whole world (state, clock) is rolled back
/// to where it was before the call and the message says why.
#[no_mangle]
pub extern "C" fn ss_step(h: u32, dt: f64, substeps: u32) -> u32 {
    table::status(h, |e| e.step(dt, substeps))
}

/// 16 statistics: step, time, volume, pressure, kinetic, elastic, gas, gravity, total energy,
/// momentum xyz, centre of mass xyz, max speed.
#[no_mangle]
pub extern "C" fn ss_stats(h: u32) -> *const f64 {
    with(h, std::ptr::null(), |e| {
        let s = e.world.stats(0);
        e.stats = [
            s.step as f64, s.time, s.volume, s.pressure, s.kinetic_energy, s.elastic_energy, s.gas_energy, s.gravity_energy,
            s.total_energy, s.momentum[0], s.momentum[1], s.momentum[2], s.center_of_mass[0], s.center_of_mass[1],
            s.center_of_mass[2], s.max_speed,
        ];
        e.stats.as_ptr()
    })
}

// ----- modeling operations -------------------------------------------------------------------

#[no_mangle]
pub extern "C" fn ss_freeze(h: u32) -> u32 {
    table::status(h, |e| {
        e.world.bodies[0].freeze();
        Ok(())
    })
}
/// Freeze under load: the body keeps carrying its current loads (see `SoftBody::freeze_under_load`).
#[no_mangle]
pub extern "C" fn ss_freeze_under_load(h: u32) -> u32 {
    table::status(h, |e| {
        e.world.bodies[0].freeze_under_load();
        Ok(())
    })
}
/// The kept load (N, 3 f64 per vertex), now and in the frozen state.
#[no_mangle]
pub extern "C" fn ss_prestress(h: u32) -> *const f64 {
    with(h, std::ptr::null(), |e| e.world.bodies[0].prestress().as_ptr())
}
#[no_mangle]
pub extern "C" fn ss_frozen_prestress(h: u32) -> *const f64 {
    with(h, std::ptr::null(), |e| e.world.bodies[0].frozen_prestress().as_ptr())
}
/// Set the kept load now (`now`) and in the frozen state (`frozen`), 3 f64 per vertex each.
///
/// # Safety
/// Both pointers must point to `3 ss_vertex_count(h)` f64.
#[no_mangle]
pub unsafe extern "C" fn ss_set_prestress(h: u32, now: *const f64, frozen: *const f64) -> u32 {
    table::status(h, |e| {
        let n = 3 * e.world.bodies[0].vertex_count();
        let a = std::slice::from_raw_parts(now, n).to_vec();
        let b = std::slice::from_raw_parts(frozen, n).to_vec();
        e.world.bodies[0].set_prestress(&a, &b).map_err(|e| e.to_string())
    })
}
#[no_mangle]
pub extern "C" fn ss_reset(h: u32) -> u32 {
    table::status(h, |e| {
        e.world.bodies[0].reset();
        Ok(())
    })
}
/// Replace the body by its Loop subdivision (frozen). All pointers of this handle change.
#[no_mangle]
pub extern "C" fn ss_subdivide(h: u32) -> u32 {
    table::status(h, |e| {
        let body = e.world.bodies[0].subdivided().map_err(|e| e.to_string())?;
        let ground = e.ground;
        *e = Entry::new(World::single(body, e.world.settings.clone()));
        e.ground = ground;
        Ok(())
    })
}
/// Multiply every rest length by `factor`.
#[no_mangle]
pub extern "C" fn ss_scale_rest(h: u32, factor: f64) -> u32 {
    table::status(h, |e| e.world.bodies[0].scale_rest_lengths(factor).map_err(|e| e.to_string()))
}
/// Multiply rest lengths by the per-vertex factors in the vertex scratch array.
#[no_mangle]
pub extern "C" fn ss_scale_rest_by_vertex(h: u32) -> u32 {
    table::status(h, |e| e.world.bodies[0].scale_rest_lengths_by_vertex(&e.scratch).map_err(|e| e.to_string()))
}
/// Set every rest length from an array of `spring_count` f64 at `ptr`.
///
/// # Safety
/// `ptr` must point to `ss_spring_count(h)` f64.
#[no_mangle]
pub unsafe extern "C" fn ss_set_rest_lengths(h: u32, ptr: *const f64) -> u32 {
    table::status(h, |e| {
        let rest = std::slice::from_raw_parts(ptr, e.world.bodies[0].spring_count()).to_vec();
        e.world.bodies[0].set_rest_lengths(&rest).map_err(|e| e.to_string())
    })
}
/// Set every vertex mass from the vertex scratch array (kg).
#[no_mangle]
pub extern "C" fn ss_set_masses(h: u32) -> u32 {
    table::status(h, |e| e.world.bodies[0].set_masses(&e.scratch).map_err(|e| e.to_string()))
}
#[no_mangle]
pub extern "C" fn ss_set_pinned(h: u32, vertex: u32, pinned: u32) -> u32 {
    table::status(h, |e| {
        e.world.bodies[0].set_pinned(vertex as usize, pinned != 0).map_err(|e| e.to_string())?;
        e.pinned[vertex as usize] = (pinned != 0) as u8;
        Ok(())
    })
}
/// Apply the user forces staged in `ss_user_forces`.
#[no_mangle]
pub extern "C" fn ss_apply_user_forces(h: u32) -> u32 {
    table::status(h, |e| e.world.bodies[0].set_user_forces(&e.user_forces).map_err(|e| e.to_string()))
}
/// Apply the face pressures staged in `ss_face_pressures`.
#[no_mangle]
pub extern "C" fn ss_apply_face_pressures(h: u32) -> u32 {
    table::status(h, |e| e.world.bodies[0].set_face_pressures(&e.face_pressures).map_err(|e| e.to_string()))
}
/// Set positions from `ptr` (3 f64 per vertex) and velocities from the vector scratch array.
///
/// # Safety
/// `ptr` must point to `3 ss_vertex_count(h)` f64.
#[no_mangle]
pub unsafe extern "C" fn ss_set_state(h: u32, ptr: *const f64) -> u32 {
    table::status(h, |e| {
        let x = std::slice::from_raw_parts(ptr, 3 * e.world.bodies[0].vertex_count()).to_vec();
        e.world.bodies[0].set_state(&x, &e.vectors).map_err(|e| e.to_string())
    })
}
/// Set the frozen state (for reset) from positions at `pos` and rest lengths at `rest`, with the
/// gas reference (Pa, m³).
///
/// # Safety
/// `pos` must point to `3 ss_vertex_count(h)` f64 and `rest` to `ss_spring_count(h)` f64.
#[no_mangle]
pub unsafe extern "C" fn ss_set_frozen(h: u32, pos: *const f64, rest: *const f64, ambient: f64, volume: f64) -> u32 {
    table::status(h, |e| {
        let x = std::slice::from_raw_parts(pos, 3 * e.world.bodies[0].vertex_count()).to_vec();
        let r = std::slice::from_raw_parts(rest, e.world.bodies[0].spring_count()).to_vec();
        e.world.bodies[0].set_frozen(&x, &r, GasReference { ambient_pressure: ambient, reference_volume: volume }).map_err(|e| e.to_string())
    })
}

/// Default ground used when the ground is switched on.
pub fn default_ground() -> Ground {
    Ground::at(0.0)
}
