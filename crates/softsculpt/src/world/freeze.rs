//! Freezing a body of the world: the world knows the gravity and what supports the body (the
//! ground, the obstacles), which a freeze under load needs (`body/freeze.rs`).

use super::World;
use crate::body::{FreezeOptions, FreezeReport, Supports};
use crate::error::SimError;

/// A vertex within this distance (m) of the ground or an obstacle's surface rests on it. The
/// contact stages put a touching vertex exactly on the surface (distance 0, up to rounding of
/// ~1e-16 m at unit scale); a gap of 1 µm counts those and nothing that hovers visibly.
pub const SUPPORT_GAP: f64 = 1e-6;

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
        let finer = if how.keep_tension { b.subdivided_keeping_tension()? } else { b.subdivided()? };
        let gas = b.gas_reference();
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
    /// freeze's report.
    pub fn remesh(&mut self, body: usize, edge: f64, under_load: bool) -> Result<(usize, FreezeReport), SimError> {
        let b = self.bodies.get(body).ok_or_else(|| no_body(body, self.bodies.len()))?;
        let even = b.remeshed(edge)?;
        let gas = b.gas_reference();
        let (_, dropped) = self.replace_body(body, even);
        let mut report = FreezeReport::default();
        if under_load {
            self.bodies[body].set_gas_reference(gas)?;
            report = self.freeze(body, FreezeOptions { under_load: true, keep_tension: false })?;
        }
        Ok((dropped, report))
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
