//! Timed events and the loads they put on bodies: the world's last stage before a step.
//!
//! An event at time t fires before the first step that starts at or after t (within half a
//! step): with dt = 1 ms an event at 0.25 s acts from step 250 on. Forces and pressures last
//! until `time + duration`, ending the same way; overlapping ones add up. A scene file gives the
//! events (`crate::scene::build` resolves regions to vertex and face lists).

use super::World;
use crate::error::SimError;

/// A resolved action on one body (indices are the body's vertices and faces).
#[derive(Debug, Clone, PartialEq)]
pub enum Action {
    /// Rest shape := current shape; `under_load` keeps carrying the weight, `keep_tension`
    /// keeps the gas pressing (see `crate::body::FreezeOptions`).
    Freeze { under_load: bool, keep_tension: bool },
    /// Back to the last frozen state.
    Reset,
    /// Gas amount n (mol) and temperature T (K); `None` keeps the current value.
    SetGas { amount: Option<f64>, temperature: Option<f64>, nrt: Option<f64> },
    /// Wind velocity (m/s): the world's, so every body feels it.
    SetWind([f64; 3]),
    /// Force (N) on each listed vertex, from now until `until` (s).
    Force { vertices: Vec<usize>, per_vertex: [f64; 3], until: f64 },
    /// Pressure (Pa, inward) on each listed face until `until` (s).
    Pressure { faces: Vec<usize>, pressure: f64, until: f64 },
    Pin(Vec<usize>),
    Unpin(Vec<usize>),
    /// Rest-length factor per vertex (1 outside the region).
    Inflate(Vec<f64>),
    SetMass { vertices: Vec<usize>, mass: f64 },
}

/// An action due at `time` (s) on body `body`.
#[derive(Debug, Clone, PartialEq)]
pub struct Event {
    pub time: f64,
    pub body: usize,
    pub action: Action,
    /// 1-based line of the event in the scene file, for run-time errors.
    pub line: usize,
}

/// A load in force: per-vertex forces (N) or per-face pressures (Pa) on one body.
#[derive(Debug, Clone, PartialEq)]
pub struct Load {
    pub body: usize,
    /// End time (s).
    pub until: f64,
    pub forces: Option<(Vec<usize>, [f64; 3])>,
    pub pressures: Option<(Vec<usize>, f64)>,
}

/// An open scene's events: all of them in time order, the cursor of the next one to fire, and
/// the loads in force. Sums of the loads per body are scratch (rebuilt whenever loads change).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Events {
    pub(crate) list: Vec<Event>,
    pub(crate) next: usize,
    pub(crate) loads: Vec<Load>,
}

impl Events {
    /// Whether the events stage at time `t` with step `dt` (s) changes anything: an event due or
    /// a load ending.
    pub(crate) fn due(&self, t: f64, dt: f64) -> bool {
        let due = t + 0.5 * dt;
        self.list.get(self.next).is_some_and(|e| e.time < due) || self.loads.iter().any(|l| l.until < due)
    }
}

/// Why the events stage failed: the event's scene line and the error.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct EventFailure {
    pub line: Option<usize>,
    pub error: SimError,
}

impl World {
    /// Give the world a scene's events (in time order, as `crate::scene::build` makes them),
    /// replacing any it had; none has fired yet.
    pub fn set_events(&mut self, events: Vec<Event>) {
        self.events = Events { list: events, next: 0, loads: Vec::new() };
    }

    /// Events not fired yet (all bodies).
    pub fn pending_events(&self) -> usize {
        self.events.list.len() - self.events.next
    }

    /// Body `i` was replaced by one with `vertices` vertices and `faces` faces (the modeler
    /// subdivided it, say): if the counts changed, its pending events and loads no longer fit
    /// and are dropped. Returns how many events were dropped.
    pub fn body_replaced(&mut self, i: usize, vertices: usize, faces: usize) -> usize {
        let (forces, pressures) = &mut self.load_sums;
        if forces.get(i).map(Vec::len) == Some(3 * vertices) && pressures.get(i).map(Vec::len) == Some(faces) {
            return 0;
        }
        if let (Some(f), Some(p)) = (forces.get_mut(i), pressures.get_mut(i)) {
            *f = vec![0.0; 3 * vertices];
            *p = vec![0.0; faces];
        }
        let ev = &mut self.events;
        ev.loads.retain(|l| l.body != i);
        let before = ev.list.len();
        // Events before `next` have fired: only pending ones are dropped, so `next` stays put.
        let next = ev.next;
        let mut k = 0;
        ev.list.retain(|e| {
            k += 1;
            k - 1 < next || e.body != i
        });
        before - ev.list.len()
    }

