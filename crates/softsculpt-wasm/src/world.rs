//! The calls on a world and its bodies (the world found by its handle: `handle.rs`). Each call
//! checks its arguments, delegates to the core, and turns the core's error into a [`Fail`].

use crate::abi::exports;
use crate::handle::{with_body, with_world};
use crate::views::BodyViews;
use crate::{bytes, fail, index, set_result, status, text, Fail, Res};
use softsculpt::body::{BodyError, FreezeOptions};
use softsculpt::mesh::{self, builtin, LoadedMesh, ObjData, TriMesh};
use softsculpt::params::{self, ParamError, Scope, Value};
use softsculpt::snapshot::SnapshotError;
use softsculpt::{
    world::{Budget, Interrupt}, Material, MeshError, SimError, SoftBody, StepError, Target, World,
};

// ----- the core's errors as `Fail` --------------------------------------------------------------

pub fn mesh_fail(e: MeshError) -> Fail {
    let line = if let MeshError::Parse { line, .. } = e {
        Some(line)
    } else {
        None
    };
    let f = Fail::new("mesh", e.to_string());
    match line {
        Some(l) => f.with("line", l),
        None => f,
    }
}

/// A simulation error: a parameter refused, a wrong length (usage), or a blow-up (step).
pub fn sim_fail(e: SimError) -> Fail {
    match &e {
        SimError::BadParameter { name, .. } => {
            Fail::new("parameter", e.to_string()).with("parameter", *name)
        }
        SimError::Length { .. } => Fail::usage(e.to_string()),
        SimError::NonFinite { step } => Fail::new("step", e.to_string())
            .with("step", *step)
            .with("cause", "non_finite"),
        SimError::Collapsed { step, volume } => Fail::new("step", e.to_string())
            .with("step", *step)
            .with("cause", "collapsed")
            .with("volume", *volume),
        SimError::NotConverged { step, time, .. } => Fail::new("step", e.to_string())
            .with("step", *step)
            .with("time", *time)
            .with("converged", false)
            .with("cause", "not_converged"),
        SimError::Interrupted { step, time } => Fail::new("step", e.to_string())
            .with("step", *step)
            .with("time", *time)
            .with("cause", "interrupted"),
    }
}

fn body_fail(e: BodyError) -> Fail {
    match e {
        BodyError::Mesh(m) => mesh_fail(m),
        BodyError::Sim(s) => sim_fail(s),
    }
}

/// Names the parameter and its unit.
pub fn param_fail(e: ParamError) -> Fail {
    let unit = params::find(&e.id).map(|p| p.unit).unwrap_or("");
    Fail::new("parameter", e.to_string())
        .with("parameter", e.id)
        .with("unit", unit)
}

fn step_fail(e: StepError) -> Fail {
    let mut f = Fail::new("step", e.to_string())
        .with("time", e.time)
        .with("step", e.step);
    // What went wrong, for the page to say in the user's terms: `cause` is `non_finite` (a
    // blow-up), `collapsed` (the gas volume fell to zero or below; `volume` m³) or
    // `not_converged` (an implicit step did not converge: a shorter step may succeed).
    match e.error {
        SimError::NotConverged { .. } => f = f.with("converged", false).with("cause", "not_converged"),
        SimError::NonFinite { .. } => f = f.with("cause", "non_finite"),
        SimError::Collapsed { volume, .. } => f = f.with("cause", "collapsed").with("volume", volume),
        SimError::Interrupted { .. } => f = f.with("cause", "interrupted"),
        _ => {}
    }
    if let Some(l) = e.line {
        f = f.with("line", l);
    }
    if let Some(t) = e.rolled_back_to {
        f = f.with("rolled_back_to", t);
    }
    if let Some(t) = e.rewound_to {
        f = f.with("rewound_to", t);
    }
    f
}

pub fn snapshot_fail(e: SnapshotError) -> Fail {
    Fail::new("snapshot", e.to_string())
}

