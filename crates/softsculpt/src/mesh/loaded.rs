//! A mesh as loaded: a source's polygons ([`ObjData`], from any format) turned into a mesh ready
//! to simulate ([`prepare`]: weld, drop degenerate faces, orient, reorder), with the report of
//! what was found and repaired and the map back to the source's own layout.

use super::format::{MeshFormat, UpAxis};
use super::obj::{self, ObjData};
use super::topology::{self, EdgeCounts};
use super::trimesh::{bounds, TriMesh};
use super::{reorder, weld};
use crate::error::MeshError;
use crate::vec3::{cross, get, norm, sub};

/// What loading found and repaired.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct MeshReport {
    /// Vertices and polygons in the source.
    pub source_vertices: usize,
    pub source_polygons: usize,
    /// Vertices merged into an earlier coincident vertex.
    pub welded: usize,
    /// Source vertices no face uses (kept in the output file, not simulated).
    pub unreferenced: usize,
    /// Triangles dropped because they had zero area or repeated a vertex.
    pub degenerate_faces: usize,
    /// Faces whose winding was reversed to make the surface consistent and outward.
    pub flipped_faces: usize,
    /// Edge statistics of the final mesh.
    pub edges: EdgeCounts,
    /// Connected pieces (shells) of the final mesh: separate surfaces sharing no vertex.
    pub pieces: usize,
    /// The file's format (`None` for a generated mesh).
    pub format: Option<MeshFormat>,
    /// The up axis: what the format says (glTF: Y), else unknown (taken as Y-up), or what
    /// [`LoadedMesh::set_up_axis`] was told.
    pub up_axis: UpAxis,
    /// The mesh was rotated from Z-up to Y-up.
    pub up_rotated: bool,
    /// Human-readable warnings (one line each).
    pub warnings: Vec<String>,
}

/// A mesh ready to simulate, plus what is needed to write it back in the source's own layout.
#[derive(Debug, Clone)]
pub struct LoadedMesh {
    pub mesh: TriMesh,
    pub report: MeshReport,
    /// The source file's polygons (unchanged) and, for each source vertex, the simulated vertex
    /// it became (`u32::MAX` if no face uses it).
    pub source: ObjData,
    pub source_to_mesh: Vec<u32>,
}

impl LoadedMesh {
    /// A generated mesh (its own source: written back in its own vertex order).
    pub fn from_trimesh(mesh: TriMesh) -> Self {
        let (ordered, old_to_new) = reorder::by_locality(&mesh);
        let source = ObjData {
            positions: mesh.positions.clone(),
            indices: mesh.triangles.iter().flatten().copied().collect(),
            arities: vec![3; mesh.triangles.len()],
        };
        let report = MeshReport {
            source_vertices: mesh.vertex_count(),
            source_polygons: mesh.triangles.len(),
            edges: mesh.edge_counts(),
            pieces: topology::count_pieces(&mesh.triangles, mesh.vertex_count()),
            ..Default::default()
        };
        LoadedMesh { mesh: ordered, report, source, source_to_mesh: old_to_new }
    }
}

/// Relative tolerance for welding and degenerate faces, times the bounding-box diagonal.
pub const WELD_RELATIVE_TOLERANCE: f64 = 1e-9;

