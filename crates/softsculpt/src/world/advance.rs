//! How time advances, once for every caller (the page, the CLI, scenes, the bindings):
//! [`World::advance`] takes a frame of simulated time under a [`Budget`] and owns the step
//! count, the split of a step the implicit solver refuses, the relaxed retry, the anytime
//! deadline and the explicit integrators' stable step ([`World::stable_dt`]).
//!
//! - **Converge** ([`Budget::converge`], the CLI's and scenes' default): every step to the
//!   world's `tolerance`; a refused step is the error it always was (or split, if the budget
//!   allows splits).
//! - **Real time** ([`Budget::real_time`], the modeler): the frame's implicit solves share a
//!   wall-clock budget. Step i of n gets the deadline t₀ + seconds (i + 1) / n
//!   (`WorldSettings::deadline`): past it a step is accepted at its current iterate if that is
//!   within `min_accuracy` (the anytime step, `body/implicit/mod.rs`). Steps run while the
//!   budget lasts (at least one): the rest of the frame is not simulated (slow motion, told by
//!   [`Advance::simulated`]).

use super::{GiveUp, Integrator, StepError, World};
use crate::error::SimError;

/// The relative residual ‖r‖/‖r_0‖ a real-time step is accepted at once its deadline passed,
/// by default: the step's forces are then at least 90 % accounted for in its velocity change
/// (the explicit prediction v⁺ = v has ρ = 1).
pub const MIN_ACCURACY: f64 = 0.1;

/// Halvings of a refused implicit step a real-time budget allows by default (dt/8), as the
/// modeler always split.
pub const SPLITS: u32 = 3;

/// A split step's Newton solve gives up after this many iterations without a new lowest
/// residual, or [`GIVE_UP_MOST`] in all, and is split again — except at the last split, where
/// a slow step that converges beats a refusal. Measured on the modeler's mushroom subdivided
/// twice and grabbed with mirror X (BENCHMARKS.md, "A step that will not converge, found out at
/// once"): 1 s of pulling took 50.6 s of wall time with the cap alone, 23–26 s giving up after
/// 8–24 stalled iterations.
pub const GIVE_UP_STALLED: u32 = 12;
pub const GIVE_UP_MOST: u32 = 48;

/// A real-time budget: the wall-clock time a frame's solves may take.
#[derive(Debug, Clone, Copy)]
pub struct RealTime {
    /// Wall-clock seconds for the frame's solves (> 0).
    pub seconds: f64,
    /// The relative residual a step stopped by its deadline is accepted at (> 0).
    pub min_accuracy: f64,
    /// The clock (s): [`wall_clock`] natively; the binding's own in WebAssembly.
    pub now: fn() -> f64,
}

/// How much work a frame may take (see the module documentation).
#[derive(Debug, Clone, Copy)]
pub struct Budget {
    /// None: converge every step. Some: share a wall-clock budget.
    pub real_time: Option<RealTime>,
    /// How many times a refused implicit step is halved before the refusal stands (0: never).
    pub splits: u32,
    /// A step no solve of the model finishes is retried with hinges let go
    /// (`WorldSettings::relax`) before it is refused or split.
    pub relax: bool,
    /// A failed frame goes back to the last sound state, not only to the failing step's start
    /// (`world/rewind.rs`; the modeler): the world keeps rewind points as it advances.
    pub rewind: bool,
}

impl Budget {
    /// Every step to the tolerance, a refused step an error (the CLI, scenes).
    pub fn converge() -> Self {
        Budget { real_time: None, splits: 0, relax: false, rewind: false }
    }

    /// `seconds` of wall-clock time per frame on the clock `now`, [`MIN_ACCURACY`], refused
    /// steps split [`SPLITS`] times and relaxed first (the modeler, which also sets
    /// `rewind`).
    pub fn real_time(seconds: f64, now: fn() -> f64) -> Self {
        Budget { real_time: Some(RealTime { seconds, min_accuracy: MIN_ACCURACY, now }), splits: SPLITS, relax: true, rewind: false }
    }
}

