//! Freezing a body of the world: the world knows the gravity and what supports the body (the
//! ground, the obstacles), which a freeze under load needs (`body/freeze.rs`).

use super::World;
use crate::body::{FreezeOptions, FreezeReport, Supports};
use crate::error::SimError;

/// A vertex within this distance (m) of the ground or an obstacle's surface rests on it. The
/// contact stages put a touching vertex exactly on the surface (distance 0, up to rounding of
/// ~1e-16 m at unit scale); a gap of 1 µm counts those and nothing that hovers visibly.
pub const SUPPORT_GAP: f64 = 1e-6;

/// The farthest a new mesh's vertex is moved back onto the support its origin rested on, as a
/// fraction of the new mesh's mean edge length (`World::put_on_supports`; a fraction, so that a
/// model of any size is treated alike): Loop subdivision lifted the octopus's tentacle tips by
/// 0.1 of an edge; a quarter covers that without flattening what stood higher.
pub const SUPPORT_LIFT: f64 = 0.25;

impl World {
    /// Freeze body `body` as `how` says (see `SoftBody::freeze_with`), under this world's gravity
    /// and supports. The report holds the tension-keeping freeze's residual.
    pub fn freeze(&mut self, body: usize, how: FreezeOptions) -> Result<FreezeReport, SimError> {
        let resting = self.resting_vertices(body)?;
        let gravity = self.settings.gravity;
        Ok(self.bodies[body].freeze_with(how, Supports { gravity, resting: &resting }))
    }

    /// Replace body `body` by its Loop subdivision, frozen as `how` says: plainly (no option,
    /// `SoftBody::subdivided`), or with the gas reference it had, under load and/or keeping the
    /// tension (carried by `SoftBody::subdivided_keeping_tension`, then solved exact). Returns
    /// how many of its pending scene events were dropped (they no longer fit) and the freeze's
    /// report.
    pub fn subdivide(&mut self, body: usize, how: FreezeOptions) -> Result<(usize, FreezeReport), SimError> {
        let b = self.bodies.get(body).ok_or_else(|| no_body(body, self.bodies.len()))?;
        let (mut finer, parents) = b.subdivided_with_parents(how.keep_tension)?;
        let gas = b.gas_reference();
        // A new vertex rests where both its parents rested (on an edge between two of them).
        let rested = self.resting_vertices(body)?;
        self.put_on_supports(&mut finer, |i| parents[i].iter().all(|&p| rested[p as usize]), !how.keep_tension);
        let (_, dropped) = self.replace_body(body, finer);
        let mut report = FreezeReport::default();
        if how.under_load || how.keep_tension {
            self.bodies[body].set_gas_reference(gas)?;
            report = self.freeze(body, how)?;
        }
        Ok((dropped, report))
    }

    /// Replace body `body` by its isotropic remeshing to edge length `edge` (m)
    /// (`SoftBody::remeshed`: masses and pins carried to the nearest new vertices), frozen
    /// plainly, or, `under_load`, with the gas reference it had and under load (as Subdivide
    /// does under gravity, so the shape holds). Returns the dropped pending events and the
    /// freeze's report. The shape is kept or the remesh refused, the world unchanged (see
    /// [`crate::mesh::remesh::remesh_keeping_shape`]); [`World::remesh_reporting`] says how.
    pub fn remesh(&mut self, body: usize, edge: f64, under_load: bool) -> Result<(usize, FreezeReport), SimError> {
        let (dropped, report, _) = self.remesh_reporting(body, edge, under_load)?;
        Ok((dropped, report))
    }

    /// [`World::remesh`] and how the shape was kept: the edge length used (shorter than `edge`
    /// when the mesh was too coarse for it), the tries, how far the surface moved.
    pub fn remesh_reporting(&mut self, body: usize, edge: f64, under_load: bool) -> Result<(usize, FreezeReport, crate::mesh::remesh::RemeshReport), SimError> {
        let b = self.bodies.get(body).ok_or_else(|| no_body(body, self.bodies.len()))?;
        let (mut even, nearest, remeshed) = b.remeshed_with_origins(edge)?;
        let gas = b.gas_reference();
        // A new vertex rests where the old vertex nearest to it rested.
        let rested = self.resting_vertices(body)?;
        self.put_on_supports(&mut even, |i| rested[nearest[i]], true);
        let (_, dropped) = self.replace_body(body, even);
        let mut report = FreezeReport::default();
        if under_load {
            self.bodies[body].set_gas_reference(gas)?;
            report = self.freeze(body, FreezeOptions { under_load: true, keep_tension: false })?;
        }
        Ok((dropped, report, remeshed))
    }

