//! PLY (Stanford polygon files): read ASCII and binary with the `ply-rs-bw` crate (a maintained
//! fork of `ply-rs`); write binary little-endian with `double` coordinates, so a written file
//! reads back bit-identical.

use super::ObjData;
use crate::error::MeshError;
use ply_rs_bw::parser::Parser;
use ply_rs_bw::ply::{DefaultElement, Property};

fn err(message: impl Into<String>) -> MeshError {
    MeshError::Format { format: "PLY", message: message.into() }
}

fn scalar(p: &Property) -> Option<f64> {
    Some(match *p {
        Property::Char(v) => v as f64,
        Property::UChar(v) => v as f64,
        Property::Short(v) => v as f64,
        Property::UShort(v) => v as f64,
        Property::Int(v) => v as f64,
        Property::UInt(v) => v as f64,
        Property::Float(v) => v as f64,
        Property::Double(v) => v,
        _ => return None,
    })
}

/// A list of vertex indices; `None` if the property is not an integer list.
fn index_list(p: &Property) -> Option<Vec<i64>> {
    Some(match p {
        Property::ListChar(v) => v.iter().map(|&i| i as i64).collect(),
        Property::ListUChar(v) => v.iter().map(|&i| i as i64).collect(),
        Property::ListShort(v) => v.iter().map(|&i| i as i64).collect(),
        Property::ListUShort(v) => v.iter().map(|&i| i as i64).collect(),
        Property::ListInt(v) => v.iter().map(|&i| i as i64).collect(),
        Property::ListUInt(v) => v.iter().map(|&i| i as i64).collect(),
        _ => return None,
    })
}

/// Parse PLY bytes: the `vertex` element's `x y z` and the `face` element's `vertex_indices`
/// (or `vertex_index`). Other elements and properties (normals, colours) are ignored.
pub fn parse(bytes: &[u8]) -> Result<ObjData, MeshError> {
    if !(bytes.starts_with(b"ply\n") || bytes.starts_with(b"ply\r\n")) {
        return Err(err("the file does not start with the line 'ply'"));
    }
    let mut cursor = std::io::Cursor::new(bytes);
    let ply = Parser::<DefaultElement>::new().read_ply(&mut cursor).map_err(|e| {
        // The parser's message may go on with its causes on further lines: keep the first.
        let text = e.to_string();
        let first = text.lines().next().unwrap_or("unreadable").trim_end_matches('.');
        // Lines are counted in the header only; in a binary body the count means nothing.
        let message = match first.strip_prefix("Line ").and_then(|rest| rest.split_once(": ")) {
            Some((_, m)) if m.contains("binary") => format!("the file ends early or its counts are wrong: {m}"),
            Some((n, m)) => format!("line {n}: {m}"),
            None => first.to_string(),
        };
        err(message)
    })?;
    let vertices = ply.payload.get("vertex").ok_or_else(|| err("no 'vertex' element"))?;
    let mut data = ObjData { positions: Vec::with_capacity(3 * vertices.len()), ..Default::default() };
    for (i, v) in vertices.iter().enumerate() {
        for key in ["x", "y", "z"] {
            let value = v
                .get(key)
                .ok_or_else(|| err(format!("the vertex element has no property '{key}'")))
                .and_then(|p| scalar(p).ok_or_else(|| err(format!("vertex property '{key}' is a list, not a number"))))?;
            if !value.is_finite() {
                return Err(err(format!("vertex {} has a coordinate that is not finite (NaN or infinity)", i + 1)));
            }
            data.positions.push(value);
        }
    }
    let nv = vertices.len() as i64;
    let faces = ply.payload.get("face").map(Vec::as_slice).unwrap_or(&[]);
    for (f, face) in faces.iter().enumerate() {
        let list = face
            .get("vertex_indices")
            .or_else(|| face.get("vertex_index"))
            .ok_or_else(|| err("the face element has no 'vertex_indices' list"))?;
        let list = index_list(list).ok_or_else(|| err("the faces' vertex indices are not an integer list"))?;
        if list.len() < 3 {
            return Err(err(format!("face {} has {} vertices; a face needs at least 3", f + 1, list.len())));
        }
        for &i in &list {
            if i < 0 || i >= nv {
                return Err(err(format!("face {} refers to vertex {i}, but the file has {nv} vertices (0 to {})", f + 1, nv - 1)));
            }
            data.indices.push(i as u32);
        }
        data.arities.push(list.len() as u32);
    }
    if data.arities.is_empty() {
        return Err(MeshError::Empty(format!("no faces: the PLY file has {nv} vertices and no 'face' element (a triangle mesh is expected)")));
    }
    Ok(data)
}

/// Binary little-endian PLY: `double x y z` per vertex in order, then the polygons
/// (`list uchar uint`, or `list uint uint` if a polygon has more than 255 corners).
pub fn write(positions: &[f64], polygons: &ObjData, header: &str) -> Vec<u8> {
    let nv = positions.len() / 3;
    let wide = polygons.arities.iter().any(|&n| n > 255);
    let mut head = String::from("ply\nformat binary_little_endian 1.0\n");
    for line in header.lines() {
        // A comment ends at the line's end; keep it on one line.
        head.push_str(&format!("comment {}\n", line.replace('\r', " ")));
    }
    head.push_str(&format!("element vertex {nv}\nproperty double x\nproperty double y\nproperty double z\n"));
    head.push_str(&format!(
        "element face {}\nproperty list {} uint vertex_indices\nend_header\n",
        polygons.arities.len(),
        if wide { "uint" } else { "uchar" }
    ));
    let mut out = head.into_bytes();
    out.reserve(positions.len() * 8 + polygons.indices.len() * 4 + polygons.arities.len() * 4);
    for x in positions {
        out.extend_from_slice(&x.to_le_bytes());
    }
    for poly in polygons.polygons() {
        if wide {
            out.extend_from_slice(&(poly.len() as u32).to_le_bytes());
        } else {
            out.push(poly.len() as u8);
        }
        for &i in poly {
            out.extend_from_slice(&i.to_le_bytes());
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_ascii_with_extra_properties_and_quads() {
        let text = b"ply\nformat ascii 1.0\ncomment hi\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n\
property uchar red\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n\
0 0 0 9\n1 0 0 9\n1 1 0 9\n0 1 0 9\n4 0 1 2 3\n";
        let d = parse(text).unwrap();
        assert_eq!(d.positions.len(), 12);
        assert_eq!(d.arities, vec![4]);
    }

    #[test]
    fn writes_binary_that_reads_back_bit_identical() {
        let pos = vec![0.1, -1.0 / 3.0, 1e-300, 12345.678901234567, -0.0, 2.0f64.sqrt(), 1e300, 5e-324, 7.0];
        let data = ObjData { positions: pos.clone(), indices: vec![0, 1, 2], arities: vec![3] };
        let back = parse(&write(&pos, &data, "a\nb")).unwrap();
        assert_eq!(back.positions.iter().map(|x| x.to_bits()).collect::<Vec<_>>(), pos.iter().map(|x| x.to_bits()).collect::<Vec<_>>());
        assert_eq!(back.indices, data.indices);
    }
}