/// What a frame did.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Advance {
    /// Steps taken (a split step counts its pieces).
    pub steps: u64,
    /// Steps that had to be split.
    pub splits: u32,
    /// Simulated seconds advanced: the frame's, unless a real-time budget ran out before its
    /// last steps.
    pub simulated: f64,
    /// The largest relative residual any implicit step of the frame was accepted at (0 for the
    /// explicit integrators): the frame's accuracy.
    pub residual: f64,
    /// Implicit steps accepted short of the tolerance at their deadline.
    pub early: u32,
    /// Wall-clock seconds the frame took (real-time budgets only; else 0).
    pub wall: f64,
}

/// Seconds since the first call (a monotonic clock) for [`Budget::real_time`].
#[cfg(not(target_arch = "wasm32"))]
pub fn wall_clock() -> f64 {
    use std::sync::OnceLock;
    use std::time::Instant;
    static START: OnceLock<Instant> = OnceLock::new();
    START.get_or_init(Instant::now).elapsed().as_secs_f64()
}

impl World {
    /// Advance by `frame_dt` simulated seconds (> 0) in steps of the world's dt (the nearest
    /// whole number of them, at least one) under `budget`. Each step is all or nothing
    /// ([`World::step_n`]); on an error the world is as after the last step taken, and the
    /// caller's settings (dt, deadline, relax, give-up) are as they were — or, under a budget
    /// that rewinds, as at the last sound state (`world/rewind.rs`, [`StepError::rewound_to`]).
    /// A step abandoned for a waiting command ([`SimError::Interrupted`]) is never rewound.
    pub fn advance(&mut self, frame_dt: f64, budget: &Budget) -> Result<Advance, StepError> {
        if budget.rewind {
            self.rewind_before(budget);
        }
        let out = self.advance_frame(frame_dt, budget);
        match out {
            Ok(a) if budget.rewind => {
                self.rewind_after(budget, a.simulated);
                Ok(a)
            }
            Err(mut e) if budget.rewind && !matches!(e.error, SimError::Interrupted { .. }) => {
                e.rewound_to = self.rewind_to_good();
                Err(e)
            }
            out => out,
        }
    }

    fn advance_frame(&mut self, frame_dt: f64, budget: &Budget) -> Result<Advance, StepError> {
        let dt = self.settings.dt;
        let n = ((frame_dt / dt).round() as u64).max(1);
        let saved = (self.settings.deadline, self.settings.relax, self.settings.give_up);
        self.settings.relax = budget.relax;
        let mut out = Advance::default();
        let t0 = budget.real_time.map(|r| (r.now)());
        let result = match self.settings.integrator {
            Integrator::Implicit => self.advance_implicit(n, budget, t0, &mut out),
            _ => self.advance_explicit(n, budget, t0, &mut out),
        };
        (self.settings.deadline, self.settings.relax, self.settings.give_up) = saved;
        if let (Some(r), Some(t0)) = (budget.real_time, t0) {
            out.wall = (r.now)() - t0;
        }
        result.map(|()| out)
    }

    /// `n` implicit steps, each with its share of a real-time budget's deadline; under a
    /// real-time budget no step starts once the budget is spent (at least one runs), so a frame
    /// ends within the budget and one Newton iteration (slow motion, told by `simulated`).
    fn advance_implicit(&mut self, n: u64, budget: &Budget, t0: Option<f64>, out: &mut Advance) -> Result<(), StepError> {
        let dt = self.settings.dt;
        for i in 0..n {
            if let (Some(r), Some(t0)) = (budget.real_time, t0) {
                if i > 0 && (r.now)() - t0 >= r.seconds {
                    break;
                }
                let at = t0 + r.seconds * (i + 1) as f64 / n as f64;
                self.settings.deadline = Some(super::Deadline { now: r.now, at, accept: r.min_accuracy });
            }
            self.step_split(dt, budget.splits, out)?;
        }
        Ok(())
    }

