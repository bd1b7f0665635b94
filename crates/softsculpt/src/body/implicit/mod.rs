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
//! the residual at v⁺ = v is more than [`search::WARM_FROM`] times the threshold; r_0 above is still
//! the residual at v⁺ = v. **Conjugate directions** ([`Implicit::conjugate`]) after
//! [`search::CONJUGATE_FROM`] Newton iterations, against the zig-zag of a wrinkling membrane.
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
mod search;
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
