//! Atomic output: write to a temporary file beside the target, then rename over it, so a failed
//! run never leaves a half-written file and never destroys an existing one.

use std::fs;
use std::io::Write;
use std::path::{Path, PathBuf};

/// A file being written; becomes visible at `path` only on [`Staged::commit`].
pub struct Staged {
    path: PathBuf,
    tmp: PathBuf,
    file: Option<std::io::BufWriter<fs::File>>,
}

impl Staged {
    pub fn create(path: &Path) -> Result<Self, String> {
        if path.is_dir() {
            return Err(format!("{}: is a directory, not a file to write", path.display()));
        }
        let parent = match path.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
            _ => PathBuf::from("."),
        };
        fs::create_dir_all(&parent).map_err(|e| format!("{}: cannot create directory: {e}", parent.display()))?;
        let name = path.file_name().ok_or_else(|| format!("{}: not a file name", path.display()))?;
        let tmp = parent.join(format!(".{}.tmp-{}", name.to_string_lossy(), std::process::id()));
        let file = fs::File::create(&tmp).map_err(|e| format!("{}: cannot write: {e}", path.display()))?;
        Ok(Staged { path: path.to_path_buf(), tmp, file: Some(std::io::BufWriter::new(file)) })
    }

    pub fn write(&mut self, bytes: &[u8]) -> Result<(), String> {
        let f = self.file.as_mut().expect("written after commit");
        f.write_all(bytes).map_err(|e| format!("{}: cannot write: {e}", self.path.display()))
    }

    /// Flush, sync and rename into place.
    pub fn commit(mut self) -> Result<(), String> {
        let f = self.file.take().expect("committed twice");
        let file = f.into_inner().map_err(|e| format!("{}: cannot write: {}", self.path.display(), e.error()))?;
        file.sync_all().map_err(|e| format!("{}: cannot write: {e}", self.path.display()))?;
        drop(file);
        fs::rename(&self.tmp, &self.path).map_err(|e| format!("{}: cannot write: {e}", self.path.display()))
    }
}

impl Drop for Staged {
    fn drop(&mut self) {
        if self.file.is_some() {
            self.file = None;
            let _ = fs::remove_file(&self.tmp);
        }
    }
}

/// Write a whole file atomically.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), String> {
    let mut s = Staged::create(path)?;
    s.write(bytes)?;
    s.commit()
}

/// Write a generated mesh (remeshed, sketched) atomically in the format `format`, in the frame `up`.
pub fn write_mesh(path: &Path, format: softsculpt::mesh::MeshFormat, mesh: &softsculpt::TriMesh, header: &str, up: softsculpt::mesh::UpAxis) -> Result<(), String> {
    let loaded = softsculpt::LoadedMesh::from_trimesh(mesh.clone());
    let options = softsculpt::mesh::format::WriteOptions { up, triangulate: false };
    let bytes = loaded.write_with(format, &loaded.mesh.positions, header, options).map_err(|e| format!("--out {}: {e}", path.display()))?;
    write_atomic(path, &bytes).map_err(|e| format!("--out {e}"))
}
