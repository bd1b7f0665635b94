//! glTF 2.0: read `.gltf` (JSON, buffers embedded as data URIs) and `.glb` with the `gltf`
//! crate; write a static `.glb` by hand (one mesh, one node, f32 positions, u32 indices).
//!
//! Reading walks the default scene (else the first; else every mesh untransformed), applies each
//! node's transform, and joins every triangle primitive into one source mesh in document order.
//! glTF is Y-up and in metres by specification.

use super::format::{fan_triangles, MeshFormat};
use super::ObjData;
use crate::error::MeshError;
use ::gltf::accessor::{DataType, Dimensions};
use ::gltf::mesh::Mode;
use ::gltf::Semantic;
use base64::Engine;

type M4 = [[f64; 4]; 4];
const IDENTITY: M4 = [[1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 1.0]];
/// Deeper node hierarchies are refused (a cycle would recurse forever).
const MAX_DEPTH: usize = 64;

struct Reader {
    format: &'static str,
    buffers: Vec<Vec<u8>>,
    data: ObjData,
}

impl Reader {
    fn err(&self, message: impl Into<String>) -> MeshError {
        MeshError::Format { format: self.format, message: message.into() }
    }

    /// The accessor's data lies inside its buffer view and the view inside its buffer (with
    /// checked arithmetic: the crate's own reader would overflow on hostile offsets).
    fn check_bounds(&self, at: &str, what: &str, a: &::gltf::Accessor, elem: usize) -> Result<(), MeshError> {
        let outside = || self.err(format!("{at}: {what} lies outside its buffer"));
        let sparse = a.sparse().is_some();
        if sparse {
            return Err(self.err(format!("{at}: {what} is a sparse accessor, which is not supported")));
        }
        let view = a.view().ok_or_else(outside)?;
        let data = self.buffers.get(view.buffer().index()).ok_or_else(outside)?;
        let view_end = view.offset().checked_add(view.length()).ok_or_else(outside)?;
        let stride = view.stride().unwrap_or(elem);
        if stride < elem {
            return Err(self.err(format!("{at}: {what}'s byte stride {stride} is smaller than one element ({elem} bytes)")));
        }
        let end = (a.count().checked_sub(1).ok_or_else(outside)?)
            .checked_mul(stride)
            .and_then(|x| x.checked_add(elem))
            .and_then(|x| x.checked_add(a.offset()))
            .ok_or_else(outside)?;
        if view_end > data.len() || end > view.length() {
            return Err(outside());
        }
        Ok(())
    }

    fn primitive(&mut self, mesh: &::gltf::Mesh, p: &::gltf::Primitive, m: &M4) -> Result<(), MeshError> {
        let at = format!("mesh {} primitive {}", mesh.index(), p.index());
        match p.mode() {
            Mode::Triangles => {}
            Mode::Points | Mode::Lines | Mode::LineLoop | Mode::LineStrip => return Ok(()), // no surface
            other => return Err(self.err(format!("{at}: mode {other:?} is not supported (export triangles)"))),
        }
        let pos = p.get(&Semantic::Positions).ok_or_else(|| self.err(format!("{at} has no POSITION attribute")))?;
        if pos.data_type() != DataType::F32 || pos.dimensions() != Dimensions::Vec3 || pos.normalized() {
            return Err(self.err(format!("{at}: POSITION must be float VEC3 (quantized or compressed positions are not supported)")));
        }
        let n = pos.count();
        if n == 0 || pos.view().is_none() && pos.sparse().is_none() {
            return Err(self.err(format!("{at}: POSITION has no data (compressed meshes are not supported)")));
        }
        self.check_bounds(&at, "POSITION", &pos, 12)?;
        let indices: Vec<u32> = match p.indices() {
            None => (0..n as u32).collect(),
            Some(ix) => {
                let size = match ix.data_type() {
                    DataType::U8 => 1,
                    DataType::U16 => 2,
                    DataType::U32 => 4,
                    other => return Err(self.err(format!("{at}: indices of type {other:?} (must be unsigned integers)"))),
                };
                if ix.count() == 0 || ix.dimensions() != Dimensions::Scalar {
                    return Err(self.err(format!("{at}: the indices accessor is empty or not a scalar list")));
                }
                self.check_bounds(&at, "the indices", &ix, size)?;
                let buffers = &self.buffers;
                let reader = p.reader(|b| buffers.get(b.index()).map(Vec::as_slice));
                let read = reader.read_indices().ok_or_else(|| self.err(format!("{at}: the indices lie outside their buffer")))?;
                read.into_u32().collect()
            }
        };
        if !indices.len().is_multiple_of(3) {
            return Err(self.err(format!("{at}: {} indices is not a whole number of triangles", indices.len())));
        }
        if let Some(bad) = indices.iter().find(|&&i| i as usize >= n) {
            return Err(self.err(format!("{at}: index {bad} is out of range ({n} vertices)")));
        }
        let buffers = &self.buffers;
        let reader = p.reader(|b| buffers.get(b.index()).map(Vec::as_slice));
        let read = reader.read_positions().ok_or_else(|| self.err(format!("{at}: POSITION lies outside its buffer")))?;
        let base = self.data.vertex_count() as u32;
        let before = self.data.positions.len();
        for q in read {
            let q = q.map(|x| x as f64);
            if *m == IDENTITY {
                self.data.positions.extend_from_slice(&q);
            } else {
                for r in 0..3 {
                    self.data.positions.push(m[0][r] * q[0] + m[1][r] * q[1] + m[2][r] * q[2] + m[3][r]);
                }
            }
        }
        if self.data.positions.len() - before != 3 * n {
            return Err(self.err(format!("{at}: POSITION lies outside its buffer")));
        }
        self.data.indices.extend(indices.iter().map(|&i| base + i));
        self.data.arities.extend(std::iter::repeat_n(3, indices.len() / 3));
        Ok(())
    }

