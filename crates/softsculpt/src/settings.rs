//! What a world imposes on every body in it, with units: gravity, wind, the ground, rigid
//! obstacles, the integrator and time step, and the contact settings. Change them freely
//! between steps (each step validates them). Defaults come from the parameter table
//! (`crate::params`).
//!
//! Below both the bodies and the world (`tests/layers.rs`): a body steps with the settings it is
//! handed, and the world owns them; `crate::world` re-exports everything here under its old
//! paths (`world::WorldSettings`, …).

use crate::error::{bad, check_positive, SimError};
use crate::obstacles::Obstacle;
use crate::params as table;
use crate::params::field::{check_fields, choice_field, number_field, Field};
use crate::params::Value;

/// Time integrator of the state (x, v).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Integrator {
    /// Explicit forward Euler: x' = x + dt v, v' = v + dt a(x, v). Order 1; gains energy.
    Euler,
    /// Explicit midpoint (RK2): slopes at (x + dt/2 v, v + dt/2 a). Order 2.
    Midpoint,
    /// Classic fourth-order Runge–Kutta on (x, v). Order 4.
    Rk4,
    /// Semi-implicit (symplectic) Euler: v' = v + dt a(x, v); x' = x + dt v'. Order 1; energy
    /// stays bounded (no drift) for conservative forces. The default.
    Symplectic,
    /// Backward (implicit) Euler: v' = v + dt M⁻¹ f(x + dt v', v'); x' = x + dt v'. Order 1;
    /// stable at any dt (it damps the modes it cannot resolve). Solved by Newton iterations with
    /// a preconditioned conjugate gradient to the world's `tolerance` (`body/implicit/`).
    Implicit,
}

impl Integrator {
    pub const NAMES: &'static [&'static str] = table::INTEGRATOR_CHOICES;
    pub fn name(self) -> &'static str {
        match self {
            Integrator::Euler => "euler",
            Integrator::Midpoint => "midpoint",
            Integrator::Rk4 => "rk4",
            Integrator::Symplectic => "symplectic",
            Integrator::Implicit => "implicit",
        }
    }
    pub fn from_name(s: &str) -> Option<Self> {
        Some(match s {
            "euler" => Integrator::Euler,
            "midpoint" => Integrator::Midpoint,
            "rk4" => Integrator::Rk4,
            "symplectic" => Integrator::Symplectic,
            "implicit" => Integrator::Implicit,
            _ => return None,
        })
    }
}

/// A rigid ground plane y = height.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ground {
    /// Height of the plane (m).
    pub height: f64,
    /// Coulomb friction coefficient μ (dimensionless): a contact impulse j along the normal
    /// removes up to μ j of tangential velocity.
    pub friction: f64,
    /// Coefficient of restitution e in [0, 1] (dimensionless): 0 is inelastic (the default).
    pub restitution: f64,
}

impl Ground {
    /// A ground at `height` (m) with the default friction and restitution.
    pub fn at(height: f64) -> Self {
        Ground { height, friction: table::GROUND_FRICTION.number(), restitution: table::GROUND_RESTITUTION.number() }
    }

    /// The `ground.*` parameters, fields of the ground (read and set only when there is one).
    pub const FIELDS: &'static [Field<Ground>] = &[
        number_field!(Ground, table::GROUND_HEIGHT, height),
        number_field!(Ground, table::GROUND_FRICTION, friction),
        number_field!(Ground, table::GROUND_RESTITUTION, restitution),
    ];
}

/// Contact between bodies and within a self-colliding body.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactSettings {
    /// Distance kept between a vertex and another body's surface (m).
    pub thickness: f64,
    /// Coulomb friction between bodies (dimensionless).
    pub friction: f64,
    /// Test edges against edges too (on by default; off only to see what it prevents).
    pub edge_contact: bool,
}

impl Default for ContactSettings {
    fn default() -> Self {
        ContactSettings { thickness: table::CONTACT_THICKNESS.number(), friction: table::CONTACT_FRICTION.number(), edge_contact: true }
    }
}

