//! STL: read text and binary and write binary with the `stl_io` crate. STL stores separate
//! triangles with f32 corners: reading merges corners with identical coordinates (`stl_io`),
//! then the usual weld; writing loses the vertex indexing and rounds positions to f32.

use super::format::{fan_triangles, stl_binary_size_matches, stl_triangle_count, STL_HEADER, STL_TRIANGLE};
use super::ObjData;
use crate::error::MeshError;

fn err(message: impl Into<String>) -> MeshError {
    MeshError::Format { format: "STL", message: message.into() }
}

/// Parse STL bytes. A file is binary when its size matches its triangle count (even if its
/// header starts with `solid`, as some exporters write); otherwise it must be text.
pub fn parse(bytes: &[u8]) -> Result<ObjData, MeshError> {
    let binary = stl_binary_size_matches(bytes);
    let text = !binary && (bytes.starts_with(b"solid ") || bytes.starts_with(b"solid\n") || bytes.starts_with(b"solid\r"));
    if !binary && !text {
        return Err(err(match stl_triangle_count(bytes) {
            None => format!("{} bytes is too short for a binary STL (84-byte header) and it is not text starting with 'solid'", bytes.len()),
            Some(n) => format!(
                "not text starting with 'solid', and as binary STL the header's {n} triangles need {} bytes, but the file has {} (truncated or not STL)",
                STL_HEADER as u64 + STL_TRIANGLE as u64 * n,
                bytes.len()
            ),
        }));
    }
    let mut owned;
    let mut input = bytes;
    if binary && bytes.starts_with(b"solid") {
        // stl_io takes any file starting with "solid " as text: hide the header's first byte
        // (the 80-byte header carries no data).
        owned = bytes.to_vec();
        owned[0] = b' ';
        input = &owned;
    } else if text && (bytes.starts_with(b"solid\n") || bytes.starts_with(b"solid\r")) {
        // An unnamed solid: stl_io wants "solid " with a space.
        owned = Vec::with_capacity(bytes.len() + 1);
        owned.extend_from_slice(b"solid ");
        owned.extend_from_slice(&bytes[5..]);
        input = &owned;
    }
    let mut cursor = std::io::Cursor::new(input);
    let mesh = stl_io::read_stl(&mut cursor).map_err(|e| {
        err(format!("{}: {e}", if binary { "binary" } else { "text" }))
    })?;
    let mut data = ObjData::default();
    data.positions.reserve(3 * mesh.vertices.len());
    for v in &mesh.vertices {
        data.positions.extend(v.0.iter().map(|&x| x as f64));
    }
    for f in &mesh.faces {
        data.indices.extend(f.vertices.iter().map(|&i| i as u32));
        data.arities.push(3);
    }
    if data.arities.is_empty() {
        return Err(MeshError::Empty("no faces: the STL file holds no triangles".into()));
    }
    Ok(data)
}

/// Binary STL of the polygons (fans), corners rounded to f32, normals from the rounded corners.
/// The 80-byte header holds the first line of `header` (never starting with `solid`).
pub fn write(positions: &[f64], polygons: &ObjData, header: &str) -> Vec<u8> {
    let tris = fan_triangles(polygons);
    let corner = |i: u32| -> [f32; 3] {
        let p = &positions[3 * i as usize..3 * i as usize + 3];
        [p[0] as f32, p[1] as f32, p[2] as f32]
    };
    let mut out = Vec::with_capacity(STL_HEADER + STL_TRIANGLE * tris.len());
    let mut head = [b' '; 80];
    let first = header.lines().next().unwrap_or("");
    for (h, b) in head.iter_mut().zip(first.bytes().filter(|b| b.is_ascii() && !b.is_ascii_control())) {
        *h = b;
    }
    if head.starts_with(b"solid") {
        head[0] = b'_';
    }
    out.extend_from_slice(&head);
    out.extend_from_slice(&(tris.len() as u32).to_le_bytes());
    for t in &tris {
        let [a, b, c] = [corner(t[0]), corner(t[1]), corner(t[2])];
        let (u, v) = ([b[0] - a[0], b[1] - a[1], b[2] - a[2]], [c[0] - a[0], c[1] - a[1], c[2] - a[2]]);
        let n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
        let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        let n = if len > 0.0 { n.map(|x| x / len) } else { [0.0; 3] };
        for x in n.iter().chain(&a).chain(&b).chain(&c) {
            out.extend_from_slice(&x.to_le_bytes());
        }
        out.extend_from_slice(&[0, 0]);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_text_and_binary_with_a_solid_header() {
        let text = b"solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n";
        let d = parse(text).unwrap();
        assert_eq!(d.arities, vec![3]);
        let data = ObjData { positions: vec![0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0], indices: vec![0, 1, 2], arities: vec![3] };
        let mut bin = write(&data.positions, &data, "x");
        bin[..6].copy_from_slice(b"solid ");
        let back = parse(&bin).unwrap();
        assert_eq!(back.positions, data.positions);
    }
}
