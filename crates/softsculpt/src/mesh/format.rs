//! Mesh file formats: which one a file is (by extension, else by its first bytes), reading any of
//! them into the same [`LoadedMesh`] (one weld, check, orientation and piece count for all), and
//! writing a simulated shape back in any of them. Bytes in, bytes out: the caller reads files.
//!
//! | format | read | written as | positions |
//! |---|---|---|---|
//! | OBJ  | text | text, shortest round-trip decimals | f64, exact |
//! | PLY  | ASCII, binary LE/BE | binary little-endian, `double x y z` | f64, exact |
//! | STL  | text, binary | binary | f32, unindexed triangles (welded back on reading) |
//! | glTF | JSON with embedded (data-URI) buffers | — | f32 |
//! | GLB  | binary glTF | GLB, one mesh, no transform | f32 |

use super::{obj, LoadedMesh, ObjData};
use crate::error::MeshError;

/// A mesh file format.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MeshFormat {
    Obj,
    Ply,
    Stl,
    Gltf,
    Glb,
}

/// Every readable format's file extensions, for messages.
pub const READ_EXTENSIONS: &str = ".obj, .ply, .stl, .gltf or .glb";
/// Every writable format's file extensions, for messages.
pub const WRITE_EXTENSIONS: &str = ".obj, .ply, .stl or .glb";

impl MeshFormat {
    pub fn name(self) -> &'static str {
        match self {
            MeshFormat::Obj => "OBJ",
            MeshFormat::Ply => "PLY",
            MeshFormat::Stl => "STL",
            MeshFormat::Gltf => "glTF",
            MeshFormat::Glb => "GLB",
        }
    }

    /// The format of a file extension (without the dot, any case).
    pub fn from_extension(ext: &str) -> Option<Self> {
        match ext.to_ascii_lowercase().as_str() {
            "obj" => Some(MeshFormat::Obj),
            "ply" => Some(MeshFormat::Ply),
            "stl" => Some(MeshFormat::Stl),
            "gltf" => Some(MeshFormat::Gltf),
            "glb" => Some(MeshFormat::Glb),
            _ => None,
        }
    }

    /// The format of a path's extension (`"dir/a.PLY"` → PLY).
    pub fn from_path(path: &str) -> Option<Self> {
        let name = path.rsplit(['/', '\\']).next().unwrap_or(path);
        let (stem, ext) = name.rsplit_once('.')?;
        if stem.is_empty() {
            return None;
        }
        Self::from_extension(ext)
    }

    /// Whether [`LoadedMesh::write`] can write it.
    pub fn writable(self) -> bool {
        self != MeshFormat::Gltf
    }

    /// The format told by a file's first bytes, where it tells: `ply` (PLY), `glTF` (GLB), a
    /// JSON object (glTF), `solid ` or a binary STL's exact size (STL). OBJ has no signature.
    pub fn sniff(bytes: &[u8]) -> Option<Self> {
        if bytes.starts_with(b"ply\n") || bytes.starts_with(b"ply\r\n") {
            return Some(MeshFormat::Ply);
        }
        if bytes.starts_with(b"glTF") {
            return Some(MeshFormat::Glb);
        }
        if super::stl::binary_size_matches(bytes) || bytes.starts_with(b"solid ") || bytes.starts_with(b"solid\n") {
            return Some(MeshFormat::Stl);
        }
        let first = bytes.iter().find(|b| !b.is_ascii_whitespace());
        if first == Some(&b'{') && bytes.windows(7).any(|w| w == b"\"asset\"") {
            return Some(MeshFormat::Gltf);
        }
        None
    }
}

/// The up axis of a file: what its format says (glTF: Y-up by specification) or what the user
/// says. OBJ, PLY and STL carry none: [`UpAxis::Unknown`], and the mesh is taken as Y-up.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum UpAxis {
    #[default]
    Unknown,
    Y,
    Z,
}