// ----- the world ----------------------------------------------------------------------------------
pub(crate) fn add(w: u32, mesh: &TriMesh, mass: f64, warnings: &[String]) -> Res<usize> {
    with_world(w, |h| {
        let body = SoftBody::new(mesh, mass, Material::default()).map_err(body_fail)?;
        set_result(serde_json::to_vec(warnings).unwrap_or_default());
        Ok(h.add(body))
    })
}

/// The clock deadlines are read on (s): the page's `performance.now()`, imported as
/// `env.ss_now` (ms); natively (the crate's tests) the core's monotonic clock.
#[cfg(target_arch = "wasm32")]
fn now() -> f64 {
    #[link(wasm_import_module = "env")]
    extern "C" {
        fn ss_now() -> f64;
    }
    // SAFETY: an import with no arguments and no memory access, given by `initEngine`.
    unsafe { ss_now() / 1000.0 }
}
#[cfg(not(target_arch = "wasm32"))]
fn now() -> f64 {
    softsculpt::world::wall_clock()
}

/// Whether the page has a command waiting that a running step should make way for: the import
/// `env.ss_interrupted` (the worker's shared counters, `web/src/engine/wasm.ts`); natively never.
#[cfg(target_arch = "wasm32")]
fn interrupted() -> bool {
    #[link(wasm_import_module = "env")]
    extern "C" {
        fn ss_interrupted() -> i32;
    }
    // SAFETY: an import with no arguments and no memory access, given by `initEngine`.
    unsafe { ss_interrupted() != 0 }
}
#[cfg(not(target_arch = "wasm32"))]
fn interrupted() -> bool {
    false
}

/// A JSON value as the parameter `id` takes it: a number, `[x, y, z]`, a choice's name, or a flag.
fn value_of(id: &str, v: &serde_json::Value) -> Result<Value, ParamError> {
    let refuse = || ParamError {
        id: id.to_string(),
        message: format!("cannot take the value {v}"),
    };
    Ok(match v {
        serde_json::Value::Number(n) => Value::Number(n.as_f64().ok_or_else(refuse)?),
        serde_json::Value::Bool(f) => Value::Flag(*f),
        serde_json::Value::String(s) => params::choice(params::find(id)?.id, s)?,
        serde_json::Value::Array(a) if a.len() == 3 => {
            let c = |k: usize| a[k].as_f64().ok_or_else(refuse);
            Value::Vector([c(0)?, c(1)?, c(2)?])
        }
        _ => return Err(refuse()),
    })
}

