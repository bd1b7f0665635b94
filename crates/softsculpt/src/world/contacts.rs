//! Stage "contacts" of a world step: bodies colliding with each other and with themselves.
//!
//! After every body has been integrated and kept out of the ground and obstacles, this stage
//! keeps every vertex of one body outside the other bodies' surfaces:
//! 1. broad phase: a spatial hash of all triangle centroids (`hash.rs`), queried around each
//!    vertex within the largest triangle radius plus the contact thickness;
//! 2. narrow phase: the closest point q on each candidate triangle of another body; a vertex p
//!    closer than `thickness` in front of the face, or behind it by less than `max_depth`, is in
//!    contact, with n the face's outward normal;
//! 3. response, between the vertex and the triangle's three vertices (barycentric weights b_k):
//!    a vertex that went behind the face is put back on it along n (only that: pushing it out to
//!    the thickness would do work and inject energy), and the relative normal velocity removed
//!    (inelastic) by an impulse J shared by inverse masses,
//!    `J = −(v_p − Σ b_k v_k) · n / (1/m_p + Σ b_k² / m_k)`,
//!    so momentum is conserved exactly; Coulomb friction removes up to μ J of relative tangential
//!    velocity the same way. Corrections move the centre of mass of the pair not at all.
//!
//! 4. edges (`edges.rs`): edge against edge, for crossings no vertex is near a face to catch.
//!
//! Self-collision (a body's `material.self_collision`): a vertex is also tested against its own
//! body's faces, except the faces near it on the surface — those whose closest point was nearer
//! than their longest edge in the rest shape (the faces around the vertex and the next ring),
//! which touch it by construction. A fold brings together parts that were far apart at rest, so
//! they still collide. The response is the same impulse, within one body.
//!
//! Bodies stepped implicitly hold their self-contacts inside the solve instead
//! (`body/selfcontact.rs`): before the bodies step, `World::find_self_contacts`
//! (`selfpairs.rs`) runs the same broad and narrow phase on each self-colliding body's start
//! positions (vertex–face pairs by the closest point, with faces farther than
//! min(2 h, longest edge) at rest; edge–edge pairs from edges at a vertex–face contact) and
//! hands the body one-sided penalty springs. This stage then only repairs their crossings (a
//! vertex behind a face), never a resting contact.

use super::{Integrator, World};
use crate::body::SoftBody;
use crate::geometry::closest_on_triangle;
use crate::hash::SpatialHash;
use crate::vec3::{add, cross, dot, get, norm, scale, sub, V3};

/// Where a self-crossing of an implicit body is put back: this fraction of the thickness in
/// front of the face.
const CLEARANCE: f64 = 1e-3;

/// Scratch of the contact stage, allocated once and reused; nothing in it carries over from
/// one step to the next (a clone starts empty).
#[derive(Debug)]
pub(crate) struct Scratch {
    pub hash: SpatialHash,
    pub centroids: Vec<f64>,
    pub owners: Vec<(u32, u32)>,
    /// Each triangle's radius about its centroid (m): a cheap first test per candidate.
    pub radii: Vec<f64>,
    pub candidates: Vec<u32>,
    /// Edge–edge broad phase: edge midpoints, their (body, spring), and the hash over them.
    pub edge_hash: SpatialHash,
    pub mids: Vec<f64>,
    pub edge_owner: Vec<(u32, u32)>,
    pub found: Vec<u32>,
    /// The largest triangle radius this step (m): how deep a crossing is still caught.
    pub reach_now: f64,
    /// Per body and vertex: near another body's surface this step (edges there are tested).
    pub near: Vec<Vec<bool>>,
    /// Per vertex of the body whose self-contacts are being found: in a vertex–face one.
    pub self_near: Vec<bool>,
}

impl Default for Scratch {
    fn default() -> Self {
        Scratch { hash: SpatialHash::new(1.0), centroids: Vec::new(), owners: Vec::new(), radii: Vec::new(), candidates: Vec::new(), edge_hash: SpatialHash::new(1.0), mids: Vec::new(), edge_owner: Vec::new(), found: Vec::new(), reach_now: 0.0, near: Vec::new(), self_near: Vec::new() }
    }
}

