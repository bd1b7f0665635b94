//! Remeshing a body ([`crate::mesh::remesh`]) while keeping what was painted on it.

use super::SoftBody;
use crate::error::SimError;
use crate::mesh::remesh::{remesh_keeping_shape, RemeshReport, Surface};
use crate::vec3::get;

impl SoftBody {
    /// The current shape remeshed to edge length `edge` (m), as a new body at rest in that shape
    /// (frozen), with the same material and gas. Masses and pins go to the nearest new vertices:
    /// every new vertex takes the mass of the old vertex nearest to it, and the masses are then
    /// scaled so the total is unchanged (a region painted ten times heavier stays ten times
    /// heavier per vertex); an old pinned vertex pins the new vertex nearest to it, and a new
    /// vertex whose nearest old vertex is pinned is pinned too (a pinned region stays pinned).
    ///
    /// The shape is kept or the remesh refused ([`remesh_keeping_shape`]): a body too coarse for
    /// `edge` is remeshed at `edge`/2 or `edge`/4 (or keeping its sharp edges), and one that no
    /// try keeps is an error, the body unchanged. [`SoftBody::remeshed_reporting`] says which.
    pub fn remeshed(&self, edge: f64) -> Result<SoftBody, SimError> {
        Ok(self.remeshed_reporting(edge)?.0)
    }

    /// [`SoftBody::remeshed`] and how: the edge length used, the tries, how far the surface moved.
    pub fn remeshed_reporting(&self, edge: f64) -> Result<(SoftBody, RemeshReport), SimError> {
        let (body, _, report) = self.remeshed_with_origins(edge)?;
        Ok((body, report))
    }

    /// [`SoftBody::remeshed_reporting`] and, per vertex of the new body, the old vertex nearest to it.
    pub(crate) fn remeshed_with_origins(&self, edge: f64) -> Result<(SoftBody, Vec<usize>, RemeshReport), SimError> {
        let bad = |e: crate::error::MeshError| SimError::BadParameter { name: "remesh", message: e.to_string() };
        let kept = remesh_keeping_shape(&self.to_mesh(), edge, None).map_err(bad)?;
        let (mesh, report) = (kept.mesh, kept.report);
        let (mesh, _) = crate::mesh::reorder::by_locality(&mesh);
        let total: f64 = self.model.mass.iter().sum();
        let mut body = SoftBody::new(&mesh, total, self.material.clone()).map_err(|e| SimError::BadParameter { name: "remesh", message: e.to_string() })?;
        let (old_near_new, new_near_old) = (nearest_vertices(&self.state.x, &mesh.positions), nearest_vertices(&mesh.positions, &self.state.x));
        let mut masses: Vec<f64> = old_near_new.iter().map(|&o| self.model.mass[o]).collect();
        let scale = total / masses.iter().sum::<f64>();
        masses.iter_mut().for_each(|m| *m *= scale);
        body.set_masses(&masses)?;
        for (new, &old) in old_near_new.iter().enumerate() {
            if self.is_pinned(old) {
                body.set_pinned(new, true)?;
            }
        }
        for (old, &new) in new_near_old.iter().enumerate() {
            if self.is_pinned(old) {
                body.set_pinned(new, true)?;
            }
        }
        body.freeze();
        Ok((body, old_near_new, report))
    }
}

/// For each point of `queries`, the index of the nearest point of `points` (both flat xyz),
/// through the projection grid with each point as a degenerate triangle.
fn nearest_vertices(points: &[f64], queries: &[f64]) -> Vec<usize> {
    let n = points.len() / 3;
    let tris: Vec<[u32; 3]> = (0..n as u32).map(|i| [i, i, i]).collect();
    let grid = Surface::new(points, &tris);
    (0..queries.len() / 3).map(|i| grid.nearest(get(queries, i)).1).collect()
}
