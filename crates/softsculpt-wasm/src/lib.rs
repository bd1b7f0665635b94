//! Thin WebAssembly binding of the SoftSculpt engine: one world handle, raw `extern "C"` exports,
//! each a delegation to the core (`softsculpt::World` and friends). No physics and no policy
//! here; nothing panics on bad input.
//!
//! # Conventions
//! - **Handles**: a world handle is an integer ≥ 1 (`ss_world_new`, `ss_workload`; the table:
//!   `handle.rs`). Bodies are indices 0, 1, … into the world's bodies.
//! - **Status and index**: every fallible call returns `i32`: 0 (ok) or an index ≥ 0, and −1 on
//!   failure. Calls returning a pointer return 0 on failure.
//! - **Errors** (`ss_error_ptr`/`ss_error_len`): after a failure, UTF-8 JSON
//!   `{"kind": K, "message": "…", …}` with K one of `mesh`, `parameter`, `step`, `snapshot`,
//!   `scene`, `delta`, `project`, `usage`, and optional fields: `parameter` and `unit`
//!   (parameter errors), `time` (s), `step`, `line` and `rolled_back_to` (s) (step errors;
//!   `converged: false` when an implicit step did not converge: a shorter step may succeed;
//!   `cause`: `non_finite`, `collapsed` (with the gas `volume`, m³) or `not_converged`),
//!   `line` and `key` (scene errors). The error slot holds only errors.
//! - **Results** (`ss_result_ptr`/`ss_result_len`): data a call returns — JSON, TOML, snapshot
//!   or delta bytes, load warnings — valid until the next call that writes a result.
//! - **Memory**: `ss_alloc(len)`/`ss_dealloc(ptr, len)` for buffers the page fills (file bytes,
//!   names, JSON values). Any call may grow wasm memory (the `ArrayBuffer` is then replaced):
//!   re-make typed-array views after every call.
//! - **Views** (`views.rs`; its calls in `world.rs`): `ss_body_views(w, b)` returns a pointer
//!   to a u32 layout table of body b's arrays in wasm memory (the engine's own f64 arrays, and arrays the binding keeps
//!   for the page: f32 render positions, u32 springs, u8 pins, f64 staging). Its pointers stay
//!   valid until a call that replaces bodies (`ss_add_*`, `ss_clear`, `ss_subdivide`,
//!   `ss_restore`, `ss_open_scene`, `ss_apply_delta`, `ss_open_project_v1`): ask again after
//!   those, and re-make the views after any call (memory growth).
//! - **One table** (`abi.rs`): every call below is written once, in an `exports!` block of its
//!   module, which records its name, doc comment and signature; the page's types for the calls
//!   (`web/src/engine/abi.ts`), with the layout table's slots, the stats order and the delta
//!   scope codes, are written from it by `tests/abi.rs` (`UPDATE_ABI=1`), never by hand. So are
//!   the interfaces of the JSON reports (`FreezeReport`, `RemeshReport`, `FileReport`,
//!   `Advance`): each is a struct written once, in a `reports!` block beside its call
//!   (`report.rs`), serialized from that struct.
//!
//! # Calls
//! | call | does |
//! |---|---|
//! | `ss_alloc(len) -> ptr`, `ss_dealloc(ptr, len)` | wasm memory for the page to fill |
//! | `ss_error_ptr/len()`, `ss_result_ptr/len()` | the error JSON; the last result's bytes |
//! | `ss_world_new() -> w` | an empty world with the parameter table's defaults |
//! | `ss_world_free(w)` | release it |
//! | `ss_workload(level) -> w` | the standard benchmark workload (`softsculpt::workload`) |
//! | `ss_use_threads(n) -> count` | step every world on n threads (threaded build: the caller and n − 1 helpers; 0: all), −1 if fewer serve |
//! | `ss_threads() -> n`, `ss_thread_passes() -> f64` | threads in use; passes a helper took part in so far |
//! | `ss_thread_serve()`, `ss_thread_trapped_flag() -> ptr` | a helper Web Worker's life on the shared memory (never returns; `web/src/engine/threads.ts`); the u32 it sets when that traps |
//! | `ss_add_builtin(w, name, len, mass) -> b` | a built-in model (`sphere`, `mushroom`, `octopus`…) of `mass` kg |
//! | `ss_add_mesh(w, pos, n_vertices, idx, n_indices, mass, prepare) -> b` | an indexed mesh (f64 xyz, u32 indices); `prepare` 1 = weld, check, orient and reorder like a file, 0 = exactly as given; result: warnings JSON |
//! | `ss_add_sketch(w, xy, n, edge, mass) -> b` | a balloon sketched from a closed outline of n points (f64 x y, m), inflated to rest (`softsculpt::sketch`); `edge` ≤ 0: the default edge length |
//! | `ss_add_obj(w, bytes, len, mass) -> b` | an OBJ file; result: warnings JSON (array of strings) |
//! | `ss_add_file(w, name, len, bytes, len, split, mass) -> b` | a mesh file of any format (`softsculpt::mesh::load`), one body or one per piece (`split` = 1, largest first); result: `{format, up_axis, pieces, …}` (`import.rs`) |
//! | `ss_apply_preset_scaled(w, b, name, len, size)` | `World::apply_preset_scaled`: the preset for a model `size` times as large (similarity); result: gas parameters skipped on an open body |
//! | `ss_animation_glb(times, n, counts, tracks, tris, frames)` | result: the GLB of recorded frames (`softsculpt::mesh::animation`, as `softsculpt run --frames` writes) |
//! | `ss_clear(w)` | drop bodies, events and loads, forget the open scene; keep settings |
//! | `ss_step(w, n)` | `World::step_n`: n steps or none (the whole world rolls back; `step` error with `time`) |
//! | `ss_advance(w, frame_dt, seconds, min_accuracy, splits, relax, rewind)` | `World::advance`: a frame under a real-time budget of `seconds` (≤ 0: converge), a failed frame rewound to the last sound state if `rewind`; result `{steps, splits, simulated, residual, early, wall}` |
//! | `ss_forget_rewind(w)` | `World::forget_rewind`: the page changed the model |
//! | `ss_stable_dt(w, name, len) -> f64` | `World::stable_dt`: the explicit integrator's largest stable step (s) for every body; 0 for implicit; −1 error |
//! | `ss_body_accuracy(w, b) -> f64` | the relative residual body b's last implicit step was accepted at when its deadline stopped it (0: converged; −1: error) |
//! | `ss_body_newton_iterations(w, b)` | Newton iterations of body b's last step (0 after an explicit one) |
//! | `ss_body_relaxed(w, b)` | what of the hinges body b's last step let go of: 0 nothing, 1 crushed faces', 2 all (`Relaxed`) |
//! | `ss_sync(w)` | refresh every body's f32 render positions, pins and stats |
//! | `ss_body_count(w)`, `ss_body_views(w, b) -> ptr` | bodies; body b's layout table (`views.rs`) |
//! | `ss_param_table()` | result: the parameter table JSON (`softsculpt::params::table_json`) |
//! | `ss_move_ground(w, height)` | `World::move_ground`: the ground to `height` m, carrying the bodies standing on it; result `{"moved"}` |
//! | `ss_let_overlapping_be(w)` | `World::let_overlapping_bodies_be`: contacts off between the bodies that overlap or touch now, until they part (an import's pieces); result `{"pairs"}` |
//! | `ss_remesh(w, b, edge, under_load)` | `World::remesh`: isotropic remeshing to `edge` m (shorter if the shape needs it, or refused), masses and pins carried; result `{"dropped_events", "edge", "requested", "crease_deg", "tries", "distance", "volume_change"}` |
//! | `ss_quality(w, b)` | `World::quality`: result JSON (smallest angle, share below 25°, shortest and mean edge, spread, poor) |
//! | `ss_material_presets()` | result: the material presets' names and help (`softsculpt::params::material_presets_json`) |
//! | `ss_params(w, b)` | result: `{id: value}` of every body and world parameter (null: no ground) |
//! | `ss_set_param(w, b, id, id_len, json, json_len)` | `World::set_param` with a JSON value (number, [x,y,z], "name", true/false) |
//! | `ss_apply_preset(w, b, name, len)` | `World::apply_preset`: a named set of values from `softsculpt::params::presets` (`modeler`) |
//! | `ss_freeze(w, b, under_load, keep_tension)`, `ss_reset(w, b)` | `World::freeze`: rest shape := current shape (carrying the weight; keeping the gas's tension), result `{"residual", "load", "iterations", "clamped"}`; back to the frozen shape |
//! | `ss_subdivide(w, b)` | Loop subdivision (body replaced; result `{"dropped_events": n}`) |
//! | `ss_scale_rest(w, b)` | rest lengths × the per-vertex factors in the vertex scratch |
//! | `ss_set_masses(w, b)` | vertex masses (kg) from the vertex scratch |
//! | `ss_set_pins(w, b)` | pins from the pinned view (u8, 1 pinned), which the page writes |
//! | `ss_apply_loads(w, b)` | user forces (N) and face pressures (Pa) from the staging views |
//! | `ss_set_targets(w, b, ptr, count)` | `SoftBody::set_targets`: target springs from `count` f64 records (vertex, anchor xyz (m), stiffness (N/m), damping (N·s/m)); 0 clears |
//! | `ss_snapshot(w)`, `ss_restore(w, ptr, len)` | result: snapshot bytes; the world from snapshot bytes (untouched on error) |
//! | `ss_scene_file(name, len, bytes, len)` | a mesh file the next `ss_open_scene` may name |
//! | `ss_open_scene(w, text, len)` | the world becomes the scene's; result `{names, dt, duration}` |
//! | `ss_save_scene(w)` | result: scene TOML (`softsculpt::scene::save`) |
//! | `ss_obstacles(w)` | result: the world's obstacles as JSON (`scene.rs`) |
//! | `ss_mark(w)` | remember the world as it is now (for `ss_delta`) |
//! | `ss_delta(w, scope)` | result: delta bytes taking the world back to the mark (scope 0 none, 1 touched, 2 all) |
//! | `ss_apply_delta(w, ptr, len)` | apply a delta; result: its inverse's bytes |
//! | `ss_open_project_v1(w, ptr, len)` | a version-1 project file of the modeler becomes the world; result `{name, ui}` |

