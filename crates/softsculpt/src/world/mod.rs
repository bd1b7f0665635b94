//! The world: the only unit of simulation. It owns its soft bodies, the settings every body
//! shares (gravity, wind, ground, obstacles, integrator, dt, contacts: [`crate::settings`],
//! defined below the bodies, which step with them, and re-exported here), the clock
//! (`clock.rs`), and an open scene's pending events and active loads (`events.rs`). A lone body
//! is a one-body world ([`World::single`]).
//!
//! One [`World::step`] runs these stages in order (after Box2D v3's `b2World_Step`):
//! 0. **events**   – fire the events due at the step's start, end expired loads (`events.rs`).
//!    They act on the state the step starts from, so an event at t = 0 acts on the first step
//!    and a new dt moves "due" with it (t + dt/2), as the scene runner always did.
//! 1. **bodies**   – each body's forces and integration (`SoftBody::integrate`, `body/`): the
//!    only stage that reads the material; it takes gravity, wind and the integrator from here.
//!    Self-colliding bodies stepped implicitly first get their self-contacts, found on the
//!    step's start positions, as penalty springs in their solve (`selfpairs.rs`).
//! 2. **ground**   – vertices below the plane go back onto it (`ground.rs`).
//! 3. **obstacles** – vertices whose path entered a rigid obstacle stop at the entry point, any
//!    inside are pushed out; then edges are kept out of thin spheres and capsules
//!    ([`crate::obstacles`]). Ground before obstacles, as a body's own step always did them,
//!    so every result is bit for bit what it was before the world owned them.
//! 4. **contacts** – between bodies, and within self-colliding ones (`contacts.rs`, `edges.rs`).
//! 5. **plastic**  – each plastic body's rest lengths flow toward its current lengths where the
//!    strain exceeds the yield strain, and its gas reference follows (`body/plastic.rs`). Its own
//!    stage after integration and contacts, on the step's final positions, so it works the same
//!    with every integrator (and changes nothing when the flow rate is 0).
//! 6. **clock**    – one step more (`clock.rs`).
//!
//! Stages 2–4 are velocity-level corrections after the integrator, so away from contact the
//! integrators are exactly themselves. A failing stage leaves the world as it failed;
//! [`World::step_n`] rolls the whole world back instead (`rollback.rs`).

mod advance;
mod clock;
mod contacts;
mod edges;
mod events;
mod freeze;
mod overlaps;
pub mod ground;
mod params;
mod rewind;
mod rollback;
mod selfpairs;

pub use advance::{Advance, Budget, RealTime, GIVE_UP_MOST, GIVE_UP_STALLED, MIN_ACCURACY, SPLITS};
pub use rewind::{HEALTHY, REWIND_BYTES, REWIND_EVERY, REWIND_KEEP, REWIND_OVERHEAD};
#[cfg(not(target_arch = "wasm32"))]
pub use advance::wall_clock;
pub use clock::Clock;
pub use events::{Action, Event, Events, Load};
pub use freeze::SUPPORT_GAP;
pub(crate) use params::set_body_param;
// Under their old paths: the settings and obstacles, moved below the bodies (`crate::settings`,
// `crate::obstacles`), and `sig3`, moved to the leaf `crate::error`.
pub use crate::error::sig3;
pub use crate::obstacles::{self, mesh_obstacle, Obstacle, Shape};
pub use crate::settings::{check_dt, ContactSettings, Deadline, GiveUp, Ground, Integrator, Interrupt, WorldSettings};

use crate::body::{SoftBody, Stats};
use crate::error::SimError;

