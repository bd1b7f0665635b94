//! Triangle meshes: reading, checking, welding, orienting, built-in models.
//!
//! The sub-modules form layers, each importing only from the ones below it (the order and why:
//! `tests/layers.rs`, `MESH_LAYERS`). This file only declares them and re-exports the names the
//! rest of the crate uses (`mesh::TriMesh`, `mesh::load`, …).

pub mod builtin;
pub mod file;
pub mod format;
pub mod gltf;
pub mod animation;
pub mod loaded;
pub mod obj;
pub mod pieces;
pub mod ply;
pub mod quality;
pub mod remesh;
pub mod reorder;
pub mod stl;
pub mod subdivide;
pub mod topology;
pub mod trimesh;
pub mod weld;

pub use file::load;
pub use format::{MeshFormat, UpAxis};
pub use loaded::{load_obj, prepare, LoadedMesh, MeshReport, WELD_RELATIVE_TOLERANCE};
pub use obj::ObjData;
pub use topology::EdgeCounts;
pub use trimesh::{bounds, TriMesh};
