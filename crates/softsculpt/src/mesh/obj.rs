//! Wavefront OBJ: parse bytes into positions and polygons, write them back.
//!
//! Why not the `tobj` crate: it re-indexes vertices per object in order of first use (so a mesh
//! could not be written back "with the input's vertex order unchanged"), its errors carry no line
//! numbers, and a few malformed statements make it index out of bounds. OBJ geometry is a handful
//! of statements, so we read them here, strictly, and say exactly which line is wrong.

use crate::error::MeshError;

/// What an OBJ file holds that we use: positions (flat `xyz…`, metres) and polygons.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ObjData {
    /// Vertex positions, 3 per vertex, in file order.
    pub positions: Vec<f64>,
    /// Polygon vertex indices (0-based), polygons concatenated.
    pub indices: Vec<u32>,
    /// Number of vertices of each polygon (≥ 3), in file order.
    pub arities: Vec<u32>,
}

impl ObjData {
    pub fn vertex_count(&self) -> usize {
        self.positions.len() / 3
    }
    /// Iterate polygons as index slices.
    pub fn polygons(&self) -> impl Iterator<Item = &[u32]> {
        let mut start = 0usize;
        self.arities.iter().map(move |&n| {
            let s = &self.indices[start..start + n as usize];
            start += n as usize;
            s
        })
    }
}

/// Statements of the OBJ format that carry no geometry we need: accepted and ignored.
const IGNORED: &[&str] = &[
    "vt", "vn", "vp", "o", "g", "s", "mg", "usemtl", "mtllib", "l", "p", "cstype", "deg", "bmat",
    "step", "curv", "curv2", "surf", "parm", "trim", "hole", "scrv", "sp", "end", "con", "bevel",
    "c_interp", "d_interp", "lod", "maplib", "usemap", "shadow_obj", "trace_obj", "ctech", "stech",
];

fn err(line: usize, message: impl Into<String>) -> MeshError {
    MeshError::Parse { line, message: message.into() }
}

/// Parse OBJ bytes. Every malformed input is an error naming the line; nothing panics.
pub fn parse(bytes: &[u8]) -> Result<ObjData, MeshError> {
    if let Some(offset) = bytes.iter().position(|&b| b == 0) {
        return Err(MeshError::NotText { offset });
    }
    let text = std::str::from_utf8(bytes).map_err(|e| MeshError::NotText { offset: e.valid_up_to() })?;
    let mut data = ObjData::default();
    // The largest positive index seen and its line: OBJ files may reference vertices defined
    // further down, so positive indices are checked once the whole file is read.
    let mut max_ref: Option<(usize, u64)> = None;

    for (n, raw) in text.lines().enumerate() {
        let line_no = n + 1;
        let line = raw.split('#').next().unwrap_or("").trim();
        if line.is_empty() {
            continue;
        }
        let mut words = line.split_whitespace();
        let keyword = words.next().unwrap_or("");
        match keyword {
            "v" => {
                let mut xyz = [0.0f64; 3];
                let mut count = 0;
                for w in words.by_ref().take(3) {
                    let value: f64 = w
                        .parse()
                        .map_err(|_| err(line_no, format!("vertex coordinate '{w}' is not a number")))?;
                    if !value.is_finite() {
                        return Err(err(line_no, format!("vertex coordinate '{w}' is not finite (NaN or infinity)")));
                    }
                    xyz[count] = value;
                    count += 1;
                }
                if count < 3 {
                    return Err(err(line_no, format!("a vertex needs 3 coordinates (x y z), found {count}")));
                }
                // Optional w or vertex colours may follow; they must still be numbers.
                for w in words {
                    if w.parse::<f64>().is_err() {
                        return Err(err(line_no, format!("unexpected '{w}' after the vertex coordinates")));
                    }
                }
                data.positions.extend_from_slice(&xyz);
            }
            "f" => {
                let defined = (data.positions.len() / 3) as i64;
                let start = data.indices.len();
                for w in words {
                    let first = w.split('/').next().unwrap_or("");
                    let idx: i64 = first
                        .parse()
                        .map_err(|_| err(line_no, format!("face vertex '{w}' is not a vertex index")))?;
                    let zero_based = if idx > 0 {
                        let i = idx as u64;
                        if max_ref.is_none_or(|(_, m)| i > m) {
                            max_ref = Some((line_no, i));
                        }
                        idx - 1
                    } else if idx < 0 {
                        // Relative index: -1 is the last vertex defined so far.
                        if -idx > defined {
                            return Err(err(
                                line_no,
                                format!("relative face index {idx} reaches before the first vertex ({defined} defined so far)"),
                            ));
                        }
                        defined + idx
                    } else {
                        return Err(err(line_no, "face index 0 is invalid (OBJ indices start at 1)"));
                    };
                    if zero_based > u32::MAX as i64 - 1 {
                        return Err(err(line_no, format!("face index {idx} is too large")));
                    }
                    data.indices.push(zero_based as u32);
                }
                let arity = data.indices.len() - start;
                if arity < 3 {
                    return Err(err(line_no, format!("a face needs at least 3 vertices, found {arity}")));
                }
                data.arities.push(arity as u32);
            }
            k if IGNORED.contains(&k) => {}
            k => {
                let shown: String = k.chars().take(20).collect();
                return Err(err(line_no, format!("unknown OBJ statement '{shown}'")));
            }
        }
    }
    let nv = data.vertex_count() as u64;
    if let Some((line, m)) = max_ref {
        if m > nv {
            return Err(err(line, format!("face refers to vertex {m}, but the file defines only {nv} vertices")));
        }
    }
    if data.arities.is_empty() {
        return Err(MeshError::Empty(format!(
            "no faces: the file defines {nv} vertices and no 'f' lines (an OBJ triangle mesh is expected)"
        )));
    }
    Ok(data)
}