/// A world of soft bodies. See the module documentation for the step.
#[derive(Debug, Clone)]
pub struct World {
    pub bodies: Vec<SoftBody>,
    /// Change freely between steps; each step validates them.
    pub settings: WorldSettings,
    pub(crate) clock: Clock,
    pub(crate) events: Events,
    /// Sums of the loads in force per body: user forces (N, flat xyz) and face pressures (Pa).
    /// Scratch, rebuilt whenever the loads change; their sizes say which mesh a body's events
    /// were resolved on (see [`World::body_replaced`]).
    pub(crate) load_sums: (Vec<Vec<f64>>, Vec<Vec<f64>>),
    /// Every body's positions at the start of the step (flat xyz, m): the obstacles' swept
    /// check and the side each contact started on. Scratch.
    pub(crate) prev: Vec<Vec<f64>>,
    pub(crate) cx: contacts::Scratch,
    /// Positions and velocities at the start of a `step_n` call. Scratch.
    pub(crate) backup: rollback::Backup,
    /// The last sound states a failed frame goes back to ([`Budget::rewind`], `rewind.rs`).
    pub(crate) rewind: rewind::Rewind,
    /// Threads the bodies' passes run on (results do not depend on their number beyond rounding:
    /// `par.rs`).
    pub(crate) threads: crate::par::Threads,
    /// Pairs of bodies that started overlapping: no contact between them until they part
    /// (`overlaps.rs`).
    pub(crate) overlaps: overlaps::Overlaps,
}

/// A step that failed: when (the time at the step's start, s, and the step's number), the scene
/// line of the event at fault if an event failed, and why.
#[derive(Debug, Clone, PartialEq)]
pub struct StepError {
    pub time: f64,
    pub step: u64,
    pub line: Option<usize>,
    pub error: SimError,
    /// Set by [`World::step_n`]: the time (s) the world was rolled back to.
    pub rolled_back_to: Option<f64>,
    /// Set by [`World::advance`] under a budget that rewinds ([`Budget::rewind`]): the time (s)
    /// of the last sound state the world went back to, further than the rollback
    /// (`world/rewind.rs`); None where it had none and the rollback stands.
    pub rewound_to: Option<f64>,
}

impl std::fmt::Display for StepError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match (self.rewound_to, self.rolled_back_to) {
            (Some(t0), _) => write!(f, "at t = {} s: {} — put back to t = {} s, the last sound state", sig3(self.time), self.error, sig3(t0)),
            (None, None) => self.error.fmt(f),
            (None, Some(t0)) => write!(f, "at t = {} s: {} — rolled back to t = {} s", sig3(self.time), self.error, sig3(t0)),
        }
    }
}

impl std::error::Error for StepError {}

impl World {
    pub fn new(bodies: Vec<SoftBody>, settings: WorldSettings) -> Self {
        let load_sums = (bodies.iter().map(|b| vec![0.0; 3 * b.vertex_count()]).collect(), bodies.iter().map(|b| vec![0.0; b.face_count()]).collect());
        World {
            clock: Clock::new(settings.dt),
            bodies,
            settings,
            events: Events::default(),
            load_sums,
            prev: Vec::new(),
            cx: contacts::Scratch::default(),
            backup: rollback::Backup::default(),
            rewind: rewind::Rewind::default(),
            threads: crate::par::Threads::single(),
            overlaps: Vec::new(),
        }
    }

    /// A one-body world: how a lone body is simulated.
    pub fn single(body: SoftBody, settings: WorldSettings) -> Self {
        World::new(vec![body], settings)
    }

    /// Add a body; returns its index.
    pub fn add_body(&mut self, body: SoftBody) -> usize {
        self.load_sums.0.push(vec![0.0; 3 * body.vertex_count()]);
        self.load_sums.1.push(vec![0.0; body.face_count()]);
        self.bodies.push(body);
        self.bodies.len() - 1
    }

    /// Run the bodies' force stages and the implicit solver on `n` threads (0: one per core;
    /// WebAssembly: the caller and the page's helpers, `par/host.rs`; one without atomics). The
    /// results do not depend on the number beyond rounding: the same bits on any count for the
    /// implicit solver, on 2 or more for the explicit stages (one thread sums their springs in
    /// another order; `par.rs`).
    pub fn set_threads(&mut self, n: usize) -> Result<(), String> {
        self.threads = crate::par::Threads::new(n)?;
        Ok(())
    }
    /// Run the passes on `threads`, a pool shared with other worlds (the page's one pool of
    /// helper threads, `par/host.rs`: a pool per world would take helpers for each).
    pub fn share_threads(&mut self, threads: &crate::par::Threads) {
        self.threads = threads.clone();
    }
    /// Threads the passes run on.
    pub fn threads(&self) -> usize {
        self.threads.count()
    }