pub mod abi;
mod bodyops;
mod fails;
mod handle;
mod history;
mod import;
mod params;
pub mod report;
mod scene;
mod views;
mod world;

use abi::exports;
pub use history::{DeltaScopeCode, SCOPES};
pub use views::{Slot, Stat, LAYOUT_LEN, SLOTS, STATS, STATS_LEN};
use std::cell::RefCell;

/// Why a call failed: a kind, a message, and extra fields for the error JSON.
#[derive(Debug)]
pub struct Fail {
    pub kind: &'static str,
    pub message: String,
    pub extra: serde_json::Map<String, serde_json::Value>,
}

impl Fail {
    pub fn new(kind: &'static str, message: impl Into<String>) -> Self {
        Fail {
            kind,
            message: message.into(),
            extra: serde_json::Map::new(),
        }
    }
    pub fn usage(message: impl Into<String>) -> Self {
        Fail::new("usage", message)
    }
    /// Add a field to the error JSON.
    pub fn with(mut self, key: &str, value: impl Into<serde_json::Value>) -> Self {
        self.extra.insert(key.to_string(), value.into());
        self
    }
}

pub type Res<T> = Result<T, Fail>;

thread_local! {
    static ERROR: RefCell<Vec<u8>> = const { RefCell::new(Vec::new()) };
    static RESULT: RefCell<Vec<u8>> = const { RefCell::new(Vec::new()) };
}