/// Write positions and polygons as OBJ text. Coordinates use Rust's shortest round-trip
/// formatting, so parsing the output gives back exactly the same `f64` values.
pub fn write(positions: &[f64], polygons: &ObjData, header: &str) -> Vec<u8> {
    use std::fmt::Write;
    let mut s = String::with_capacity(positions.len() * 12 + polygons.indices.len() * 8);
    for line in header.lines() {
        let _ = writeln!(s, "# {line}");
    }
    for p in positions.chunks_exact(3) {
        let _ = writeln!(s, "v {:?} {:?} {:?}", p[0], p[1], p[2]);
    }
    for poly in polygons.polygons() {
        s.push('f');
        for &i in poly {
            let _ = write!(s, " {}", i + 1);
        }
        s.push('\n');
    }
    s.into_bytes()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn writes_coordinates_that_parse_back_bit_identical() {
        let pos = vec![0.1, -1.0 / 3.0, 1e-300, 12345.678901234567, -0.0, 2.0f64.sqrt(), 1e300, 5e-324, 7.0];
        let data = ObjData { positions: pos.clone(), indices: vec![0, 1, 2], arities: vec![3] };
        let text = write(&pos, &data, "test");
        let back = parse(&text).unwrap();
        for (a, b) in pos.iter().zip(&back.positions) {
            assert_eq!(a.to_bits(), b.to_bits(), "{a} != {b}");
        }
        assert_eq!(back.indices, data.indices);
    }

    #[test]
    fn reads_slashes_relative_indices_and_polygons() {
        let text = b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1/1 3//1 -1\n";
        let d = parse(text).unwrap();
        assert_eq!(d.arities, vec![4]);
        assert_eq!(d.indices, vec![0, 1, 2, 3]);
    }

    #[test]
    fn names_the_line_of_each_defect() {
        let cases: &[(&[u8], &str)] = &[
            (b"v 0 0 0\nv 1 0\n", "line 2"),
            (b"v 0 0 nan\n", "not finite"),
            (b"v 0 0 inf\n", "not finite"),
            (b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n", "index 0"),
            (b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n", "only 3 vertices"),
            (b"v 0 0 0\nf 1 -5 1\n", "relative"),
            (b"v 0 0 0\nv 1 0 0\nf 1 2\n", "at least 3"),
            (b"hello world\n", "unknown OBJ statement"),
            (b"", "no faces"),
            (b"\x00\x01\x02", "not a text"),
            (b"v 1 2 3\n\xff\xfe", "not a text"),
            (b"v 0 0 0\nf a b c\n", "not a vertex index"),
        ];
        for (bytes, needle) in cases {
            let e = parse(bytes).unwrap_err().to_string();
            assert!(e.contains(needle), "{:?}: '{e}' lacks '{needle}'", String::from_utf8_lossy(bytes));
        }
    }
}
