//! Playing a scene: step the world, firing each event at its time.
//!
//! Time is `steps · dt` (never a running sum, so no drift). An event at time t fires before the
//! first step that starts at or after t (within half a step): with dt = 1 ms an event at 0.25 s
//! acts from step 250 on. Forces and pressures last until `time + duration`, ending the same way;
//! overlapping ones add up.

use super::build::{build, BuiltBody, Resolver};
use super::events::{Action, Event};
use super::{parse, SceneError};
use crate::error::SimError;
use crate::world::World;

/// A load in force: per-vertex forces (N, flat xyz) or per-face pressures (Pa) on one body.
struct Load {
    body: usize,
    until: f64,
    forces: Option<(Vec<usize>, [f64; 3])>,
    pressures: Option<(Vec<usize>, f64)>,
}

pub struct SceneRun {
    /// The scene as parsed (what saving writes back its obstacles and events from).
    pub spec: super::SceneSpec,
    pub world: World,
    /// Each body's name and loaded mesh, in the world's body order.
    pub names: Vec<String>,
    pub meshes: Vec<crate::mesh::LoadedMesh>,
    /// Time step and length of the run (s).
    pub dt: f64,
    pub duration: f64,
    /// Time (s) when `dt` last changed, and steps since.
    t_base: f64,
    since: u64,
    events: Vec<Event>,
    next: usize,
    loads: Vec<Load>,
    steps: u64,
    forces: Vec<Vec<f64>>,
    pressures: Vec<Vec<f64>>,
}

impl SceneRun {
    /// Parse and build a scene; `resolve` reads the mesh files it names.
    pub fn load(text: &str, resolve: Resolver) -> Result<SceneRun, SceneError> {
        let spec = parse(text)?;
        let built = build(&spec, text, resolve)?;
        let mut names = Vec::new();
        let mut meshes = Vec::new();
        let mut bodies = Vec::new();
        for BuiltBody { name, body, mesh } in built.bodies {
            names.push(name);
            meshes.push(mesh);
            bodies.push(body);
        }
        let forces = bodies.iter().map(|b| vec![0.0; 3 * b.vertex_count()]).collect();
        let pressures = bodies.iter().map(|b| vec![0.0; b.face_count()]).collect();
        let mut world = World::new(bodies, built.contact_thickness);
        world.friction = built.contact_friction;
        Ok(SceneRun {
            spec,
            world,
            names,
            meshes,
            dt: built.dt,
            duration: built.duration,
            t_base: 0.0,
            since: 0,
            events: built.events,
            next: 0,
            loads: Vec::new(),
            steps: 0,
            forces,
            pressures,
        })
    }

    /// Simulated time (s): steps · dt since the last change of dt (never a running sum).
    pub fn time(&self) -> f64 {
        self.t_base + self.since as f64 * self.dt
    }

    /// Change the time step from now on (s).
    pub fn set_dt(&mut self, dt: f64) {
        if dt != self.dt && dt.is_finite() && dt > 0.0 {
            self.t_base = self.time();
            self.since = 0;
            self.dt = dt;
        }
    }

    /// Body `i` was replaced by one with `vertices` vertices and `faces` faces (the modeler
    /// subdivided it, say): if the counts changed, its pending events and loads no longer fit
    /// and are dropped. Returns how many events were dropped.
    pub fn body_replaced(&mut self, i: usize, vertices: usize, faces: usize) -> usize {
        if self.forces[i].len() == 3 * vertices && self.pressures[i].len() == faces {
            return 0;
        }
        self.forces[i] = vec![0.0; 3 * vertices];
        self.pressures[i] = vec![0.0; faces];
        self.loads.retain(|l| l.body != i);
        let before = self.events.len();
        // Events before `next` have fired: only pending ones are dropped, so `next` stays put.
        let next = self.next;
        let mut k = 0;
        self.events.retain(|e| {
            k += 1;
            k - 1 < next || e.body != i
        });
        before - self.events.len()
    }

    /// Events not fired yet (all bodies).
    pub fn pending_events(&self) -> usize {
        self.events.len() - self.next
    }

    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// Steps in the whole run: duration / dt, rounded.
    pub fn total_steps(&self) -> u64 {
        (self.duration / self.dt).round() as u64
    }

    pub fn finished(&self) -> bool {
        self.time() >= self.duration - 0.5 * self.dt
    }

    /// Fire due events, end expired loads, then step the world once.
    pub fn step(&mut self) -> Result<(), SceneError> {
        let t = self.time();
        let due = t + 0.5 * self.dt;
        let mut loads_changed = false;
        while self.next < self.events.len() && self.events[self.next].time < due {
            let e = self.events[self.next].clone();
            self.next += 1;
            loads_changed |= self.fire(&e).map_err(|m| SceneError { line: Some(e.line), key: None, message: format!("at {t} s: {m}") })?;
        }
        let before = self.loads.len();
        self.loads.retain(|l| l.until >= due);
        loads_changed |= self.loads.len() != before;
        if loads_changed {
            self.apply_loads().map_err(|e| SceneError { line: None, key: None, message: e.to_string() })?;
        }
        self.world.step(self.dt).map_err(|e| SceneError { line: None, key: None, message: format!("at {t} s: {e}") })?;
        self.steps += 1;
        self.since += 1;
        Ok(())
    }

    /// Run to the end, calling `frame(self)` after every step.
    pub fn run(&mut self, mut each: impl FnMut(&SceneRun)) -> Result<(), SceneError> {
        while !self.finished() {
            self.step()?;
            each(self);
        }
        Ok(())
    }

    /// Apply one event; true if it changed the loads.
    fn fire(&mut self, e: &Event) -> Result<bool, SimError> {
        let b = &mut self.world.bodies[e.body];
        match &e.action {
            Action::Freeze { under_load } => {
                if *under_load {
                    b.freeze_under_load()
                } else {
                    b.freeze()
                }
            }
            Action::Reset => b.reset(),
            Action::SetGas { amount, temperature, nrt } => {
                let t = temperature.unwrap_or(b.params.temperature);
                let n = match (amount, nrt) {
                    (Some(a), _) => *a,
                    (None, Some(n)) => n / (crate::GAS_CONSTANT * t),
                    (None, None) => b.params.gas_amount,
                };
                b.set_gas(n, t)?
            }
            Action::SetWind(w) => b.params.wind = *w,
            Action::Force { vertices, per_vertex, until } => {
                self.loads.push(Load { body: e.body, until: *until, forces: Some((vertices.clone(), *per_vertex)), pressures: None });
                return Ok(true);
            }
            Action::Pressure { faces, pressure, until } => {
                self.loads.push(Load { body: e.body, until: *until, forces: None, pressures: Some((faces.clone(), *pressure)) });
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
        for f in &mut self.forces {
            f.fill(0.0);
        }
        for p in &mut self.pressures {
            p.fill(0.0);
        }
        for l in &self.loads {
            if let Some((vs, f)) = &l.forces {
                for &v in vs {
                    for d in 0..3 {
                        self.forces[l.body][3 * v + d] += f[d];
                    }
                }
            }
            if let Some((fs, p)) = &l.pressures {
                for &f in fs {
                    self.pressures[l.body][f] += p;
                }
            }
        }
        for (k, b) in self.world.bodies.iter_mut().enumerate() {
            b.set_user_forces(&self.forces[k])?;
            b.set_face_pressures(&self.pressures[k])?;
        }
        Ok(())
    }
}
