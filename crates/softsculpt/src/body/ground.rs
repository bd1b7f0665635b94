//! Ground contact: a rigid plane y = h that no vertex may end a step below.
//!
//! Applied after the integrator, as a velocity-level impulse, so that away from contact the
//! integrators are exactly themselves. A vertex found below the plane is put back on it, and:
//!   normal:     vy ← −e vy (if moving down), an impulse per unit mass j = (1 + e)|vy|;
//!   tangential: Coulomb friction removes up to μ j of the tangential speed |vt| (stick if
//!               |vt| ≤ μ j, otherwise vt ← vt (1 − μ j / |vt|)).
//! A vertex resting on the plane under gravity is pushed below it by g dt² every step and gets
//! j = g dt back, so friction grips with μ g dt per step: Coulomb's law with normal force m g.

use super::Ground;

/// Pinned vertices (`inv_mass` 0) are left where they are.
pub fn project(ground: &Ground, inv_mass: &[f64], x: &mut [f64], v: &mut [f64]) {
    let h = ground.height;
    for ((p, u), &im) in x.chunks_exact_mut(3).zip(v.chunks_exact_mut(3)).zip(inv_mass) {
        if p[1] >= h || im == 0.0 {
            continue;
        }
        p[1] = h;
        let b = super::contact::bounce([u[0], u[1], u[2]], [0.0, 1.0, 0.0], ground.friction, ground.restitution);
        u.copy_from_slice(&b);
    }
}
