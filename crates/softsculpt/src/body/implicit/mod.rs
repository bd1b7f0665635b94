//! The `implicit` integrator: backward Euler on every force of the model.
//!
//!   v⁺ = v + dt M⁻¹ f(x + dt v⁺, v⁺),    x⁺ = x + dt v⁺
//!
//! solved for v⁺ by Newton iterations on the residual
//!
//!   r(v⁺) = M (v⁺ − v) − dt f(x + dt v⁺, v⁺)        (kg·m/s per coordinate)
//!
//! each Newton step δ from A δ = −r with A = M + dt D + dt² K (K, D the projected stiffness and
//! damping, `system/`) by a preconditioned conjugate gradient (`cg.rs`; block Jacobi, or a
//! multigrid V-cycle from `multigrid::MULTIGRID_FROM` vertices, or
//! `multigrid::HINGED_FROM` with the hinges on: `multigrid/`), then a
//! line search along δ ([`Implicit::line_search`]). Anchors: Baraff & Witkin 1998 (large steps in cloth simulation).
//!
//! **Convergence** (what `tolerance` means): with the mass-weighted norm
//! ‖r‖²_{M⁻¹} = Σ_i |r_i|² / m_i over the free vertices and r_0 the residual of the first guess
//! v⁺ = v (the explicit prediction's residual, −dt f(x + dt v, v)), the step is accepted when
//!
//!   ‖r_k‖_{M⁻¹} ≤ tolerance · max(‖r_0‖_{M⁻¹}, ‖dt M g‖_{M⁻¹})
//!
//! The second term, the weight's impulse over the step (dt |g| sqrt(Σ m_i)), keeps the test
//! meaningful for a body at rest under gravity: there ‖r_0‖ is only the step's small imbalance
//! (a body resting on the ground is an exact equilibrium of the solve, [`ground`]), and a
//! tolerance relative to it alone asked for 1e-3 of almost nothing: measured on the modeler's
//! 642-vertex sphere at rest, 3–11 Newton iterations per step to reach residuals of 1e-8. With
//! the floor, a step's accepted velocity error is at most `tolerance` times what gravity adds in
//! a step (1e-3 · g dt = 0.16 mm/s at 1/60 s), whatever the state. Without gravity, and for
//! self-colliding bodies, the test is relative to ‖r_0‖ alone, as before (with the floor, the
//! crushed mushroom of `tests/self_contact.rs` folded differently and had a vertex through its
//! skin after 8 s; its penalty contacts are not yet robust to that looser solve).
//!
//! or when ‖r_k‖ is down to the rounding of the terms summed into it (16 ε times their
//! magnitudes: a body at equilibrium has r_0 ≈ 0 and nothing left to reduce). ‖r‖_{M⁻¹} is a
//! velocity error weighted by mass, so heavy and light vertices count by their momentum. The
//! linear solve of Newton iteration k stops at the relative accuracy
//! η_k = min(0.1, max(ρ_k², tolerance / (2 ρ_k))), ρ_k = ‖r_k‖/‖r_0‖: loose while far away,
//! just tight enough near the end (an Eisenstat–Walker-like forcing term).
//!
//! **Warm start** ([`Implicit::warm_start`]): Newton starts from the last step's velocity change
//! when that lowers the residual (nearly the answer at a quasi-static state), tried only where
//! the residual at v⁺ = v is more than [`WARM_FROM`] times the threshold; r_0 above is still
//! the residual at v⁺ = v. **Conjugate directions** ([`Implicit::conjugate`]) after
//! [`CONJUGATE_FROM`] Newton iterations, against the zig-zag of a wrinkling membrane.
//!
//! **Kept coarse levels** (`keep.rs`): a step starting within [`keep::KEEP_WITHIN`] times the
//! threshold reuses the multigrid levels of an earlier step made for the same problem; where they
//! were assembled is state, so a restored world assembles the same ones.
//!
//! **Momentum** ([`Implicit::keep_momentum`]): a free body's accepted step is moved by the one
//! uniform velocity that takes the net impulse out of its residual, so its momentum follows
//! backward Euler's exactly at any tolerance.
//!
//! **The ground** ([`ground`]): vertices resting on it at the step's start are constrained in
//! the solve (v⁺_y = 0), and so are those landing in the step (predicted from the step's start
//! or put below the plane by an early iterate: v⁺_y = (h − y) / dt, they end the step on it);
//! each is released where the plane would have to pull it; a body at rest on the ground is an
//! equilibrium of the step.
//!
//! At most `newton_iterations` Newton iterations (world setting) and [`cg::LINEAR_MAX`] linear
//! iterations per Newton iteration; a step that has not converged is refused with the state
//! untouched (the world reports the time and suggests a smaller dt). The iterations of the last
//! step are kept for the statistics (`solver_iterations`).
//!
//! All scratch is allocated on the first implicit step of a body and reused.

