//! Rigid obstacles: spheres, boxes (axis-aligned or rotated) and capsules that soft-body vertices
//! cannot enter. Usable as floors, walls and tools.
//!
//! Contact is handled like the ground (see `world/ground.rs`), after the integrator: a vertex
//! whose straight path during the step (from x_prev to x) enters an obstacle is stopped at the
//! entry point — a continuous check, so a fast vertex cannot tunnel through a thin wall — and a
//! vertex found inside is pushed out to the nearest surface point. Then, with n the outward
//! normal there, the velocity loses its inward normal part (inelastic: impulse per unit mass
//! j = −v·n) and Coulomb friction removes up to μ j of its tangential part ([`bounce`]).
//! Then the edges (`resolve_edges`): spheres and capsules thinner than the mesh's edges would
//! otherwise pass between two vertices.
//!
//! Below the settings that hold them and the world that runs them (`tests/layers.rs`); the world
//! re-exports this module under its old paths, `world::obstacles` and `world::mesh_obstacle`.

pub mod mesh_obstacle;

use crate::geometry::{closest_segments, lerp, rotate};
use crate::mesh::TriMesh;
use crate::vec3::{add, dot, norm, scale, sub, V3};
use mesh_obstacle::MeshShape;
use std::sync::Arc;

/// The shape of an obstacle (metres).
#[derive(Debug, Clone, PartialEq)]
pub enum Shape {
    Sphere { center: V3, radius: f64 },
    /// A box of half extents `half` along its local axes; `axes` are those axes in world
    /// coordinates (orthonormal rows; the identity for an axis-aligned box).
    Box { center: V3, half: V3, axes: [V3; 3] },
    /// All points within `radius` of the segment from `a` to `b`.
    Capsule { a: V3, b: V3, radius: f64 },
    /// A static triangle mesh: solid behind its faces (see `mesh_obstacle.rs`).
    Mesh(Arc<MeshShape>),
}

impl PartialEq for MeshShape {
    fn eq(&self, other: &Self) -> bool {
        std::ptr::eq(self, other)
    }
}

/// Friction of an obstacle unless set (dimensionless), from the parameter table.
pub const DEFAULT_FRICTION: f64 = crate::params::OBSTACLE_FRICTION.number();

/// A rigid obstacle with its Coulomb friction coefficient (dimensionless).
#[derive(Debug, Clone, PartialEq)]
pub struct Obstacle {
    pub shape: Shape,
    pub friction: f64,
}

impl Obstacle {
    pub fn sphere(center: V3, radius: f64) -> Self {
        Obstacle { shape: Shape::Sphere { center, radius }, friction: DEFAULT_FRICTION }
    }
    pub fn aabb(center: V3, half: V3) -> Self {
        Obstacle { shape: Shape::Box { center, half, axes: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]] }, friction: DEFAULT_FRICTION }
    }
    /// A box rotated by `angle` radians about the unit `axis`.
    pub fn rotated_box(center: V3, half: V3, axis: V3, angle: f64) -> Self {
        let (s, c) = angle.sin_cos();
        let k = crate::vec3::normalize(axis);
        // R e_i for the three basis vectors; the rows of `axes` are the rotated axes.
        let rot = |v: V3| rotate(v, k, s, c);
        let axes = [rot([1.0, 0.0, 0.0]), rot([0.0, 1.0, 0.0]), rot([0.0, 0.0, 1.0])];
        Obstacle { shape: Shape::Box { center, half, axes }, friction: DEFAULT_FRICTION }
    }
    pub fn capsule(a: V3, b: V3, radius: f64) -> Self {
        Obstacle { shape: Shape::Capsule { a, b, radius }, friction: DEFAULT_FRICTION }
    }
    /// A static triangle mesh (its faces' normals say which side is outside).
    pub fn triangle_mesh(mesh: &TriMesh) -> Result<Self, String> {
        Ok(Obstacle { shape: Shape::Mesh(Arc::new(MeshShape::new(mesh)?)), friction: DEFAULT_FRICTION })
    }

    /// Every number finite, sizes positive, axes orthonormal.
    pub fn validate(&self) -> Result<(), String> {
        let finite = |v: &[f64]| v.iter().all(|x| x.is_finite());
        if !(self.friction.is_finite() && self.friction >= 0.0) {
            return Err(format!("friction must be finite and ≥ 0, got {}", self.friction));
        }
        match &self.shape {
            Shape::Sphere { center, radius } if finite(center) && radius.is_finite() && *radius > 0.0 => Ok(()),
            Shape::Box { center, half, axes }
                if finite(center) && finite(half) && half.iter().all(|h| *h > 0.0) && axes.iter().all(|a| finite(a)) =>
            {
                for i in 0..3 {
                    for j in 0..3 {
                        let want = if i == j { 1.0 } else { 0.0 };
                        if (dot(axes[i], axes[j]) - want).abs() > 1e-9 {
                            return Err("box axes must be orthonormal".into());
                        }
                    }
                }
                Ok(())
            }
            Shape::Capsule { a, b, radius } if finite(a) && finite(b) && radius.is_finite() && *radius > 0.0 => Ok(()),
            Shape::Mesh(_) => Ok(()), // checked when built
            _ => Err(format!("obstacle sizes must be finite and positive: {:?}", self.shape)),
        }
    }
}

