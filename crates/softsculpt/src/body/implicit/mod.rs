//! The `implicit` integrator: backward Euler on every force of the model.
//!
//!   v⁺ = v + dt M⁻¹ f(x + dt v⁺, v⁺),    x⁺ = x + dt v⁺
//!
//! solved for v⁺ by Newton iterations on the residual
//!
//!   r(v⁺) = M (v⁺ − v) − dt f(x + dt v⁺, v⁺)        (kg·m/s per coordinate)
//!
//! each Newton step δ from A δ = −r with A = M + dt D + dt² K (K, D the projected stiffness and
//! damping, `system.rs`) by a preconditioned conjugate gradient (`cg.rs`; block Jacobi, or a
//! multigrid V-cycle from `multigrid::MULTIGRID_FROM` vertices: `multigrid.rs`), then a
//! line search along δ ([`Implicit::line_search`]). Anchors: Baraff & Witkin 1998 (large steps in cloth simulation).
//!
//! **Convergence** (what `tolerance` means): with the mass-weighted norm
//! ‖r‖²_{M⁻¹} = Σ_i |r_i|² / m_i over the free vertices and r_0 the residual of the first guess
//! v⁺ = v (the explicit prediction's residual, −dt f(x + dt v, v)), the step is accepted when
//!
//!   ‖r_k‖_{M⁻¹} ≤ tolerance · ‖r_0‖_{M⁻¹}
//!
//! or when ‖r_k‖ is down to the rounding of the terms summed into it (16 ε times their
//! magnitudes: a body at equilibrium has r_0 ≈ 0 and nothing left to reduce). ‖r‖_{M⁻¹} is a
//! velocity error weighted by mass, so heavy and light vertices count by their momentum. The
//! linear solve of Newton iteration k stops at the relative accuracy
//! η_k = min(0.1, max(ρ_k², tolerance / (2 ρ_k))), ρ_k = ‖r_k‖/‖r_0‖: loose while far away,
//! just tight enough near the end (an Eisenstat–Walker-like forcing term).
//!
//! At most `newton_iterations` Newton iterations (world setting) and [`cg::LINEAR_MAX`] linear
//! iterations per Newton iteration; a step that has not converged is refused with the state
//! untouched (the world reports the time and suggests a smaller dt). The iterations of the last
//! step are kept for the statistics (`solver_iterations`).
//!
//! All scratch is allocated on the first implicit step of a body and reused.

mod adjacency;
mod aggregate;
mod cg;
mod multigrid;
mod system;

use super::forces::Fault;
use super::{Material, Model, State};
use crate::par::Threads;
use crate::world::WorldSettings;
use system::{Frame, System};

/// Iterations of the last step: Newton iterations and conjugate-gradient iterations (summed
/// over the Newton iterations). Zero for the explicit integrators.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct SolverIterations {
    pub newton: u32,
    pub linear: u32,
}

/// Most trials of the line search after the full step.
const LINE_MAX: u32 = 6;

/// Scratch of the implicit integrator (one per body, allocated on first use).
#[derive(Debug, Clone, Default)]
pub(crate) struct Implicit {
    sys: System,
    mg: multigrid::Multigrid,
    cg: cg::Cg,
    vp: Vec<f64>,
    xt: Vec<f64>,
    r: Vec<f64>,
    delta: Vec<f64>,
}

impl Implicit {
    pub fn new(m: &Model) -> Self {
        let n = m.mass.len();
        let sys = System::new(m);
        let chunks = sys.vslots.len();
        let mg = multigrid::Multigrid::new(&sys, n, multigrid::MULTIGRID_FROM);
        Implicit { sys, mg, cg: cg::Cg::new(n, chunks), vp: vec![0.0; 3 * n], xt: vec![0.0; 3 * n], r: vec![0.0; 3 * n], delta: vec![0.0; 3 * n] }
    }

    /// Built for a body with `m`'s vertex, spring and face counts.
    pub fn fits(&self, m: &Model) -> bool {
        self.sys.fits(m)
    }

    /// x_t = x + dt v⁺, then the system at (x_t, v⁺): (‖r‖_{M⁻¹}, its rounding level).
    fn eval(&mut self, th: &Threads, fr: &Frame) -> Result<(f64, f64), Fault> {
        for ((xt, &x), &vp) in self.xt.iter_mut().zip(fr.x).zip(&self.vp) {
            *xt = x + fr.dt * vp;
        }
        let e = self.sys.eval(th, fr, &self.vp, &self.xt, &mut self.r)?;
        Ok((e.res2.sqrt(), e.noise2.sqrt()))
    }

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
    /// not defined for damping or wind): its slope is the residual. At most [`LINE_MAX`] trials;
    /// the last one is kept. Returns the new (‖r‖, noise); r and the system are those of the
    /// new v⁺.
    fn line_search(&mut self, th: &Threads, fr: &Frame) -> Result<(f64, f64), Fault> {
        let slope = |me: &Self| -> f64 { me.delta.iter().zip(&me.r).map(|(d, r)| d * r).sum() };
        let s0 = slope(self);
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
        for _ in 0..LINE_MAX {
            let s = if out.is_ok() { slope(self) } else { f64::NAN };
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
        out
    }

    /// One backward-Euler step of `dt` (s): the state is replaced only on success.
    pub fn step(&mut self, th: &Threads, p: &Material, w: &WorldSettings, m: &Model, s: &mut State, dt: f64) -> Result<SolverIterations, Fault> {
        let fr = Frame { p, w, m, x: &s.x, v: &s.v, dt };
        let mut it = SolverIterations::default();
        self.vp.copy_from_slice(&s.v);
        let (r0, mut noise) = self.eval(th, &fr)?;
        let mut norm = r0;
        loop {
            if norm <= (w.tolerance * r0).max(noise) {
                break;
            }
            let rho = norm / r0;
            if it.newton >= w.newton_iterations {
                return Err(Fault::NotConverged { iterations: it.newton, residual: rho });
            }
            let eta = 0.1f64.min((rho * rho).max(0.5 * w.tolerance / rho));
            if it.newton == 0 {
                self.mg.assemble(&self.sys, m, &self.xt);
            }
            it.linear += self.cg.solve(th, &self.sys, &mut self.mg, m, &self.r, eta, &mut self.delta);
            it.newton += 1;
            // Line search along δ on φ(λ) = ‖r(v⁺_k + λ δ)‖: see `line_search`.
            (norm, noise) = self.line_search(th, &fr)?;
        }
        // Accepted: x⁺ = x + dt v⁺ (already in x_t), v⁺.
        s.x.copy_from_slice(&self.xt);
        s.v.copy_from_slice(&self.vp);
        Ok(it)
    }
}
