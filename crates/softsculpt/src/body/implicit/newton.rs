//! The Newton iterations of one backward-Euler solve ([`Implicit::newton`]), as stages: the
//! start (the ground's constraints, the first residual and its reference, the warm start),
//! then per iteration the ground's set updated (vertices released, vertices added), the
//! verdict (converged, accepted at a deadline, refused), the coarse levels brought up to date,
//! and one Newton step (linear solve, conjugate direction, line search). The loop's state is
//! [`Solve`]; the maths is in the module doc of `mod.rs`.

use super::search::WARM_FROM;
use super::{cg, ground, keep, weight_impulse, Implicit, Kept, SolverIterations};
use super::super::forces::Fault;
use super::system::Frame;
use crate::par::Threads;
use crate::settings::{Deadline, Ground};

/// The state of one Newton solve between its iterations.
struct Solve {
    /// The convergence test's reference ‖r_0‖_{M⁻¹} (at least the weight's impulse, see the
    /// module doc of `mod.rs`).
    r0: f64,
    /// ‖r_k‖_{M⁻¹} of the current iterate and its rounding level.
    norm: f64,
    noise: f64,
    /// Newton iterations so far.
    k: u32,
    /// −r·z of the last Newton step (`Implicit::conjugate`); 0: the next one is plain Newton.
    gyprev: f64,
    /// The iteration at which the ground last released vertices, and last added some.
    released: Option<u32>,
    added: Option<u32>,
    /// The coarse matrices need assembling (`multigrid/`): at the first V-cycle of this
    /// solve and after the matrices change (ground vertices released, compressed springs
    /// switched to the absolute value: a stale coarse level mis-preconditions the
    /// conjugate gradient; measured on the 10,242-vertex sphere at k = 500 landing, 205,797
    /// CG iterations in 60 steps with the first iteration's coarse levels, 6,733 with these;
    /// 8,527 with the held vertices' F A F as well, on another Newton path: BENCHMARKS.md).
    stale: bool,
    /// Nearly at rest: this solve's first assembly may be the kept one (`keep.rs`).
    may_keep: bool,
    /// The last linear solve's fine products (the blocks' rule, `Cg::solve`).
    products_last: u32,
    /// The lowest relative residual so far and the iteration it was reached at (the stall
    /// test, `WorldSettings::give_up`); from scratch when the ground's set changes (another
    /// problem, another residual).
    best: (f64, u32),
}

impl Solve {
    /// Converged: ‖r_k‖ within the tolerance of the reference, or down to its rounding.
    fn converged(&self, tolerance: f64) -> bool {
        self.norm <= (tolerance * self.r0).max(self.noise)
    }

    /// The ground's set changed at iteration k: another problem, so another residual (the
    /// stall test from scratch) and stale coarse levels.
    fn ground_changed(&mut self) {
        self.best = (f64::INFINITY, self.k);
        self.stale = true;
    }
}

impl Implicit {
    /// Newton iterations from v⁺ = v, or from the warm start `warm` (Δv_w, dt / dt_w) if that
    /// has the smaller residual, until converged; iterations added to `it`. On success v⁺ is in
    /// `vp` and x + dt v⁺ in `xt`.
    pub(super) fn newton(&mut self, th: &Threads, fr: &Frame, (warm, kept): (Option<(&[f64], f64)>, &Kept), held: bool, it: &mut SolverIterations) -> Result<(), Fault> {
        let w = fr.w;
        // The ground's constraints from the step's start (`ground.rs`: the vertices resting on
        // it and those predicted to land in the step), their velocities in v⁺ (`held`; not for
        // self-colliding bodies: `ground.rs`).
        let ground = if fr.p.self_collision || !held { None } else { w.ground.as_ref() };
        let mut st = self.start_solve(th, fr, warm, ground)?;
        loop {
            if w.interrupt.is_some_and(|i| i.asked()) {
                return Err(Fault::Interrupted);
            }
            let converged = st.converged(w.tolerance);
            if self.release_ground(th, fr, &mut st, converged)? || self.add_ground(th, fr, ground, &mut st, converged)? {
                continue;
            }
            if converged {
                self.reached = (if st.r0 > 0.0 { st.norm / st.r0 } else { 0.0 }, false);
                return Ok(());
            }
            let rho = st.norm / st.r0;
            // The anytime step (`WorldSettings::deadline`): past the deadline, after at least
            // one Newton iteration, an iterate within `accept` is the step.
            let late = w.deadline.filter(|d| d.passed());
            if let Some(d) = late {
                if st.k >= 1 && rho <= d.accept {
                    self.reached = (rho, true);
                    return Ok(());
                }
            }
            self.refuse(fr, &mut st, rho)?;
            let eta = 0.1f64.min((rho * rho).max(0.5 * w.tolerance / rho));
            if st.stale {
                self.refresh_coarse(th, fr, kept, &mut st)?;
            }
            self.newton_step(th, fr, &mut st, eta, late, it)?;
        }
    }

