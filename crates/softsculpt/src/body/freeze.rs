//! Freezing: the current shape becomes the rest shape, in three ways ([`FreezeOptions`]).
//!
//! - **plain** ([`SoftBody::freeze`]): every rest length := the current length, the gas
//!   re-referenced (P_ref := P), so no force acts and the shape is at rest. The skin is slack:
//!   nothing but the gas's volume stiffness resists a press, so a press moves whole parts.
//! - **under load** ([`SoftBody::freeze_under_load`]): the plain freeze plus a constant
//!   "prestress" f_p that carries the body's weight: f_p,i = m_i g ŷ on every free vertex, and
//!   the opposite total −Σ_free m_i g ŷ shared by the supported vertices (pinned, or resting on
//!   the ground or an obstacle) in proportion to their masses, pressing them onto the support.
//!   Σ f_p = 0. Every free vertex then feels f_p,i − m_i g ŷ = 0 and every supported one is
//!   pushed onto its support: any shape, at rest or moving, grabbed or not, is held exactly.
//!   Without any support the weight is not carried (a falling body carries nothing): f_p = 0.
//! - **keeping the tension** ([`SoftBody::freeze_keeping_tension`]): the gas keeps its
//!   reference (P_ref unchanged, so it keeps pressing with P − P_ref), and the rest lengths L_e
//!   (edge and bending springs) are corrected so that the current shape is an equilibrium under
//!   the gas (and under load, the weight, with the supports taking what they carry): the least
//!   change of tension Δt (Σ Δt² / k = Σ k ΔL², `tension.rs`) that cancels the net force F the
//!   springs with the current rest lengths, the gas and the weight leave on every free vertex,
//!   then L_e −= Δt_e / k_e. A body at rest has F = 0 and keeps its rest lengths: the skin stays
//!   taut as it is, so a press dents it as before the freeze. (The least tension from scratch,
//!   closest to the current lengths, balances too but was unstable: docs/model.md.) No
//!   prestress. The net force left on the free vertices is the [`FreezeReport`]'s residual.
//!
//! Every kind zeroes the velocities, sets the gas energy's reference volume V0 to the current
//! volume and records the frozen state for [`SoftBody::reset`].

use super::tension::{self, SpringSet};
use super::{gas, Frozen, SoftBody};

/// How to freeze (see the module documentation).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct FreezeOptions {
    /// Keep carrying the body's weight (when something supports it).
    pub under_load: bool,
    /// Keep the gas pressing and solve rest lengths so the shape is an equilibrium.
    pub keep_tension: bool,
}

/// What a freeze leaves unbalanced (the tension-keeping one; the others leave nothing).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct FreezeReport {
    /// Largest net force (N) on a free vertex at rest right after the freeze, over the rows the
    /// freeze balances (a supported vertex's vertical row is its support's).
    pub residual: f64,
    /// Largest load (N) the springs were asked to balance on a vertex: the residual's scale.
    pub load: f64,
    /// Conjugate-gradient iterations of the tension solve.
    pub iterations: usize,
    /// Springs whose solved rest length came out negative and was set to 0 (more tension than
    /// a spring can give: the residual then shows it).
    pub clamped: usize,
}

/// The body's weight and what carries it: gravity g (m/s², along −y) and, per vertex, whether
/// it rests on a support (ground or obstacle; pinned vertices always count as supported).
#[derive(Debug, Clone, Copy)]
pub struct Supports<'a> {
    pub gravity: f64,
    pub resting: &'a [bool],
}

impl SoftBody {
    /// Plain freeze: every rest length becomes the current length (so the springs exert no
    /// force), velocities become zero, and the gas is re-referenced: the surroundings' pressure
    /// P_ref becomes the current gas pressure P = nRT / V, so the net gas force (P − P_ref) ∂V/∂x
    /// is zero. With nothing else acting, the body then stays exactly where it is. The gas
    /// energy reference V0 becomes the current volume; the prestress is cleared.
    /// [`SoftBody::reset`] returns to this state.
    pub fn freeze(&mut self) {
        self.model.springs.rest_to_current(&self.state.x);
        self.model.bending.rest_to_current(&self.state.x);
        let volume = self.step_volume();
        self.model.gas.ambient_pressure = gas::pressure(self.material.nrt(), volume);
        self.finish_freeze(None);
    }

    /// Freeze under load: the plain freeze plus the constant load that carries the body's
    /// weight onto its supports (module documentation). `supports.resting` has one flag per
    /// vertex (other lengths count as none resting).
    pub fn freeze_under_load(&mut self, supports: Supports) {
        let carried = self.carried_weight(supports);
        self.freeze();
        self.model.prestress = carried;
        self.update_external();
        self.frozen.prestress = self.model.prestress.clone();
    }

