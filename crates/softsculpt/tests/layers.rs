//! No circles between the core's modules (issue #39): they form layers, and a module imports
//! only from its own layer or the ones below it. Lowest first:
//!
//! 0. `vec3`, `geometry`, `hash`, `error`, `par`: leaf utilities (vector arithmetic, closest
//!    points, hashing, the error types with their messages and checks, threads), which know
//!    nothing of meshes, bodies or worlds.
//! 1. `mesh`, `params`: plain data built on the utilities: a triangle mesh and its formats; the
//!    parameter table (defaults, units, ranges, the presets' values) that everything above reads.
//! 2. `obstacles`: rigid shapes (spheres, boxes, capsules, triangle meshes) made from meshes,
//!    with the table's default friction.
//! 3. `settings`: what a world imposes on every body (gravity, wind, ground, obstacles,
//!    integrator, dt, contacts): it holds obstacles and takes its defaults from the table.
//! 4. `body`: a soft body, stepped with the settings it is handed.
//! 5. `world`: the unit of simulation, which owns bodies and settings and runs the step.
//! 6. `scene`, `snapshot`, `delta`, `workload`, `sketch`, `compat`, and the crate root `lib`:
//!    they build, save, load, compare or drive whole worlds.
//!
//! Modules of one layer may import each other (`delta` and `compat` import `snapshot`; none of
//! them imports back).
//!
//! The sub-modules of `snapshot` are its format's versions, each built on the one before
//! (`SNAPSHOT_LAYERS`): `v1` (versions 1 and 2), `v3` … `v7`, then `mod` (the header, the
//! policy, the reader that dispatches on the version). A version's file reads and writes its
//! own extension and the payload below it; it never imports a newer version or `mod`. Before
//! issue #39 they were `snapshot_v3` … `snapshot_v7` beside `snapshot.rs`, which imported them
//! and was imported back for the older versions' types.
//!
//! The sub-modules of `mesh` form layers the same way (`MESH_LAYERS`; `mesh/mod.rs` only
//! declares them and re-exports their names). Lowest first:
//!
//! 0. `obj`, `topology`, `weld`: a file's polygons as read (`ObjData`, and the OBJ text format),
//!    edges and orientation of triangles, welding coincident points: they import nothing of
//!    `mesh`.
//! 1. `trimesh`, `format`: the triangle mesh (`TriMesh`, `bounds`); what a format is (`MeshFormat`,
//!    its signature, `UpAxis`, the axis rotations, `WriteOptions`, the fans every triangle-only
//!    writer makes), which every format's reader and writer shares.
//! 2. `ply`, `stl`, `gltf`, `reorder`, `pieces`, `quality`, `subdivide`, `remesh`: one format
//!    read and written; one operation on a `TriMesh`.
//! 3. `loaded`, `animation`: a source's polygons made ready to simulate (`prepare`,
//!    `LoadedMesh`, `MeshReport`); frames written as an animated GLB (through `gltf`).
//! 4. `file`, `builtin`: any format read into a `LoadedMesh` and written back (`load`,
//!    `LoadedMesh::write`); the built-in models (one is an OBJ file, read by `load_obj`).
//! 5. `mod`: `mesh/mod.rs`, the declarations and re-exports.
//!
//! Before issue #39, `format` (the formats and the dispatch to their readers) imported `gltf` and
//! `stl`, which imported `format` back for `MeshFormat` and the fans; and `mesh/mod.rs` defined
//! `TriMesh` and `prepare`, imported by the sub-modules it imported. Now the dispatch is `file`,
//! above the readers, and what they share is `format`, below them.
//!
//! What counts as an import (`support/imports.rs`): every `crate::` path (in `use` lines and
//! inline) with its groups expanded, every `super::` path resolved from the file's module, and a
//! name a module's file re-exports (`lib.rs`'s or `mesh/mod.rs`'s `pub use`) as the module it
//! comes from. Only code counts: a file is read up to its `#[cfg(test)]` line (tests may use
//! anything), and `//` comments are skipped (a doc comment may name or link a higher module
//! without depending on it).

#[path = "support/imports.rs"]
mod imports;

use imports::{imports, module_path, module_under, root_names, sources, Level};
use std::path::{Path, PathBuf};

/// The layers, lowest first (see the module documentation for why each is where it is).
const LAYERS: &[&[&str]] = &[
    &["vec3", "geometry", "hash", "error", "par"],
    &["mesh", "params"],
    &["obstacles"],
    &["settings"],
    &["body"],
    &["world"],
    &["scene", "snapshot", "delta", "workload", "sketch", "compat", "lib"],
];

/// The versions of the snapshot format, oldest first (`mod`: `snapshot/mod.rs`; see the
/// module documentation).
const SNAPSHOT_LAYERS: &[&[&str]] = &[&["v1"], &["v3"], &["v4"], &["v5"], &["v6"], &["v7"], &["mod"]];

/// The layers of `mesh`'s sub-modules, lowest first (`mod`: `mesh/mod.rs`; see the module
/// documentation).
const MESH_LAYERS: &[&[&str]] = &[
    &["obj", "topology", "weld"],
    &["trimesh", "format"],
    &["ply", "stl", "gltf", "reorder", "pieces", "quality", "subdivide", "remesh"],
    &["loaded", "animation"],
    &["file", "builtin"],
    &["mod"],
];