impl UpAxis {
    pub fn from_name(s: &str) -> Option<Self> {
        match s.to_ascii_lowercase().as_str() {
            "y" => Some(UpAxis::Y),
            "z" => Some(UpAxis::Z),
            _ => None,
        }
    }
    pub fn name(self) -> &'static str {
        match self {
            UpAxis::Unknown => "unknown",
            UpAxis::Y => "y",
            UpAxis::Z => "z",
        }
    }
}

/// Read mesh bytes of the given format (or, without one, the format [`MeshFormat::sniff`]
/// finds) and prepare them: weld, drop degenerate faces, orient, count pieces.
pub fn load(bytes: &[u8], format: Option<MeshFormat>) -> Result<LoadedMesh, MeshError> {
    let format = match format.or_else(|| MeshFormat::sniff(bytes)) {
        Some(f) => f,
        None => {
            return Err(MeshError::Invalid(format!(
                "cannot tell the file's format: it is none of {READ_EXTENSIONS} by its first bytes"
            )))
        }
    };
    let data = match format {
        MeshFormat::Obj => obj::parse(bytes)?,
        MeshFormat::Ply => super::ply::parse(bytes)?,
        MeshFormat::Stl => super::stl::parse(bytes)?,
        MeshFormat::Gltf | MeshFormat::Glb => super::gltf::parse(bytes, format)?,
    };
    check_finite(&data, format)?;
    let mut loaded = super::prepare(data)?;
    loaded.report.format = Some(format);
    if matches!(format, MeshFormat::Gltf | MeshFormat::Glb) {
        loaded.report.up_axis = UpAxis::Y;
    }
    Ok(loaded)
}

fn check_finite(data: &ObjData, format: MeshFormat) -> Result<(), MeshError> {
    if let Some(i) = data.positions.iter().position(|x| !x.is_finite()) {
        return Err(MeshError::Format {
            format: format.name(),
            message: format!("vertex {} has a coordinate that is not finite (NaN or infinity)", i / 3 + 1),
        });
    }
    Ok(())
}

/// Rotate Z-up coordinates to Y-up: (x, y, z) → (x, z, −y), a proper rotation (−90° about X),
/// so windings stay outward and lengths, volumes and units are unchanged.
pub fn z_up_to_y_up(positions: &mut [f64]) {
    for p in positions.chunks_exact_mut(3) {
        let (y, z) = (p[1], p[2]);
        p[1] = z;
        p[2] = -y;
    }
}

/// How [`LoadedMesh::write_with`] writes: in which frame, and whether OBJ and PLY polygons are
/// split into triangles (some readers, trimesh among them, refuse a PLY mixing quads and
/// triangles). The default: Y-up, the source's polygons.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct WriteOptions {
    pub up: UpAxis,
    pub triangulate: bool,
}

/// The inverse of [`z_up_to_y_up`]: (x, y, z) → (x, −z, y), for writing a Z-up file.
pub fn y_up_to_z_up(positions: &mut [f64]) {
    for p in positions.chunks_exact_mut(3) {
        let (y, z) = (p[1], p[2]);
        p[1] = -z;
        p[2] = y;
    }
}

impl LoadedMesh {
    /// Declare the file's up axis. `Z` rotates the mesh (and its source) to Y-up; `Y` keeps it.
    /// Returns a warning when this contradicts what the format says (glTF is Y-up).
    pub fn set_up_axis(&mut self, up: UpAxis) -> Option<String> {
        let gltf = matches!(self.report.format, Some(MeshFormat::Gltf | MeshFormat::Glb));
        if up == UpAxis::Z {
            z_up_to_y_up(&mut self.mesh.positions);
            z_up_to_y_up(&mut self.source.positions);
        }
        self.report.up_axis = up;
        self.report.up_rotated = up == UpAxis::Z;
        (gltf && up == UpAxis::Z)
            .then(|| "glTF files are Y-up by specification; rotated from Z-up anyway, as asked".to_string())
    }