impl Shape {
    /// Signed distance of `p` to the surface (negative inside, m) and the outward unit normal
    /// at the closest surface point.
    pub fn distance(&self, p: V3) -> (f64, V3) {
        match self {
            Shape::Sphere { center, radius } => {
                let d = sub(p, *center);
                let r = norm(d);
                let n = if r > 0.0 { scale(d, 1.0 / r) } else { [0.0, 1.0, 0.0] };
                (r - radius, n)
            }
            Shape::Box { center, half, axes } => {
                let d = sub(p, *center);
                let q = [dot(d, axes[0]), dot(d, axes[1]), dot(d, axes[2])];
                let out = [q[0].abs() - half[0], q[1].abs() - half[1], q[2].abs() - half[2]];
                let sign = |k: usize| if q[k] < 0.0 { -1.0 } else { 1.0 };
                if out.iter().all(|&o| o <= 0.0) {
                    // Inside: the nearest face.
                    let k = (0..3).max_by(|&a, &b| out[a].total_cmp(&out[b])).unwrap_or(0);
                    return (out[k], scale(axes[k], sign(k)));
                }
                let e = [out[0].max(0.0) * sign(0), out[1].max(0.0) * sign(1), out[2].max(0.0) * sign(2)];
                let dist = norm(e);
                let local = scale(e, 1.0 / dist);
                let n = add(add(scale(axes[0], local[0]), scale(axes[1], local[1])), scale(axes[2], local[2]));
                (dist, n)
            }
            Shape::Capsule { a, b, radius } => {
                let ab = sub(*b, *a);
                let len2 = dot(ab, ab);
                let t = if len2 > 0.0 { (dot(sub(p, *a), ab) / len2).clamp(0.0, 1.0) } else { 0.0 };
                let c = add(*a, scale(ab, t));
                let d = sub(p, c);
                let r = norm(d);
                let n = if r > 0.0 { scale(d, 1.0 / r) } else { [0.0, 1.0, 0.0] };
                (r - radius, n)
            }
            // Beyond its reach a mesh reports "that far outside", which is all the contact
            // stage needs to know.
            Shape::Mesh(m) => m.closest(p, m.reach).unwrap_or((m.reach, [0.0, 1.0, 0.0])),
        }
    }

    /// The signed distance (m) and outward normal at `p` if the surface is within `reach` (m) of
    /// it: exact for every shape (a mesh's `distance` says only "that far" beyond its reach).
    pub(crate) fn distance_within(&self, p: V3, reach: f64) -> Option<(f64, V3)> {
        match self {
            Shape::Mesh(m) => m.closest(p, reach),
            _ => Some(self.distance(p)).filter(|(d, _)| d.abs() <= reach),
        }
    }

    /// Where the segment p0 → p1 (p0 outside) first touches the surface, as a fraction t of the
    /// way; found by bisection on the signed distance after a conservative march, which is exact
    /// to 1e-12 of the segment for these convex shapes.
    fn entry(&self, p0: V3, p1: V3) -> Option<f64> {
        if let Shape::Mesh(m) = self {
            return if self.distance(p0).0 <= TOUCH { None } else { m.first_hit(p0, p1) };
        }
        let at = |t: f64| self.distance(add(p0, scale(sub(p1, p0), t))).0;
        if at(0.0) <= TOUCH {
            return None; // starts on or in the surface: handled by the caller
        }
        // March by the distance (sphere tracing): never steps over the surface of a convex
        // shape, so a thin wall between p0 and p1 is found.
        let len = norm(sub(p1, p0));
        if len == 0.0 {
            return None;
        }
        let mut t = 0.0;
        for _ in 0..64 {
            let d = at(t);
            if d <= 1e-12 * (1.0 + len) {
                return Some(t);
            }
            t += d / len;
            if t >= 1.0 {
                return None;
            }
        }
        // Slow convergence (grazing): bisect between t and 1 if the end is inside.
        if at(1.0) < 0.0 {
            let (mut lo, mut hi) = (t, 1.0);
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                if at(mid) < 0.0 { hi = mid } else { lo = mid }
            }
            return Some(lo);
        }
        None
    }
}

