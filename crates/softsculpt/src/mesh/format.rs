//! Mesh file formats: which one a file is (by extension, else by its first bytes), its up axis,
//! and what reading and writing keep. What every format's reader and writer shares lives here,
//! below them (`obj`, `ply`, `stl`, `gltf`); reading any format into a mesh and writing one back
//! is [`file`](super::file), above them.
//!
//! | format | read | written as | positions |
//! |---|---|---|---|
//! | OBJ  | text | text, shortest round-trip decimals | f64, exact |
//! | PLY  | ASCII, binary LE/BE | binary little-endian, `double x y z` | f64, exact |
//! | STL  | text, binary | binary | f32, unindexed triangles (welded back on reading) |
//! | glTF | JSON with embedded (data-URI) buffers | — | f32 |
//! | GLB  | binary glTF | GLB, one mesh, no transform | f32 |

use super::obj::ObjData;

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

    /// Whether [`LoadedMesh::write`](super::LoadedMesh::write) can write it.
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
        if stl_binary_size_matches(bytes) || bytes.starts_with(b"solid ") || bytes.starts_with(b"solid\n") {
            return Some(MeshFormat::Stl);
        }
        let first = bytes.iter().find(|b| !b.is_ascii_whitespace());
        if first == Some(&b'{') && bytes.windows(7).any(|w| w == b"\"asset\"") {
            return Some(MeshFormat::Gltf);
        }
        None
    }
}

/// A binary STL: an 84-byte header (80 free bytes, then the u32 triangle count), 50 bytes per
/// triangle. Its size is its signature (STL has no magic number); `stl.rs` reads and writes it.
pub(crate) const STL_HEADER: usize = 84;
pub(crate) const STL_TRIANGLE: usize = 50;

/// The triangle count of a binary STL header, if the file is long enough to have one.
pub(crate) fn stl_triangle_count(bytes: &[u8]) -> Option<u64> {
    let c = bytes.get(80..84)?;
    Some(u32::from_le_bytes([c[0], c[1], c[2], c[3]]) as u64)
}

/// A binary STL's size is exactly 84 + 50 × its triangle count.
pub fn stl_binary_size_matches(bytes: &[u8]) -> bool {
    stl_triangle_count(bytes).is_some_and(|n| n > 0 && bytes.len() as u64 == STL_HEADER as u64 + STL_TRIANGLE as u64 * n)
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

/// Rotate Z-up coordinates to Y-up: (x, y, z) → (x, z, −y), a proper rotation (−90° about X),
/// so windings stay outward and lengths, volumes and units are unchanged.
pub fn z_up_to_y_up(positions: &mut [f64]) {
    for p in positions.chunks_exact_mut(3) {
        let (y, z) = (p[1], p[2]);
        p[1] = z;
        p[2] = -y;
    }
}

/// How [`LoadedMesh::write_with`](super::LoadedMesh::write_with) writes: in which frame, and
/// whether OBJ and PLY polygons are split into triangles (some readers, trimesh among them,
/// refuse a PLY mixing quads and triangles). The default: Y-up, the source's polygons.
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