/// Everything a world imposes on its bodies.
#[derive(Debug, Clone, PartialEq)]
pub struct WorldSettings {
    /// Gravitational acceleration g (m/s²) along −y.
    pub gravity: f64,
    /// Wind velocity w (m/s).
    pub wind: [f64; 3],
    /// Wind drag coefficient cw (N·s/m³ = kg/(m²·s)): force cw · area · ((w − v_face) · n) n on a
    /// face that sees the wind.
    pub wind_drag: f64,
    /// Optional ground plane.
    pub ground: Option<Ground>,
    /// Rigid obstacles (spheres, boxes, capsules, triangle meshes) no body can enter.
    pub obstacles: Vec<Obstacle>,
    /// Time integrator.
    pub integrator: Integrator,
    /// Time step (s). Changing it rebases the clock (see `clock.rs`).
    pub dt: f64,
    /// Implicit integrator only: the relative residual (dimensionless) at which a step's Newton
    /// iterations stop, ‖r_k‖ / ‖r_0‖ in the mass-weighted norm (`body/implicit/mod.rs`).
    pub tolerance: f64,
    /// Implicit integrator only: at most this many Newton iterations per step (≥ 1); a step
    /// that has not converged by then is refused.
    pub newton_iterations: u32,
    /// Implicit integrator only, the caller's choice for a run (not saved in scenes or
    /// snapshots; [`World::step_n_splitting`](crate::world::World::step_n_splitting) sets it
    /// for its steps): when a Newton solve gives up before the cap (`body/implicit/mod.rs`).
    /// `None`: only at the cap.
    pub give_up: Option<GiveUp>,
    /// Implicit integrator only, the caller's choice for a run (not saved in scenes or
    /// snapshots; [`World::step_n_with`](crate::world::World::step_n_with) sets it for its
    /// steps): a step that no solve of the model finishes is tried again with the hinges of
    /// crushed faces let go, then with no hinges for that step (`body::implicit::Relaxed`),
    /// before it is refused. Off: refused (the CLI and scenes); the modeler turns it on for its
    /// steps rather than pause the user's work.
    pub relax: bool,
    /// Implicit integrator only, the caller's choice for a run (not saved in scenes or
    /// snapshots; [`World::advance`](crate::world::World::advance) sets it under a real-time
    /// budget): a wall-clock time after which a step's solve stops at its current iterate, if
    /// that is within [`Deadline::accept`] (the anytime step, `body/implicit/mod.rs`). `None`:
    /// every step to `tolerance`.
    pub deadline: Option<Deadline>,
    /// Implicit integrator only, the caller's choice for a run (not saved): asked between the
    /// solver's iterations; when it answers yes the step is abandoned (`SimError::Interrupted`)
    /// and, through [`World::step_n`](crate::world::World::step_n), the world is as before the
    /// call. The page's worker asks whether a command is waiting, so Undo or a new model never
    /// waits for a slow step.
    pub interrupt: Option<Interrupt>,
    /// Contact between bodies and self-collision.
    pub contact: ContactSettings,
}

/// When an implicit step's Newton solve gives up before `newton_iterations` (the step is then
/// refused as at the cap, the state untouched), for a caller that splits a refused step into
/// shorter ones (the modeler): such a step costs a few iterations instead of the cap, in each
/// of the integrator's attempts (warm start, cold, without the ground's vertices if it held
/// some). It can refuse a step that would have converged (the residual is not monotone: the
/// line search follows the slope of the step's incremental potential), so the caller's last,
/// shortest split should step without it. Measured on the modeler's mushroom subdivided twice
/// and grabbed (BENCHMARKS.md, "A step that will not converge, found out at once").
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct GiveUp {
    /// Iterations without a new lowest residual (≥ 1): the solve has stalled.
    pub stalled: u32,
    /// Iterations in all (≥ 1): a step this slow costs more than two of half its dt.
    pub most: u32,
}

/// When an implicit step's solve may stop short of the tolerance (the anytime step): once the
/// clock `now` reads `at` or later, the solve stops after the Newton iteration in progress (its
/// conjugate gradient stops at once, after at least one iteration: any iterate of a
/// preconditioned CG from δ = 0 is a descent direction of the step's quadratic model) and the
/// step is accepted at its current iterate if the relative residual ‖r‖/‖r_0‖ there is at most
/// `accept`; else the solve goes on until it is (or refuses the step at the cap, as always).
/// Every accepted iterate passed the line search (`Implicit::line_search`: a zero of the step's
/// incremental potential's slope along the Newton direction, not a guaranteed decrease), so a
/// step stopped early is a shorter move towards the backward-Euler solution; measured on a drop
/// (`tests/advance.rs`), the total energy never rises and the body rests where converged steps
/// put it.
#[derive(Debug, Clone, Copy)]
pub struct Deadline {
    /// The clock (s, any fixed origin): [`crate::world::wall_clock`] natively, the page's
    /// `performance.now()` in WebAssembly.
    pub now: fn() -> f64,
    /// When the solve should stop (s, on `now`'s clock).
    pub at: f64,
    /// The largest relative residual (dimensionless, > 0) a step stopped by the deadline is
    /// accepted with.
    pub accept: f64,
}

impl Deadline {
    /// Whether the deadline has passed.
    pub fn passed(&self) -> bool {
        (self.now)() >= self.at
    }
}