    /// One step of `h` seconds; if the solver refuses it and `depth` > 0, two of h/2 instead
    /// (each split again as needed). Only at depth 0 does the solve run to the Newton cap
    /// (before: [`GiveUp`] after [`GIVE_UP_STALLED`] stalled or [`GIVE_UP_MOST`] iterations).
    fn step_split(&mut self, h: f64, depth: u32, out: &mut Advance) -> Result<(), StepError> {
        let dt = self.settings.dt;
        self.settings.dt = h;
        self.settings.give_up = (depth > 0).then_some(GiveUp { stalled: GIVE_UP_STALLED, most: GIVE_UP_MOST });
        let taken = self.step_n(1);
        self.settings.dt = dt;
        match taken {
            Ok(()) => {
                out.steps += 1;
                out.simulated += h;
                for b in &self.bodies {
                    let it = b.solver_iterations();
                    out.residual = out.residual.max(it.residual);
                    out.early += it.early as u32;
                }
                Ok(())
            }
            Err(e) if depth > 0 && matches!(e.error, SimError::NotConverged { .. }) => {
                out.splits += 1;
                self.step_split(h / 2.0, depth - 1, out)?;
                self.step_split(h / 2.0, depth - 1, out)
            }
            Err(e) => Err(e),
        }
    }

    /// `n` explicit steps: all at once under *converge*; under a real-time budget in chunks
    /// while the budget lasts (at least one step).
    fn advance_explicit(&mut self, n: u64, budget: &Budget, t0: Option<f64>, out: &mut Advance) -> Result<(), StepError> {
        let dt = self.settings.dt;
        let (Some(r), Some(t0)) = (budget.real_time, t0) else {
            self.step_n(n)?;
            (out.steps, out.simulated) = (n, n as f64 * dt);
            return Ok(());
        };
        // Chunks of about a tenth of the budget, sized by the measured cost of a step, so the
        // budget is overrun by at most about a tenth.
        let mut chunk = 1u64;
        while out.steps < n {
            let c0 = (r.now)();
            let k = chunk.min(n - out.steps);
            self.step_n(k)?;
            out.steps += k;
            let now = (r.now)();
            if now - t0 >= r.seconds {
                break;
            }
            let per = ((now - c0) / k as f64).max(1e-9);
            chunk = ((0.1 * r.seconds / per) as u64).max(1);
        }
        out.simulated = out.steps as f64 * dt;
        Ok(())
    }
}

/// Forward Euler's share of the stable step ([`World::stable_dt`]). Its amplification on an
/// undamped mode of frequency ω is √(1 + ω² dt²) > 1 at any dt: it is stable only where damping
/// outweighs that, dt ≲ 2 γ / ω² for a mode damped at rate γ, and the skin's transverse
/// (wrinkling) modes get no spring damping (it acts along the springs), only the viscous c.
/// Measured: the modeler's resting mushroom switched to Euler at the symplectic step (5e-4 s)
/// grew a mode ~8× a second from 6 s on, while at 2e-4 and 1e-4 s it stayed at rest
/// (web/test/explicit.test.ts). A quarter leaves a margin of two over that.
const EULER_SHARE: f64 = 0.25;

impl World {
    /// The largest stable time step (s) of an explicit `integrator` for every body of the world
    /// (the smallest over its bodies), a round number (1, 2 or 5 × 10ⁿ), at most 1 ms; `None`
    /// for the implicit integrator (stable at any step). For each body, with m its smallest
    /// vertex mass (kg), k + k_b its springs' stiffness (N/m) and k_h = 6.2 D / h² its hinges'
    /// (D the rigidity, h the shortest rest length: their Gauss–Newton matrix D w ∇θ ∇θᵀ bounded
    /// by Gershgorin on a near-equilateral mesh, |∇θ| ≤ 2/(√3 h), w = 2/√3, 12 hinges around a
    /// vertex: ω² ≤ 74 D / (h² m), against 12 k / m for springs), the limits are, with a safety
    /// factor of 0.3 ([`SAFETY`]): dt ≤ 0.3 · 2/ω, ω² = 12 (k + k_b + k_h) / m (a vertex's fastest mode);
    /// dt ≤ 0.3 · 2 m / (12 · 2 c_s) (the spring damping); for hinges with τ = c_s / k,
    /// dt ≤ 0.3 · 2 / (τ ω_h²), ω_h² = 12 k_h / m; forward Euler also
    /// dt ≤ max(τ / (1 + τ² ω_h² / 4), c / ω_h²) (its amplification √((1 − γ dt)² + ω² dt²),
    /// γ = (c + τ ω²) / 2), then [`EULER_SHARE`] of it all. The modeler's rule since the
    /// explicit integrators were in its panel, now in the core once.
    pub fn stable_dt(&self, integrator: Integrator) -> Option<f64> {
        if integrator == Integrator::Implicit {
            return None;
        }
        let dt = self.bodies.iter().map(|b| body_stable_dt(b, integrator, SAFETY, 1e-3)).fold(1e-3, f64::min);
        let ten = 10f64.powf(dt.log10().floor());
        Some([5.0, 2.0, 1.0].iter().map(|f| f * ten).find(|&v| v <= dt).unwrap_or(ten))
    }