/// Turn parsed OBJ data into a simulation mesh: triangulate (fans), weld coincident vertices,
/// drop degenerate faces, drop unused vertices, orient consistently and outward, and order the
/// vertices for memory locality ([`reorder`](super::reorder)).
pub fn prepare(source: ObjData) -> Result<LoadedMesh, MeshError> {
    let ns = source.vertex_count();
    let mut report = MeshReport { source_vertices: ns, source_polygons: source.arities.len(), ..Default::default() };
    let (lo, hi) = bounds(&source.positions);
    let diag = norm(sub(hi, lo));
    if !(diag > 0.0) {
        return Err(MeshError::Invalid("all vertices coincide: the mesh has no extent".into()));
    }
    let tol = WELD_RELATIVE_TOLERANCE * diag;
    let rep = weld::weld(&source.positions, tol);

    // Triangulate as fans and weld; drop triangles that repeat a vertex or have (near) zero area.
    let area_tol = tol * diag; // |(b−a)×(c−a)| below this is a sliver of width ~tol
    let mut tris = Vec::with_capacity(source.indices.len());
    for poly in source.polygons() {
        for k in 1..poly.len() - 1 {
            let t = [rep[poly[0] as usize], rep[poly[k] as usize], rep[poly[k + 1] as usize]];
            let (a, b, c) = (get(&source.positions, t[0] as usize), get(&source.positions, t[1] as usize), get(&source.positions, t[2] as usize));
            if t[0] == t[1] || t[1] == t[2] || t[0] == t[2] || norm(cross(sub(b, a), sub(c, a))) <= area_tol {
                report.degenerate_faces += 1;
            } else {
                tris.push(t);
            }
        }
    }
    if tris.is_empty() {
        return Err(MeshError::Empty("every face is degenerate (zero area): nothing to simulate".into()));
    }

    // Keep only referenced representatives, in source order.
    let mut used = vec![false; ns];
    for t in &tris {
        for &i in t {
            used[i as usize] = true;
        }
    }
    let mut compact = vec![u32::MAX; ns];
    let mut positions = Vec::new();
    for i in 0..ns {
        if used[i] {
            compact[i] = (positions.len() / 3) as u32;
            positions.extend_from_slice(&source.positions[3 * i..3 * i + 3]);
        }
    }
    for t in &mut tris {
        for i in t.iter_mut() {
            *i = compact[*i as usize];
        }
    }
    let source_to_mesh: Vec<u32> = (0..ns).map(|i| compact[rep[i] as usize]).collect();
    report.welded = (0..ns).filter(|&i| rep[i] as usize != i && compact[rep[i] as usize] != u32::MAX).count();
    report.unreferenced = source_to_mesh.iter().filter(|&&m| m == u32::MAX).count();

    let before = topology::count_edges(&tris);
    report.flipped_faces = topology::orient_outward(&mut tris, &positions)?;
    report.edges = topology::count_edges(&tris);
    report.pieces = topology::count_pieces(&tris, positions.len() / 3);

    if report.welded > 0 {
        report.warnings.push(format!("welded {} duplicated vertices (seams)", report.welded));
    }
    if report.degenerate_faces > 0 {
        report.warnings.push(format!("dropped {} degenerate faces (zero area or repeated vertex)", report.degenerate_faces));
    }
    if report.unreferenced > 0 {
        report.warnings.push(format!("{} vertices are used by no face and are not simulated", report.unreferenced));
    }
    if before.inconsistent > 0 || report.flipped_faces > 0 {
        report.warnings.push(format!(
            "re-oriented {} faces ({} edges had inconsistent winding) so that normals point outward",
            report.flipped_faces, before.inconsistent
        ));
    }
    if report.pieces > 1 {
        report.warnings.push(format!("the mesh is {} separate pieces (sharing no vertex), simulated as one body", report.pieces));
    }
    if report.edges.boundary > 0 {
        report.warnings.push(format!("the surface is open: {} boundary edges", report.edges.boundary));
    }
    if report.edges.non_manifold > 0 {
        report.warnings.push(format!("{} non-manifold edges (shared by more than two faces)", report.edges.non_manifold));
    }
    let (mesh, old_to_new) = reorder::by_locality(&TriMesh { positions, triangles: tris });
    let source_to_mesh = source_to_mesh.into_iter().map(|m| if m == u32::MAX { m } else { old_to_new[m as usize] }).collect();
    Ok(LoadedMesh { mesh, report, source, source_to_mesh })
}

/// Parse OBJ bytes and prepare the mesh.
pub fn load_obj(bytes: &[u8]) -> Result<LoadedMesh, MeshError> {
    prepare(obj::parse(bytes)?)
}
