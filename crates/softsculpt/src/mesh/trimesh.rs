//! The indexed triangle mesh every other part of the crate simulates, and its bounding box.

use super::obj::{self, ObjData};
use super::topology::{self, EdgeCounts};

/// An indexed triangle mesh: positions (flat `xyz…`, metres) and counter-clockwise triangles
/// (seen from outside, so `(xb − xa) × (xc − xa)` points outward).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct TriMesh {
    pub positions: Vec<f64>,
    pub triangles: Vec<[u32; 3]>,
}

impl TriMesh {
    pub fn vertex_count(&self) -> usize {
        self.positions.len() / 3
    }
    pub fn edge_counts(&self) -> EdgeCounts {
        topology::count_edges(&self.triangles)
    }
    /// Closed and manifold: every edge shared by exactly two faces.
    pub fn is_closed(&self) -> bool {
        let c = self.edge_counts();
        c.boundary == 0 && c.non_manifold == 0
    }
    pub fn volume(&self) -> f64 {
        topology::signed_volume(&self.triangles, &self.positions)
    }
    /// Axis-aligned bounding box `(min, max)`.
    pub fn bounds(&self) -> ([f64; 3], [f64; 3]) {
        bounds(&self.positions)
    }
    /// Positions as OBJ text.
    pub fn to_obj(&self, header: &str) -> Vec<u8> {
        let data = ObjData {
            positions: Vec::new(),
            indices: self.triangles.iter().flatten().copied().collect(),
            arities: vec![3; self.triangles.len()],
        };
        obj::write(&self.positions, &data, header)
    }
}

pub fn bounds(positions: &[f64]) -> ([f64; 3], [f64; 3]) {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in positions.chunks_exact(3) {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    (lo, hi)
}
