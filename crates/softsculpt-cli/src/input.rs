//! Reading the INPUT argument: an `.obj` file or `builtin:NAME`.

use softsculpt::mesh::{builtin, LoadedMesh};
use std::path::Path;

/// Load and prepare a mesh; errors name the input and what is wrong with it.
pub fn load(input: &str) -> Result<LoadedMesh, String> {
    if let Some(name) = input.strip_prefix("builtin:") {
        return builtin::builtin(name).map(LoadedMesh::from_trimesh).map_err(|e| format!("{input}: {e}"));
    }
    let path = Path::new(input);
    let ext = path.extension().map(|e| e.to_string_lossy().to_lowercase());
    if path.is_dir() {
        return Err(format!("{input}: is a directory, not a mesh file"));
    }
    if !path.exists() {
        return Err(format!("{input}: no such file (give an .obj file or builtin:NAME, NAME one of {})", builtin::NAMES.join(", ")));
    }
    match ext.as_deref() {
        Some("obj") => {}
        Some(other) => return Err(format!("{input}: unsupported file type '.{other}' (only .obj is read)")),
        None => return Err(format!("{input}: no file extension (only .obj is read)")),
    }
    let bytes = std::fs::read(path).map_err(|e| format!("{input}: cannot read: {e}"))?;
    softsculpt::mesh::load_obj(&bytes).map_err(|e| format!("{input}: {e}"))
}

/// Print the loader's warnings on stderr.
pub fn warn(input: &str, mesh: &LoadedMesh) {
    for w in &mesh.report.warnings {
        eprintln!("warning: {input}: {w}");
    }
}
