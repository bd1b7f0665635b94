//! Reading the INPUT argument: a mesh file (OBJ, PLY, STL, glTF, GLB) or `builtin:NAME`.

use softsculpt::mesh::format::READ_EXTENSIONS;
use softsculpt::mesh::{builtin, LoadedMesh, MeshFormat, UpAxis};
use std::path::Path;

/// `--up y|z`.
pub fn parse_up(s: &str) -> Result<UpAxis, String> {
    UpAxis::from_name(s).ok_or_else(|| format!("unknown up axis '{s}' (use y or z)"))
}

/// The frame an output of `format` is written in: `--out-up` if given, else the input's
/// (`--up`), else Y; glTF is always Y-up (its specification): `--out-up z` for a .glb is
/// refused, and a Z-up input is written to .glb Y-up.
pub fn out_up(out_up: Option<UpAxis>, up: Option<UpAxis>, format: MeshFormat) -> Result<UpAxis, String> {
    let gltf = matches!(format, MeshFormat::Glb | MeshFormat::Gltf);
    match (out_up.or(up), gltf) {
        (Some(UpAxis::Z), true) if out_up == Some(UpAxis::Z) => Err("--out-up z: glTF is Y-up by specification, so a .glb is written Y-up (use .obj, .ply or .stl for Z-up)".into()),
        (Some(UpAxis::Z), false) => Ok(UpAxis::Z),
        _ => Ok(UpAxis::Y),
    }
}

/// Load and prepare a mesh, rotated to Y-up if `up` is Z; errors name the input and what is
/// wrong with it.
pub fn load(input: &str, up: Option<UpAxis>) -> Result<LoadedMesh, String> {
    let mut loaded = read(input)?;
    if let Some(up) = up {
        if let Some(w) = loaded.set_up_axis(up) {
            loaded.report.warnings.push(w);
        }
    }
    Ok(loaded)
}

fn read(input: &str) -> Result<LoadedMesh, String> {
    if let Some(name) = input.strip_prefix("builtin:") {
        let mut m = builtin::builtin(name).map(LoadedMesh::from_trimesh).map_err(|e| format!("{input}: {e}"))?;
        m.report.up_axis = UpAxis::Y; // built-in models are made Y-up
        return Ok(m);
    }
    let path = Path::new(input);
    if path.is_dir() {
        return Err(format!("{input}: is a directory, not a mesh file"));
    }
    if !path.exists() {
        return Err(format!("{input}: no such file (give a {READ_EXTENSIONS} file or builtin:NAME, NAME one of {})", builtin::NAMES.join(", ")));
    }
    let ext = path.extension().map(|e| e.to_string_lossy().to_lowercase());
    let format = match ext.as_deref() {
        Some(e) => Some(MeshFormat::from_extension(e).ok_or_else(|| format!("{input}: unsupported file type '.{e}' (read: {READ_EXTENSIONS})"))?),
        None => None,
    };
    let bytes = read_file(path, input)?;
    let format = match format.or_else(|| MeshFormat::sniff(&bytes)) {
        Some(f) => f,
        None => return Err(format!("{input}: no file extension, and the first bytes are not those of a PLY, STL, glTF or GLB file (name it {READ_EXTENSIONS})")),
    };
    softsculpt::mesh::load(&bytes, Some(format)).map_err(|e| format!("{input}: {e}"))
}

/// The largest input file read (bytes): 1 GiB, above the largest meshes the engine runs (an
/// ASCII STL of 2 M triangles, the remesher's limit, is ~0.5 GB), so a wrong file cannot grow
/// the process without bound (`simulate /dev/zero` grew to 4.7 GB in 6 s before this limit).
pub const MAX_INPUT_BYTES: u64 = 1 << 30;

/// The bytes of the input file at `path` (`shown` in errors): only a regular file of at most
/// [`MAX_INPUT_BYTES`] (a device, pipe or socket is refused before anything is read), read
/// with a cap so a file growing while it is read stops there too.
pub fn read_file(path: &Path, shown: &str) -> Result<Vec<u8>, String> {
    use std::io::Read;
    let meta = std::fs::metadata(path).map_err(|e| format!("{shown}: cannot read: {e}"))?;
    if !meta.is_file() {
        return Err(format!("{shown}: not a regular file (a device, pipe or socket is not read: save the mesh to a file)"));
    }
    let too_big = |n: u64| format!("{shown}: {n} bytes is more than the {} MiB an input file may have", MAX_INPUT_BYTES >> 20);
    if meta.len() > MAX_INPUT_BYTES {
        return Err(too_big(meta.len()));
    }
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    let file = std::fs::File::open(path).map_err(|e| format!("{shown}: cannot read: {e}"))?;
    file.take(MAX_INPUT_BYTES + 1).read_to_end(&mut bytes).map_err(|e| format!("{shown}: cannot read: {e}"))?;
    if bytes.len() as u64 > MAX_INPUT_BYTES {
        return Err(too_big(bytes.len() as u64));
    }
    Ok(bytes)
}

/// The output format of `--out`, from its extension: one clear error before anything runs.
pub fn out_format(out: &Path) -> Result<MeshFormat, String> {
    use softsculpt::mesh::format::WRITE_EXTENSIONS;
    let ext = out.extension().map(|e| e.to_string_lossy().to_lowercase());
    match ext.as_deref().and_then(MeshFormat::from_extension) {
        Some(f) if f.writable() => Ok(f),
        Some(_) => Err(format!("--out {}: .gltf text is not written; use .glb ({WRITE_EXTENSIONS})", out.display())),
        None => Err(format!(
            "--out {}: unknown output type {} (the extension chooses the format: {WRITE_EXTENSIONS})",
            out.display(),
            ext.map_or("(no extension)".to_string(), |e| format!("'.{e}'"))
        )),
    }
}

/// Print the loader's warnings on stderr.
pub fn warn(input: &str, mesh: &LoadedMesh) {
    for w in &mesh.report.warnings {
        eprintln!("warning: {input}: {w}");
    }
}

/// How the up axis was found, for `info`.
pub fn up_text(mesh: &LoadedMesh) -> String {
    let r = &mesh.report;
    match r.up_axis {
        UpAxis::Z => "z (given by --up; rotated to Y-up)".into(),
        UpAxis::Y if matches!(r.format, Some(MeshFormat::Gltf | MeshFormat::Glb)) => "y (glTF is Y-up by specification)".into(),
        UpAxis::Y => "y".into(),
        UpAxis::Unknown => "unknown (the file does not say; taken as Y-up; --up z rotates a Z-up file)".into(),
    }
}