/// The velocity change of a vertex touching any rigid surface (an obstacle, the ground:
/// `world/ground.rs`): with n the surface's outward unit normal and u·n < 0 (moving in),
///   normal:     u·n ← −e (u·n), an impulse per unit mass j = (1 + e)|u·n|;
///   tangential: Coulomb friction removes up to μ j of the tangential speed |u_t|.
/// A vertex moving out (u·n ≥ 0) keeps its velocity.
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

/// Distance below which a vertex counts as touching a surface (m).
const TOUCH: f64 = 1e-12;

/// Stage "obstacles": keep every vertex out of every obstacle. Pinned vertices (`inv_mass` 0)
/// are left alone. For a vertex that moved from `x_prev` (p0) to `x` (p1) during the step:
/// - touching at the start and moving inward: its motion is kept in the tangent plane at p0
///   (it slides along the surface; friction acts below), then pushed out if still inside;
/// - otherwise, if its path enters the obstacle: stopped at the entry point (continuous check);
/// - otherwise, if it ends inside: pushed out to the nearest surface point.
pub fn resolve(obstacles: &[Obstacle], inv_mass: &[f64], x_prev: &[f64], x: &mut [f64], v: &mut [f64]) {
    for (i, &im) in inv_mass.iter().enumerate() {
        if im == 0.0 {
            continue;
        }
        for o in obstacles {
            let p1 = [x[3 * i], x[3 * i + 1], x[3 * i + 2]];
            let p0 = [x_prev[3 * i], x_prev[3 * i + 1], x_prev[3 * i + 2]];
            let step = sub(p1, p0);
            let (d0, n0) = o.shape.distance(p0);
            let (p, n) = if d0 <= TOUCH && dot(n0, step) < 0.0 {
                let slid = sub(p1, scale(n0, dot(n0, step)));
                let (d, n) = o.shape.distance(slid);
                (if d < 0.0 { sub(slid, scale(n, d)) } else { slid }, n0)
            } else if let Some(t) = o.shape.entry(p0, p1) {
                let p = add(p0, scale(step, t));
                (p, o.shape.distance(p).1)
            } else {
                let (d1, n1) = o.shape.distance(p1);
                if d1 >= 0.0 {
                    continue;
                }
                (sub(p1, scale(n1, d1)), n1)
            };
            x[3 * i..3 * i + 3].copy_from_slice(&p);
            // Inelastic (restitution 0) with Coulomb friction, as on the ground.
            let u = bounce([v[3 * i], v[3 * i + 1], v[3 * i + 2]], n, o.friction, 0.0);
            v[3 * i..3 * i + 3].copy_from_slice(&u);
        }
    }
}

