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