    /// Put back on its support every vertex of `b` (a new mesh of a body of this world) for
    /// which `rested(i)` says its origin rested there: the ground or the obstacle nearest to it,
    /// moved along the surface's normal by its distance, from above or from below (the remesher
    /// left 48 of the settled sphere's bottom vertices 1.4 mm under the ground), by at most
    /// [`SUPPORT_LIFT`] of the new mesh's mean edge length (a smoothing's lift, not a leap).
    /// Why: Loop subdivision and remeshing smooth the mesh, which lifts the vertices that stood
    /// on the ground (the octopus's tentacle tips by 6.4 mm, 0.1 of its edges after one
    /// subdivision). Nothing would then rest within [`SUPPORT_GAP`], so a freeze under load
    /// found no support and carried none of the weight, and the subdivided octopus sagged from
    /// 1.76 m to 1.33 m within a second as if frozen plainly. With `refreeze`, a body that moved
    /// is frozen plainly again at the new shape (its springs at rest there).
    fn put_on_supports(&self, b: &mut crate::SoftBody, rested: impl Fn(usize) -> bool, refreeze: bool) {
        let rest = b.rest_lengths();
        let lift = SUPPORT_LIFT * rest.iter().sum::<f64>() / rest.len().max(1) as f64;
        let mut x = b.positions().to_vec();
        let mut moved = false;
        for (i, p) in x.chunks_exact_mut(3).enumerate() {
            if !rested(i) {
                continue;
            }
            let q = [p[0], p[1], p[2]];
            let ground = self.settings.ground.map(|g| (q[1] - g.height, [0.0, 1.0, 0.0])).filter(|(d, _)| d.abs() <= lift);
            let obstacles = self.settings.obstacles.iter().filter_map(|o| o.shape.distance_within(q, lift)).filter(|(d, _)| d.abs() <= lift);
            let nearest = obstacles.chain(ground).min_by(|a, b| a.0.total_cmp(&b.0));
            if let Some((d, n)) = nearest {
                if d.abs() > SUPPORT_GAP {
                    for k in 0..3 {
                        p[k] -= d * n[k];
                    }
                    moved = true;
                }
            }
        }
        if moved {
            let v = vec![0.0; x.len()];
            b.set_state(&x, &v).expect("same length, finite");
            if refreeze {
                b.freeze();
            }
        }
    }

    /// The triangle quality of body `body`'s current shape (`mesh::quality`).
    pub fn quality(&self, body: usize) -> Result<crate::mesh::quality::Quality, SimError> {
        let b = self.bodies.get(body).ok_or_else(|| no_body(body, self.bodies.len()))?;
        Ok(crate::mesh::quality::quality(&b.to_mesh(), None))
    }

    /// Per vertex of body `body`: whether it rests on the ground or on an obstacle (within
    /// [`SUPPORT_GAP`]).
    pub fn resting_vertices(&self, body: usize) -> Result<Vec<bool>, SimError> {
        let b = self.bodies.get(body).ok_or_else(|| no_body(body, self.bodies.len()))?;
        let ground = self.settings.ground.map(|g| g.height);
        Ok(b.positions()
            .chunks_exact(3)
            .map(|p| ground.is_some_and(|h| p[1] <= h + SUPPORT_GAP) || self.settings.obstacles.iter().any(|o| o.shape.distance([p[0], p[1], p[2]]).0 <= SUPPORT_GAP))
            .collect())
    }
}

fn no_body(body: usize, count: usize) -> SimError {
    SimError::BadParameter { name: "body", message: format!("there is no body {body} (the world has {count})") }
}
