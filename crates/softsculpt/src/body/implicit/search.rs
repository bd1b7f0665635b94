//! The Newton step's direction and length (`super`'s module doc has the maths): the line
//! search along δ, the conjugate directions after a stalled start, and the warm start from
//! the last step's velocity change; with the constants that tune them, each with its measurement.

use super::super::forces::Fault;
use super::system::Frame;
use super::{potential, Implicit};
use crate::par::Threads;

/// Most trials of the line search after the full step.
pub(super) const LINE_MAX: u32 = 6;
/// A full Newton step whose slope along δ has turned positive beyond this fraction of its
/// starting magnitude, s(1) > OVERSHOOT |s(0)| (for a quadratic along the plain Newton direction:
/// the true curvature is more than (1 + OVERSHOOT)× the model's, s(1)/s(0) = 1 − c_true/c_model;
/// an inexact linear solve, or a conjugate direction from [`CONJUGATE_FROM`] on, blurs this —
/// a needless switch costs speed only), switches the rest of this Newton solve's matrices to the
/// absolute-value projection of compressed springs (the multigrid's coarse levels are assembled
/// again from them) (`system/`; Chen et al. 2024, "Trust-region eigenvalue filtering for
/// projected Newton"). Why: on a compressed, flattened bottom (a body on the ground), a vertex
/// whose springs are all compressed has almost nothing but its mass against moving out of the
/// surface in the clamped matrix (m = 1e-4 kg against dt² k ≈ 0.14 kg at 10,242 vertices and
/// k = 500 N/m); Newton then moves it by centimetres, the springs stretch at second order
/// (measured: l/L 1.02 → 1.12 in one trial, s(1) = 11 |s(0)|) and Newton wanders at a relative
/// residual of 1e-2: 230–275 Newton iterations per step, most steps failing. The absolute value
/// gives such a mode the stiffness k |1 − L/l| (2–4 % of k there). Measured on a 10,242-vertex
/// sphere landing on the ground with k = k_b = 500 N/m (BENCHMARKS.md): 3,906 → 702 Newton
/// iterations in its first 40 steps (4,795 → 3,473 in 60: once it rolls on its flattened bottom
/// some steps still fail). Not from the start of every step: at the modeler's k = 100 N/m the
/// absolute value throughout cost 11 % more iterations (253 against 228 in 40 steps); the
/// clamp under-estimates nothing there, and the switch leaves it unchanged (229).
pub(super) const OVERSHOOT: f64 = 0.5;
/// Newton iterations of plain Newton directions before conjugate ones ([`Implicit::conjugate`];
/// measured: 4 and 8 both rescue the stalled step, 8 costs nothing on fast steps).
pub(super) const CONJUGATE_FROM: u32 = 8;
/// The fraction of the last step's velocity change the warm start takes. With all of it, each
/// step's within-tolerance error repeats the last one's and no longer damps out: measured on the
/// modeler's 2,562-vertex sphere at rest at tolerance 1e-3, 1.1e-4 J of kinetic energy kept
/// (a steady breathing) against 3.3e-6 J cold; with 0.9, 7e-7 J, at 884 Newton iterations in
/// 240 steps (1.0: 611, 0.8: 1061, cold: 3681). Under-relaxed, the guess errs towards v⁺ = v,
/// as a cold start does, which damps.
pub(super) const WARM_FRACTION: f64 = 0.9;
/// The warm start is tried only where the residual at v⁺ = v is more than this many times the
/// convergence threshold. Closer than that one Newton iteration from v⁺ = v finishes the step,
/// and at a body coming to rest the last step's Δv is mostly noise: measured on the modeler's
/// 10,242-vertex sphere landing (8 s), of 106 warm starts tried at ratios 1–2, 92 were rejected
/// (each costing two evaluations: the warm one and the cold one again) and 6 converged at once;
/// at 2–5, 27 of 34 were taken.
pub(super) const WARM_FROM: f64 = 2.0;

