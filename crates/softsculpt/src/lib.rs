//! SoftSculpt core: a mass-spring-damper soft body with ideal-gas pressure.
//!
//! The model (see `docs/model.md` at the repository root for the full derivation):
//! vertices of a closed triangle mesh are point masses, every edge is a damped Hooke spring, and a
//! gas with `P = nRT / V` pushes every face outward (Matyka & Ollila 2003). Gravity, wind, user
//! forces and a ground plane act from outside.
//!
//! Layout: [`mesh`] parses, checks and builds meshes (bytes in, bytes out: no file-system access);
//! [`body`] holds the simulation state as flat arrays and steps it as a list of named stages.
//! The crate has no I/O and no binding code.

pub mod body;
pub mod error;
pub mod geometry;
pub mod hash;
pub mod mesh;
pub mod scene;
pub mod vec3;
pub mod workload;
pub mod world;

pub use body::{Integrator, Params, SoftBody, Stats, VolumeMode, GAS_CONSTANT};
pub use error::{MeshError, SimError};
pub use mesh::{prepare, LoadedMesh, MeshReport, TriMesh};