impl Clone for Scratch {
    fn clone(&self) -> Self {
        Scratch::default()
    }
}

/// Zones where a body can touch another, per body: boxes (lo, hi) (`World::contact_zones`).
type Zones = Vec<Vec<(V3, V3)>>;

/// A vertex's deepest contact with a face: body `ob`, face `f`, the closest point's barycentric
/// weights `w`, the face's unit normal `n` (to the side the vertex is kept on) and the signed
/// distance `s` along it (m).
pub(super) struct FaceContact {
    pub ob: usize,
    f: usize,
    w: [f64; 3],
    n: V3,
    s: f64,
}

impl World {
    /// The stage's steps: triangles' bounds, where bodies can touch, the broad phase's hash,
    /// then each vertex in a zone against its candidate faces, then edge against edge.
    pub(super) fn collide(&mut self) {
        let reach = self.gather_triangles();
        let radius = reach + self.settings.contact.thickness;
        if !(radius.is_finite() && radius > 0.0) {
            return;
        }
        self.cx.reach_now = reach;
        self.clear_near();
        let zones = self.contact_zones(radius);
        if !self.hash_triangles_in(&zones, radius) {
            return;
        }
        for bi in 0..self.bodies.len() {
            let zones = &zones[bi];
            if zones.is_empty() {
                continue;
            }
            for vi in 0..self.bodies[bi].vertex_count() {
                let p = get(self.bodies[bi].positions(), vi);
                if !in_zones(zones, p, 0.0) {
                    continue;
                }
                if let Some(c) = self.deepest_contact(bi, vi, p, radius, reach) {
                    self.cx.near[bi][vi] = true;
                    self.respond_to(bi, vi, c);
                }
            }
        }
        if self.settings.contact.edge_contact {
            self.collide_edges(&zones);
        }
    }

    /// Every triangle's centroid and radius (about the centroid) into the scratch; returns the
    /// largest radius, which sets the reach of the queries.
    pub(super) fn gather_triangles(&mut self) -> f64 {
        self.cx.centroids.clear();
        self.cx.owners.clear();
        self.cx.radii.clear();
        let mut reach: f64 = 0.0;
        for (bi, b) in self.bodies.iter().enumerate() {
            let x = b.positions();
            for (f, t) in b.triangles().iter().enumerate() {
                let (a, bb, c) = (get(x, t[0] as usize), get(x, t[1] as usize), get(x, t[2] as usize));
                let g = scale(add(add(a, bb), c), 1.0 / 3.0);
                let r = norm(sub(a, g)).max(norm(sub(bb, g))).max(norm(sub(c, g)));
                reach = reach.max(r);
                self.cx.radii.push(r);
                self.cx.centroids.extend_from_slice(&g);
                self.cx.owners.push((bi as u32, f as u32));
            }
        }
        reach
    }

    /// No vertex near another body's surface yet this step (one flag per body and vertex).
    pub(super) fn clear_near(&mut self) {
        self.cx.near.resize(self.bodies.len(), Vec::new());
        for (n, b) in self.cx.near.iter_mut().zip(&self.bodies) {
            n.clear();
            n.resize(b.vertex_count(), false);
        }
    }