/// Put `f` in the error slot.
pub(crate) fn fail(f: Fail) {
    let mut m = f.extra;
    m.insert("kind".into(), f.kind.into());
    m.insert("message".into(), f.message.into());
    ERROR.with(|e| *e.borrow_mut() = serde_json::Value::Object(m).to_string().into_bytes());
}

/// Put a call's data in the result slot.
pub fn set_result(bytes: Vec<u8>) {
    RESULT.with(|r| *r.borrow_mut() = bytes);
}

/// 0 if `f` succeeded, −1 (error set) otherwise.
pub fn status(f: impl FnOnce() -> Res<()>) -> i32 {
    index(|| f().map(|()| 0))
}

/// The index `f` returned, or −1 (error set).
pub fn index(f: impl FnOnce() -> Res<usize>) -> i32 {
    match f().and_then(|i| i32::try_from(i).map_err(|_| Fail::usage("index out of range"))) {
        Ok(i) => i,
        Err(e) => {
            fail(e);
            -1
        }
    }
}

/// `len` bytes at `ptr` (empty if null or 0).
///
/// # Safety
/// `ptr` must point to `len` readable bytes.
pub(crate) unsafe fn bytes<'a>(ptr: *const u8, len: usize) -> &'a [u8] {
    if len == 0 || ptr.is_null() {
        &[]
    } else {
        std::slice::from_raw_parts(ptr, len)
    }
}

