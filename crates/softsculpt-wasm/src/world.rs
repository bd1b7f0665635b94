//! The calls on a world and its bodies (the world found by its handle: `handle.rs`): bodies
//! added, stepping and the clock, what a body's last step did, its views, overlapping pieces
//! and snapshots. Each call checks its arguments, delegates to the core, and turns the core's
//! error into a [`Fail`] (`fails.rs`). Parameters: `params.rs`; operations on one body's shape:
//! `bodyops.rs`.

use crate::abi::exports;
use crate::fails::{body_fail, mesh_fail, snapshot_fail, step_fail};
use crate::handle::with_world;
use crate::report::{self, reports};
use crate::{bytes, fail, index, set_result, status, text, Fail, Res};
use softsculpt::mesh::{self, builtin, LoadedMesh, ObjData, TriMesh};
use softsculpt::{
    world::{Budget, Interrupt}, Material, MeshError, SoftBody, World,
};

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


reports! {
    /// What a frame did (`World.advance`, the core's `Advance`).
    pub struct Advance {
        /// Steps taken (a split step counts its pieces).
        pub steps: u64,
        /// Steps that had to be split.
        pub splits: u32,
        /// Simulated seconds advanced.
        pub simulated: f64,
        /// The largest relative residual a step was accepted at.
        pub residual: f64,
        /// Implicit steps stopped at their deadline, short of the tolerance.
        pub early: u32,
        /// Wall-clock seconds the frame took (real-time budgets).
        pub wall: f64,
    }
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
                let out = Advance { steps: a.steps, splits: a.splits, simulated: a.simulated, residual: a.residual, early: a.early, wall: a.wall };
                set_result(report::json(&out));
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
