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
//! obstacles: with n the surface's outward unit normal and u·n < 0 (moving in),
//!   normal:     u·n ← −e (u·n), an impulse per unit mass j = (1 + e)|u·n|;
//!   tangential: Coulomb friction removes up to μ j of the tangential speed |u_t|.
//! A vertex moving out (u·n ≥ 0) keeps its velocity.

use super::Ground;
use crate::vec3::{add, dot, norm, scale, sub, V3};

pub fn bounce(u: V3, n: V3, friction: f64, restitution: f64) -> V3 {
    let un = dot(u, n);
    if un >= 0.0 {
        return u;
    }
    let j = (1.0 + restitution) * -un;
    let ut = sub(u, scale(n, un));
    let vt = norm(ut);
    let drop = friction * j;
    let ut = if vt <= drop { [0.0; 3] } else { scale(ut, 1.0 - drop / vt) };
    add(ut, scale(n, -restitution * un))
}

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
    /// lowest vertex is on the old plane or below it ([`STANDING`]) is moved up or down with it,
    /// pins and all (a rooted mushroom's foot is pinned on the ground; a body resting on it has
    /// its bottom held there), so raising the ground lifts the model instead of burying its
    /// pinned foot and crushing the rest against the plane (measured before: the mushroom's
    /// elastic energy 1.8 → 7.0 J at 0.1 m, a failed implicit step at 0.5 m). Bodies in the air
    /// stay where they are. Returns how many bodies moved; a bad height, or no ground, is
    /// refused as by [`crate::World::set_param`] ("ground.height") with nothing changed.
    pub fn move_ground(&mut self, height: f64) -> Result<usize, crate::params::ParamError> {
        let old = self.settings.ground.map(|g| g.height);
        self.set_param(0, "ground.height", crate::params::Value::Number(height))?;
        let Some(old) = old else { return Ok(0) };
        let rise = height - old;
        let mut moved = 0;
        for body in &mut self.bodies {
            let x = body.positions();
            let (mut lo, mut hi) = ([f64::MAX; 3], [f64::MIN; 3]);
            for p in x.chunks_exact(3) {
                for d in 0..3 {
                    lo[d] = lo[d].min(p[d]);
                    hi[d] = hi[d].max(p[d]);
                }
            }
            let size = norm(sub(hi, lo));
            if x.is_empty() || rise == 0.0 || lo[1] > old + STANDING * size {
                continue;
            }
            let lifted: Vec<f64> = x.iter().enumerate().map(|(k, &q)| if k % 3 == 1 { q + rise } else { q }).collect();
            let v = body.velocities().to_vec();
            body.set_state(&lifted, &v).expect("a translation of finite positions is finite");
            moved += 1;
        }
        Ok(moved)
    }
}
