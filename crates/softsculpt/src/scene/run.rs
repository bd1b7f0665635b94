//! Playing a scene: the world a scene file builds (bodies, settings, events: the world steps
//! itself and fires the events on time, see `crate::world`), with what output needs — each
//! body's name and loaded mesh, the parsed file, the run's length.

use super::build::{build, BuiltBody, Resolver};
use super::{parse, SceneError};
use crate::world::{StepError, World};

pub struct SceneRun {
    /// The scene as parsed (what saving writes back its obstacles and events from).
    pub spec: super::SceneSpec,
    pub world: World,
    /// Each body's name and loaded mesh, in the world's body order.
    pub names: Vec<String>,
    pub meshes: Vec<crate::mesh::LoadedMesh>,
    /// Length of the run (s).
    pub duration: f64,
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
        let mut world = World::new(bodies, built.settings);
        world.set_events(built.events);
        Ok(SceneRun { spec, world, names, meshes, duration: built.duration })
    }

    /// Simulated time (s): steps · dt since the last change of dt (never a running sum).
    pub fn time(&self) -> f64 {
        self.world.time()
    }

    /// The time step (s).
    pub fn dt(&self) -> f64 {
        self.world.settings.dt
    }

    /// Change the time step from now on (s); the clock stays continuous.
    pub fn set_dt(&mut self, dt: f64) {
        if dt.is_finite() && dt > 0.0 {
            self.world.settings.dt = dt;
        }
    }

    /// See [`World::body_replaced`].
    pub fn body_replaced(&mut self, i: usize, vertices: usize, faces: usize) -> usize {
        self.world.body_replaced(i, vertices, faces)
    }

    /// Events not fired yet (all bodies).
    pub fn pending_events(&self) -> usize {
        self.world.pending_events()
    }

    pub fn steps(&self) -> u64 {
        self.world.steps()
    }

    /// Steps in the whole run: duration / dt, rounded.
    pub fn total_steps(&self) -> u64 {
        (self.duration / self.dt()).round() as u64
    }

    pub fn finished(&self) -> bool {
        self.time() >= self.duration - 0.5 * self.dt()
    }

    /// Step the world once (events due first), naming the event's line if one failed.
    pub fn step(&mut self) -> Result<(), SceneError> {
        self.world.step().map_err(|e| scene_error(&e))
    }

    /// Run to the end, calling `frame(self)` after every step.
    pub fn run(&mut self, mut each: impl FnMut(&SceneRun)) -> Result<(), SceneError> {
        while !self.finished() {
            self.step()?;
            each(self);
        }
        Ok(())
    }
}

/// A failed step as a scene error: "line L: at t s: why" for an event, "at t s: why" otherwise.
pub fn scene_error(e: &StepError) -> SceneError {
    SceneError { line: e.line, key: None, message: format!("at {} s: {}", e.time, e.error) }
}