    fn node(&mut self, node: ::gltf::Node, parent: &M4, depth: usize) -> Result<(), MeshError> {
        if depth > MAX_DEPTH {
            return Err(self.err(format!("the node hierarchy is deeper than {MAX_DEPTH} (a cycle?)")));
        }
        let local = node.transform().matrix().map(|c| c.map(|x| x as f64));
        let m = if local == IDENTITY { *parent } else { mul(parent, &local) };
        if let Some(mesh) = node.mesh() {
            for p in mesh.primitives() {
                self.primitive(&mesh, &p, &m)?;
            }
        }
        for child in node.children() {
            self.node(child, &m, depth + 1)?;
        }
        Ok(())
    }
}

/// Column-major 4×4 product a·b.
fn mul(a: &M4, b: &M4) -> M4 {
    let mut out = [[0.0; 4]; 4];
    for (c, col) in out.iter_mut().enumerate() {
        for (r, x) in col.iter_mut().enumerate() {
            *x = (0..4).map(|k| a[k][r] * b[c][k]).sum();
        }
    }
    out
}

/// Parse glTF JSON or GLB bytes into one source mesh (positions in metres, Y-up).
pub fn parse(bytes: &[u8], format: MeshFormat) -> Result<ObjData, MeshError> {
    let name = format.name();
    let fail = |message: String| MeshError::Format { format: name, message };
    match format {
        MeshFormat::Glb if !bytes.starts_with(b"glTF") => return Err(fail("the file does not start with the GLB magic 'glTF'".into())),
        MeshFormat::Gltf if bytes.starts_with(b"glTF") => return Err(fail("the file is binary glTF: name it .glb".into())),
        _ => {}
    }
    if format == MeshFormat::Glb {
        let declared = bytes.get(8..12).map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as usize);
        match declared {
            None => return Err(fail(format!("{} bytes is shorter than the 12-byte GLB header", bytes.len()))),
            Some(n) if n != bytes.len() => {
                return Err(fail(format!("the header says the file has {n} bytes, but it has {} (truncated or corrupt)", bytes.len())))
            }
            _ => {}
        }
    }
    let doc = ::gltf::Gltf::from_slice_without_validation(bytes).map_err(|e| fail(e.to_string().trim_end_matches([';', '.', ' ']).to_string()))?;
    dangling_accessors(doc.as_json()).map_err(fail)?;
    let doc = ::gltf::Gltf::from_slice(bytes).map_err(|e| fail(e.to_string().trim_end_matches([';', '.', ' ']).to_string()))?;
    let mut buffers = Vec::new();
    for b in doc.buffers() {
        let data = match b.source() {
            ::gltf::buffer::Source::Bin => doc.blob.clone().ok_or_else(|| fail(format!("buffer {} refers to a missing BIN chunk", b.index())))?,
            ::gltf::buffer::Source::Uri(uri) => {
                let Some(rest) = uri.strip_prefix("data:") else {
                    let shown: String = uri.chars().take(60).collect();
                    return Err(fail(format!("buffer {} is an external file '{shown}', which is not read: embed it (data URI) or use .glb", b.index())));
                };
                let (_, payload) = rest.split_once(";base64,").ok_or_else(|| fail(format!("buffer {}: only base64 data URIs are read", b.index())))?;
                base64::engine::general_purpose::STANDARD
                    .decode(payload)
                    .map_err(|e| fail(format!("buffer {}: its data URI is not valid base64 ({e})", b.index())))?
            }
        };
        if data.len() < b.length() {
            return Err(fail(format!("buffer {} declares {} bytes but holds {} (truncated)", b.index(), b.length(), data.len())));
        }
        buffers.push(data);
    }
    let mut r = Reader { format: name, buffers, data: ObjData::default() };
    match doc.default_scene().or_else(|| doc.scenes().next()) {
        Some(scene) => {
            for node in scene.nodes() {
                r.node(node, &IDENTITY, 0)?;
            }
        }
        None => {
            for mesh in doc.meshes() {
                for p in mesh.primitives() {
                    r.primitive(&mesh, &p, &IDENTITY)?;
                }
            }
        }
    }
    if r.data.arities.is_empty() {
        return Err(MeshError::Empty(format!("no faces: the {name} file's scene holds no triangles")));
    }
    Ok(r.data)
}