impl Implicit {
    /// Move v⁺ from v⁺_k to v⁺_k + λ δ, λ a root of the slope s(λ) = δ · r(v⁺_k + λ δ).
    ///
    /// For conservative forces r is the gradient of the step's incremental potential
    /// G(v⁺) = ½ (v⁺ − v)ᵀ M (v⁺ − v) + Φ(x + dt v⁺) (Φ the potential energy), so s is G's
    /// slope along δ, negative at λ = 0 (A is positive definite), and a λ where it is back to
    /// near zero (|s| ≤ ½ |s(0)|, before any rise of G) is a step down G. λ = 1 is tried first
    /// and is what Newton's method takes near the solution; where the projected matrix
    /// over-estimates the curvature (a compressed, buckling body: the clamped transverse
    /// stiffness is really negative) the full step is too short and λ is extrapolated by the
    /// secant; past a root, regula falsi in the bracket; a trial where the state fails (a
    /// collapsed volume) is a bracket end too, halved towards. G itself is never needed (it is
    /// not needed for this): its slope is the residual. At most [`LINE_MAX`] trials; the last
    /// one is kept.
    ///
    /// **Then, for a solve a deadline may stop (`WorldSettings::deadline`: a real-time budget),
    /// the Armijo test on G** (`potential.rs`; the damping's directions frozen at
    /// λ = 0, so G's slope there is s(0) exactly): the step is halved, at most
    /// [`potential::BACKTRACK_MAX`] times, until G(λ) ≤ G(0) + c λ s(0) (c =
    /// [`potential::ARMIJO`]) or until G's change is below its rounding (near convergence,
    /// relative residuals below ~1e-5: there the slope test decides). So every iterate the
    /// solver accepts lowers G, and one stopped at a deadline (the anytime step) is a state the
    /// step's potential went down to. Measured, the slope test's λ already passed it in every
    /// line search of the grabs and drops tried (`potential.rs`): the halving is the guarantee,
    /// an evaluation each where it acts; G's two evaluations per line search cost ~3 % of a
    /// budgeted frame (BENCHMARKS.md). A solve run to
    /// its tolerance (no deadline: the CLI, scenes) skips the test: its result is the same
    /// backward-Euler step whichever path its iterates took, and it stays today's bit for bit.
    /// Returns the new (‖r‖, noise); r and the system are those of the new v⁺.
    pub(super) fn line_search(&mut self, th: &Threads, fr: &Frame) -> Result<(f64, f64), Fault> {
        let slope = |me: &Self| -> f64 { me.delta.iter().zip(&me.r).map(|(d, r)| d * r).sum() };
        let s0 = slope(self);
        // The Armijo test on G, where a deadline may stop the solve (below).
        let armijo = fr.w.deadline.is_some() && s0 < 0.0;
        let g0 = armijo.then(|| {
            self.frozen.take(&self.sys, fr);
            self.sys.potential(fr, &self.vp, &self.xt, &self.frozen)
        });
        let mut at = 0.0;
        let mut go = |me: &mut Self, lambda: f64| {
            for (vp, d) in me.vp.iter_mut().zip(&me.delta) {
                *vp += (lambda - at) * d;
            }
            at = lambda;
            me.eval(th, fr)
        };
        let mut lambda = 1.0;
        let (mut lo, mut s_lo) = (0.0, s0);
        let mut hi: Option<(f64, f64)> = None; // (λ, slope), slope NaN where the state failed
        let mut out = go(self, lambda);
        for trial in 0..LINE_MAX {
            let s = if out.is_ok() { slope(self) } else { f64::NAN };
            if trial == 0 && s0 < 0.0 && s > -OVERSHOOT * s0 {
                // The full step went well past the minimum along δ: the matrix under-estimates
                // the curvature (`OVERSHOOT`); from here on this step's matrices take compressed
                // springs' transverse stiffness by its absolute value (`system/`). The next
                // trial's evaluation already builds them.
                self.sys.absolute = true;
            }
            if !(s0 < 0.0) || s.abs() <= 0.5 * s0.abs() {
                break;
            }
            if s < 0.0 {
                (lo, s_lo) = (lambda, s);
            } else {
                hi = Some((lambda, s));
            }
            lambda = match hi {
                Some((h, sh)) if sh.is_finite() => lo - s_lo * (h - lo) / (sh - s_lo),
                Some((h, _)) => 0.5 * (lo + h),
                None if s_lo > s0 => (lo - s_lo * lo / (s_lo - s0)).min(16.0 * lo),
                None => 4.0 * lo,
            };
            out = go(self, lambda);
        }
        self.lines.searches += 1;
        if let Some(g0) = g0 {
            let mut halved = 0;
            loop {
                let g1 = out.is_ok().then(|| self.sys.potential(fr, &self.vp, &self.xt, &self.frozen));
                if let Some(g1) = g1 {
                    let change = g1.value - g0.value;
                    if change.abs() <= g0.noise + g1.noise {
                        self.lines.unresolved += 1;
                        break;
                    }
                    #[cfg(test)]
                    self.trace.push((g0.value, g1.value, g0.noise + g1.noise));
                    if change <= potential::ARMIJO * lambda * s0 {
                        break;
                    }
                }
                if halved == potential::BACKTRACK_MAX {
                    self.lines.rose += 1;
                    break;
                }
                halved += 1;
                lambda *= 0.5;
                out = go(self, lambda);
            }
            if halved > 0 {
                self.lines.backtracked += 1;
            }
        }
        out
    }

