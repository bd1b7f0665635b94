//! Vertex order for memory locality.
//!
//! Springs and faces gather the positions of their vertices. If vertices that are close on the
//! surface are also close in memory, those gathers hit the cache; a mesh as exported (or an
//! icosphere, whose new vertices are appended level by level) often has neighbours far apart in
//! memory. We sort vertices along a Morton (Z-order) curve of their positions, then faces by
//! their smallest vertex; spring order follows from the faces ((i, j) sorted). This changes
//! nothing physical: only the order of summation, hence rounding in the last bits.

use super::TriMesh;

/// Interleave the low 21 bits of x, y, z into a 63-bit Morton code.
fn morton(x: u64, y: u64, z: u64) -> u64 {
    fn spread(mut v: u64) -> u64 {
        v &= 0x1f_ffff;
        v = (v | v << 32) & 0x1f00000000ffff;
        v = (v | v << 16) & 0x1f0000ff0000ff;
        v = (v | v << 8) & 0x100f00f00f00f00f;
        v = (v | v << 4) & 0x10c30c30c30c30c3;
        v = (v | v << 2) & 0x1249249249249249;
        v
    }
    spread(x) | spread(y) << 1 | spread(z) << 2
}

/// The mesh with vertices in Morton order and faces sorted by smallest vertex, and for every
/// old vertex its new index.
pub fn by_locality(mesh: &TriMesh) -> (TriMesh, Vec<u32>) {
    let n = mesh.vertex_count();
    let (lo, hi) = mesh.bounds();
    let scale: Vec<f64> = (0..3).map(|k| if hi[k] > lo[k] { ((1u64 << 21) - 1) as f64 / (hi[k] - lo[k]) } else { 0.0 }).collect();
    let key = |i: usize| {
        let q = |k: usize| ((mesh.positions[3 * i + k] - lo[k]) * scale[k]) as u64;
        morton(q(0), q(1), q(2))
    };
    let mut order: Vec<u32> = (0..n as u32).collect();
    order.sort_by_key(|&i| (key(i as usize), i));
    let mut old_to_new = vec![0u32; n];
    let mut positions = Vec::with_capacity(3 * n);
    for (new, &old) in order.iter().enumerate() {
        old_to_new[old as usize] = new as u32;
        positions.extend_from_slice(&mesh.positions[3 * old as usize..3 * old as usize + 3]);
    }
    let mut triangles: Vec<[u32; 3]> = mesh.triangles.iter().map(|t| t.map(|i| old_to_new[i as usize])).collect();
    triangles.sort_by_key(|t| {
        let mut s = *t;
        s.sort_unstable();
        s
    });
    (TriMesh { positions, triangles }, old_to_new)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::builtin::icosphere;

    #[test]
    fn reordering_keeps_the_surface() {
        let m = icosphere(3, 1.0);
        let (r, map) = by_locality(&m);
        assert_eq!(r.vertex_count(), m.vertex_count());
        assert_eq!(r.edge_counts(), m.edge_counts());
        assert!((r.volume() - m.volume()).abs() < 1e-13);
        for i in 0..m.vertex_count() {
            let j = map[i] as usize;
            assert_eq!(m.positions[3 * i..3 * i + 3], r.positions[3 * j..3 * j + 3]);
        }
    }
}
