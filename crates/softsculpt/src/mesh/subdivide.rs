//! Loop subdivision (Loop 1987, with Warren's weights): every triangle becomes four.
//!
//! New edge vertex on edge (a, b) with opposite vertices c, d: 3/8 (a + b) + 1/8 (c + d); on a
//! boundary edge the midpoint. Old vertex with n neighbours: (1 − n β) v + β Σ neighbours,
//! β = 3/16 for n = 3 and 3/(8n) otherwise; an old boundary vertex: 3/4 v + 1/8 (its two
//! boundary neighbours). The result of a closed outward mesh is closed and outward.

use super::{topology, TriMesh};
use std::collections::HashMap;

/// The subdivided mesh and, for each of its vertices, the one or two vertices of the input it
/// comes from (old vertices first, in order; then one vertex per edge, `[a, b]`).
pub fn loop_subdivide(mesh: &TriMesh) -> (TriMesh, Vec<[u32; 2]>) {
    let n = mesh.vertex_count();
    let edges = topology::edges(&mesh.triangles);
    let edge_index: HashMap<(u32, u32), u32> = edges.iter().enumerate().map(|(k, e)| ((e[0], e[1]), k as u32)).collect();
    let key = |a: u32, b: u32| if a < b { (a, b) } else { (b, a) };
    // Opposite vertices of each edge (up to two).
    let mut opposite: Vec<Vec<u32>> = vec![Vec::new(); edges.len()];
    for t in &mesh.triangles {
        for k in 0..3 {
            let e = edge_index[&key(t[k], t[(k + 1) % 3])] as usize;
            opposite[e].push(t[(k + 2) % 3]);
        }
    }
    let p = |i: u32| &mesh.positions[3 * i as usize..3 * i as usize + 3];
    let mut pos = vec![0.0; 3 * (n + edges.len())];
    // Neighbours of old vertices, and boundary neighbours.
    let mut neighbours: Vec<Vec<u32>> = vec![Vec::new(); n];
    let mut boundary: Vec<Vec<u32>> = vec![Vec::new(); n];
    for (k, e) in edges.iter().enumerate() {
        neighbours[e[0] as usize].push(e[1]);
        neighbours[e[1] as usize].push(e[0]);
        if opposite[k].len() != 2 {
            boundary[e[0] as usize].push(e[1]);
            boundary[e[1] as usize].push(e[0]);
        }
    }
    for i in 0..n {
        let out = &mut pos[3 * i..3 * i + 3];
        let v = p(i as u32);
        if boundary[i].len() == 2 {
            let (a, b) = (p(boundary[i][0]), p(boundary[i][1]));
            for d in 0..3 {
                out[d] = 0.75 * v[d] + 0.125 * (a[d] + b[d]);
            }
        } else if boundary[i].is_empty() && !neighbours[i].is_empty() {
            let m = neighbours[i].len();
            let beta = if m == 3 { 3.0 / 16.0 } else { 3.0 / (8.0 * m as f64) };
            for d in 0..3 {
                let sum: f64 = neighbours[i].iter().map(|&j| p(j)[d]).sum();
                out[d] = (1.0 - m as f64 * beta) * v[d] + beta * sum;
            }
        } else {
            out.copy_from_slice(v); // corners of non-manifold or odd boundaries stay
        }
    }
    for (k, e) in edges.iter().enumerate() {
        let out = &mut pos[3 * (n + k)..3 * (n + k) + 3];
        let (a, b) = (p(e[0]), p(e[1]));
        if opposite[k].len() == 2 {
            let (c, d2) = (p(opposite[k][0]), p(opposite[k][1]));
            for d in 0..3 {
                out[d] = 0.375 * (a[d] + b[d]) + 0.125 * (c[d] + d2[d]);
            }
        } else {
            for d in 0..3 {
                out[d] = 0.5 * (a[d] + b[d]);
            }
        }
    }
    let mid = |a: u32, b: u32| n as u32 + edge_index[&key(a, b)];
    let mut tris = Vec::with_capacity(4 * mesh.triangles.len());
    for &[a, b, c] in &mesh.triangles {
        let (ab, bc, ca) = (mid(a, b), mid(b, c), mid(c, a));
        tris.extend_from_slice(&[[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
    }
    let parents = (0..n as u32).map(|i| [i, i]).chain(edges.iter().copied()).collect();
    (TriMesh { positions: pos, triangles: tris }, parents)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::builtin::{builtin, icosphere};

    #[test]
    fn subdividing_keeps_a_closed_outward_surface_and_quadruples_faces() {
        for m in [icosphere(1, 1.0), builtin("octopus").unwrap()] {
            let (s, parents) = loop_subdivide(&m);
            let c = s.edge_counts();
            assert_eq!((c.boundary, c.non_manifold, c.inconsistent), (0, 0, 0));
            assert_eq!(s.triangles.len(), 4 * m.triangles.len());
            assert_eq!(s.vertex_count(), m.vertex_count() + m.edge_counts().edges);
            assert_eq!(parents.len(), s.vertex_count());
            assert!(s.volume() > 0.0);
        }
    }

    /// Loop subdivision shrinks a convex body slightly (it approximates, not interpolates):
    /// the unit icosphere's volume decreases but stays close.
    #[test]
    fn subdivision_smooths_toward_the_limit_surface() {
        let m = icosphere(2, 1.0);
        let (s, _) = loop_subdivide(&m);
        assert!(s.volume() < m.volume() && s.volume() > 0.9 * m.volume());
    }
}
