//! The standard benchmark workload, defined once for `softsculpt bench`, the criterion bench and
//! the comparison with other engines (`shared/bench/`).
//!
//! An icosphere of radius 1 m at a subdivision level (level 4, 5, 6, 7: 2,562 / 10,242 / 40,962 /
//! 163,842 vertices), every vertex 1/2562 kg (so the step stays stable at every level),
//! k = 1000 N/m, cs = 1 N·s/m, c = 0, nRT = 2 J, no gravity, no ground, symplectic Euler,
//! dt = 1e-4 s.

use crate::body::{Material, SoftBody};
use crate::mesh::{builtin::icosphere, reorder};
use crate::world::{Integrator, World, WorldSettings};

/// Time step of the standard workload (s).
pub const DT: f64 = 1e-4;

/// Mass of every vertex (kg).
pub const VERTEX_MASS: f64 = 1.0 / 2562.0;

pub fn material() -> Material {
    let mut p = Material { stiffness: 1000.0, spring_damping: 1.0, damping: 0.0, ..Material::default() };
    p.set_nrt(2.0);
    p
}

/// The workload's world: no gravity, no ground, symplectic Euler, dt = [`DT`].
pub fn settings() -> WorldSettings {
    WorldSettings { gravity: 0.0, ground: None, integrator: Integrator::Symplectic, dt: DT, ..WorldSettings::default() }
}

/// The workload's body at `level`.
pub fn body(level: u32) -> SoftBody {
    // Vertices in the engine's locality order, as every loaded mesh (see `mesh::reorder`).
    let (mesh, _) = reorder::by_locality(&icosphere(level, 1.0));
    let n = mesh.vertex_count() as f64;
    SoftBody::new(&mesh, n * VERTEX_MASS, material()).expect("the standard workload is valid")
}

/// The workload at `level` as the one-body world that steps it.
pub fn world(level: u32) -> World {
    World::single(body(level), settings())
}
