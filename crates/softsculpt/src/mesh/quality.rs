//! Triangle quality: how good a mesh is as a spring network. Long thin triangles make springs of
//! very different lengths and stiffness per area, so a mesh report shows the smallest angle, the
//! share of angles below [`SMALL_ANGLE_DEG`] and the spread of edge lengths.

use super::{topology, TriMesh};
use crate::vec3::{dot, get, norm, sub};

/// Angles below this (degrees) count as small (a common bound for a "good" triangulation: a
/// Delaunay refinement guarantees about 20.7°–30°, isotropic remeshing keeps most above it).
pub const SMALL_ANGLE_DEG: f64 = 25.0;
/// A regular mesh has its edges within this factor band of their mean length: [0.75, 1.33].
pub const LENGTH_BAND: (f64, f64) = (0.75, 4.0 / 3.0);

#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Quality {
    /// Smallest and largest interior angle over all triangles (degrees).
    pub min_angle_deg: f64,
    pub max_angle_deg: f64,
    /// Fraction of all angles below [`SMALL_ANGLE_DEG`].
    pub small_angle_share: f64,
    /// Edge lengths (m): shortest, mean, longest, and the relative standard deviation σ/mean.
    pub edge_min: f64,
    pub edge_mean: f64,
    pub edge_max: f64,
    pub edge_spread: f64,
    /// Fraction of edges with lengths within [`LENGTH_BAND`] × `reference` (the mean unless given).
    pub edges_in_band: f64,
}

impl Quality {
    /// Poor for simulation: more than a tenth of the angles are small, or the edges spread by
    /// more than half their mean.
    pub fn is_poor(&self) -> bool {
        self.small_angle_share > 0.1 || self.edge_spread > 0.5
    }
}

/// The quality of `mesh`; the length band is taken about `reference` (m), or the mean edge.
pub fn quality(mesh: &TriMesh, reference: Option<f64>) -> Quality {
    let p = |i: u32| get(&mesh.positions, i as usize);
    let mut q = Quality { min_angle_deg: 180.0, ..Default::default() };
    let (mut small, mut angles) = (0usize, 0usize);
    for t in &mesh.triangles {
        for k in 0..3 {
            let (a, b, c) = (p(t[k]), p(t[(k + 1) % 3]), p(t[(k + 2) % 3]));
            let (u, v) = (sub(b, a), sub(c, a));
            let denom = norm(u) * norm(v);
            let angle = if denom > 0.0 { (dot(u, v) / denom).clamp(-1.0, 1.0).acos().to_degrees() } else { 0.0 };
            q.min_angle_deg = q.min_angle_deg.min(angle);
            q.max_angle_deg = q.max_angle_deg.max(angle);
            small += (angle < SMALL_ANGLE_DEG) as usize;
            angles += 1;
        }
    }
    q.small_angle_share = small as f64 / angles.max(1) as f64;
    let lengths: Vec<f64> = topology::edges(&mesh.triangles).iter().map(|e| norm(sub(p(e[0]), p(e[1])))).collect();
    if lengths.is_empty() {
        return Quality::default();
    }
    let n = lengths.len() as f64;
    q.edge_min = lengths.iter().copied().fold(f64::INFINITY, f64::min);
    q.edge_max = lengths.iter().copied().fold(0.0, f64::max);
    q.edge_mean = lengths.iter().sum::<f64>() / n;
    q.edge_spread = (lengths.iter().map(|l| (l - q.edge_mean).powi(2)).sum::<f64>() / n).sqrt() / q.edge_mean;
    let r = reference.unwrap_or(q.edge_mean);
    q.edges_in_band = lengths.iter().filter(|&&l| l >= LENGTH_BAND.0 * r && l <= LENGTH_BAND.1 * r).count() as f64 / n;
    q
}