/// Whether the caller wants the step in progress abandoned (`WorldSettings::interrupt`).
#[derive(Debug, Clone, Copy)]
pub struct Interrupt(pub fn() -> bool);

impl Interrupt {
    pub fn asked(&self) -> bool {
        (self.0)()
    }
}

impl PartialEq for Interrupt {
    /// Any two (a caller's run-time choice, like the deadline: not part of what a world is).
    fn eq(&self, _: &Self) -> bool {
        true
    }
}

impl PartialEq for Deadline {
    /// Two deadlines at the same time with the same acceptance (the clocks are not compared).
    fn eq(&self, o: &Self) -> bool {
        self.at == o.at && self.accept == o.accept
    }
}

impl Default for WorldSettings {
    /// The defaults of the parameter table: gravity on, no wind, no ground, no obstacles.
    fn default() -> Self {
        WorldSettings {
            gravity: table::GRAVITY.number(),
            wind: table::WIND.vector(),
            wind_drag: table::WIND_DRAG.number(),
            ground: None,
            obstacles: Vec::new(),
            integrator: Integrator::from_name(table::INTEGRATOR.choice()).unwrap_or(Integrator::Symplectic),
            dt: table::DT.number(),
            tolerance: table::TOLERANCE.number(),
            newton_iterations: table::NEWTON_ITERATIONS.number() as u32,
            give_up: None,
            relax: false,
            deadline: None,
            interrupt: None,
            contact: ContactSettings::default(),
        }
    }
}

impl WorldSettings {
    /// The world parameters that are fields of the settings, each with its table entry: get,
    /// set and validation by id read this list (`world/params.rs`). A new world parameter is
    /// its table entry, its field and its line here. (Not here: `ground`, whether there is one,
    /// and `ground.*`, the fields of [`Ground::FIELDS`].)
    pub const FIELDS: &'static [Field<WorldSettings>] = &[
        number_field!(WorldSettings, table::DT, dt),
        choice_field!(WorldSettings, table::INTEGRATOR, integrator: Integrator, "integrator"),
        number_field!(WorldSettings, table::TOLERANCE, tolerance),
        Field {
            param: &table::NEWTON_ITERATIONS,
            get: |w: &WorldSettings| Value::Number(w.newton_iterations as f64),
            // A count: the table's range bounds it (1 to MAX_NEWTON), a fraction is refused.
            set: |w: &mut WorldSettings, v| match v {
                Value::Number(x) if x.fract() == 0.0 => {
                    w.newton_iterations = x as u32;
                    Ok(())
                }
                Value::Number(x) => Err(format!("must be a whole number, got {x}")),
                other => Err(format!("expected a number, got {other:?}")),
            },
        },
        number_field!(WorldSettings, table::GRAVITY, gravity),
        Field {
            param: &table::WIND,
            get: |w: &WorldSettings| Value::Vector(w.wind),
            set: |w: &mut WorldSettings, v| match v {
                Value::Vector(x) => {
                    w.wind = x;
                    Ok(())
                }
                other => Err(format!("expected three numbers, got {other:?}")),
            },
        },
        number_field!(WorldSettings, table::WIND_DRAG, wind_drag),
        number_field!(WorldSettings, table::CONTACT_THICKNESS, contact.thickness),
        number_field!(WorldSettings, table::CONTACT_FRICTION, contact.friction),
    ];

    /// Reject non-finite or out-of-range values with a message naming the parameter (its table
    /// id) and its unit: every field against its table range ([`WorldSettings::FIELDS`], and
    /// the ground's [`Ground::FIELDS`]); then what is not a table parameter (the give-up rule,
    /// the deadline, the obstacles).
    pub fn validate(&self) -> Result<(), SimError> {
        check_fields(WorldSettings::FIELDS, self)?;
        if let Some(g) = &self.ground {
            check_fields(Ground::FIELDS, g)?;
        }
        if let Some(g) = self.give_up {
            if g.stalled == 0 || g.most == 0 {
                return Err(bad("give-up", format!("must be at least 1 iteration each, got {g:?}")));
            }
        }
        if let Some(d) = self.deadline {
            if !(d.accept > 0.0) || d.at.is_nan() {
                return Err(bad("min-accuracy", format!("must be a relative residual above 0, got {}", d.accept)));
            }
        }
        for (k, o) in self.obstacles.iter().enumerate() {
            o.validate().map_err(|m| bad("obstacle", format!("obstacle {}: {m}", k + 1)))?;
        }
        Ok(())
    }
}

/// The largest Newton iteration cap (the table's range).
pub const MAX_NEWTON: u32 = table::NEWTON_ITERATIONS.range.max as u32;

/// Time step (s): finite and > 0.
pub fn check_dt(dt: f64) -> Result<(), SimError> {
    check_positive("dt", dt)
}