mod adjacency;
mod aggregate;
mod blocks;
mod cg;
mod ground;
mod keep;
mod multigrid;
mod newton;
mod potential;
mod system;

pub use keep::Kept;
pub use potential::LineStats;

use super::forces::Fault;
use super::{Material, Model, State};
use crate::par::Threads;
use crate::settings::WorldSettings;
use system::{Frame, System};

/// Iterations of the last step: Newton iterations and conjugate-gradient iterations (summed
/// over the Newton iterations, over every attempt). Zero for the explicit integrators.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct SolverIterations {
    pub newton: u32,
    pub linear: u32,
    /// What of the hinges the step let go of to finish ([`Relaxed`]; only where the world's
    /// `relax` allows it).
    pub relaxed: Relaxed,
    /// The relative residual ‖r‖/‖r_0‖ (mass-weighted, see the module doc) the step was accepted
    /// at: at most `tolerance` for a converged step (or the rounding level), at most the
    /// deadline's `accept` for one stopped early. 0 for the explicit integrators.
    pub residual: f64,
    /// The step was accepted short of the tolerance because its deadline passed
    /// (`WorldSettings::deadline`, the anytime step).
    pub early: bool,
}

/// What of the model's bending a step let go of to finish, when the world allows a relaxed
/// retry (`WorldSettings::relax`, the modeler's steps; only for a step one of whose faithful
/// iterates crushed a face): `No`, the model as it is; `Crushed`, the hinges of faces squashed
/// below `hinges::FADE_BELOW` of their frozen height over the hinge's edge (where the model
/// fades them, `hinges::bend`; cut at once, so from 0.5 down a hinge loses even a nearly
/// unfaded force) give nothing for this step; `Unbent`, no hinge at all for this step
/// (rigidity D taken as 0; bending springs stay).
///
/// Why: the strongest grab crushes faces against their edges under hinges bent by ~2 rad
/// (BENCHMARKS.md, the 20th–22nd sessions). There ∇θ grows as 1/h and the curvature the
/// Gauss–Newton matrix drops, D w (θ − θ̄) ∇²θ, as 1/h²; Newton's directions overshoot along
/// those vertices and the step is refused even at dt/64, so the modeler paused. Replayed
/// (BENCHMARKS.md, 23rd session): the 8 bunny steps that paused main all finish `Crushed`
/// (2–32 Newton iterations); of two mushroom steps, one `Crushed`, one only `Unbent`. Dropping
/// those hinges for one step of ≤ 1/60 s changes the shape by that step's bending impulse only
/// (a force with no net force or moment), while a refusal stops the user's work.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum Relaxed {
    #[default]
    No,
    Crushed,
    Unbent,
}

impl Relaxed {
    /// 0, 1, 2 (for the bindings).
    pub fn level(self) -> u32 {
        self as u32
    }
}

/// Most trials of the line search after the full step.
const LINE_MAX: u32 = 6;
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
const OVERSHOOT: f64 = 0.5;
/// Newton iterations of plain Newton directions before conjugate ones ([`Implicit::conjugate`];
/// measured: 4 and 8 both rescue the stalled step, 8 costs nothing on fast steps).
const CONJUGATE_FROM: u32 = 8;
/// The fraction of the last step's velocity change the warm start takes. With all of it, each
/// step's within-tolerance error repeats the last one's and no longer damps out: measured on the
/// modeler's 2,562-vertex sphere at rest at tolerance 1e-3, 1.1e-4 J of kinetic energy kept
/// (a steady breathing) against 3.3e-6 J cold; with 0.9, 7e-7 J, at 884 Newton iterations in
/// 240 steps (1.0: 611, 0.8: 1061, cold: 3681). Under-relaxed, the guess errs towards v⁺ = v,
/// as a cold start does, which damps.
const WARM_FRACTION: f64 = 0.9;
/// The warm start is tried only where the residual at v⁺ = v is more than this many times the
/// convergence threshold. Closer than that one Newton iteration from v⁺ = v finishes the step,
/// and at a body coming to rest the last step's Δv is mostly noise: measured on the modeler's
/// 10,242-vertex sphere landing (8 s), of 106 warm starts tried at ratios 1–2, 92 were rejected
/// (each costing two evaluations: the warm one and the cold one again) and 6 converged at once;
/// at 2–5, 27 of 34 were taken.
const WARM_FROM: f64 = 2.0;