    /// The start of a solve: the ground's constraints found (`ground`: None, none held), v⁺ = v
    /// (the held vertices' prescribed), its residual and the reference, then the warm start
    /// where it is worth trying.
    fn start_solve(&mut self, th: &Threads, fr: &Frame, warm: Option<(&[f64], f64)>, ground: Option<&Ground>) -> Result<Solve, Fault> {
        let w = fr.w;
        self.sys.ground.find(fr.m, ground, fr.x, fr.v, fr.dt);
        self.sys.absolute = false;
        self.warmed = false;
        self.held_any = self.sys.ground.active();
        self.vp.copy_from_slice(fr.v);
        self.sys.ground.prescribe(&mut self.vp);
        let (mut r0, mut noise) = self.eval(th, fr)?;
        let mut norm = r0;
        // The reference is at least the weight's impulse over the step (see the module doc; not
        // for self-colliding bodies, whose contacts keep the tolerance relative to r_0 alone).
        if !fr.p.self_collision {
            r0 = r0.max(weight_impulse(fr));
        }
        // Nearly at rest: this solve's first assembly may be the kept one (`keep.rs`).
        let may_keep = norm <= keep::KEEP_WITHIN * (w.tolerance * r0).max(noise);
        if let Some((dv, scale)) = warm {
            if norm > WARM_FROM * (w.tolerance * r0).max(noise) {
                (norm, noise) = self.warm_start(th, fr, dv, scale, (norm, noise))?;
            }
        }
        Ok(Solve { r0, norm, noise, k: 0, gyprev: 0.0, released: None, added: None, stale: true, may_keep, products_last: 0, best: (f64::INFINITY, 0) })
    }

    /// Vertices the ground would have to pull down are let go for the rest of the step
    /// (the set only shrinks: no cycling), at convergence and at iterations 1, 2, 3, 4,
    /// 8, 16, … (`ground::release_due`). True if some were (the iterate evaluated again).
    fn release_ground(&mut self, th: &Threads, fr: &Frame, st: &mut Solve, converged: bool) -> Result<bool, Fault> {
        let k = st.k;
        if (converged || ground::release_due(k)) && st.released != Some(k) && self.sys.ground.active() && self.sys.ground.release() {
            st.released = Some(k);
            st.ground_changed();
            (st.norm, st.noise) = self.eval(th, fr)?;
            return Ok(true);
        }
        Ok(false)
    }

    /// Vertices the iterate puts below the plane are taken into the set, each once in a
    /// step (no cycling), at iterations 1, 2, 4, …, `ground::ADD_UNTIL` (`ground.rs`). True if
    /// some were (their velocities prescribed, the iterate evaluated again).
    fn add_ground(&mut self, th: &Threads, fr: &Frame, ground: Option<&Ground>, st: &mut Solve, converged: bool) -> Result<bool, Fault> {
        let k = st.k;
        if let (Some(g), true) = (ground, !converged && (1..=ground::ADD_UNTIL).contains(&k) && k.is_power_of_two() && st.added != Some(k)) {
            st.added = Some(k);
            if self.sys.ground.add(fr.m, g, fr.dt, fr.x, &self.xt) {
                self.held_any = true;
                self.sys.ground.prescribe(&mut self.vp);
                // The last direction moved the new vertices' y freely: the next one is a
                // plain Newton step (`conjugate`), so their prescribed v⁺_y stays.
                st.gyprev = 0.0;
                st.ground_changed();
                (st.norm, st.noise) = self.eval(th, fr)?;
                return Ok(true);
            }
        }
        Ok(false)
    }