    /// Freeze keeping the tension: the gas reference is kept and the rest lengths are corrected
    /// (least change) so that the current shape is an equilibrium under the gas, and under `load`
    /// (if given) the weight too (module documentation, `tension.rs`). Returns the residual.
    pub fn freeze_keeping_tension(&mut self, load: Option<Supports>) -> FreezeReport {
        let n = self.vertex_count();
        let x = self.state.x.clone();
        // Rows the springs must balance: not pinned; a resting vertex's vertical row is its
        // support's (only when its weight is being carried).
        let weight = load.map(|s| (s.gravity, self.supported(s))).filter(|(g, sup)| *g != 0.0 && self.carries(sup));
        let mut free = vec![true; 3 * n];
        for i in 0..n {
            if self.is_pinned(i) {
                free[3 * i..3 * i + 3].fill(false);
            } else if let Some((_, sup)) = &weight {
                if sup[i] {
                    free[3 * i + 1] = false;
                }
            }
        }
        // The loads: the gas as it presses now, and the weight.
        let mut f = self.gas_force(&x);
        if let Some((g, _)) = weight {
            for i in 0..n {
                f[3 * i + 1] -= self.model.mass[i] * g;
            }
        }
        // What the springs must change: the net force with the current rest lengths (at rest).
        let (k, kb) = (self.material.stiffness, self.material.bending_stiffness);
        let zero = vec![0.0; 3 * n];
        let mut net = f.clone();
        self.model.springs.accumulate(k, 0.0, &x, &zero, &mut net);
        if kb > 0.0 {
            self.model.bending.accumulate(kb, 0.0, &x, &zero, &mut net);
        }
        let solved = tension::balance(&[SpringSet { springs: &self.model.springs, k }, SpringSet { springs: &self.model.bending, k: kb }], &x, &net, &free);
        let mut clamped = 0;
        for (s, (dt, stiffness)) in [&mut self.model.springs, &mut self.model.bending].into_iter().zip(solved.t.iter().zip([k, kb])) {
            if stiffness == 0.0 {
                continue;
            }
            for (rest, d) in s.rest.iter_mut().zip(dt) {
                let target = *rest - d / stiffness;
                if target < 0.0 {
                    clamped += 1;
                }
                *rest = target.max(0.0);
            }
        }
        // What is left: springs + loads on the balanced rows, at rest.
        let mut r = f.clone();
        self.model.springs.accumulate(k, 0.0, &x, &zero, &mut r);
        if kb > 0.0 {
            self.model.bending.accumulate(kb, 0.0, &x, &zero, &mut r);
        }
        let row_norm = |v: &[f64], i: usize| (0..3).filter(|&c| free[3 * i + c]).map(|c| v[3 * i + c].powi(2)).sum::<f64>().sqrt();
        let report = FreezeReport {
            residual: (0..n).map(|i| row_norm(&r, i)).fold(0.0, f64::max),
            load: (0..n).map(|i| row_norm(&f, i)).fold(0.0, f64::max),
            iterations: solved.iterations,
            clamped,
        };
        self.finish_freeze(Some(vec![0.0; 3 * n]));
        report
    }

    /// Freeze as `how` says, the weight (under load) carried onto `supports`.
    pub fn freeze_with(&mut self, how: FreezeOptions, supports: Supports) -> FreezeReport {
        match (how.keep_tension, how.under_load) {
            (true, under_load) => self.freeze_keeping_tension(under_load.then_some(supports)),
            (false, true) => {
                self.freeze_under_load(supports);
                FreezeReport::default()
            }
            (false, false) => {
                self.freeze();
                FreezeReport::default()
            }
        }
    }

    /// Zero velocities, V0 := V (`GasReference::volume_for`: 1 m³ without a positive volume),
    /// the prestress (cleared if `None`), and the frozen state.
    fn finish_freeze(&mut self, prestress: Option<Vec<f64>>) {
        self.state.v.fill(0.0);
        self.model.gas.reference_volume = gas::GasReference::volume_for(self.volume());
        match prestress {
            Some(p) => self.model.prestress = p,
            None => self.model.prestress.fill(0.0),
        }
        self.update_external();
        self.frozen = Frozen { x: self.state.x.clone(), rest: self.model.springs.rest.clone(), bending_rest: self.model.bending.rest.clone(), gas: self.model.gas, prestress: self.model.prestress.clone() };
        self.hinges_to_frozen();
    }

    /// Per vertex: pinned, or resting on a support.
    fn supported(&self, s: Supports) -> Vec<bool> {
        (0..self.vertex_count()).map(|i| self.is_pinned(i) || s.resting.get(i).copied().unwrap_or(false)).collect()
    }

    /// Whether anything supports the body (some vertex supported, some free).
    fn carries(&self, supported: &[bool]) -> bool {
        supported.iter().any(|&s| s) && supported.iter().any(|&s| !s)
    }

    /// The prestress that carries the weight (module documentation), N flat xyz.
    fn carried_weight(&self, s: Supports) -> Vec<f64> {
        let n = self.vertex_count();
        let mut p = vec![0.0; 3 * n];
        let sup = self.supported(s);
        if s.gravity == 0.0 || !self.carries(&sup) {
            return p;
        }
        let m = &self.model.mass;
        let weight: f64 = (0..n).filter(|&i| !sup[i]).map(|i| m[i] * s.gravity).sum();
        let support_mass: f64 = (0..n).filter(|&i| sup[i]).map(|i| m[i]).sum();
        for i in 0..n {
            p[3 * i + 1] = if sup[i] { -weight * m[i] / support_mass } else { m[i] * s.gravity };
        }
        p
    }

    /// The gas force (P − P_ref) ∂V/∂x (N, flat xyz) at `x`, as the forces stage computes it.
    fn gas_force(&self, x: &[f64]) -> Vec<f64> {
        let mut g = vec![0.0; x.len()];
        let nrt = self.material.nrt();
        if nrt == 0.0 && self.model.gas.ambient_pressure == 0.0 {
            return g;
        }
        let six_v = self.model.faces.volume6_and_normals(x, &mut g);
        let volume = gas::measure(self.model.faces.triangles(), self.material.volume_mode, six_v, x);
        let s = (gas::pressure(nrt, volume) - self.model.gas.ambient_pressure) / 6.0;
        g.iter_mut().for_each(|v| *v *= s);
        g
    }
}