    /// Replace body `i` (by a subdivided or restored one), dropping its pending events if its
    /// vertex or face count changed (see [`World::body_replaced`]). Returns the old body and how
    /// many events were dropped.
    pub fn replace_body(&mut self, i: usize, body: crate::SoftBody) -> (crate::SoftBody, usize) {
        let (nv, nf) = (body.vertex_count(), body.face_count());
        let old = std::mem::replace(&mut self.bodies[i], body);
        (old, self.body_replaced(i, nv, nf))
    }

    /// Stage "events": fire the events due at the start of this step (time `t`), end expired
    /// loads, and apply the loads if they changed.
    pub(crate) fn fire_due(&mut self, t: f64, dt: f64) -> Result<(), EventFailure> {
        let due = t + 0.5 * dt;
        let mut loads_changed = false;
        while self.events.next < self.events.list.len() && self.events.list[self.events.next].time < due {
            let e = self.events.list[self.events.next].clone();
            self.events.next += 1;
            loads_changed |= self.fire(&e).map_err(|error| EventFailure { line: Some(e.line), error })?;
        }
        let before = self.events.loads.len();
        self.events.loads.retain(|l| l.until >= due);
        loads_changed |= self.events.loads.len() != before;
        if loads_changed {
            self.apply_loads().map_err(|error| EventFailure { line: None, error })?;
        }
        Ok(())
    }

    /// Apply one event; true if it changed the loads.
    fn fire(&mut self, e: &Event) -> Result<bool, SimError> {
        if e.body >= self.bodies.len() {
            return Err(SimError::BadParameter { name: "event", message: format!("there is no body {}", e.body) });
        }
        if let Action::Freeze { under_load, keep_tension } = e.action {
            // The world's freeze: it knows the gravity and the supports.
            self.freeze(e.body, crate::body::FreezeOptions { under_load, keep_tension })?;
            return Ok(false);
        }
        let b = &mut self.bodies[e.body];
        match &e.action {
            Action::Freeze { .. } => {}
            Action::Reset => b.reset(),
            Action::SetGas { amount, temperature, nrt } => {
                let t = temperature.unwrap_or(b.material.temperature);
                let n = match (amount, nrt) {
                    (Some(a), _) => *a,
                    (None, Some(n)) => crate::body::moles(*n, t),
                    (None, None) => b.material.gas_amount,
                };
                b.set_gas(n, t)?
            }
            Action::SetWind(w) => self.settings.wind = *w,
            Action::Force { vertices, per_vertex, until } => {
                self.events.loads.push(Load { body: e.body, until: *until, forces: Some((vertices.clone(), *per_vertex)), pressures: None });
                return Ok(true);
            }
            Action::Pressure { faces, pressure, until } => {
                self.events.loads.push(Load { body: e.body, until: *until, forces: None, pressures: Some((faces.clone(), *pressure)) });
                return Ok(true);
            }
            Action::Pin(vs) | Action::Unpin(vs) => {
                let on = matches!(e.action, Action::Pin(_));
                for &v in vs {
                    b.set_pinned(v, on)?;
                }
            }
            Action::Inflate(factors) => b.scale_rest_lengths_by_vertex(factors)?,
            Action::SetMass { vertices, mass } => {
                for &v in vertices {
                    b.set_vertex_mass(v, *mass)?;
                }
            }
        }
        Ok(false)
    }

    /// Sum the loads in force into each body's user forces and face pressures.
    fn apply_loads(&mut self) -> Result<(), SimError> {
        let (forces, pressures) = &mut self.load_sums;
        forces.resize_with(self.bodies.len(), Vec::new);
        pressures.resize_with(self.bodies.len(), Vec::new);
        for (k, b) in self.bodies.iter().enumerate() {
            forces[k].clear();
            forces[k].resize(3 * b.vertex_count(), 0.0);
            pressures[k].clear();
            pressures[k].resize(b.face_count(), 0.0);
        }
        for l in &self.events.loads {
            let out_of_range = || SimError::BadParameter { name: "event", message: format!("a load does not fit body {}", l.body) };
            if let Some((vs, f)) = &l.forces {
                let sum = forces.get_mut(l.body).ok_or_else(out_of_range)?;
                for &v in vs {
                    for d in 0..3 {
                        *sum.get_mut(3 * v + d).ok_or_else(out_of_range)? += f[d];
                    }
                }
            }
            if let Some((fs, p)) = &l.pressures {
                let sum = pressures.get_mut(l.body).ok_or_else(out_of_range)?;
                for &f in fs {
                    *sum.get_mut(f).ok_or_else(out_of_range)? += p;
                }
            }
        }
        for (k, b) in self.bodies.iter_mut().enumerate() {
            b.set_user_forces(&forces[k])?;
            b.set_face_pressures(&pressures[k])?;
        }
        Ok(())
    }
}