exports! {
    /// A built-in model by name, of total mass `mass` (kg), with the default material.
    ///
    /// # Safety
    /// `name` must point to `len` readable bytes.
    pub unsafe fn ss_add_builtin(w: u32, name: *const u8, len: usize, mass: f64) -> i32 {
        index(|| {
            let name = text(name, len, "the model name")?;
            let loaded = builtin::builtin(name)
                .map(LoadedMesh::from_trimesh)
                .map_err(mesh_fail)?;
            add(w, &loaded.mesh, mass, &[])
        })
    }

    /// A body from OBJ bytes (welded, checked, oriented, reordered); warnings in the result.
    ///
    /// # Safety
    /// `ptr` must point to `len` readable bytes.
    pub unsafe fn ss_add_obj(w: u32, ptr: *const u8, len: usize, mass: f64) -> i32 {
        index(|| {
            let loaded = mesh::load_obj(bytes(ptr, len)).map_err(mesh_fail)?;
            add(w, &loaded.mesh, mass, &loaded.report.warnings)
        })
    }

    /// A body sketched from a closed outline of `n` points (`2 n` f64: x y, m): the pillow inflated
    /// to rest (`softsculpt::sketch`); `edge` ≤ 0 takes the default edge length.
    ///
    /// # Safety
    /// `xy` must point to `2 n` f64.
    pub unsafe fn ss_add_sketch(w: u32, xy: *const f64, n: usize, edge: f64, mass: f64) -> i32 {
        index(|| add(w, &softsculpt::sketch::sketch_points(if xy.is_null() { &[] } else { std::slice::from_raw_parts(xy, 2 * n) }, edge).map_err(mesh_fail)?, mass, &[]))
    }

    /// A body from an indexed triangle mesh (f64 xyz, u32 indices): `prepare` = 1 prepares it like
    /// a file (weld, check, orient, reorder), 0 takes it exactly as given.
    ///
    /// # Safety
    /// `pos` must point to `3 n_vertices` f64 and `idx` to `n_indices` u32.
    pub unsafe fn ss_add_mesh(
        w: u32,
        pos: *const f64,
        n_vertices: usize,
        idx: *const u32,
        n_indices: usize,
        mass: f64,
        prepare: u32,
    ) -> i32 {
        index(|| {
            if pos.is_null() || idx.is_null() || !n_indices.is_multiple_of(3) {
                return Err(Fail::usage(
                    "a mesh needs positions and a multiple of 3 indices",
                ));
            }
            let positions = std::slice::from_raw_parts(pos, 3 * n_vertices).to_vec();
            let indices = std::slice::from_raw_parts(idx, n_indices).to_vec();
            if let Some(bad) = indices.iter().find(|&&i| i as usize >= n_vertices) {
                return Err(mesh_fail(MeshError::Invalid(format!(
                    "index {bad} out of range ({n_vertices} vertices)"
                ))));
            }
            if prepare == 0 {
                let triangles = indices
                    .chunks_exact(3)
                    .map(|t| [t[0], t[1], t[2]])
                    .collect();
                return add(
                    w,
                    &TriMesh {
                        positions,
                        triangles,
                    },
                    mass,
                    &[],
                );
            }
            let data = ObjData {
                positions,
                arities: vec![3; n_indices / 3],
                indices,
            };
            let loaded = mesh::prepare(data).map_err(mesh_fail)?;
            add(w, &loaded.mesh, mass, &loaded.report.warnings)
        })
    }

    /// Drop every body, the events and loads, and forget the open scene (names, file); keep the
    /// settings (obstacles included). The clock starts again at 0.
    pub fn ss_clear(w: u32) -> i32 {
        status(|| {
            with_world(w, |h| {
                h.world = World::new(Vec::new(), h.world.settings.clone());
                h.views.clear();
                h.scene = None;
                Ok(())
            })
        })
    }

    /// `n` steps (`World::step_n`), or none: on failure the whole world is as before the call and
    /// the error (kind `step`) has `time` (s), `step`, `rolled_back_to` (s) and an event's `line`.
    pub fn ss_step(w: u32, n: u32) -> i32 {
        status(|| with_world(w, |h| h.world.step_n(n as u64).map_err(step_fail)))
    }

    /// `World::advance`: `frame_dt` simulated seconds; under a real-time budget of `seconds` of
    /// wall-clock time (> 0; ≤ 0: converge every step) accepting a step past its deadline at a
    /// relative residual of `min_accuracy` (≤ 0: the core's `MIN_ACCURACY`); a refused implicit
    /// step halved up to `splits` times; `relax` 1: the relaxed retry; `rewind` 1: a failed frame
    /// goes back to the last sound state (`world/rewind.rs`; the error's `rewound_to`, s). Result
    /// `{"steps", "splits", "simulated", "residual", "early", "wall"}`; on failure the error is a
    /// step error as `ss_step`'s (the world as after the last step taken, or rewound); under a
    /// real-time budget a step is also abandoned when the page has a command waiting (cause
    /// `interrupted`; never rewound).
    pub fn ss_advance(w: u32, frame_dt: f64, seconds: f64, min_accuracy: f64, splits: u32, relax: u32, rewind: u32) -> i32 {
        status(|| {
            with_world(w, |h| {
                if !(frame_dt > 0.0 && frame_dt.is_finite()) {
                    return Err(Fail::usage(format!("the frame must be a positive time in seconds, got {frame_dt}")));
                }
                let mut budget = if seconds > 0.0 { Budget::real_time(seconds, now) } else { Budget::converge() };
                if let Some(r) = budget.real_time.as_mut() {
                    if min_accuracy > 0.0 {
                        r.min_accuracy = min_accuracy;
                    }
                }
                (budget.splits, budget.relax, budget.rewind) = (splits, relax != 0, rewind != 0);
                // Under a real-time budget a waiting command abandons the step in progress (the
                // world as before it).
                let saved = h.world.settings.interrupt;
                if budget.real_time.is_some() {
                    h.world.settings.interrupt = Some(Interrupt(interrupted));
                }
                let a = h.world.advance(frame_dt, &budget);
                h.world.settings.interrupt = saved;
                let a = a.map_err(step_fail)?;
                let out = serde_json::json!({
                    "steps": a.steps, "splits": a.splits, "simulated": a.simulated,
                    "residual": a.residual, "early": a.early, "wall": a.wall,
                });
                set_result(out.to_string().into_bytes());
                Ok(())
            })
        })
    }

    /// `World::forget_rewind`: the page changed the model; the rewind points before it go.
    pub fn ss_forget_rewind(w: u32) -> i32 {
        status(|| with_world(w, |h| {
            h.world.forget_rewind();
            Ok(())
        }))
    }

    /// `World::stable_dt`: the largest stable step (s) of the explicit integrator `name` for every
    /// body of the world; 0 for `implicit` (stable at any step); −1 on error (set).
    ///
    /// # Safety
    /// `name` must point to `len` bytes.
    pub unsafe fn ss_stable_dt(w: u32, name: *const u8, len: usize) -> f64 {
        let out = text(name, len, "the integrator").and_then(|n| {
            let integrator = softsculpt::Integrator::from_name(n).ok_or_else(|| Fail::usage(format!("no integrator '{n}' (one of {})", softsculpt::Integrator::NAMES.join(", "))))?;
            with_world(w, |h| Ok(h.world.stable_dt(integrator).unwrap_or(0.0)))
        });
        match out {
            Ok(dt) => dt,
            Err(e) => {
                crate::fail(e);
                -1.0
            }
        }
    }

    // ----- views (`views.rs`) -------------------------------------------------------------------------

    /// Refresh every body's render positions, pins and stats.
    pub fn ss_sync(w: u32) -> i32 {
        status(|| {
            with_world(w, |h| {
                for (i, v) in h.views.iter_mut().enumerate() {
                    v.sync(&h.world, i);
                }
                Ok(())
            })
        })
    }

    /// Number of bodies, or −1 for a bad handle.
    pub fn ss_body_count(w: u32) -> i32 {
        index(|| with_world(w, |h| Ok(h.world.bodies.len())))
    }

    /// Newton iterations of body `b`'s last step (0 after an explicit one), or −1 (error set).
    pub fn ss_body_newton_iterations(w: u32, b: u32) -> i32 {
        index(|| {
            with_world(w, |h| {
                Ok(h.world.bodies[h.body(b)?].solver_iterations().newton as usize)
            })
        })
    }

    /// The relative residual ‖r‖/‖r_0‖ body `b`'s last implicit step was accepted at when its
    /// deadline stopped it short of the tolerance (the anytime step); 0 for a step that converged
    /// (or an explicit one); −1 (error set).
    pub fn ss_body_accuracy(w: u32, b: u32) -> f64 {
        match with_world(w, |h| {
            let it = h.world.bodies[h.body(b)?].solver_iterations();
            Ok(if it.early { it.residual } else { 0.0 })
        }) {
            Ok(r) => r,
            Err(e) => {
                fail(e);
                -1.0
            }
        }
    }

    /// What of the hinges body `b`'s last step let go of to finish (`Relaxed`: 0 nothing, 1 the
    /// crushed faces' hinges, 2 every hinge), or −1 (error set).
    pub fn ss_body_relaxed(w: u32, b: u32) -> i32 {
        index(|| with_world(w, |h| Ok(h.world.bodies[h.body(b)?].solver_iterations().relaxed.level() as usize)))
    }

    /// Body `b`'s layout table (see the module documentation), or 0 (error set).
    pub fn ss_body_views(w: u32, b: u32) -> *const u32 {
        let r = with_world(w, |h| {
            let i = h.body(b)?;
            Ok(h.views[i].layout(&h.world, i))
        });
        match r {
            Ok(p) => p,
            Err(e) => {
                fail(e);
                std::ptr::null()
            }
        }
    }

    // ----- parameters -----------------------------------------------------------------------------

    /// Every body and world parameter of body `b` and its world, as a JSON object in the result
    /// (`null` for the ground's when there is no ground).
    pub fn ss_params(w: u32, b: u32) -> i32 {
        status(|| {
            with_body(w, b, |h, i| {
                let out: serde_json::Map<String, serde_json::Value> = h
                    .world
                    .param_values(i, &[Scope::Body, Scope::World])
                    .into_iter()
                    .map(|(id, v)| (id.to_string(), v.and_then(|v| serde_json::to_value(v).ok()).unwrap_or(serde_json::Value::Null)))
                    .collect();
                set_result(serde_json::Value::Object(out).to_string().into_bytes());
                Ok(())
            })
        })
    }

    /// Apply preset `name` (`softsculpt::params::presets`): its body parameters on body `b`, its
    /// world parameters on the world; all or nothing.
    ///
    /// # Safety
    /// `name` must point to `len` bytes.
    pub unsafe fn ss_apply_preset(w: u32, b: u32, name: *const u8, len: usize) -> i32 {
        status(|| {
            let name = text(name, len, "the preset name")?;
            with_world(w, |h| h.world.apply_preset(b as usize, name).map_err(param_fail))
        })
    }

    /// Set parameter `id` (body parameters on body `b`, world parameters on the world) from a JSON
    /// value; refused with an error naming the parameter and its unit.
    ///
    /// # Safety
    /// `id` must point to `id_len` bytes and `json` to `json_len` bytes.
    pub unsafe fn ss_set_param(
        w: u32,
        b: u32,
        id: *const u8,
        id_len: usize,
        json: *const u8,
        json_len: usize,
    ) -> i32 {
        status(|| {
            let id = text(id, id_len, "the parameter id")?;
            let v: serde_json::Value = serde_json::from_slice(bytes(json, json_len)).map_err(|e| {
                param_fail(ParamError {
                    id: id.to_string(),
                    message: format!("the value is not JSON ({e})"),
                })
            })?;
            let value = value_of(id, &v).map_err(param_fail)?;
            with_world(w, |h| {
                h.world.set_param(b as usize, id, value).map_err(param_fail)
            })
        })
    }

    /// `World::move_ground`: the ground to `height` m, carrying the bodies standing on it; result
    /// `{"moved": n}` (bodies moved). Refused like `ss_set_param("ground.height")`.
    pub fn ss_move_ground(w: u32, height: f64) -> i32 {
        status(|| {
            with_world(w, |h| {
                let moved = h.world.move_ground(height).map_err(param_fail)?;
                set_result(serde_json::json!({ "moved": moved }).to_string().into_bytes());
                Ok(())
            })
        })
    }

    /// `World::let_overlapping_bodies_be`: contacts off between the bodies that overlap or touch
    /// now, until they part (an import's pieces); result `{"pairs": [[a, b], …]}`.
    pub fn ss_let_overlapping_be(w: u32) -> i32 {
        status(|| {
            with_world(w, |h| {
                let pairs = h.world.let_overlapping_bodies_be();
                set_result(serde_json::json!({ "pairs": pairs }).to_string().into_bytes());
                Ok(())
            })
        })
    }

    // ----- operations on a body --------------------------------------------------------------------

    /// Rest shape := current shape; `under_load` = 1 keeps carrying the weight, `keep_tension` = 1
    /// keeps the gas pressing (rest lengths solved); result `{"residual": N, "load": N,
    /// "iterations": n, "clamped": n}`.
    pub fn ss_freeze(w: u32, b: u32, under_load: u32, keep_tension: u32) -> i32 {
        status(|| {
            with_body(w, b, |h, i| {
                let how = FreezeOptions { under_load: under_load != 0, keep_tension: keep_tension != 0 };
                let r = h.world.freeze(i, how).map_err(sim_fail)?;
                set_result(serde_json::json!({ "residual": r.residual, "load": r.load, "iterations": r.iterations, "clamped": r.clamped }).to_string().into_bytes());
                Ok(())
            })
        })
    }

    /// Back to the last frozen shape.
    pub fn ss_reset(w: u32, b: u32) -> i32 {
        status(|| {
            with_body(w, b, |h, i| {
                h.world.bodies[i].reset();
                Ok(())
            })
        })
    }

    /// Replace body `b` by its isotropic remeshing to edge length `edge` (m)
    /// (`World::remesh_reporting`; `under_load` ≠ 0: frozen under load); result
    /// `{"dropped_events": n, "edge": m, "requested": m, "crease_deg": deg | null, "tries": n,
    /// "distance": m, "volume_change": fraction}`: the edge length used (shorter than asked when the
    /// shape needed it), keeping creases or not, and how far the surface moved. A remesh that would
    /// change the shape is an error and changes nothing. Its views change.
    pub fn ss_remesh(w: u32, b: u32, edge: f64, under_load: u32) -> i32 {
        status(|| {
            with_body(w, b, |h, i| {
                let (dropped, _, r) = h.world.remesh_reporting(i, edge, under_load != 0).map_err(sim_fail)?;
                h.views[i] = BodyViews::new(&h.world, i);
                let json = serde_json::json!({
                    "dropped_events": dropped, "edge": r.edge, "requested": r.requested, "crease_deg": r.crease_deg,
                    "tries": r.tries, "distance": r.departure.distance(), "volume_change": r.departure.volume_change,
                });
                set_result(json.to_string().into_bytes());
                Ok(())
            })
        })
    }

    /// Body `b`'s triangle quality (`World::quality`); result: JSON with the smallest angle and the
    /// share of angles below 25° (degrees, fraction), the shortest and mean edge (m), the edges'
    /// spread (σ/mean) and `poor` (`Quality::is_poor`).
    pub fn ss_quality(w: u32, b: u32) -> i32 {
        status(|| {
            with_body(w, b, |h, i| {
                let q = h.world.quality(i).map_err(sim_fail)?;
                let json = serde_json::json!({
                    "min_angle_deg": q.min_angle_deg, "small_angle_share": q.small_angle_share,
                    "edge_min": q.edge_min, "edge_mean": q.edge_mean, "edge_spread": q.edge_spread, "poor": q.is_poor(),
                });
                set_result(json.to_string().into_bytes());
                Ok(())
            })
        })
    }

    /// Replace body `b` by its Loop subdivision (frozen plainly, its resting vertices kept on their
    /// support: `World::subdivide`); result `{"dropped_events": n}` (its pending scene events no
    /// longer fit). Its views change.
    pub fn ss_subdivide(w: u32, b: u32) -> i32 {
        status(|| {
            with_body(w, b, |h, i| {
                let (dropped, _) = h.world.subdivide(i, softsculpt::body::FreezeOptions::default()).map_err(sim_fail)?;
                h.views[i] = BodyViews::new(&h.world, i);
                set_result(
                    serde_json::json!({ "dropped_events": dropped })
                        .to_string()
                        .into_bytes(),
                );
                Ok(())
            })
        })
    }

    /// Multiply rest lengths by the per-vertex factors in the vertex scratch (a spring takes the
    /// mean of its ends).
    pub fn ss_scale_rest(w: u32, b: u32) -> i32 {
        status(|| {
            with_body(w, b, |h, i| {
                h.world.bodies[i]
                    .scale_rest_lengths_by_vertex(&h.views[i].scratch)
                    .map_err(sim_fail)
            })
        })
    }

    /// Vertex masses (kg) from the vertex scratch.
    pub fn ss_set_masses(w: u32, b: u32) -> i32 {
        status(|| {
            with_body(w, b, |h, i| {
                h.world.bodies[i]
                    .set_masses(&h.views[i].scratch)
                    .map_err(sim_fail)
            })
        })
    }

    /// Pins from the pinned view (1 pinned, 0 free); only vertices that change are touched.
    pub fn ss_set_pins(w: u32, b: u32) -> i32 {
        status(|| {
            with_body(w, b, |h, i| {
                let body = &mut h.world.bodies[i];
                for (v, &p) in h.views[i].pinned.iter().enumerate() {
                    if body.is_pinned(v) != (p != 0) {
                        body.set_pinned(v, p != 0).map_err(sim_fail)?;
                    }
                }
                Ok(())
            })
        })
    }

    /// User forces (N, 3 per vertex) and face pressures (Pa, 1 per face) from the staging views.
    pub fn ss_apply_loads(w: u32, b: u32) -> i32 {
        status(|| {
            with_body(w, b, |h, i| {
                let (body, v) = (&mut h.world.bodies[i], &h.views[i]);
                body.set_user_forces(&v.user_forces).map_err(sim_fail)?;
                body.set_face_pressures(&v.face_pressures).map_err(sim_fail)
            })
        })
    }

    /// Target springs of body `b` (`SoftBody::set_targets`), replacing any it had: `count` records
    /// of 6 f64 at `ptr`, (vertex, anchor x, y, z (m), stiffness (N/m), damping (N·s/m)); 0 clears.
    ///
    /// # Safety
    /// `ptr` must point to `6 count` f64 (or be null with `count` 0).
    pub unsafe fn ss_set_targets(w: u32, b: u32, ptr: *const f64, count: usize) -> i32 {
        status(|| {
            if ptr.is_null() && count > 0 {
                return Err(Fail::usage("targets need a buffer"));
            }
            let rec = if count == 0 {
                &[][..]
            } else {
                std::slice::from_raw_parts(ptr, 6 * count)
            };
            let mut targets = Vec::with_capacity(count);
            for r in rec.chunks_exact(6) {
                if !(r[0] >= 0.0 && r[0].fract() == 0.0 && r[0] < u32::MAX as f64) {
                    return Err(Fail::usage(format!(
                        "a target's vertex must be a whole number ≥ 0, got {}",
                        r[0]
                    )));
                }
                targets.push(Target {
                    vertex: r[0] as usize,
                    anchor: [r[1], r[2], r[3]],
                    stiffness: r[4],
                    damping: r[5],
                });
            }
            with_body(w, b, |h, i| {
                h.world.bodies[i].set_targets(&targets).map_err(sim_fail)
            })
        })
    }

    // ----- snapshots ------------------------------------------------------------------------------

    /// The whole world as snapshot bytes (`docs/snapshot.md`) in the result.
    pub fn ss_snapshot(w: u32) -> i32 {
        status(|| {
            with_world(w, |h| {
                set_result(h.world.snapshot());
                Ok(())
            })
        })
    }

    /// The world from snapshot bytes; on error (kind `snapshot`, the core's message) the world is
    /// untouched. Every body's views change.
    ///
    /// # Safety
    /// `ptr` must point to `len` readable bytes.
    pub unsafe fn ss_restore(w: u32, ptr: *const u8, len: usize) -> i32 {
        status(|| {
            with_world(w, |h| {
                h.world
                    .restore_from(bytes(ptr, len))
                    .map_err(snapshot_fail)?;
                h.rebuild_views();
                Ok(())
            })
        })
    }
}
