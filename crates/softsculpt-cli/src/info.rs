//! `softsculpt info INPUT`: what a mesh is made of.

use crate::input;
use clap::Args;
use serde_json::json;
use softsculpt::mesh::quality::quality;

#[derive(Args, Debug)]
pub struct InfoArgs {
    /// Mesh: an .obj, .ply, .stl, .gltf or .glb file, or builtin:NAME.
    pub input: String,
    /// The file's up axis: z rotates a Z-up file to Y-up (x, y, z → x, z, −y); y keeps it.
    /// Units are never changed.
    #[arg(long, value_parser = input::parse_up, value_name = "y|z")]
    pub up: Option<softsculpt::mesh::UpAxis>,
    /// Print one JSON object instead of text.
    #[arg(long)]
    pub json: bool,
}

pub fn run(a: InfoArgs) -> Result<(), String> {
    let loaded = input::load(&a.input, a.up)?;
    let m = &loaded.mesh;
    let r = &loaded.report;
    let (lo, hi) = m.bounds();
    let closed = r.edges.boundary == 0 && r.edges.non_manifold == 0;
    let q = quality(m, None);
    if a.json {
        let v = json!({
            "input": a.input,
            "format": r.format.map_or("builtin", |f| f.name()),
            "vertices": m.vertex_count(),
            "faces": m.triangles.len(),
            "edges": r.edges.edges,
            "pieces": r.pieces,
            "source_vertices": r.source_vertices,
            "source_polygons": r.source_polygons,
            "welded_vertices": r.welded,
            "unreferenced_vertices": r.unreferenced,
            "degenerate_faces": r.degenerate_faces,
            "flipped_faces": r.flipped_faces,
            "boundary_edges": r.edges.boundary,
            "non_manifold_edges": r.edges.non_manifold,
            "closed": closed,
            // null for an open surface (no inside: the text says "not meaningful").
            "volume": closed.then(|| m.volume()),
            "bounds_min": lo,
            "bounds_max": hi,
            "up_axis": r.up_axis.name(),
            "rotated_to_y_up": r.up_rotated,
            "warnings": r.warnings,
            "quality": {
                "min_angle_deg": q.min_angle_deg,
                "max_angle_deg": q.max_angle_deg,
                "small_angle_share": q.small_angle_share,
                "edge_min": q.edge_min,
                "edge_mean": q.edge_mean,
                "edge_max": q.edge_max,
                "edge_spread": q.edge_spread,
                "edges_within_band_of_mean": q.edges_in_band,
                "poor": q.is_poor(),
            },
        });
        println!("{v}");
        return Ok(());
    }
    println!("input:               {}", a.input);
    println!("format:              {}", r.format.map_or("built-in model", |f| f.name()));
    println!("vertices:            {} (source {})", m.vertex_count(), r.source_vertices);
    println!("faces:               {} triangles (source {} polygons)", m.triangles.len(), r.source_polygons);
    println!("edges:               {}", r.edges.edges);
    println!("pieces:              {}", r.pieces);
    println!("welded vertices:     {} (seams)", r.welded);
    println!("unused vertices:     {}", r.unreferenced);
    println!("degenerate faces:    {}", r.degenerate_faces);
    println!("re-oriented faces:   {}", r.flipped_faces);
    println!("boundary edges:      {}", r.edges.boundary);
    println!("non-manifold edges:  {}", r.edges.non_manifold);
    println!("closed:              {}", if closed { "yes" } else { "no (gas cannot be used)" });
    println!("volume:              {} m^3{}", m.volume(), if closed { "" } else { " (not meaningful: open surface)" });
    println!("up axis:             {}", input::up_text(&loaded));
    println!("bounding box:        [{}, {}, {}] .. [{}, {}, {}] m", lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]);
    println!("triangle quality:    {}", crate::remesh::summary(&q).replace(" within", " of edges within").replace("×", "× the mean"));
    if q.is_poor() {
        println!("                     poor for springs: try softsculpt remesh {} {} --out OUT", a.input, remesh_flags(m, q.edge_mean));
    }
    Ok(())
}

/// Meshes up to this many triangles are remeshed by `info` to find the edge that keeps their
/// shape (a fraction of a second); larger ones are suggested their mean edge.
const TRIED_UP_TO: usize = 20_000;

/// The `remesh` flags `info` suggests for a poor mesh: the edge (and crease) `remesh` would
/// settle on — the mean edge, or the shorter one that keeps the shape
/// (`remesh_keeping_shape`, tried here on meshes up to [`TRIED_UP_TO`] triangles), so the
/// suggestion is not then called too coarse (an 8-vertex tower: suggested 0.064, remeshed at
/// 0.016 keeping its edges).
fn remesh_flags(m: &softsculpt::mesh::TriMesh, mean: f64) -> String {
    use softsculpt::mesh::remesh::remesh_keeping_shape;
    let tried = (m.triangles.len() <= TRIED_UP_TO).then(|| remesh_keeping_shape(m, mean, None).ok()).flatten();
    match tried.map(|k| k.report) {
        Some(r) => format!("--edge {}{}", softsculpt::world::sig3(r.edge), r.crease_deg.map_or(String::new(), |c| format!(" --crease {c}"))),
        None => format!("--edge {}", softsculpt::world::sig3(mean)),
    }
}

