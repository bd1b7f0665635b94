//! Reading mesh files of every format into bodies, the modeler's preset at a model's size, and
//! the animation file of a recording: delegations to `softsculpt::mesh` and
//! `softsculpt::params::similarity`.

use crate::abi::exports;
use crate::handle::with_world;
use crate::fails::{mesh_fail, param_fail};
use crate::world::add;
use crate::{bytes, index, set_result, status, text, Fail};
use softsculpt::mesh::{self, animation, pieces, MeshFormat};
use crate::report::{self, reports};
use serde_json::json;

reports! {
    /// What a mesh file held (`ss_add_file`): its format, the up axis it declares, its pieces.
    pub struct FileReport {
        /// The format read (`OBJ`, `PLY`, `STL`, `glTF`, `GLB`), or null.
        pub format: Option<&'static str>,
        /// 'y' (glTF says so) or 'unknown' (OBJ, PLY, STL).
        #[ts = "'y' | 'z' | 'unknown'"]
        pub up_axis: &'static str,
        /// Its pieces (one body each when split), largest area first.
        pub pieces: Vec<PieceReport>,
        pub boundary_edges: usize,
        pub non_manifold_edges: usize,
        /// What the reader mended or doubts, a line each.
        pub warnings: Vec<String>,
    }

    /// One piece of a mesh file (`FileReport.pieces`): its size (area in m²) and whether it is
    /// closed.
    pub struct PieceReport {
        pub vertices: usize,
        pub faces: usize,
        pub area: f64,
        pub closed: bool,
        pub boundary_edges: usize,
    }
}

exports! {
    /// A mesh file (`name`'s extension says its format, else its first bytes) read like the CLI
    /// reads it (`softsculpt::mesh::load`: weld, checks, orientation, pieces): one body of `mass` kg,
    /// or with `split` = 1 one body per piece, largest area first, each of `mass` kg. Returns the
    /// first body's index; result: `{format, up_axis, pieces: [{vertices, faces, area, closed,
    /// boundary_edges}], boundary_edges, non_manifold_edges, warnings}`. Nothing is rotated: the
    /// page asks the up axis.
    ///
    /// # Safety
    /// `name` must point to `name_len` bytes and `ptr` to `len` bytes.
    pub unsafe fn ss_add_file(w: u32, name: *const u8, name_len: usize, ptr: *const u8, len: usize, split: u32, mass: f64) -> i32 {
        index(|| {
            let name = text(name, name_len, "the file name")?;
            let loaded = mesh::load(bytes(ptr, len), MeshFormat::from_path(name)).map_err(mesh_fail)?;
            let parts = if split == 1 { pieces::split(&loaded.mesh) } else { vec![loaded.mesh.clone()] };
            let r = &loaded.report;
            let report = FileReport {
                format: r.format.map(|f| f.name()),
                up_axis: r.up_axis.name(),
                pieces: parts
                    .iter()
                    .map(|p| PieceReport {
                        vertices: p.vertex_count(),
                        faces: p.triangles.len(),
                        area: pieces::area(&p.positions, &p.triangles),
                        closed: p.is_closed(),
                        boundary_edges: p.edge_counts().boundary,
                    })
                    .collect(),
                boundary_edges: r.edges.boundary,
                non_manifold_edges: r.edges.non_manifold,
                warnings: r.warnings.clone(),
            };
            let mut first = None;
            for p in &parts {
                let b = add(w, p, mass, &[])?;
                first.get_or_insert(b);
            }
            set_result(report::json(&report));
            first.ok_or_else(|| Fail::usage("the file has no pieces"))
        })
    }

    /// `World::apply_preset_scaled`: preset `name` for a model `size` times as large as the one it was
    /// tuned for (similarity, `softsculpt::params::similarity`); result: the gas parameters skipped
    /// because the body is open (JSON array).
    ///
    /// # Safety
    /// `name` must point to `len` bytes.
    pub unsafe fn ss_apply_preset_scaled(w: u32, b: u32, name: *const u8, len: usize, size: f64) -> i32 {
        status(|| {
            let name = text(name, len, "the preset name")?;
            let skipped = with_world(w, |h| h.world.apply_preset_scaled(b as usize, name, size).map_err(param_fail))?;
            set_result(json!(skipped).to_string().into_bytes());
            Ok(())
        })
    }

    /// The GLB of a recording (`softsculpt::mesh::animation`, the format of `softsculpt run
    /// --frames`): `n_frames` times (s); per track `counts` holds (vertices, triangles); `tris` the
    /// tracks' triangles one after the other (u32, 3 per triangle, per track's vertices); `frames`
    /// per track its `n_frames` frames of xyz (f32), one track after the other. Result: the bytes.
    ///
    /// # Safety
    /// The pointers must hold the counts they are said to hold.
    pub unsafe fn ss_animation_glb(times: *const f64, n_frames: usize, counts: *const u32, n_tracks: usize, tris: *const u32, frames: *const f32) -> i32 {
        status(|| {
            if n_frames == 0 || n_tracks == 0 || times.is_null() || counts.is_null() || tris.is_null() || frames.is_null() {
                return Err(Fail::usage("an animation needs at least one frame and one track"));
            }
            let times = std::slice::from_raw_parts(times, n_frames);
            let counts = std::slice::from_raw_parts(counts, 2 * n_tracks);
            let (nv, nt): (usize, usize) = counts.chunks_exact(2).fold((0, 0), |(a, b), c| (a + c[0] as usize, b + c[1] as usize));
            let tris = std::slice::from_raw_parts(tris, 3 * nt);
            let frames = std::slice::from_raw_parts(frames, 3 * nv * n_frames);
            let names: Vec<String> = (0..n_tracks).map(|k| if k == 0 { "softsculpt".into() } else { format!("softsculpt.{k:03}") }).collect();
            let mut data = Vec::with_capacity(n_tracks);
            let (mut at_t, mut at_f) = (0, 0);
            for c in counts.chunks_exact(2) {
                let (v, t) = (c[0] as usize, c[1] as usize);
                let triangles: Vec<[u32; 3]> = tris[3 * at_t..3 * (at_t + t)].chunks_exact(3).map(|x| [x[0], x[1], x[2]]).collect();
                if triangles.iter().flatten().any(|&i| i as usize >= v) {
                    return Err(mesh_fail(softsculpt::error::MeshError::Invalid("a triangle refers to a vertex the track does not have".into())));
                }
                let fs: Vec<Vec<f64>> = (0..n_frames).map(|k| frames[at_f + 3 * v * k..at_f + 3 * v * (k + 1)].iter().map(|&x| x as f64).collect()).collect();
                data.push((triangles, fs));
                at_t += t;
                at_f += 3 * v * n_frames;
            }
            let tracks: Vec<animation::Track> = data.iter().zip(&names).map(|((t, f), n)| animation::Track { name: n, triangles: t, frames: f }).collect();
            set_result(animation::animation_glb(&tracks, times, "SoftSculpt modeler"));
            Ok(())
        })
    }
}
