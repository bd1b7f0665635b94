//! Ground contact: a rigid plane y = h that no vertex may end a step below.
//!
//! Applied after the integrator, as a velocity-level impulse, so that away from contact the
//! integrators are exactly themselves. A vertex found below the plane is put back on it, and:
//!   normal:     vy ← −e vy (if moving down), an impulse per unit mass j = (1 + e)|vy|;
//!   tangential: Coulomb friction removes up to μ j of the tangential speed |vt| (stick if
//!               |vt| ≤ μ j, otherwise vt ← vt (1 − μ j / |vt|)).
//! A vertex resting on the plane under gravity is pushed below it by g dt² every step and gets
//! j = g dt back, so friction grips with μ g dt per step: Coulomb's law with normal force m g.
//!
//! [`bounce`] is the velocity change of a vertex touching any rigid surface, shared with the
//! obstacles (defined with them, `obstacles/mod.rs`, the lower module).

use super::Ground;
pub use crate::obstacles::bounce;
use crate::vec3::{norm, sub};

/// Pinned vertices (`inv_mass` 0) are left where they are.
pub fn project(ground: &Ground, inv_mass: &[f64], x: &mut [f64], v: &mut [f64]) {
    let h = ground.height;
    for ((p, u), &im) in x.chunks_exact_mut(3).zip(v.chunks_exact_mut(3)).zip(inv_mass) {
        if p[1] >= h || im == 0.0 {
            continue;
        }
        p[1] = h;
        let b = bounce([u[0], u[1], u[2]], [0.0, 1.0, 0.0], ground.friction, ground.restitution);
        u.copy_from_slice(&b);
    }
}

/// A body stands on the ground if its lowest vertex is within this fraction of its size (the
/// bounding-box diagonal) of the plane, or below it: resting bodies lie on it to rounding (the
/// implicit step holds them there, the projection puts them there), so 1e-3 (2.5 mm on the
/// modeler's 2.5 m models) takes in every resting body and no body a visible gap above it.
pub const STANDING: f64 = 1e-3;

impl super::World {
    /// Move the ground plane to `height` (m), carrying what stands on it: every body whose
    /// lowest vertex is on the old plane or below it ([`STANDING`]) is moved up or down with it —
    /// its positions, pins, frozen shape (so Reset puts it back on the new plane) and grab anchors
    /// (`SoftBody::lift`) — so raising the ground lifts the model instead of burying its pinned
    /// foot and crushing the rest against the plane (measured before: the rooted mushroom's
    /// elastic energy 1.8 → 7.0 J at 0.1 m, a failed implicit step at 0.5 m). Bodies in the air
    /// stay where they are, and so do obstacles; a body resting on another body that stands on
    /// the ground is not carried (only what touches the plane is). Returns how many bodies moved.
    /// A bad height, a move that would take a position out of the finite numbers, or no ground,
    /// is refused as by [`crate::World::set_param`] ("ground.height") with nothing changed.
    pub fn move_ground(&mut self, height: f64) -> Result<usize, crate::params::ParamError> {
        let fail = |message: String| crate::params::ParamError { id: "ground.height".into(), message };
        let old = self.settings.ground.map(|g| g.height);
        let rise = old.map_or(0.0, |h| height - h);
        let standing: Vec<bool> = self
            .bodies
            .iter()
            .map(|b| {
                let x = b.positions();
                let (lo, hi) = crate::mesh::bounds(x);
                !x.is_empty() && old.is_some_and(|h| lo[1] <= h + STANDING * norm(sub(hi, lo)))
            })
            .collect();
        let moves = standing.iter().any(|&s| s) && rise != 0.0;
        if moves {
            let lifted_finite = |b: &crate::SoftBody| b.positions().chunks_exact(3).all(|p| (p[1] + rise).is_finite());
            if !rise.is_finite() || self.bodies.iter().zip(&standing).any(|(b, &s)| s && !lifted_finite(b)) {
                return Err(fail(format!("moving the ground from {} m to {height} m would move the bodies on it out of range", old.unwrap_or(0.0))));
            }
        }
        self.set_param(0, "ground.height", crate::params::Value::Number(height))?;
        if !moves {
            return Ok(0);
        }
        for (body, _) in self.bodies.iter_mut().zip(&standing).filter(|(_, &s)| s) {
            body.lift(rise);
        }
        Ok(standing.iter().filter(|&&s| s).count())
    }
}