    /// The source's positions with every used vertex replaced by its simulated position.
    fn source_positions(&self, positions: &[f64]) -> Vec<f64> {
        let mut out = self.source.positions.clone();
        for (s, &m) in self.source_to_mesh.iter().enumerate() {
            if m != u32::MAX {
                out[3 * s..3 * s + 3].copy_from_slice(&positions[3 * m as usize..3 * m as usize + 3]);
            }
        }
        out
    }

    /// The shape `positions` (the simulated vertices, flat `xyz…`) as a file of `format`, in the
    /// source's vertex order and polygons (triangulated as fans where the format needs
    /// triangles). glTF text is not written: use GLB.
    pub fn write(&self, format: MeshFormat, positions: &[f64], header: &str) -> Result<Vec<u8>, MeshError> {
        self.write_with(format, positions, header, WriteOptions::default())
    }

    /// [`LoadedMesh::write`] with `options`: the frame (Z turns the Y-up positions to Z-up,
    /// [`y_up_to_z_up`], the inverse of what reading with `Z` did, so a file read Z-up is written
    /// back Z-up) and whether OBJ and PLY get the source's polygons or triangles (fans).
    pub fn write_with(&self, format: MeshFormat, positions: &[f64], header: &str, options: WriteOptions) -> Result<Vec<u8>, MeshError> {
        let mut out = self.source_positions(positions);
        if options.up == UpAxis::Z {
            y_up_to_z_up(&mut out);
        }
        let fans;
        let polygons = if options.triangulate {
            let tris = fan_triangles(&self.source);
            fans = ObjData { positions: Vec::new(), arities: vec![3; tris.len()], indices: tris.into_iter().flatten().collect() };
            &fans
        } else {
            &self.source
        };
        Ok(match format {
            MeshFormat::Obj => obj::write(&out, polygons, header),
            MeshFormat::Ply => super::ply::write(&out, polygons, header),
            MeshFormat::Stl => super::stl::write(&out, &self.source, header),
            MeshFormat::Glb => super::gltf::write_glb(&out, &self.source, header),
            MeshFormat::Gltf => {
                return Err(MeshError::Invalid(format!("cannot write .gltf text; write {WRITE_EXTENSIONS}")));
            }
        })
    }

    /// OBJ text in the source's vertex order and polygons, with positions taken from `positions`
    /// (the simulated vertices, flat `xyz…`). Unused source vertices keep their position.
    pub fn write_obj(&self, positions: &[f64], header: &str) -> Vec<u8> {
        obj::write(&self.source_positions(positions), &self.source, header)
    }
}

/// Triangles of the source polygons, as fans (what PLY quads become in STL and GLB).
pub(crate) fn fan_triangles(source: &ObjData) -> Vec<[u32; 3]> {
    let mut tris = Vec::with_capacity(source.indices.len());
    for poly in source.polygons() {
        for k in 1..poly.len() - 1 {
            tris.push([poly[0], poly[k], poly[k + 1]]);
        }
    }
    tris
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tells_formats_by_extension_and_first_bytes() {
        assert_eq!(MeshFormat::from_path("a/b.PLY"), Some(MeshFormat::Ply));
        assert_eq!(MeshFormat::from_path("a.b/c"), None);
        assert_eq!(MeshFormat::from_path(".glb"), None);
        assert_eq!(MeshFormat::sniff(b"ply\nformat ascii 1.0\n"), Some(MeshFormat::Ply));
        assert_eq!(MeshFormat::sniff(b"glTF\x02\0\0\0"), Some(MeshFormat::Glb));
        assert_eq!(MeshFormat::sniff(b"solid x\nendsolid x\n"), Some(MeshFormat::Stl));
        assert_eq!(MeshFormat::sniff(b" {\"asset\":{\"version\":\"2.0\"}}"), Some(MeshFormat::Gltf));
        assert_eq!(MeshFormat::sniff(b"v 0 0 0\n"), None);
    }

    #[test]
    fn z_up_becomes_y_up_by_a_rotation() {
        let mut p = vec![1.0, 2.0, 3.0];
        z_up_to_y_up(&mut p);
        assert_eq!(p, vec![1.0, 3.0, -2.0]);
    }
}
