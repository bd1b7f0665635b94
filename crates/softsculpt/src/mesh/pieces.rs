//! Pieces: the connected shells of a mesh (surfaces sharing no vertex), each as a mesh of its own.
//! A file made of separate shells (overlapping convex parts, a character's eyes and body…) is
//! one [`TriMesh`] after loading; the modeler offers one body per piece, or the largest only.

use super::TriMesh;
use crate::vec3::{cross, get, norm, sub};

/// The pieces of `mesh`, largest surface area first (ties: in order of their first face). Each
/// keeps its vertices in the order they have in `mesh` and its triangles' windings.
pub fn split(mesh: &TriMesh) -> Vec<TriMesh> {
    let n = mesh.vertex_count();
    let mut parent: Vec<u32> = (0..n as u32).collect();
    fn find(parent: &mut [u32], mut i: u32) -> u32 {
        while parent[i as usize] != i {
            parent[i as usize] = parent[parent[i as usize] as usize];
            i = parent[i as usize];
        }
        i
    }
    for t in &mesh.triangles {
        for k in 1..3 {
            let (a, b) = (find(&mut parent, t[0]), find(&mut parent, t[k]));
            if a != b {
                parent[a.max(b) as usize] = a.min(b);
            }
        }
    }
    // Pieces numbered by their first face; each face to its piece.
    let mut piece_of_root = vec![u32::MAX; n];
    let mut faces: Vec<Vec<[u32; 3]>> = Vec::new();
    for t in &mesh.triangles {
        let r = find(&mut parent, t[0]) as usize;
        if piece_of_root[r] == u32::MAX {
            piece_of_root[r] = faces.len() as u32;
            faces.push(Vec::new());
        }
        faces[piece_of_root[r] as usize].push(*t);
    }
    let mut pieces: Vec<(f64, TriMesh)> = faces
        .into_iter()
        .map(|tris| {
            // Vertices renumbered in their order in `mesh`.
            let mut used: Vec<u32> = tris.iter().flatten().copied().collect();
            used.sort_unstable();
            used.dedup();
            let mut new_of = std::collections::HashMap::with_capacity(used.len());
            let mut positions = Vec::with_capacity(3 * used.len());
            for (k, &v) in used.iter().enumerate() {
                new_of.insert(v, k as u32);
                positions.extend_from_slice(&mesh.positions[3 * v as usize..3 * v as usize + 3]);
            }
            let triangles: Vec<[u32; 3]> = tris.iter().map(|t| t.map(|v| new_of[&v])).collect();
            (area(&mesh.positions, &tris), TriMesh { positions, triangles })
        })
        .collect();
    // Stable: equal areas keep their order.
    pieces.sort_by(|a, b| b.0.total_cmp(&a.0));
    pieces.into_iter().map(|(_, m)| m).collect()
}

/// Surface area (m²) of `tris`: Σ |(b − a) × (c − a)| / 2.
pub fn area(positions: &[f64], tris: &[[u32; 3]]) -> f64 {
    tris.iter()
        .map(|t| {
            let (a, b, c) = (get(positions, t[0] as usize), get(positions, t[1] as usize), get(positions, t[2] as usize));
            norm(cross(sub(b, a), sub(c, a))) / 2.0
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::builtin;

    fn shifted(m: &TriMesh, scale: f64, dx: f64) -> TriMesh {
        TriMesh { positions: m.positions.chunks_exact(3).flat_map(|p| [p[0] * scale + dx, p[1] * scale, p[2] * scale]).collect(), triangles: m.triangles.clone() }
    }

    #[test]
    fn two_shells_split_largest_first_with_their_areas_and_windings() {
        let ball = builtin::icosphere(1, 1.0);
        // A small ball first in the file, a ball twice its size second.
        let small = shifted(&ball, 0.5, -3.0);
        let big = shifted(&ball, 1.0, 3.0);
        let nv = small.vertex_count() as u32;
        let mut both = small.clone();
        both.positions.extend_from_slice(&big.positions);
        both.triangles.extend(big.triangles.iter().map(|t| t.map(|v| v + nv)));
        let pieces = split(&both);
        assert_eq!(pieces.len(), 2);
        assert_eq!(pieces[0], big, "the larger piece first, vertices and windings as in the file");
        assert_eq!(pieces[1], small);
        // Area scales with the square of the size: 4× (exact up to rounding, 1e-12 relative).
        let (a0, a1) = (area(&pieces[0].positions, &pieces[0].triangles), area(&pieces[1].positions, &pieces[1].triangles));
        assert!((a0 / a1 - 4.0).abs() < 1e-12, "{a0} / {a1}");
        // Each piece is closed, as the ball was; the volumes add up to the whole's.
        assert!(pieces.iter().all(|p| p.is_closed()));
        let v: f64 = pieces.iter().map(|p| p.volume()).sum();
        assert!((v - both.volume()).abs() < 1e-12 * v.abs());
    }

    #[test]
    fn one_shell_is_one_piece_unchanged() {
        let ball = builtin::icosphere(2, 1.0);
        assert_eq!(split(&ball), vec![ball]);
    }
}
