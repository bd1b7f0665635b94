//! `softsculpt sketch OUTLINE.txt --out OUT.obj [--edge L] [--gas NRT]`: an outline becomes an
//! inflated balloon.

use crate::{args, input, output};
use clap::Args;
use softsculpt::sketch::{outline, sketch, Outline};
use std::path::PathBuf;

#[derive(Args, Debug)]
pub struct SketchArgs {
    /// The outline: lines of `x y` (metres), a closed polygon in the xy plane (`#` comments).
    pub outline: PathBuf,
    /// Where to write the inflated body, atomically; the extension chooses the format: .obj,
    /// .ply, .stl or .glb.
    #[arg(long, value_name = "FILE")]
    pub out: PathBuf,
    /// Target edge length [m] (default √(area / 150): about 350 triangles a side).
    #[arg(long, value_parser = args::finite, value_name = "L", allow_hyphen_values = true)]
    pub edge: Option<f64>,
    /// Gas as the product nRT [J] (default: the amount that stretches the skin about 2 %).
    #[arg(long, value_parser = args::finite, value_name = "NRT", allow_hyphen_values = true)]
    pub gas: Option<f64>,    /// Off a terminal, print a progress line every 5 s on stderr (on a terminal a bar shows anyway).
    #[arg(long)]
    pub progress: bool,
}

pub fn run(a: SketchArgs) -> Result<(), String> {
    let format = input::out_format(&a.out)?;
    let name = a.outline.display().to_string();
    let text = input::read_file(&a.outline, &name)?;
    let text = String::from_utf8(text).map_err(|_| format!("{name}: not a text file (lines of 'x y')"))?;
    let points = outline::parse(&text).map_err(|e| format!("{name}: {e}"))?;
    let o = Outline::new(&points).map_err(|e| format!("{name}: {e}"))?;
    if let Some(g) = a.gas {
        if !(g > 0.0) {
            return Err(format!("--gas {g}: a sketch needs gas to inflate (nRT > 0 J)"));
        }
    }
    let spin = crate::progress::Progress::spinner(&format!("sketching {name}"), true, a.progress);
    let s = sketch(&o, a.edge, a.gas);
    spin.finish();
    let s = s.map_err(|e| format!("{name}: {e}"))?;
    let header = format!("SoftSculpt sketch {name} — edge {:.4} m, gas nRT {:.4} J", s.edge, s.nrt);
    output::write_mesh(&a.out, format, &s.mesh, &header, softsculpt::mesh::UpAxis::Y)?;
    eprintln!(
        "wrote {}: {} vertices, {} faces, edge {:.4} m, gas {:.4} J, volume {:.6} m^3, {} steps{}",
        a.out.display(),
        s.mesh.vertex_count(),
        s.mesh.triangles.len(),
        s.edge,
        s.nrt,
        s.mesh.volume(),
        s.steps,
        if s.at_rest { " (at rest)" } else { " (not yet at rest: the step limit)" }
    );
    Ok(())
}