/// A static GLB: the positions (f32) in order and the polygons as triangle fans (u32 indices).
pub fn write_glb(positions: &[f64], polygons: &ObjData, header: &str) -> Vec<u8> {
    use serde_json::json;
    let tris = fan_triangles(polygons);
    let nv = positions.len() / 3;
    let (mut lo, mut hi) = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
    let mut bin = Vec::with_capacity(positions.len() * 4 + tris.len() * 12);
    for p in positions.chunks_exact(3) {
        for d in 0..3 {
            let x = p[d] as f32;
            lo[d] = lo[d].min(x);
            hi[d] = hi[d].max(x);
            bin.extend_from_slice(&x.to_le_bytes());
        }
    }
    let pos_len = bin.len();
    for i in tris.iter().flatten() {
        bin.extend_from_slice(&i.to_le_bytes());
    }
    let doc = json!({
        "asset": { "version": "2.0", "generator": "SoftSculpt", "extras": { "header": header } },
        "scene": 0,
        "scenes": [{ "nodes": [0] }],
        "nodes": [{ "mesh": 0 }],
        "meshes": [{ "primitives": [{ "attributes": { "POSITION": 0 }, "indices": 1, "mode": 4 }] }],
        "buffers": [{ "byteLength": bin.len() }],
        "bufferViews": [
            { "buffer": 0, "byteOffset": 0, "byteLength": pos_len, "target": 34962 },
            { "buffer": 0, "byteOffset": pos_len, "byteLength": bin.len() - pos_len, "target": 34963 },
        ],
        "accessors": [
            { "bufferView": 0, "componentType": 5126, "count": nv, "type": "VEC3", "min": lo, "max": hi },
            { "bufferView": 1, "componentType": 5125, "count": 3 * tris.len(), "type": "SCALAR" },
        ],
    });
    glb_container(&doc, bin)
}

/// The GLB container (glTF 2.0 §4.4): a 12-byte header, the JSON chunk padded with spaces and
/// the BIN chunk padded with zeros to 4 bytes.
pub fn glb_container(doc: &serde_json::Value, mut bin: Vec<u8>) -> Vec<u8> {
    let mut text = serde_json::to_vec(doc).unwrap_or_default();
    while !text.len().is_multiple_of(4) {
        text.push(b' ');
    }
    while !bin.len().is_multiple_of(4) {
        bin.push(0);
    }
    let total = 12 + 8 + text.len() + 8 + bin.len();
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(text.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&text);
    out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(&bin);
    out
}

/// A primitive's attribute or indices naming an accessor the file does not have: one error here,
/// since `gltf-json` 1.4's validation indexes the POSITION accessor before it checks the index
/// and panics on such a file (`{"meshes":[{"primitives":[{"attributes":{"POSITION":7}}]}]}`).
fn dangling_accessors(root: &::gltf::json::Root) -> Result<(), String> {
    let n = root.accessors.len();
    for (m, mesh) in root.meshes.iter().enumerate() {
        for (p, prim) in mesh.primitives.iter().enumerate() {
            let named = prim.attributes.iter().map(|(k, i)| (format!("attribute {}", semantic(k)), i.value())).chain(prim.indices.iter().map(|i| ("indices".to_string(), i.value())));
            for (what, i) in named {
                if i >= n {
                    return Err(format!("mesh {m} primitive {p}: its {what} names accessor {i}, but the file has {n} accessor{}", if n == 1 { "" } else { "s" }));
                }
            }
        }
    }
    Ok(())
}

fn semantic(k: &::gltf::json::validation::Checked<::gltf::json::mesh::Semantic>) -> String {
    match k {
        ::gltf::json::validation::Checked::Valid(s) => s.to_string(),
        ::gltf::json::validation::Checked::Invalid => "(unknown)".into(),
    }
}
