//! `softsculpt info INPUT`: what a mesh is made of.

use crate::input;
use clap::Args;
use serde_json::json;

#[derive(Args, Debug)]
pub struct InfoArgs {
    /// Mesh: an .obj file or builtin:NAME.
    pub input: String,
    /// Print one JSON object instead of text.
    #[arg(long)]
    pub json: bool,
}

pub fn run(a: InfoArgs) -> Result<(), String> {
    let loaded = input::load(&a.input)?;
    let m = &loaded.mesh;
    let r = &loaded.report;
    let (lo, hi) = m.bounds();
    let closed = r.edges.boundary == 0 && r.edges.non_manifold == 0;
    if a.json {
        let v = json!({
            "input": a.input,
            "vertices": m.vertex_count(),
            "faces": m.triangles.len(),
            "edges": r.edges.edges,
            "source_vertices": r.source_vertices,
            "source_polygons": r.source_polygons,
            "welded_vertices": r.welded,
            "unreferenced_vertices": r.unreferenced,
            "degenerate_faces": r.degenerate_faces,
            "flipped_faces": r.flipped_faces,
            "boundary_edges": r.edges.boundary,
            "non_manifold_edges": r.edges.non_manifold,
            "closed": closed,
            "volume": m.volume(),
            "bounds_min": lo,
            "bounds_max": hi,
            "warnings": r.warnings,
        });
        println!("{v}");
        return Ok(());
    }
    println!("input:               {}", a.input);
    println!("vertices:            {} (source {})", m.vertex_count(), r.source_vertices);
    println!("faces:               {} triangles (source {} polygons)", m.triangles.len(), r.source_polygons);
    println!("edges:               {}", r.edges.edges);
    println!("welded vertices:     {}", r.welded);
    println!("unused vertices:     {}", r.unreferenced);
    println!("degenerate faces:    {}", r.degenerate_faces);
    println!("re-oriented faces:   {}", r.flipped_faces);
    println!("boundary edges:      {}", r.edges.boundary);
    println!("non-manifold edges:  {}", r.edges.non_manifold);
    println!("closed:              {}", if closed { "yes" } else { "no (gas cannot be used)" });
    println!("volume:              {} m^3{}", m.volume(), if closed { "" } else { " (not meaningful: open surface)" });
    println!("bounding box:        [{}, {}, {}] .. [{}, {}, {}] m", lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]);
    Ok(())
}
