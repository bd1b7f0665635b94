//! SoftSculpt core: a mass-spring-damper soft body with ideal-gas pressure.
//!
//! The model (see `docs/model.md` at the repository root for the full derivation):
//! vertices of a closed triangle mesh are point masses, every edge is a damped Hooke spring, and a
//! gas with `P = nRT / V` pushes every face outward (Matyka & Ollila 2003). Gravity, wind, user
//! forces and a ground plane act from outside.
//!
//! Layout: [`mesh`] parses, checks and builds meshes (bytes in, bytes out: no file-system access);
//! [`params`] is the table of every parameter; [`obstacles`] are the rigid shapes and
//! [`settings`] what a world imposes on its bodies (gravity, ground, obstacles, integrator, dt);
//! [`body`] holds a body's material and state as flat arrays, with its force and integration
//! stage; [`world`] is the unit of simulation (its bodies and settings, clock, the step's stages,
//! contacts, events); [`scene`] turns a scene file into a world; [`snapshot`] is the binary
//! snapshot format. The modules form layers, and each imports only from its own layer or lower
//! ones: the leaf utilities ([`vec3`], [`geometry`], [`hash`], [`error`], [`par`]); `mesh` and
//! `params`; `obstacles`; `settings`; `body`; `world`; `scene`, `snapshot` and the rest
//! (`tests/layers.rs` lists the layers and checks every import). The crate has no I/O and no
//! binding code.

pub mod body;
pub mod compat;
pub mod delta;
pub mod error;
pub mod geometry;
pub mod hash;
pub mod mesh;
pub mod obstacles;
pub mod par;
pub mod params;
pub mod scene;
pub mod settings;
pub mod sketch;
pub mod snapshot;
pub mod vec3;
pub mod workload;
pub mod world;

pub use body::{Material, Relaxed, SoftBody, SolverIterations, Stats, Target, VolumeMode, GAS_CONSTANT};
pub use world::{Advance, Budget, Deadline, Ground, Integrator, RealTime, StepError, World, WorldSettings};
pub use error::{MeshError, SimError};
pub use mesh::{prepare, LoadedMesh, MeshReport, TriMesh};