fn src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

#[test]
fn no_module_imports_one_above_it() {
    let files = sources(&src());
    let problems = Level::new(&files, &[], "lib").layer_problems(LAYERS, "LAYERS in tests/layers.rs");
    assert!(problems.is_empty(), "{} imports from a higher layer (see tests/layers.rs):\n{}", problems.len(), problems.join("\n"));
}

#[test]
fn no_mesh_module_imports_one_above_it() {
    let files = sources(&src());
    let mesh = Level::new(&files, &["mesh"], "mod");
    assert!(mesh.modules.len() > 10 && mesh.modules.contains(&"format".to_string()), "the sub-modules of mesh were not found: {:?}", mesh.modules);
    let problems = mesh.layer_problems(MESH_LAYERS, "MESH_LAYERS in tests/layers.rs");
    assert!(problems.is_empty(), "{} imports from a higher layer of mesh (see tests/layers.rs):\n{}", problems.len(), problems.join("\n"));
}

#[test]
fn no_snapshot_version_imports_a_newer_one() {
    let files = sources(&src());
    let snapshot = Level::new(&files, &["snapshot"], "mod");
    assert_eq!(snapshot.modules.len(), 6, "the versions of snapshot were not found: {:?}", snapshot.modules);
    let problems = snapshot.layer_problems(SNAPSHOT_LAYERS, "SNAPSHOT_LAYERS in tests/layers.rs");
    assert!(problems.is_empty(), "{} imports of a newer snapshot version (see tests/layers.rs):\n{}", problems.len(), problems.join("\n"));
}

/// The scan reads what the compiler would: paths in `use` lines and inline, groups across
/// lines and nested, `super::` resolved from the file's module, re-exports; not comments, not
/// tests, not paths that merely end in `crate::`-like text.
#[test]
fn the_scan_reads_every_kind_of_import_but_not_comments_or_tests() {
    let modules: Vec<String> = ["body", "mesh", "world", "settings", "error"].map(String::from).to_vec();
    let roots = root_names("pub use body::{Material, SoftBody};\npub use world::{World as W, Advance};\n");
    assert_eq!(roots.get("SoftBody").map(String::as_str), Some("body"));
    assert_eq!(roots.get("W").map(String::as_str), Some("world"));
    let text = "\
//! Stepped by a [`crate::world::World`].
use crate::settings::WorldSettings;
use crate::{
    mesh::TriMesh,
    SoftBody,
};
use super::super::error::SimError;
use super::sibling;
fn f() -> f64 { crate::world::sig3(1.0); $crate::mesh::x(); my_crate::world::y(); 0.0 } // crate::body
pub(crate) fn g(_: &crate::Unknown) {}
#[cfg(test)]
mod tests {
    use crate::world::World;
}
";
    let path = ["body".to_string(), "implicit".to_string()];
    let found = imports(&path, text);
    let got: Vec<(usize, String)> = found.iter().filter_map(|i| Some((i.line, module_under(&[], &i.path, &modules, &roots)?))).collect();
    let want = [(2, "settings"), (4, "mesh"), (5, "body"), (7, "error"), (8, "body"), (9, "world"), (10, "?Unknown")];
    assert_eq!(got, want.map(|(l, m)| (l, m.to_string())).to_vec());
    assert_eq!(module_path(Path::new("world/mod.rs")), ["world"]);
    assert_eq!(module_path(Path::new("body/implicit/ground.rs")), ["body", "implicit", "ground"]);
    assert!(module_path(Path::new("lib.rs")).is_empty());

    // One level down: a sub-module's imports of its siblings, through `super::`, `crate::mesh::`
    // and nested groups, and names the parent re-exports.
    let mesh = ["mesh".to_string()];
    let children: Vec<String> = ["format", "obj", "trimesh", "stl"].map(String::from).to_vec();
    let roots = root_names("pub use trimesh::{bounds, TriMesh};\npub use obj::ObjData;\n");
    let text = "\
use super::format::{fan_triangles, MeshFormat};
use super::{obj::{self, ObjData as Polygons}, TriMesh};
use crate::error::MeshError;
use crate::mesh::{stl, Defined};
fn f() { super::super::mesh::bounds(&[]); }
";
    let path = ["mesh".to_string(), "gltf".to_string()];
    let got: Vec<(usize, String)> = imports(&path, text).iter().filter_map(|i| Some((i.line, module_under(&mesh, &i.path, &children, &roots)?))).collect();
    let want = [(1, "format"), (1, "format"), (2, "obj"), (2, "obj"), (2, "trimesh"), (4, "stl"), (4, "?Defined"), (5, "trimesh")];
    assert_eq!(got, want.map(|(l, m)| (l, m.to_string())).to_vec());
    let path = ["mesh".to_string(), "remesh".to_string(), "project".to_string()];
    let got: Vec<Vec<String>> = imports(&path, "fn f() { super::super::bounds(&[]); }\n").into_iter().map(|i| i.path).collect();
    assert_eq!(got, [["mesh", "bounds"].map(String::from).to_vec()]);
}