    /// Steps taken and simulated time (s).
    pub fn steps(&self) -> u64 {
        self.clock.steps()
    }
    pub fn time(&self) -> f64 {
        self.clock.time()
    }
    pub fn clock(&self) -> Clock {
        self.clock
    }
    /// Take another world's clock (a binding that shows one body of a scene on its own).
    pub fn set_clock(&mut self, clock: Clock) {
        self.clock = clock;
    }

    /// Statistics of body `i` (energies with the world's gravity), at the world's step and time.
    pub fn stats(&self, i: usize) -> Stats {
        self.bodies[i].stats_at(self.settings.gravity, self.clock.steps(), self.clock.time())
    }

    /// Total of every body's energies (J), for diagnostics.
    pub fn total_energy(&self) -> f64 {
        (0..self.bodies.len()).map(|i| self.stats(i).total_energy).sum()
    }

    /// Every position and velocity of every body is finite.
    pub fn is_finite(&self) -> bool {
        self.bodies.iter().all(SoftBody::is_finite)
    }

    /// Whether the contact stage has anything to do: several bodies, or one colliding with
    /// itself.
    fn has_contacts(&self) -> bool {
        self.bodies.len() > 1 || self.bodies.iter().any(|b| b.material.self_collision)
    }

    /// One step of `settings.dt` seconds: the stages of the module documentation.
    pub fn step(&mut self) -> Result<(), StepError> {
        let (step, time) = (self.clock.steps() + 1, self.clock.time());
        let fail = |line: Option<usize>, error: SimError| StepError { time, step, line, error, rolled_back_to: None, rewound_to: None };
        self.settings.validate().map_err(|e| fail(None, e))?;
        self.clock.rebase(self.settings.dt);
        let dt = self.settings.dt;

        // Stage 0: events due at the start of the step.
        self.fire_due(time, dt).map_err(|e| fail(e.line, e.error))?;

        // Where every vertex starts, for the swept obstacle check and the contacts' sides.
        let contacts = self.has_contacts();
        if contacts || !self.settings.obstacles.is_empty() {
            self.prev.resize_with(self.bodies.len(), Vec::new);
            for (p, b) in self.prev.iter_mut().zip(&self.bodies) {
                p.clear();
                p.extend_from_slice(b.positions());
            }
        }

        // Stage 1: each body's forces and integration; self-colliding bodies stepped implicitly
        // carry their self-contacts into the solve (found here, dropped after: `selfpairs.rs`).
        let self_contacts = self.settings.integrator == Integrator::Implicit && self.bodies.iter().any(|b| b.material.self_collision);
        if self_contacts {
            self.find_self_contacts();
        }
        let mut stepped = Ok(());
        for b in &mut self.bodies {
            stepped = b.integrate(&self.settings, dt, step, time, &self.threads);
            if stepped.is_err() {
                break;
            }
        }
        if self_contacts {
            for b in &mut self.bodies {
                b.model.self_contacts.list.clear();
            }
        }
        stepped.map_err(|e| fail(None, e))?;

        // Stage 2: ground.
        if let Some(g) = self.settings.ground {
            for b in &mut self.bodies {
                let v = b.rigid_view();
                ground::project(&g, v.inv_mass, v.x, v.v);
            }
        }

        // Stage 3: obstacles (vertices, then edges against thin round ones).
        if !self.settings.obstacles.is_empty() {
            let obstacles = &self.settings.obstacles;
            for (b, x_prev) in self.bodies.iter_mut().zip(&self.prev) {
                let v = b.rigid_view();
                obstacles::resolve(obstacles, v.inv_mass, x_prev, v.x, v.v);
                obstacles::resolve_edges(obstacles, v.inv_mass, v.ei, v.ej, v.x, v.v);
            }
        }

        // Stage 4: contacts between bodies and within self-colliding ones.
        if contacts {
            self.collide();
        }

        // Stage 5: plasticity.
        for b in &mut self.bodies {
            b.plastic_flow(dt);
        }

        // Stage 6: the clock.
        self.clock.tick();
        Ok(())
    }
}
