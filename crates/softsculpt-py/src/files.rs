//! Reading what a world is made from: mesh files (or `builtin:NAME`) and scene files with the
//! meshes they name, under the CLI's limits (regular files only, at most 1 GiB: see the CLI's
//! `input::read_file`), so a wrong path cannot hang or grow the process.

use pyo3::exceptions::{PyFileNotFoundError, PyOSError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use softsculpt::mesh::{builtin, LoadedMesh, MeshFormat};
use std::path::{Path, PathBuf};

/// The largest input file read (bytes), as the CLI's `MAX_INPUT_BYTES`.
pub const MAX_INPUT_BYTES: u64 = 1 << 30;

/// Why a file was not read: the reason as the CLI's `input::read_file` words it after
/// "PATH: ", and whether it is missing (FileNotFoundError) or otherwise unreadable (OSError).
pub struct Unread {
    pub missing: bool,
    pub reason: String,
}

/// The bytes of the regular file at `path` (at most [`MAX_INPUT_BYTES`]).
pub fn read_bytes(path: &Path) -> Result<Vec<u8>, Unread> {
    use std::io::Read;
    let fail = |e: std::io::Error| Unread { missing: e.kind() == std::io::ErrorKind::NotFound, reason: format!("cannot read: {e}") };
    let meta = std::fs::metadata(path).map_err(fail)?;
    if !meta.is_file() {
        return Err(Unread { missing: false, reason: "not a regular file (a device, pipe or socket is not read: save the mesh to a file)".into() });
    }
    let too_big = |n: u64| Unread { missing: false, reason: format!("{n} bytes is more than the {} MiB an input file may have", MAX_INPUT_BYTES >> 20) };
    if meta.len() > MAX_INPUT_BYTES {
        return Err(too_big(meta.len()));
    }
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    let file = std::fs::File::open(path).map_err(fail)?;
    file.take(MAX_INPUT_BYTES + 1).read_to_end(&mut bytes).map_err(fail)?;
    if bytes.len() as u64 > MAX_INPUT_BYTES {
        return Err(too_big(bytes.len() as u64));
    }
    Ok(bytes)
}

/// [`read_bytes`] with its refusal as a Python exception: "PATH: reason".
pub fn read_file(path: &Path) -> PyResult<Vec<u8>> {
    read_bytes(path).map_err(|u| {
        let message = format!("{}: {}", path.display(), u.reason);
        if u.missing {
            PyFileNotFoundError::new_err(message)
        } else {
            PyOSError::new_err(message)
        }
    })
}

/// A scene's resolver reading from the folder `dir` (the reason alone on a refusal: the
/// scene's error names the file and its line), recording what it read.
pub fn disk_resolver<'a>(dir: &'a Path, read: &'a mut Vec<(String, Vec<u8>)>) -> impl FnMut(&str) -> Result<Vec<u8>, String> + 'a {
    move |name: &str| {
        let bytes = read_bytes(&dir.join(name)).map_err(|u| u.reason.trim_start_matches("cannot read: ").to_string())?;
        read.push((name.to_string(), bytes.clone()));
        Ok(bytes)
    }
}

/// A mesh file (OBJ, PLY, STL, glTF, GLB; the extension or the first bytes say which) or
/// `builtin:NAME`, loaded and prepared as the CLI loads its INPUT.
pub fn load_mesh(input: &str) -> PyResult<LoadedMesh> {
    if let Some(name) = input.strip_prefix("builtin:") {
        let mut m = builtin::builtin(name).map(LoadedMesh::from_trimesh).map_err(|e| PyValueError::new_err(format!("{input}: {e}")))?;
        m.report.up_axis = softsculpt::mesh::UpAxis::Y;
        return Ok(m);
    }
    let path = Path::new(input);
    let bytes = read_file(path)?;
    let ext = path.extension().map(|e| e.to_string_lossy().to_lowercase());
    let format = match ext.as_deref() {
        Some(e) => Some(MeshFormat::from_extension(e).ok_or_else(|| PyValueError::new_err(format!("{input}: unsupported file type '.{e}' (read: {})", softsculpt::mesh::format::READ_EXTENSIONS)))?),
        None => MeshFormat::sniff(&bytes),
    };
    softsculpt::mesh::load(&bytes, format).map_err(|e| PyValueError::new_err(format!("{input}: {e}")))
}

/// `scene_files(path) -> (text, {name: bytes})`: a scene file's text and the files it names,
/// read once here so that a sweep ships them to its workers (which need not see this disk).
/// A scene that does not build raises its error, as `World.from_scene` would.
#[pyfunction]
pub fn scene_files<'py>(py: Python<'py>, path: PathBuf) -> PyResult<(String, Bound<'py, PyDict>)> {
    let (text, _, files) = crate::world::load_scene(&path)?;
    let dict = PyDict::new(py);
    for (name, bytes) in files {
        dict.set_item(name, pyo3::types::PyBytes::new(py, &bytes))?;
    }
    Ok((text, dict))
}
