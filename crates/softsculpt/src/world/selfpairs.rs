//! Stage 1's self-contacts for bodies stepped implicitly (see `contacts.rs` for the contact
//! stage and `body/selfcontact.rs` for the springs they become): before the bodies step, the
//! vertex–face and edge–edge pairs of each self-colliding body's own surface that the step may
//! bring within the contact thickness, found by the contact stage's broad phase (`hash.rs`) on
//! the step's start positions.

use super::contacts::{far_at_rest, inv_mass, self_reach, Scratch};
use super::{Integrator, World};
use crate::body::selfcontact::{SelfContact, SelfContacts, KAPPA};
use crate::body::SoftBody;
use crate::geometry::{closest_on_triangle, closest_segments, lerp};
use crate::vec3::{add, cross, dot, get, norm, scale, sub, V3};

/// sin of the smallest angle between two edges in self-contact (10°).
const PARALLEL: f64 = 0.17;

impl World {
    /// Stage 1's self-contacts (before the bodies step): for every self-colliding body stepped
    /// implicitly, the pairs of its own surface the step may bring within the thickness h, into
    /// its model's list (`body/selfcontact.rs`; every other body's list is emptied): a vertex
    /// and a face of its own body (farther apart at rest than `self_reach`) whose closest point
    /// is nearer than h + 2 dt v_max (v_max the body's largest speed: within reach of the
    /// step's motion), the normal from that point to the vertex; then edge–edge pairs
    /// (`self_edge_pairs`); each with the stiffness k_c = κ μ / dt². Pairs found but not within
    /// h cost nothing until the solve brings them there.
    pub(super) fn find_self_contacts(&mut self) {
        let (dt, h) = (self.settings.dt, self.settings.contact.thickness);
        for bi in 0..self.bodies.len() {
            let mut list = std::mem::take(&mut self.bodies[bi].model.self_contacts.list);
            list.clear();
            let b = &self.bodies[bi];
            if b.material.self_collision && self.settings.integrator == Integrator::Implicit && h > 0.0 {
                self_pairs(&mut self.cx, b, dt, h, &mut list);
            }
            self.bodies[bi].model.self_contacts = SelfContacts { list, thickness: h };
        }
    }
}

/// The self-contacts of body `b` into `list` (see `World::find_self_contacts`).
fn self_pairs(cx: &mut Scratch, b: &SoftBody, dt: f64, h: f64, list: &mut Vec<SelfContact>) {
    let x = b.positions();
    cx.centroids.clear();
    cx.radii.clear();
    let mut reach: f64 = 0.0;
    for t in b.triangles() {
        let (a, bb, c) = (get(x, t[0] as usize), get(x, t[1] as usize), get(x, t[2] as usize));
        let g = scale(add(add(a, bb), c), 1.0 / 3.0);
        let r = norm(sub(a, g)).max(norm(sub(bb, g))).max(norm(sub(c, g)));
        reach = reach.max(r);
        cx.radii.push(r);
        cx.centroids.extend_from_slice(&g);
    }
    // How far the step may close a gap: twice the largest speed times dt, at most a triangle
    // radius (the query's reach stays bounded).
    let margin = (2.0 * dt * b.max_speed()).min(reach);
    let band = h + margin;
    let radius = reach + band;
    if !(radius.is_finite() && radius > 0.0) || cx.radii.is_empty() {
        return;
    }
    cx.hash.set_spacing(radius);
    cx.hash.build(&cx.centroids);
    for vi in 0..b.vertex_count() {
        let p = get(x, vi);
        cx.hash.query(p, radius, &mut cx.candidates);
        for &f in &cx.candidates {
            let f = f as usize;
            let t = b.triangles()[f];
            if t.contains(&(vi as u32)) {
                continue;
            }
            let r = cx.radii[f] + band;
            let d = sub(p, get(&cx.centroids, f));
            if dot(d, d) > r * r {
                continue;
            }
            // The closest point q on the face; the contact's normal is the direction from q to
            // p (the face's normal where p is over the face, the direction from the rim where
            // it is beside it: a vertex coming round a ridge of the other skin is held too).
            let (a, bb, c) = (get(x, t[0] as usize), get(x, t[1] as usize), get(x, t[2] as usize));
            let (w, q) = closest_on_triangle(p, a, bb, c);
            let gap = norm(sub(p, q));
            if gap >= band || !far_at_rest(b, vi, t, self_reach(Integrator::Implicit, h)) {
                continue;
            }
            let n = if gap > 1e-12 * (1.0 + norm(p)) {
                scale(sub(p, q), 1.0 / gap)
            } else {
                let nf = cross(sub(bb, a), sub(c, a));
                let len = norm(nf);
                if len == 0.0 {
                    continue;
                }
                scale(nf, 1.0 / len)
            };
            push_contact(b, dt, [vi as u32, t[0], t[1], t[2]], [1.0, -w[0], -w[1], -w[2]], n, list);
        }
    }
    cx.self_near.clear();
    cx.self_near.resize(b.vertex_count(), false);
    for c in list.iter() {
        for i in c.idx {
            cx.self_near[i as usize] = true;
        }
    }
    self_edge_pairs(cx, b, dt, h, band, list);
}

