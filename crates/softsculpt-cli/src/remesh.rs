//! `softsculpt remesh IN --edge L --out OUT`: isotropic remeshing to a target edge length.

use crate::{args, input, output};
use clap::Args;
use softsculpt::mesh::quality::{quality, Quality};
use softsculpt::mesh::remesh;
use std::path::PathBuf;

#[derive(Args, Debug)]
pub struct RemeshArgs {
    /// Mesh: an .obj, .ply, .stl, .gltf or .glb file, or builtin:NAME.
    pub input: String,
    /// Target edge length [m]: positive, at most the mesh's bounding-box diagonal, and long
    /// enough to make at most 2 M triangles.
    #[arg(long, value_parser = args::finite, value_name = "L", allow_hyphen_values = true)]
    pub edge: f64,
    /// Where to write the result, atomically; the extension chooses the format: .obj, .ply,
    /// .stl or .glb.
    #[arg(long, value_name = "FILE")]
    pub out: PathBuf,
    /// Keep creases: edges whose faces' normals differ by more than DEG degrees stay (off: sharp
    /// edges are remeshed like the rest, which makes the most regular mesh).
    #[arg(long, value_parser = args::finite, value_name = "DEG")]
    pub crease: Option<f64>,
    /// The file's up axis: z reads a Z-up file (the output is written Z-up too); y keeps it.
    #[arg(long, value_parser = input::parse_up, value_name = "y|z")]
    pub up: Option<softsculpt::mesh::UpAxis>,
    /// The output's up axis (default: the input's, --up): z writes it Z-up (Blender's PLY and
    /// STL importers), y Y-up.
    #[arg(long = "out-up", value_parser = input::parse_up, value_name = "y|z")]
    pub out_up: Option<softsculpt::mesh::UpAxis>,    /// Off a terminal, print a progress line every 5 s on stderr (on a terminal a bar shows anyway).
    #[arg(long)]
    pub progress: bool,
}

pub fn run(a: RemeshArgs) -> Result<(), String> {
    let format = input::out_format(&a.out)?;
    input::out_up(a.out_up, a.up, format)?;
    if let Some(c) = a.crease {
        if !(c > 0.0 && c < 180.0) {
            return Err(format!("--crease {c}: the crease angle is in degrees, between 0 and 180"));
        }
    }
    let loaded = input::load(&a.input, a.up)?;
    input::warn(&a.input, &loaded);
    remesh::check_edge_length(&loaded.mesh, a.edge).map_err(|e| format!("--edge: {e}"))?;
    // The shape is kept or the remesh refused (mesh::remesh::remesh_keeping_shape): a mesh too
    // coarse for --edge is remeshed at a half or a quarter of it, and says so.
    let spin = crate::progress::Progress::spinner(&format!("remeshing {} at edge {} m", a.input, a.edge), true, a.progress);
    let kept = remesh::remesh_keeping_shape(&loaded.mesh, a.edge, a.crease);
    spin.finish();
    let kept = kept.map_err(|e| format!("{}: {e}", a.input))?;
    let (out, r) = (kept.mesh, kept.report);
    // The header names what made the file (the edge and crease angle used), so the command it
    // shows makes it again.
    let crease = r.crease_deg.map(|c| format!(" --crease {c}")).unwrap_or_default();
    let header = format!("SoftSculpt remesh {} --edge {}{crease}", a.input, r.edge);
    output::write_mesh(&a.out, format, &out, &header, input::out_up(a.out_up, a.up, format)?)?;
    let (q0, q1) = (quality(&loaded.mesh, Some(r.edge)), quality(&out, Some(r.edge)));
    if r.shortened() {
        let creases = if a.crease.is_none() && r.crease_deg.is_some() { format!(", keeping edges sharper than {}°", remesh::CREASE) } else { String::new() };
        eprintln!("note: --edge {} would have changed the shape (the mesh is too coarse for it): remeshed at edge {} m{creases}", a.edge, r.edge);
    }
    eprintln!(
        "wrote {}: {} -> {} triangles, volume {:.6} -> {:.6} m^3, surface moved by at most {:.3e} m",
        a.out.display(),
        loaded.mesh.triangles.len(),
        out.triangles.len(),
        loaded.mesh.volume(),
        out.volume(),
        r.departure.distance()
    );
    eprintln!("  before: {}", summary(&q0));
    eprintln!("  after:  {}", summary(&q1));
    Ok(())
}

/// One line of triangle quality, about the target length.
pub fn summary(q: &Quality) -> String {
    format!(
        "min angle {:.1}°, {:.1} % of angles below 25°, edges {:.4}..{:.4} m (mean {:.4}, spread {:.0} %), {:.1} % within 0.75–1.33×",
        q.min_angle_deg,
        100.0 * q.small_angle_share,
        q.edge_min,
        q.edge_max,
        q.edge_mean,
        100.0 * q.edge_spread,
        100.0 * q.edges_in_band
    )
}