/// ‖dt M g‖_{M⁻¹} = dt |g| sqrt(Σ m_i) over the free vertices (kg^½·m/s): the weight's impulse
/// over one step, the floor of the convergence test's reference.
fn weight_impulse(fr: &Frame) -> f64 {
    let g = fr.w.gravity.abs();
    if g == 0.0 {
        return 0.0;
    }
    let free: f64 = fr.m.mass.iter().zip(&fr.m.inv_mass).filter(|(_, &im)| im != 0.0).map(|(&m, _)| m).sum();
    fr.dt * g * free.sqrt()
}

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
    /// The last Newton step and line-search direction (`conjugate`).
    zprev: Vec<f64>,
    pprev: Vec<f64>,
    /// The last `newton` started from the warm start (not from v⁺ = v).
    warmed: bool,
    /// The last `newton` held a vertex on the ground at some iteration (if not, the retry
    /// without the ground's vertices would repeat it: `step`).
    held_any: bool,
    /// What the multigrid's coarse levels were assembled from (`keep.rs`); None: unknown.
    built: Option<Kept>,
    /// The coarse levels were assembled afresh in this step (the accepted step keeps them).
    assembled: bool,
    /// This step's [`keep::inputs`], once computed.
    inputs: Option<u64>,
    /// Some evaluation of this step met a hinge with a crushed face (`System::crushed`).
    crushed: bool,
    /// The relative residual the last successful `newton` stopped at, and whether its deadline
    /// stopped it (`WorldSettings::deadline`).
    reached: (f64, bool),
    /// What the line search's potential holds fixed (`potential.rs`).
    frozen: potential::Frozen,
    /// How the line searches ended (`potential::LineStats`).
    pub lines: LineStats,
    /// Per line search, G at its start and where it ended and their rounding (J) (the tests).
    #[cfg(test)]
    pub trace: Vec<(f64, f64, f64)>,
}