/// Edge against edge within body `b` (see `World::find_self_contacts`): two skins crossing
/// where no vertex is over a face — a coarse skin crumpling, two sheets meeting edge on — are
/// held by the closest points of the two edges. Only edges with an end in a vertex–face contact
/// (`self_near`) are tested, against every edge (measured: testing all edges of the idle
/// mushroom cost 1.5 ms a step, all of it spent rejecting neighbours): edges sharing no vertex, farther apart at rest
/// than `self_reach`, closer than `band` now, closest points inside both (an end point is a
/// vertex–face contact's business); n from the second edge's point to the first's.
fn self_edge_pairs(cx: &mut Scratch, b: &SoftBody, dt: f64, h: f64, band: f64, list: &mut Vec<SelfContact>) {
    let x = b.positions();
    let (ei, ej) = b.spring_ends();
    // Midpoints and half-lengths (in `radii`, free after the vertex pass).
    cx.mids.clear();
    cx.radii.clear();
    let mut half: f64 = 0.0;
    for (&i, &j) in ei.iter().zip(ej) {
        let (p, q) = (get(x, i as usize), get(x, j as usize));
        let r = 0.5 * norm(sub(q, p));
        half = half.max(r);
        cx.radii.push(r);
        cx.mids.extend_from_slice(&scale(add(p, q), 0.5));
    }
    // Two edges within `band` have midpoints within their half-lengths plus `band`: each edge
    // queries its half-length plus the longest half plus `band`, in cells that size (a query
    // then spans at most 3³ cells of it: fewer candidates than 2³ cells twice as large).
    let radius = 2.0 * half + band;
    if ei.is_empty() || !(radius.is_finite() && radius > 0.0) {
        return;
    }
    cx.edge_hash.set_spacing(radius);
    cx.edge_hash.build(&cx.mids);
    let rest = b.frozen_positions();
    let reach = self_reach(Integrator::Implicit, h);
    for e in 0..ei.len() {
        let near = |k: usize| cx.self_near[ei[k] as usize] || cx.self_near[ej[k] as usize];
        if !near(e) {
            continue;
        }
        let a = [ei[e], ej[e]];
        let (me, he) = (get(&cx.mids, e), cx.radii[e]);
        cx.edge_hash.query(me, he + half + band, &mut cx.found);
        for &f in &cx.found {
            let f = f as usize;
            // Each pair once: from its first edge if both are near, else from the near one.
            if f == e || (f < e && near(f)) {
                continue;
            }
            let (d, r) = (sub(get(&cx.mids, f), me), he + cx.radii[f] + band);
            if dot(d, d) > r * r {
                continue;
            }
            let c = [ei[f], ej[f]];
            if a.iter().any(|v| c.contains(v)) {
                continue;
            }
            let (a0, a1, c0, c1) = (get(x, a[0] as usize), get(x, a[1] as usize), get(x, c[0] as usize), get(x, c[1] as usize));
            if (0..3).any(|d| a0[d].max(a1[d]) + band < c0[d].min(c1[d]) || c0[d].max(c1[d]) + band < a0[d].min(a1[d])) {
                continue;
            }
            // Nearly parallel edges (under ~10°) are left to the vertex–face contacts: their
            // closest points jump along them from step to step, and the contact's frame with them.
            let (da, dc) = (sub(a1, a0), sub(c1, c0));
            if norm(cross(da, dc)) < PARALLEL * norm(da) * norm(dc) {
                continue;
            }
            let (s, t) = closest_segments(a0, a1, c0, c1);
            if s <= 1e-6 || s >= 1.0 - 1e-6 || t <= 1e-6 || t >= 1.0 - 1e-6 {
                continue;
            }
            let dv = sub(lerp(a0, a1, s), lerp(c0, c1, t));
            let gap = norm(dv);
            if gap >= band || gap <= 1e-12 * (1.0 + norm(a0)) {
                continue;
            }
            // Not neighbours on the surface: as far apart at rest as the vertex–face rule asks.
            let (r0, r1, q0, q1) = (get(rest, a[0] as usize), get(rest, a[1] as usize), get(rest, c[0] as usize), get(rest, c[1] as usize));
            let (rs, rt) = closest_segments(r0, r1, q0, q1);
            let longer = norm(sub(r1, r0)).max(norm(sub(q1, q0)));
            if norm(sub(lerp(r0, r1, rs), lerp(q0, q1, rt))) < reach.map_or(longer, |r| r.min(longer)) {
                continue;
            }
            push_contact(b, dt, [a[0], a[1], c[0], c[1]], [1.0 - s, s, -(1.0 - t), -t], scale(dv, 1.0 / gap), list);
        }
    }
}

/// A self-contact of body `b` on vertices `idx` with weights `g` and normal `n`, its stiffness
/// k_c = κ μ / dt² from the effective mass μ = 1 / Σ g_k² / m_k (none if every vertex is
/// pinned).
fn push_contact(b: &SoftBody, dt: f64, idx: [u32; 4], g: [f64; 4], n: V3, list: &mut Vec<SelfContact>) {
    let wsum: f64 = (0..4).map(|k| g[k] * g[k] * inv_mass(b, idx[k] as usize)).sum();
    if wsum > 0.0 {
        list.push(SelfContact { idx, g, n, k: KAPPA / (dt * dt * wsum) });
    }
}