    /// Where each body can touch another: the overlaps of its bounding box with the others'
    /// (both grown by the query radius). Only vertices and faces inside these zones take
    /// part — most of a body, most of the time, does not. A self-colliding body can touch
    /// itself anywhere.
    /// Pairs of bodies whose contacts are off (`overlaps.rs`) touch nowhere; those whose boxes
    /// have parted are dropped from that set here.
    pub(super) fn contact_zones(&mut self, radius: f64) -> Zones {
        let boxes: Vec<(V3, V3)> = self
            .bodies
            .iter()
            .map(|b| {
                let (lo, hi) = crate::mesh::bounds(b.positions());
                (sub(lo, [radius; 3]), add(hi, [radius; 3]))
            })
            .collect();
        if !self.overlaps.is_empty() {
            self.part_overlaps(&boxes);
        }
        (0..self.bodies.len())
            .map(|bi| {
                if self.bodies[bi].material.self_collision {
                    return vec![boxes[bi]];
                }
                boxes
                    .iter()
                    .enumerate()
                    .filter(|&(ob, _)| ob != bi && !self.overlooked(bi, ob))
                    .map(|(_, other)| (max3(boxes[bi].0, other.0), min3(boxes[bi].1, other.1)))
                    .filter(|(lo, hi)| (0..3).all(|d| lo[d] <= hi[d]))
                    .collect()
            })
            .collect()
    }

    /// Broad phase over the centroids of the triangles in the zones (the others dropped in
    /// place), hashed at twice the query radius; false if no triangle is in a zone.
    pub(super) fn hash_triangles_in(&mut self, zones: &Zones, radius: f64) -> bool {
        let mut kept = 0;
        for k in 0..self.cx.owners.len() {
            let (g, r) = (get(&self.cx.centroids, k), self.cx.radii[k]);
            if in_zones(&zones[self.cx.owners[k].0 as usize], g, r) {
                self.cx.owners[kept] = self.cx.owners[k];
                self.cx.radii[kept] = r;
                self.cx.centroids.copy_within(3 * k..3 * k + 3, 3 * kept);
                kept += 1;
            }
        }
        self.cx.owners.truncate(kept);
        self.cx.radii.truncate(kept);
        self.cx.centroids.truncate(3 * kept);
        if self.cx.owners.is_empty() {
            return false;
        }
        self.cx.hash.set_spacing(2.0 * radius);
        self.cx.hash.build(&self.cx.centroids);
        true
    }

    /// Narrow phase of vertex `vi` of body `bi` (at p) against the hashed faces within
    /// `radius`: the deepest contact with a face decides this vertex's response. Marks the
    /// vertex near another body's surface on the way. `reach` is the largest triangle radius,
    /// also the deepest a crossing is still caught (max_depth).
    pub(super) fn deepest_contact(&mut self, bi: usize, vi: usize, p: V3, radius: f64, reach: f64) -> Option<FaceContact> {
        let max_depth = reach;
        let h = self.settings.contact.thickness;
        self.cx.hash.query(p, radius, &mut self.cx.candidates);
        let mut best: Option<FaceContact> = None;
        for &c in &self.cx.candidates {
            let (ob, f) = self.cx.owners[c as usize];
            let ob = ob as usize;
            if ob != bi && self.overlooked(bi, ob) {
                continue;
            }
            let g = get(&self.cx.centroids, c as usize);
            // A vertex within the thickness of the triangle is within its radius plus the
            // thickness of its centroid; so is one that crossed it less deeply than the
            // distance from its crossing point to the rim (a crossing within one step).
            let r = self.cx.radii[c as usize] + h;
            let d = sub(p, g);
            let d2 = dot(d, d);
            // Near another body's surface (within a triangle radius more): its edges
            // take part in the edge–edge test.
            if ob != bi && d2 <= (r + reach) * (r + reach) {
                self.cx.near[bi][vi] = true;
            }
            if d2 > r * r {
                continue;
            }
            let other = &self.bodies[ob];
            let t = other.triangles()[f as usize];
            if ob == bi && (!other.material.self_collision || t.contains(&(vi as u32))) {
                continue;
            }
            let Some((w, mut n, mut s)) = narrow(p, other.positions(), t, h, h.max(max_depth)) else {
                continue;
            };
            if ob == bi {
                // Only faces away from the vertex on the surface (the checks cost two
                // more closest points, so they come after the cheap ones). Inside a
                // closed body its own skin is met from behind: the side the vertex was
                // on at the start of the step is the side to keep it on.
                if !far_at_rest(other, vi, t, self_reach(self.settings.integrator, h)) {
                    continue;
                }
                let side = self_side(&self.prev[bi], vi, t);
                n = scale(n, side);
                s *= side;
            }
            if s < h && s > -max_depth && best.as_ref().is_none_or(|bst| s < bst.s) {
                best = Some(FaceContact { ob, f: f as usize, w, n, s });
            }
        }
        best
    }

