//! The calls that change one body's shape, masses, pins or loads: freeze, reset, remesh,
//! quality, subdivide, scale the rest shape, set masses, pins, loads and targets.

use crate::abi::exports;
use crate::fails::sim_fail;
use crate::handle::with_body;
use crate::views::BodyViews;
use crate::report::{json, reports};
use crate::{set_result, status, Fail};
use softsculpt::body::FreezeOptions;
use softsculpt::Target;

reports! {
    /// What a freeze leaves unbalanced (`softsculpt::body::FreezeReport`): forces in N.
    pub struct FreezeReport {
        /// Largest net force on a free vertex at rest right after the freeze.
        pub residual: f64,
        /// Largest load the springs were asked to balance on a vertex: the residual's scale.
        pub load: f64,
        /// Conjugate-gradient iterations of the tension solve.
        pub iterations: usize,
        /// Springs whose solved rest length came out negative and was set to 0.
        pub clamped: usize,
    }

    /// What `ss_remesh` reports (lengths in m; `volume_change` relative, before the remesher's
    /// correction).
    pub struct RemeshReport {
        /// The body's pending scene events that no longer fit and were dropped.
        pub dropped_events: usize,
        /// The edge length used.
        pub edge: f64,
        /// The edge length asked for.
        pub requested: f64,
        /// The crease angle kept (degrees), or null.
        pub crease_deg: Option<f64>,
        /// 1: remeshed as asked; more: the shape needed a shorter edge or its sharp edges kept.
        pub tries: usize,
        /// The largest distance between the old and the new surface.
        pub distance: f64,
        pub volume_change: f64,
    }
}

exports! {
    /// Rest shape := current shape; `under_load` = 1 keeps carrying the weight, `keep_tension` = 1
    /// keeps the gas pressing (rest lengths solved); result `{"residual": N, "load": N,
    /// "iterations": n, "clamped": n}`.
    pub fn ss_freeze(w: u32, b: u32, under_load: u32, keep_tension: u32) -> i32 {
        status(|| {
            with_body(w, b, |h, i| {
                let how = FreezeOptions { under_load: under_load != 0, keep_tension: keep_tension != 0 };
                let r = h.world.freeze(i, how).map_err(sim_fail)?;
                set_result(json(&FreezeReport { residual: r.residual, load: r.load, iterations: r.iterations, clamped: r.clamped }));
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
                set_result(json(&RemeshReport {
                    dropped_events: dropped,
                    edge: r.edge,
                    requested: r.requested,
                    crease_deg: r.crease_deg,
                    tries: r.tries,
                    distance: r.departure.distance(),
                    volume_change: r.departure.volume_change,
                }));
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
}