    /// Step with the implicit integrator if the explicit one's step is above the model's
    /// stability bound ([`World::dt_limit`]): what a material preset tuned for the implicit
    /// integrator needs when the caller chose neither the integrator nor the step (the CLI's
    /// `simulate --preset`, the Python package's `World.from_mesh(preset=…)`). Returns the
    /// bound (s) when it switched, for the caller's note.
    pub fn implicit_if_unstable(&mut self) -> Option<f64> {
        let limit = self.dt_limit(self.settings.integrator)?;
        if self.settings.dt <= limit {
            return None;
        }
        self.settings.integrator = Integrator::Implicit;
        Some(limit)
    }

    /// The largest step (s) the explicit integrator `integrator` is linearly stable at for
    /// every body: [`World::stable_dt`]'s bounds without its safety factor (`safety` 1 in place
    /// of [`SAFETY`]), its 1 ms cap and its rounding (forward Euler keeps [`EULER_SHARE`]).
    /// None for the implicit integrator (stable at any step). Above it a run is all but sure to
    /// blow up: the command line refuses such a `--dt` unless `--force`; below it but above
    /// `stable_dt` it may still ring (the bound is for the springs' linear modes, Gershgorin's
    /// over-estimate of the fastest, not the gas or contact).
    pub fn dt_limit(&self, integrator: Integrator) -> Option<f64> {
        (integrator != Integrator::Implicit).then(|| self.bodies.iter().map(|b| body_stable_dt(b, integrator, 1.0, f64::INFINITY)).fold(f64::INFINITY, f64::min))
    }
}

/// The share of the stability bounds [`World::stable_dt`] takes (its margin for what the
/// bounds leave out: the gas, contacts, a large deformation).
const SAFETY: f64 = 0.3;

/// [`World::stable_dt`] of one body at `safety` × its bounds and at most `cap` (before forward
/// Euler's share), before rounding (s).
fn body_stable_dt(b: &crate::body::SoftBody, integrator: Integrator, safety: f64, cap: f64) -> f64 {
    let p = &b.material;
    let m = b.masses().iter().copied().fold(f64::INFINITY, f64::min);
    let h = b.rest_lengths().iter().copied().filter(|&l| l > 0.0).fold(f64::INFINITY, f64::min);
    let kh = if p.rigidity > 0.0 && h.is_finite() { 6.2 * p.rigidity / (h * h) } else { 0.0 };
    let k = p.stiffness + p.bending_stiffness + kh;
    let mut limit = cap;
    if k > 0.0 {
        limit = limit.min(safety * 2.0 / (12.0 * k / m).sqrt());
    }
    let cs = 2.0 * p.spring_damping;
    if cs > 0.0 {
        limit = limit.min(safety * 2.0 * m / (12.0 * cs));
    }
    let mut euler_limit = f64::INFINITY;
    if kh > 0.0 {
        let w2 = 12.0 * kh / m;
        let tau = if p.stiffness > 0.0 { p.spring_damping / p.stiffness } else { 0.0 };
        if tau > 0.0 {
            limit = limit.min(safety * 2.0 / (tau * w2));
        }
        let euler = (tau / (1.0 + tau * tau * w2 / 4.0)).max(p.damping / w2);
        if euler > 0.0 {
            euler_limit = euler;
        }
    }
    if integrator == Integrator::Euler {
        limit.min(euler_limit) * EULER_SHARE
    } else {
        limit
    }
}