    /// The response to vertex `vi` of body `bi` in contact `c`.
    ///
    /// Velocities respond within the thickness; positions only where a vertex went behind the
    /// face (moving them further would inject energy). Within one body a steady load (its
    /// weight, a press) would otherwise close the gap to nothing and leave the two skins
    /// coplanar, one step from crossing: self-contacts of explicit bodies are pushed halfway
    /// back to the thickness each step. Implicit bodies hold their self-contacts in the solve
    /// (penalty springs, `body/selfcontact.rs`), so here only a vertex that still went behind
    /// the face is put back (to a thousandth of the thickness in front, so that it has a side
    /// next step, as `edges.rs` does) and its approach stopped: a resting contact is left
    /// alone.
    fn respond_to(&mut self, bi: usize, vi: usize, c: FaceContact) {
        let FaceContact { ob, f, w, n, s } = c;
        let h = self.settings.contact.thickness;
        if ob == bi && self.settings.integrator == Integrator::Implicit {
            if s < 0.0 {
                self.respond(bi, vi, ob, f, w, n, CLEARANCE * h - s);
            }
        } else {
            let depth = if ob == bi { 0.5 * (h - s) } else { (-s).max(0.0) };
            self.respond(bi, vi, ob, f, w, n, depth);
        }
    }

    /// Push vertex `vi` of body `bi` and face `f` of body `ob` apart by `depth` along n and
    /// remove their approaching relative velocity, sharing both by inverse mass.
    #[allow(clippy::too_many_arguments)]
    fn respond(&mut self, bi: usize, vi: usize, ob: usize, f: usize, w: [f64; 3], n: V3, depth: f64) {
        let t = self.bodies[ob].triangles()[f];
        let ip = inv_mass(&self.bodies[bi], vi);
        let it = t.map(|k| inv_mass(&self.bodies[ob], k as usize));
        let wsum = ip + (0..3).map(|k| w[k] * w[k] * it[k]).sum::<f64>();
        if wsum == 0.0 {
            return;
        }
        // Positions: the vertex moves along +n, the face's vertices along −n, by inverse mass.
        let lambda = depth / wsum;
        // Velocities: inelastic normal impulse and Coulomb friction.
        let vp = get(self.bodies[bi].velocities(), vi);
        let vo = self.bodies[ob].velocities();
        let vq = (0..3).fold([0.0; 3], |acc, k| add(acc, scale(get(vo, t[k] as usize), w[k])));
        let impulse = contact_impulse(sub(vp, vq), n, wsum, self.settings.contact.friction);
        self.bodies[bi].nudge(vi, scale(n, lambda * ip), scale(impulse, ip));
        for k in 0..3 {
            self.bodies[ob].nudge(t[k] as usize, scale(n, -lambda * w[k] * it[k]), scale(impulse, -w[k] * it[k]));
        }
    }
}

/// The impulse (per unit of the weights' inverse mass) that removes the approaching normal part
/// of the relative velocity `rel` along n (inelastic) and up to μ times that of its tangential
/// part (Coulomb friction), for a contact whose effective inverse mass is `wsum`
/// (Σ weight² / mass over the vertices involved): zero if they are separating.
pub(crate) fn contact_impulse(rel: V3, n: V3, wsum: f64, friction: f64) -> V3 {
    let vn = dot(rel, n);
    if vn >= 0.0 {
        return [0.0; 3];
    }
    let j = -vn / wsum;
    let tangent = sub(rel, scale(n, vn));
    let vt = norm(tangent);
    if vt == 0.0 {
        return scale(n, j);
    }
    let jt = (friction * j).min(vt / wsum);
    sub(scale(n, j), scale(tangent, jt / vt))
}