/// Stage "obstacle edges": keep the edges (springs) of the mesh out of spheres and capsules, so
/// a bar or a ball thinner than the edges cannot slip between two vertices. For an edge from
/// x_i to x_j whose closest point x_e = (1 − s) x_i + s x_j is inside the obstacle by depth d
/// along n (the outward normal there), both ends move out by inverse mass w, as one constraint
/// C = distance − radius ≥ 0 with gradients (1 − s) n and s n:
///     Δx_i = (1 − s) w_i λ n,  Δx_j = s w_j λ n,  λ = d / ((1 − s)² w_i + s² w_j),
/// and the inward normal velocity of x_e is removed by the impulse shared the same way
/// (inelastic, like the vertex contact). The end points themselves are left to the vertex
/// stage (s strictly inside (0, 1)).
///
/// An edge of length L whose two ends rest on a round surface of radius r dips into it by the
/// sagitta r − √(r² − L²/4) (a chord): that much is allowed, or the stage would push resting
/// bodies off every ball and bar (and do work doing it). Thin obstacles (r < L/2), the ones
/// that can pass between two vertices, allow nothing.
pub fn resolve_edges(obstacles: &[Obstacle], inv_mass: &[f64], ei: &[u32], ej: &[u32], x: &mut [f64], v: &mut [f64]) {
    for o in obstacles {
        if !matches!(o.shape, Shape::Sphere { .. } | Shape::Capsule { .. }) {
            continue;
        }
        for (&i, &j) in ei.iter().zip(ej) {
            let (i, j) = (i as usize, j as usize);
            let (wi, wj) = (inv_mass[i], inv_mass[j]);
            if wi == 0.0 && wj == 0.0 {
                continue;
            }
            let (a, b) = ([x[3 * i], x[3 * i + 1], x[3 * i + 2]], [x[3 * j], x[3 * j + 1], x[3 * j + 2]]);
            let (s, core, radius) = match &o.shape {
                Shape::Sphere { center, radius } => {
                    let ab = sub(b, a);
                    let l2 = dot(ab, ab);
                    let s = if l2 > 0.0 { (dot(sub(*center, a), ab) / l2).clamp(0.0, 1.0) } else { 0.0 };
                    (s, *center, *radius)
                }
                Shape::Capsule { a: qa, b: qb, radius } => {
                    let (s, t) = closest_segments(a, b, *qa, *qb);
                    (s, lerp(*qa, *qb, t), *radius)
                }
                _ => unreachable!(),
            };
            if s <= 1e-9 || s >= 1.0 - 1e-9 {
                continue;
            }
            let e = lerp(a, b, s);
            let off = sub(e, core);
            let dist = norm(off);
            if dist >= radius || dist == 0.0 {
                continue;
            }
            let half = 0.5 * norm(sub(b, a));
            let sagitta = if radius > half { radius - (radius * radius - half * half).sqrt() } else { 0.0 };
            let depth = radius - dist - sagitta;
            if depth <= 0.0 {
                continue;
            }
            let n = scale(off, 1.0 / dist);
            let (gi, gj) = (1.0 - s, s);
            let wsum = gi * gi * wi + gj * gj * wj;
            let lambda = depth / wsum;
            let ve = add(scale([v[3 * i], v[3 * i + 1], v[3 * i + 2]], gi), scale([v[3 * j], v[3 * j + 1], v[3 * j + 2]], gj));
            let vn = dot(ve, n);
            let jn = if vn < 0.0 { -vn / wsum } else { 0.0 };
            for (k, g, w) in [(i, gi, wi), (j, gj, wj)] {
                for d in 0..3 {
                    x[3 * k + d] += g * w * lambda * n[d];
                    v[3 * k + d] += g * w * jn * n[d];
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn signed_distances_of_each_shape() {
        let s = Shape::Sphere { center: [0.0; 3], radius: 1.0 };
        assert_eq!(s.distance([2.0, 0.0, 0.0]), (1.0, [1.0, 0.0, 0.0]));
        let b = Obstacle::aabb([0.0; 3], [1.0, 2.0, 3.0]).shape;
        assert_eq!(b.distance([0.0, 0.0, 5.0]).0, 2.0);
        assert_eq!(b.distance([0.5, 0.0, 0.0]), (-0.5, [1.0, 0.0, 0.0]));
        assert!((b.distance([2.0, 3.0, 0.0]).0 - 2f64.sqrt()).abs() < 1e-15);
        let c = Shape::Capsule { a: [0.0, 0.0, 0.0], b: [0.0, 2.0, 0.0], radius: 0.5 };
        assert_eq!(c.distance([1.0, 1.0, 0.0]).0, 0.5);
        assert_eq!(c.distance([0.0, 3.0, 0.0]).0, 0.5);
        // A box turned 45° about z: the corner now points along +x at distance √2.
        let r = Obstacle::rotated_box([0.0; 3], [1.0, 1.0, 1.0], [0.0, 0.0, 1.0], std::f64::consts::FRAC_PI_4).shape;
        assert!((r.distance([2f64.sqrt() + 0.1, 0.0, 0.0]).0 - 0.1).abs() < 1e-12);
    }

    #[test]
    fn the_sweep_finds_a_thin_wall_between_two_positions() {
        let wall = Obstacle::aabb([0.0; 3], [0.01, 5.0, 5.0]).shape;
        let t = wall.entry([-1.0, 0.0, 0.0], [1.0, 0.0, 0.0]).expect("crosses the wall");
        assert!((t - 0.495).abs() < 1e-9, "{t}");
        assert!(wall.entry([-1.0, 0.0, 0.0], [-0.5, 0.0, 0.0]).is_none());
    }
}
