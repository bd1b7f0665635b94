//! Stepping with rollback: [`World::step_n`] either takes all its steps or leaves the whole world
//! as it was before the call — every body's state, the clock, the event cursor, the fired
//! events' effects (frozen shapes, gas, pins, masses, wind…) and the loads.
//!
//! Cheaply: a step without an event changes only positions, velocities, the implicit
//! integrator's warm start and kept coarse levels (`body/implicit/`) and the clock (the rest of
//! what it touches is scratch) — and, for a plastic body, its rest lengths, gas reference and
//! plastic dissipation (`body/plastic.rs`) — so those are copied at the start of each call, into
//! buffers kept from call to call. Only before the first step of the call at which an event fires or a
//! load ends (`Events::due`) is the rest copied too (a clone of the bodies, settings, events and
//! load sums). A rollback restores that full copy if there is one, then the positions,
//! velocities and clock of the call's start: the steps before the first event changed nothing
//! else.

use super::{Clock, Events, GiveUp, StepError, World, WorldSettings};
use crate::body::{SoftBody, State};
use crate::error::SimError;

/// What the events stage can change besides positions, velocities and the clock.
struct Full {
    bodies: Vec<SoftBody>,
    settings: WorldSettings,
    events: Events,
    load_sums: (Vec<Vec<f64>>, Vec<Vec<f64>>),
}

/// Every body's state at the start of a call (`body::State`: positions, velocities, the
/// implicit warm start and kept coarse levels), copied with `clone_from` into buffers kept from
/// call to call; and what the plastic stage changes, of the plastic bodies.
#[derive(Debug, Clone, Default)]
pub(crate) struct Backup {
    state: Vec<State>,
    plastic: Vec<Option<crate::body::PlasticState>>,
}

impl World {
    /// [`World::step_n`] for a caller that splits a refused step into shorter ones (the
    /// modeler): each implicit step's Newton solve gives up as `give_up` says
    /// ([`WorldSettings::give_up`]). The setting is back as it was after the call.
    pub fn step_n_splitting(&mut self, n: u64, give_up: GiveUp) -> Result<(), StepError> {
        self.step_n_with(n, Some(give_up), false)
    }

    /// [`World::step_n`] with the caller's choices for these steps only: when an implicit
    /// step's Newton solve gives up (`give_up`, [`WorldSettings::give_up`]) and whether a step
    /// no solve of the model finishes is retried with hinges let go (`relax`,
    /// [`WorldSettings::relax`]). The settings are back as they were after the call.
    pub fn step_n_with(&mut self, n: u64, give_up: Option<GiveUp>, relax: bool) -> Result<(), StepError> {
        let was = (std::mem::replace(&mut self.settings.give_up, give_up), std::mem::replace(&mut self.settings.relax, relax));
        let out = self.step_n(n);
        (self.settings.give_up, self.settings.relax) = was;
        out
    }

    /// Take `n` steps, or none: on failure the whole world is back where it was before the call
    /// and the error names the simulated time of the failing step (3 significant digits) and the
    /// time rolled back to. A state that became non-finite without failing a step (it would fail
    /// the next one) counts as a failure at the end of the call.
    pub fn step_n(&mut self, n: u64) -> Result<(), StepError> {
        let mut backup = std::mem::take(&mut self.backup);
        backup.save(&self.bodies);
        let (clock, overlaps) = (self.clock, self.overlaps.clone());
        let mut full: Option<Full> = None;
        let mut result = Ok(());
        for _ in 0..n {
            if full.is_none() && self.events.due(self.clock.time(), self.settings.dt) {
                full = Some(Full { bodies: self.bodies.clone(), settings: self.settings.clone(), events: self.events.clone(), load_sums: self.load_sums.clone() });
            }
            if let Err(e) = self.step() {
                result = Err(e);
                break;
            }
        }
        if result.is_ok() && !self.is_finite() {
            let error = SimError::NonFinite { step: self.clock.steps() };
            result = Err(StepError { time: self.clock.time(), step: self.clock.steps(), line: None, error, rolled_back_to: None, rewound_to: None });
        }
        if let Err(mut e) = result {
            self.roll_back(full, &backup, clock);
            self.overlaps = overlaps;
            e.rolled_back_to = Some(self.clock.time());
            self.backup = backup;
            return Err(e);
        }
        self.backup = backup;
        Ok(())
    }

    fn roll_back(&mut self, full: Option<Full>, backup: &Backup, clock: Clock) {
        if let Some(f) = full {
            self.bodies = f.bodies;
            self.settings = f.settings;
            self.events = f.events;
            self.load_sums = f.load_sums;
        }
        backup.restore(&mut self.bodies);
        self.clock = clock;
    }
}

impl Backup {
    /// Copy what a step without an event changes of `bodies` (see the module documentation),
    /// into the buffers kept from the last call.
    pub(crate) fn save(&mut self, bodies: &[SoftBody]) {
        self.state.resize_with(bodies.len(), State::default);
        for (b, s) in bodies.iter().zip(self.state.iter_mut()) {
            s.clone_from(&b.state);
        }
        self.plastic.clear();
        self.plastic.extend(bodies.iter().map(|b| b.material.is_plastic().then(|| b.plastic_state())));
    }

    /// Whether this backup was saved from bodies of the sizes of `bodies` (what `restore` needs:
    /// vertices, and for plastic bodies the rest lengths).
    pub(crate) fn fits(&self, bodies: &[SoftBody]) -> bool {
        let plastic = |b: &SoftBody, p: &Option<crate::body::PlasticState>| match p {
            Some(p) => b.material.is_plastic() && p.len() == b.model.springs.rest.len() + b.model.bending.rest.len() + b.model.hinges.rest.len(),
            None => !b.material.is_plastic(),
        };
        self.state.len() == bodies.len()
            && self.plastic.len() == bodies.len()
            && bodies.iter().zip(&self.state).all(|(b, s)| s.x.len() == b.state.x.len())
            && bodies.iter().zip(&self.plastic).all(|(b, p)| plastic(b, p))
    }

    /// Put it back into `bodies` (saved from them: [`Backup::fits`]).
    pub(crate) fn restore(&self, bodies: &mut [SoftBody]) {
        for (b, s) in bodies.iter_mut().zip(&self.state) {
            b.state.clone_from(s);
        }
        for (b, p) in bodies.iter_mut().zip(&self.plastic) {
            if let Some(p) = p {
                b.set_plastic_state(p);
            }
        }
    }

    /// Its size in bytes, about (the f64 and u32 arrays).
    pub(crate) fn bytes(&self) -> usize {
        let plastic: usize = self.plastic.iter().flatten().map(|p| p.len()).sum();
        self.state.iter().map(State::bytes).sum::<usize>() + 8 * plastic
    }
}