/// Narrow phase of vertex p against face `t` in positions `x`: (barycentric weights of the
/// closest point q, the face's unit normal n, the signed distance s = (p − q) · n) when p lies
/// over the face (its offset from q along the face is under half the thickness `h`) and
/// |s| < `reach` (m); None for a degenerate face.
pub(crate) fn narrow(p: V3, x: &[f64], t: [u32; 3], h: f64, reach: f64) -> Option<([f64; 3], V3, f64)> {
    let (a, b, cc) = (get(x, t[0] as usize), get(x, t[1] as usize), get(x, t[2] as usize));
    let nf = cross(sub(b, a), sub(cc, a));
    let len = norm(nf);
    if len == 0.0 {
        return None;
    }
    let n = scale(nf, 1.0 / len);
    let (w, q) = closest_on_triangle(p, a, b, cc);
    let s = dot(sub(p, q), n);
    let lateral = norm(sub(sub(p, q), scale(n, s)));
    if lateral >= 1e-9 + 0.5 * h.max(1e-6) || s.abs() >= reach {
        return None;
    }
    Some((w, n, s))
}

/// +1 if vertex `v` was in front of face `t` (along its normal) in positions `x0`, else −1.
fn self_side(x0: &[f64], v: usize, t: [u32; 3]) -> f64 {
    let (p, a, b, c) = (get(x0, v), get(x0, t[0] as usize), get(x0, t[1] as usize), get(x0, t[2] as usize));
    let (_, q) = closest_on_triangle(p, a, b, c);
    if dot(sub(p, q), cross(sub(b, a), sub(c, a))) >= 0.0 { 1.0 } else { -1.0 }
}

/// How far from a vertex (m) a face of its own body must have been at rest to be in
/// self-contact with it: `None`, the face's longest edge (explicit bodies: the faces around the
/// vertex and the next ring are left out). Implicit bodies, whose self-contacts are springs
/// in the solve, keep every face farther than 2 h at rest (h the thickness), so that a skin
/// crumpled at the scale of one triangle — a vertex folding onto a face of its next ring —
/// is held too (measured on the crushed mushroom: those local folds were the first crossings,
/// and tangled the rest); at rest such a face is an altitude (~0.9 edge) away, beyond the
/// thickness, and only a fold brings the vertex over it.
pub(super) fn self_reach(integrator: Integrator, h: f64) -> Option<f64> {
    (integrator == Integrator::Implicit).then_some(2.0 * h)
}

/// Whether vertex `v` was far from face `t` in the rest shape (so it is not one of the faces
/// around it): at least `reach` (m) away, or with `None` the face's longest edge.
pub(super) fn far_at_rest(b: &SoftBody, v: usize, t: [u32; 3], reach: Option<f64>) -> bool {
    if t.contains(&(v as u32)) {
        return false;
    }
    let x = b.frozen_positions();
    let (p, a, bb, c) = (get(x, v), get(x, t[0] as usize), get(x, t[1] as usize), get(x, t[2] as usize));
    let (_, q) = closest_on_triangle(p, a, bb, c);
    let longest = norm(sub(bb, a)).max(norm(sub(c, bb))).max(norm(sub(a, c)));
    norm(sub(p, q)) >= reach.map_or(longest, |r| r.min(longest))
}

/// Whether p lies in one of the boxes `zones` (lo, hi), each grown by `grow` (m).
pub(super) fn in_zones(zones: &[(V3, V3)], p: V3, grow: f64) -> bool {
    zones.iter().any(|(lo, hi)| (0..3).all(|d| p[d] >= lo[d] - grow && p[d] <= hi[d] + grow))
}

fn max3(a: V3, b: V3) -> V3 {
    [a[0].max(b[0]), a[1].max(b[1]), a[2].max(b[2])]
}
fn min3(a: V3, b: V3) -> V3 {
    [a[0].min(b[0]), a[1].min(b[1]), a[2].min(b[2])]
}

pub(super) fn inv_mass(b: &SoftBody, i: usize) -> f64 {
    if b.is_pinned(i) { 0.0 } else { 1.0 / b.masses()[i] }
}