    /// From Newton iteration [`CONJUGATE_FROM`] + 1 on, the direction of the line search is the
    /// Newton step z_k = −A_k⁻¹ r_k made conjugate to the last direction p_{k−1} (nonlinear
    /// conjugate gradient preconditioned by the Newton solve, Polak–Ribière+):
    ///
    ///   p_k = z_k + β p_{k−1},  β = max(0, r_k·(z_{k−1} − z_k) / (−r_{k−1}·z_{k−1}))
    ///
    /// (back to z_k if p_k is not a descent direction, p_k·r_k ≥ 0). Why: on a compressed,
    /// wrinkling membrane the projected matrix over-estimates the curvature of a soft mode many
    /// times (the line search's λ reaches 3–35), and plain Newton zig-zags in it: measured on the
    /// implicit tests' dropped balloon at tolerance 1e-6, 100 iterations stalled at a relative
    /// residual of 2–9e-6, which the conjugate directions take to convergence. Before that
    /// iteration it is plain Newton (the conjugate term cost ~10 % more iterations at
    /// 1e-3 and 1e-4 on steps that converge fast). `delta` holds z_k on entry and the
    /// direction on return; `zprev`, `pprev` the last ones. Returns −r_k·z_k for the next call.
    pub(super) fn conjugate(&mut self, k: u32, gyprev: f64) -> f64 {
        let dot = |a: &[f64], b: &[f64]| -> f64 { a.iter().zip(b).map(|(x, y)| x * y).sum() };
        let gy = -dot(&self.r, &self.delta);
        if k > CONJUGATE_FROM && gyprev > 0.0 {
            let beta = ((gy + dot(&self.r, &self.zprev)) / gyprev).max(0.0);
            self.zprev.copy_from_slice(&self.delta);
            for (d, p) in self.delta.iter_mut().zip(&self.pprev) {
                *d += beta * p;
            }
            if !(dot(&self.r, &self.delta) < 0.0) {
                self.delta.copy_from_slice(&self.zprev);
            }
        } else {
            self.zprev.copy_from_slice(&self.delta);
        }
        gy
    }

    /// Start Newton from v⁺ = v + [`WARM_FRACTION`] (dt / dt_w) Δv_w, Δv_w = v⁺ − v of the last accepted step
    /// (its dt_w; pinned vertices keep v), if its residual is below `cold`'s, the residual at
    /// v⁺ = v (else back to v⁺ = v). At a quasi-static state (a slow drift) every step solves
    /// nearly the same problem, and the last answer is most of this one: measured (BENCHMARKS.md,
    /// before the ground was part of the solve) 15 Newton iterations per step from v, 1 from the
    /// warm start. The
    /// tolerance is still relative to ‖r_0‖ at v⁺ = v, so an accepted step is as close to the
    /// backward-Euler solution as a cold one. Costs one more evaluation.
    pub(super) fn warm_start(&mut self, th: &Threads, fr: &Frame, warm: &[f64], scale: f64, cold: (f64, f64)) -> Result<(f64, f64), Fault> {
        let free = fr.m.inv_mass.iter().flat_map(|&im| [im != 0.0; 3]);
        for (((vp, &v), &d), free) in self.vp.iter_mut().zip(fr.v).zip(warm).zip(free) {
            *vp = if free { v + WARM_FRACTION * scale * d } else { v };
        }
        self.sys.ground.prescribe(&mut self.vp);
        match self.eval(th, fr) {
            Ok(e) if e.0 < cold.0 => {
                self.warmed = true;
                return Ok(e);
            }
            _ => {}
        }
        self.vp.copy_from_slice(fr.v);
        self.sys.ground.prescribe(&mut self.vp);
        self.eval(th, fr)?;
        Ok(cold)
    }
}