/// UTF-8 text at `ptr`, or a usage error naming `what`.
///
/// # Safety
/// `ptr` must point to `len` readable bytes.
pub(crate) unsafe fn text<'a>(ptr: *const u8, len: usize, what: &str) -> Res<&'a str> {
    std::str::from_utf8(bytes(ptr, len)).map_err(|e| {
        Fail::usage(format!(
            "{what} is not UTF-8 text (byte {})",
            e.valid_up_to()
        ))
    })
}

exports! {
    /// Allocate `len` bytes in wasm memory for the page to fill.
    pub fn ss_alloc(len: usize) -> *mut u8 {
        let mut v = Vec::<u8>::with_capacity(len.max(1));
        let p = v.as_mut_ptr();
        std::mem::forget(v);
        p
    }

    /// Free memory from [`ss_alloc`].
    ///
    /// # Safety
    /// `ptr` and `len` must come from one call of `ss_alloc`.
    pub unsafe fn ss_dealloc(ptr: *mut u8, len: usize) {
        if !ptr.is_null() {
            drop(Vec::from_raw_parts(ptr, 0, len.max(1)));
        }
    }

    /// The last error, JSON (see the crate documentation).
    pub fn ss_error_ptr() -> *const u8 {
        ERROR.with(|e| e.borrow().as_ptr())
    }
    pub fn ss_error_len() -> usize {
        ERROR.with(|e| e.borrow().len())
    }

    /// The last result's bytes.
    pub fn ss_result_ptr() -> *const u8 {
        RESULT.with(|r| r.borrow().as_ptr())
    }
    pub fn ss_result_len() -> usize {
        RESULT.with(|r| r.borrow().len())
    }

    /// The material presets as JSON (`softsculpt::params::material_presets_json`: name, help) in the
    /// result slot.
    pub fn ss_material_presets() -> i32 {
        status(|| {
            set_result(softsculpt::params::material_presets_json().into_bytes());
            Ok(())
        })
    }

    /// The parameter table as JSON (`softsculpt::params::table_json`) in the result slot.
    pub fn ss_param_table() -> i32 {
        status(|| {
            set_result(softsculpt::params::table_json().into_bytes());
            Ok(())
        })
    }
}

/// Every raw export of the binding, module by module (`abi.rs`): what `tests/abi.rs` writes the
/// page's `web/src/engine/abi.ts` from.
pub fn exports() -> impl Iterator<Item = &'static abi::Export> {
    [EXPORTS, handle::EXPORTS, world::EXPORTS, params::EXPORTS, bodyops::EXPORTS, import::EXPORTS, scene::EXPORTS, history::EXPORTS]
        .into_iter()
        .flatten()
}

/// Every JSON report of the binding (`report.rs`), for `tests/abi.rs`.
pub fn reports() -> impl Iterator<Item = &'static report::Report> {
    [bodyops::REPORTS, import::REPORTS, world::REPORTS].into_iter().flatten()
}
