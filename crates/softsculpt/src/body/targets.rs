//! Target springs: a load that pulls chosen vertices towards anchor points, what the modeler's
//! grab (and press) use, the anchors moved between steps to follow the cursor.
//!
//! On vertex i with anchor a_i (m), stiffness k_t (N/m) and damping c_t (N·s/m):
//!
//!   f_i = k_t (a_i − x_i) − c_t v_i                                         (N)
//!
//! a zero-length spring to a fixed point plus a dashpot to the ground frame (the anchor is held
//! still within a step). The explicit integrators add it as a force (stable for
//! dt ≲ 2 / sqrt(k_t / m_i)); the implicit one also puts k_t I into the stiffness and c_t I into
//! the damping of its system (`implicit/system/`), exactly, so any strength is stable: with
//! k_t ≫ m/dt² the vertex lands on the anchor in one step. It is external work, not part of the
//! energies in the statistics. Pinned vertices ignore it. Kept in snapshots.

use super::SoftBody;
use crate::error::SimError;

/// One target spring.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Target {
    /// Vertex index.
    pub vertex: usize,
    /// Anchor point (m).
    pub anchor: [f64; 3],
    /// Stiffness k_t (N/m), ≥ 0.
    pub stiffness: f64,
    /// Damping c_t (N·s/m), ≥ 0.
    pub damping: f64,
}

/// The targets of a body: the list, and per vertex (dense, allocated on first use) k_t, c_t and
/// the anchor, which the force passes read.
#[derive(Debug, Clone, Default)]
pub(crate) struct Targets {
    pub list: Vec<Target>,
    pub k: Vec<f64>,
    pub c: Vec<f64>,
    pub anchor: Vec<f64>,
}

impl Targets {
    pub fn active(&self) -> bool {
        !self.list.is_empty()
    }

    /// Stage "targets" of the explicit integrators: add the forces, times `scale`, into `f`.
    pub fn accumulate(&self, x: &[f64], v: &[f64], scale: f64, f: &mut [f64]) {
        for t in &self.list {
            for d in 0..3 {
                let k = 3 * t.vertex + d;
                f[k] += scale * (t.stiffness * (t.anchor[d] - x[k]) - t.damping * v[k]);
            }
        }
    }
}

impl SoftBody {
    /// Replace the body's target springs by `targets` (an empty list removes them). Each vertex
    /// at most once; anchors finite, stiffness and damping finite and ≥ 0. On error nothing
    /// changes.
    pub fn set_targets(&mut self, targets: &[Target]) -> Result<(), SimError> {
        let n = self.vertex_count();
        let mut seen = std::collections::HashSet::with_capacity(targets.len());
        for t in targets {
            let bad = |message: String| SimError::BadParameter { name: "target", message };
            if t.vertex >= n {
                return Err(bad(format!("vertex {} out of range (the body has {n} vertices)", t.vertex)));
            }
            if !seen.insert(t.vertex) {
                return Err(bad(format!("vertex {} is listed twice", t.vertex)));
            }
            if t.anchor.iter().any(|a| !a.is_finite()) {
                return Err(bad(format!("anchor of vertex {} must be finite, got {:?} m", t.vertex, t.anchor)));
            }
            if !(t.stiffness.is_finite() && t.stiffness >= 0.0) {
                return Err(bad(format!("stiffness must be finite and ≥ 0 N/m, got {}", t.stiffness)));
            }
            if !(t.damping.is_finite() && t.damping >= 0.0) {
                return Err(bad(format!("damping must be finite and ≥ 0 N·s/m, got {}", t.damping)));
            }
        }
        let tg = &mut self.model.targets;
        if tg.k.len() != n {
            (tg.k, tg.c, tg.anchor) = (vec![0.0; n], vec![0.0; n], vec![0.0; 3 * n]);
        }
        for t in &tg.list {
            (tg.k[t.vertex], tg.c[t.vertex]) = (0.0, 0.0);
        }
        for t in targets {
            (tg.k[t.vertex], tg.c[t.vertex]) = (t.stiffness, t.damping);
            tg.anchor[3 * t.vertex..3 * t.vertex + 3].copy_from_slice(&t.anchor);
        }
        tg.list = targets.to_vec();
        Ok(())
    }

    /// Move the body up by `dy` (m): its positions, its frozen shape (what Reset goes back to)
    /// and its target springs' anchors — a translation, which changes no internal force.
    pub(crate) fn lift(&mut self, dy: f64) {
        for x in [&mut self.state.x, &mut self.frozen.x] {
            for p in x.chunks_exact_mut(3) {
                p[1] += dy;
            }
        }
        let tg = &mut self.model.targets;
        for t in &mut tg.list {
            t.anchor[1] += dy;
            tg.anchor[3 * t.vertex + 1] += dy;
        }
    }

    /// Remove every target spring.
    pub fn clear_targets(&mut self) {
        // An empty list is always valid.
        let _ = self.set_targets(&[]);
    }

    /// The target springs in force.
    pub fn targets(&self) -> &[Target] {
        &self.model.targets.list
    }
}