    /// The solve refused (not converged) at relative residual `rho`: a held attempt stalled,
    /// the iteration cap, or given up early; else the lowest residual so far recorded.
    fn refuse(&self, fr: &Frame, st: &mut Solve, rho: f64) -> Result<(), Fault> {
        let (w, k) = (fr.w, st.k);
        // A held attempt stalled this long is redone from v⁺ = v without the ground
        // (`step`; `ground.rs`).
        if k == ground::GIVE_UP && self.sys.ground.active() {
            return Err(Fault::NotConverged { iterations: k, residual: rho });
        }
        if k >= w.newton_iterations {
            return Err(Fault::NotConverged { iterations: k, residual: rho });
        }
        // Given up early (a caller that splits refused steps asks for this: `GiveUp`):
        // stalled, no new lowest residual for `stalled` iterations, or `most` iterations in
        // all. Measured on the modeler's mushroom subdivided twice and grabbed (5,762
        // vertices, BENCHMARKS.md): a step that buckles (the mass term m/dt² no longer
        // outweighs the negative stiffness along the line search's direction: its slope
        // steepens as it goes) got to a relative residual of 1e-3 in 3 iterations, was
        // thrown to 2–50 by the line search's extrapolation, wandered back to ~1e-2 and
        // stayed there until the cap — in each of the step's attempts (warm, cold, and
        // without the ground if it held vertices). Not at the caller's last split
        // (`World::advance`, `world/advance.rs`): there a slow step that converges beats a refusal.
        if rho < st.best.0 {
            st.best = (rho, k);
        }
        if w.give_up.is_some_and(|g| k - st.best.1 >= g.stalled || k >= g.most) {
            return Err(Fault::NotConverged { iterations: k, residual: rho });
        }
        Ok(())
    }

    /// The coarse levels up to date for the current iterate: the kept ones (`keep.rs`) where
    /// this solve may keep them, else assembled afresh.
    fn refresh_coarse(&mut self, th: &Threads, fr: &Frame, kept: &Kept, st: &mut Solve) -> Result<(), Fault> {
        if st.may_keep && self.keeps(fr, kept) {
            if !self.built.as_ref().is_some_and(|b| b.same(kept)) {
                let rebuilt = self.rebuild(th, fr, kept).is_ok();
                // The current iterate's system again (the same bits as before).
                self.eval(th, fr)?;
                if !rebuilt {
                    self.assemble(fr);
                }
            }
        } else {
            self.assemble(fr);
        }
        (st.stale, st.may_keep) = (false, false);
        Ok(())
    }

    /// One Newton iteration: δ from A δ = −r to the relative accuracy `eta`, made conjugate
    /// (`conjugate`), then the line search along it (`late`: the deadline has passed).
    fn newton_step(&mut self, th: &Threads, fr: &Frame, st: &mut Solve, eta: f64, late: Option<Deadline>, it: &mut SolverIterations) -> Result<(), Fault> {
        let w = fr.w;
        // The products' blocks (hinged bodies, `blocks.rs`) from the start of the solve if
        // this Newton solve's last one was long, else once it is (`cg::BLOCKS_AFTER`).
        let upfront = st.products_last >= cg::BLOCKS_AFTER;
        // A linear solve started before the deadline stops when it passes (after one
        // iteration: still a descent direction); one started after it runs to η, since
        // the iterate was not yet good enough to accept.
        // An interrupt stops it too (the loop's next check abandons the step).
        let deadline = if late.is_none() { w.deadline } else { None };
        let stop = || deadline.is_some_and(|d| d.passed()) || w.interrupt.is_some_and(|i| i.asked());
        let (linear, products) = self.cg.solve(th, &mut self.sys, &mut self.mg, fr.m, &self.r, eta, upfront, &stop, &mut self.delta);
        (it.linear, st.products_last) = (it.linear + linear, products);
        if w.interrupt.is_some_and(|i| i.asked()) {
            return Err(Fault::Interrupted);
        }
        it.newton += 1;
        st.k += 1;
        st.gyprev = self.conjugate(st.k, st.gyprev);
        // Line search along δ on φ(λ) = ‖r(v⁺_k + λ δ)‖: see `line_search`.
        let was = self.sys.absolute;
        (st.norm, st.noise) = self.line_search(th, fr)?;
        st.stale |= self.sys.absolute != was;
        self.pprev.copy_from_slice(&self.delta);
        Ok(())
    }
}