impl Implicit {
    pub fn new(m: &Model) -> Self {
        let n = m.mass.len();
        let sys = System::new(m);
        let chunks = sys.vslots.len();
        let mut mg = multigrid::Multigrid::new(&sys, n, multigrid::HINGED_FROM);
        mg.unhinged_from = multigrid::MULTIGRID_FROM;
        Implicit { sys, mg, cg: cg::Cg::new(n, chunks), vp: vec![0.0; 3 * n], xt: vec![0.0; 3 * n], r: vec![0.0; 3 * n], delta: vec![0.0; 3 * n], zprev: vec![0.0; 3 * n], pprev: vec![0.0; 3 * n], warmed: false, held_any: false, built: None, assembled: false, inputs: None, crushed: false, reached: (0.0, false), frozen: Default::default(), lines: LineStats::default(), #[cfg(test)] trace: Vec::new() }
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
        let e = self.sys.eval(th, fr, &self.vp, &self.xt, &mut self.r);
        self.crushed |= self.sys.crushed;
        let e = e?;
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
    fn line_search(&mut self, th: &Threads, fr: &Frame) -> Result<(f64, f64), Fault> {
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
    fn conjugate(&mut self, k: u32, gyprev: f64) -> f64 {
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
    fn warm_start(&mut self, th: &Threads, fr: &Frame, warm: &[f64], scale: f64, cold: (f64, f64)) -> Result<(f64, f64), Fault> {
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

    /// This step's model inputs to the coarse levels' assembly (`keep::inputs`), computed once.
    fn inputs(&mut self, fr: &Frame) -> u64 {
        *self.inputs.get_or_insert_with(|| keep::inputs(fr))
    }

    /// The coarse levels afresh from the system at the current iterate (`self.xt`), recorded as
    /// what the scratch levels now are — except with target springs, whose stiffness is in the
    /// system's diagonal (`system/`) but not in [`Kept`]: levels assembled with them are
    /// never kept (`built` None: a later resting step assembles from the state's [`Kept`]
    /// again, as a restored world would).
    fn assemble(&mut self, fr: &Frame) {
        self.mg.assemble(&self.sys, fr.m, &self.xt);
        if !self.mg.cycles(&self.sys, fr.m.mass.len()) {
            return;
        }
        if fr.m.targets.active() || fr.relax != Relaxed::No {
            self.built = None;
            return;
        }
        let inputs = self.inputs(fr);
        let b = self.built.get_or_insert_with(Kept::default);
        b.xt.clone_from(&self.xt);
        b.held.clone_from(&self.sys.ground.list);
        (b.absolute, b.inputs) = (self.sys.absolute, inputs);
        self.assembled = true;
    }

    /// Whether this solve's problem is the one `kept` was assembled for (`keep.rs`, "Rule").
    fn keeps(&mut self, fr: &Frame, kept: &Kept) -> bool {
        let (p, m) = (fr.p, fr.m);
        kept.xt.len() == self.xt.len()
            && self.mg.cycles(&self.sys, m.mass.len())
            && !p.self_collision
            && !m.targets.active()
            && fr.relax == Relaxed::No
            && kept.absolute == self.sys.absolute
            && kept.held == self.sys.ground.list
            && kept.inputs == self.inputs(fr)
    }

    /// The coarse levels again from `kept` (a world whose scratch levels are not its state's:
    /// restored, undone, cloned): the system evaluated at `kept.xt`, then assembled (`keeps`
    /// has checked that the held vertices and the projection are this solve's, so only x_t
    /// differs). Leaves the system's coefficients those of `kept.xt`: the caller evaluates the
    /// current iterate again. On an error (not expected: that state was evaluated before) the
    /// levels are unknown (`built` None) and the caller assembles afresh.
    fn rebuild(&mut self, th: &Threads, fr: &Frame, kept: &Kept) -> Result<(), Fault> {
        let mut b = self.built.take().unwrap_or_default();
        self.sys.eval(th, fr, &self.vp, &kept.xt, &mut self.zprev)?;
        self.mg.assemble(&self.sys, fr.m, &kept.xt);
        b.clone_from(kept);
        self.built = Some(b);
        Ok(())
    }

    /// The accepted v⁺ moved by one uniform velocity u that takes the net impulse out of its
    /// residual (Σ_i r_i = 0), where the body's forces are those of a free body: no pinned
    /// vertex, no target springs, no vertex held by the ground, no wind.
    ///
    /// Why: backward Euler conserves momentum exactly (Σ_i r_i = Σ m_i Δv_i − dt F_ext with
    /// the internal forces summing to zero), but an accepted step only has ‖r‖ within the
    /// tolerance, and whatever net impulse that residual carries is momentum gained or lost:
    /// how much depends on the inexact linear solves, not on the physics (measured at the
    /// modeler's 1e-3: 5.1e-5 kg·m/s in 30 steps of a swirling ball, `tests/implicit.rs`; a
    /// looser forcing term drifted 4.4e-10 of Σ m|v| at 1e-8: BENCHMARKS.md). Among the
    /// velocities within the tolerance this picks the one that conserves it.
    ///
    /// Derivation: the internal forces (springs and their damping, bending, hinges, gas, face
    /// pressures, self-contacts) depend only on differences of positions and velocities, so
    /// they do not change when every x_t moves by dt u and every v⁺ by u; gravity, user forces
    /// and kept loads are constant; the viscous damping −c m v changes by −c m u. So
    /// r_i(v⁺ + u) = r_i(v⁺) + (1 + dt c) m_i u exactly, and u = −Σ r_i / ((1 + dt c) Σ m_i)
    /// gives Σ r_i = 0. It also only lowers ‖r‖_{M⁻¹}: r'_i = r_i − m_i Σ r / Σ m (the (1 + dt c)
    /// cancels), the mass-weighted mean projected out, ‖r'‖² = ‖r‖² − |Σ r_i|² / Σ m_i, so the
    /// step stays within the tolerance.
    /// Pins, targets and a held ground take impulse from outside (momentum is not conserved
    /// there, and the correction would not be exact); the wind's force depends on v⁺ itself.
    fn keep_momentum(&mut self, fr: &Frame) {
        let (w, m) = (fr.w, fr.m);
        let wind = w.wind_drag > 0.0 && w.wind != [0.0; 3];
        if wind || m.targets.active() || self.sys.ground.active() || m.inv_mass.contains(&0.0) {
            return;
        }
        let mut net = [0.0; 3];
        for r in self.r.chunks_exact(3) {
            for d in 0..3 {
                net[d] += r[d];
            }
        }
        let mass: f64 = m.mass.iter().sum();
        let u = net.map(|s| -s / ((1.0 + fr.dt * fr.p.damping) * mass));
        for (vp, xt) in self.vp.chunks_exact_mut(3).zip(self.xt.chunks_exact_mut(3)) {
            for d in 0..3 {
                vp[d] += u[d];
                xt[d] += fr.dt * u[d];
            }
        }
    }

    /// One backward-Euler step of `dt` (s): the state is replaced only on success.
    pub fn step(&mut self, th: &Threads, p: &Material, w: &WorldSettings, m: &Model, s: &mut State, dt: f64) -> Result<SolverIterations, Fault> {
        let fr = Frame { p, w, m, x: &s.x, v: &s.v, dt, relax: Relaxed::No };
        let mut it = SolverIterations::default();
        let warm = (s.warm.len() == s.v.len() && s.warm_dt > 0.0).then(|| (&s.warm[..], dt / s.warm_dt));
        // A warm-started solve that fails (the guess can lead Newton on this non-convex problem
        // to a slower path than v⁺ = v does) is redone cold, from v⁺ = v, with the whole
        // iteration cap again: at any state, a step that converged without the warm start still
        // does.
        // And a cold solve that fails with the ground's vertices held (`ground.rs`) is redone
        // without them (the plane then only the after-step projection, as before it was part of
        // the solve).
        // (Only if the warm start was taken: otherwise the cold solve was the one that failed;
        // and only if the failed solve held a vertex on the ground: otherwise it was already
        // the solve without them.)
        (self.assembled, self.inputs, self.crushed) = (false, None, false);
        let kept = &s.kept;
        let mut solved = match self.newton(th, &fr, (warm, kept), true, &mut it) {
            Err(Fault::Interrupted) => return Err(Fault::Interrupted),
            Err(_) if self.warmed => self.newton(th, &fr, (None, kept), true, &mut it),
            done => done,
        };
        if matches!(solved, Err(Fault::Interrupted)) {
            return solved.map(|()| it);
        }
        if solved.is_err() && w.ground.is_some() && self.held_any {
            solved = self.newton(th, &fr, (None, kept), false, &mut it);
        }
        // Where the caller allows it (`WorldSettings::relax`), the faithful solves did not
        // converge and one of their iterates crushed a face under a hinge: the step again, cold,
        // with the crushed faces' hinges let go, then with none ([`Relaxed`]). The faithful
        // model is tried first, always; the iterations record what was let go. If neither
        // converges, the faithful solve's refusal is what the caller hears (it may split).
        if matches!(solved, Err(Fault::NotConverged { .. })) && w.relax && self.crushed && p.rigidity > 0.0 {
            for relax in [Relaxed::Crushed, Relaxed::Unbent] {
                match self.newton(th, &Frame { relax, ..fr }, (None, kept), true, &mut it) {
                    Ok(()) => {
                        (solved, it.relaxed) = (Ok(()), relax);
                        break;
                    }
                    Err(Fault::Interrupted) => return Err(Fault::Interrupted),
                    Err(_) => {}
                }
            }
        }
        solved?;
        (it.residual, it.early) = self.reached;
        if self.assembled {
            if let Some(b) = &self.built {
                s.kept.clone_from(b);
            }
        }
        self.keep_momentum(&fr);
        // Accepted: x⁺ = x + dt v⁺ (already in x_t), v⁺.
        s.warm.resize(s.v.len(), 0.0);
        for ((d, &vp), &v) in s.warm.iter_mut().zip(&self.vp).zip(&s.v) {
            *d = vp - v;
        }
        s.warm_dt = dt;
        if let Some(g) = w.ground {
            // Friction, then the vertices that landed in the step come to rest on the plane.
            self.sys.ground.friction(m, g.friction, &mut self.vp);
            self.sys.ground.land(g.height, &mut self.xt, &mut self.vp);
        }
        s.x.copy_from_slice(&self.xt);
        s.v.copy_from_slice(&self.vp);
        Ok(it)
    }
}
