//! The velocity change of a vertex touching a rigid surface, shared by the ground and the
//! obstacles: with n the surface's outward unit normal and u·n < 0 (moving in),
//!   normal:     u·n ← −e (u·n), an impulse per unit mass j = (1 + e)|u·n|;
//!   tangential: Coulomb friction removes up to μ j of the tangential speed |u_t|
//!               (stick if |u_t| ≤ μ j, otherwise u_t ← u_t (1 − μ j / |u_t|)).
//! A vertex moving out (u·n ≥ 0) keeps its velocity.

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
