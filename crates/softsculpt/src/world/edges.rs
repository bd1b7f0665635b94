//! Edge–edge contact between bodies (and within a self-colliding body).
//!
//! Vertex–face contact misses two edges crossing where no vertex is near a face: two coarse
//! bodies meeting edge to edge, two thin tentacles crossing. Here every edge (spring) with an end
//! near another body's surface or in contact (found by the vertex–face pass) is tested against the nearby
//! edges of the other bodies — found by a spatial hash of edge midpoints — through the closest
//! points of the two segments,
//!     p_a = (1 − s) x_a0 + s x_a1,   p_b = (1 − t) x_b0 + t x_b1   (s, t ∈ (0, 1)).
//! The side to keep them on is the one they were on at the start of the step, n = the unit
//! vector from p_b to p_a then, and the gap is (p_a − p_b) · n: negative when the two edges
//! crossed during the step. Only a crossing gets a response (touching without crossing is left
//! to the vertex–face contact, which already holds resting bodies): the same as vertex–face's,
//! with four vertices and weights g = (1 − s, s, 1 − t, t) — the gap is closed (to a thousandth
//! of the thickness: edges left exactly touching would have no side next step; the work done is
//! that force times 1e-3 thickness) and the approaching normal velocity removed by the impulse
//! J = −v_rel · n / Σ g_k² w_k shared by inverse masses w (momentum conserved), with Coulomb
//! friction.

use super::World;
use crate::geometry::{closest_segments, lerp};
use crate::vec3::{add, dot, get, norm, scale, sub, V3};

impl World {
    pub(super) fn collide_edges(&mut self, zones: &[Vec<(V3, V3)>]) {
        self.cx.mids.clear();
        self.cx.edge_owner.clear();
        let mut longest: f64 = 0.0;
        for (bi, b) in self.bodies.iter().enumerate() {
            if zones[bi].is_empty() {
                continue;
            }
            let (ei, ej) = b.spring_ends();
            let x = b.positions();
            for (e, (&i, &j)) in ei.iter().zip(ej).enumerate() {
                // Edges near another body's surface or in contact (with itself too) only.
                let near = &self.cx.near[bi];
                if !near[i as usize] && !near[j as usize] {
                    continue;
                }
                let (p, q) = (get(x, i as usize), get(x, j as usize));
                let m = scale(add(p, q), 0.5);
                let half = 0.5 * norm(sub(q, p));
                if super::contacts::in_zones(&zones[bi], m, half) {
                    longest = longest.max(half);
                    self.cx.mids.extend_from_slice(&m);
                    self.cx.edge_owner.push((bi as u32, e as u32));
                }
            }
        }
        if self.cx.edge_owner.len() < 2 {
            return;
        }
        // Two segments within the thickness of each other have midpoints within the sum of their
        // half lengths plus the thickness: each edge queries with its own half length.
        self.cx.edge_hash.set_spacing(2.0 * (2.0 * longest + self.settings.contact.thickness));
        self.cx.edge_hash.build(&self.cx.mids);
        let mut found = std::mem::take(&mut self.cx.found);
        for k in 0..self.cx.edge_owner.len() {
            let (bi, e) = self.cx.edge_owner[k];
            let (i, j) = self.bodies[bi as usize].spring_ends();
            let x = self.bodies[bi as usize].positions();
            let half = 0.5 * norm(sub(get(x, j[e as usize] as usize), get(x, i[e as usize] as usize)));
            self.cx.edge_hash.query(get(&self.cx.mids, k), half + longest + self.settings.contact.thickness, &mut found);
            for &c in &found {
                let (ob, f) = self.cx.edge_owner[c as usize];
                // Each pair once; within one body only if it collides with itself.
                if (ob, f) <= (bi, e) || (ob == bi && !self.bodies[bi as usize].material.self_collision) || (ob != bi && self.overlooked(bi as usize, ob as usize)) {
                    continue;
                }
                self.edge_pair(bi as usize, e as usize, ob as usize, f as usize);
            }
        }
        self.cx.found = found;
    }

    fn edge_pair(&mut self, ba: usize, ea: usize, bb: usize, eb: usize) {
        let ends = |w: &World, b: usize, e: usize| {
            let (i, j) = w.bodies[b].spring_ends();
            [i[e] as usize, j[e] as usize]
        };
        let (a, b) = (ends(self, ba, ea), ends(self, bb, eb));
        if ba == bb && (a.iter().any(|v| b.contains(v)) || !far_apart_at_rest(self, ba, a, b)) {
            return;
        }
        let (xa, xb) = (self.bodies[ba].positions(), self.bodies[bb].positions());
        let (a0, a1, b0, b1) = (get(xa, a[0]), get(xa, a[1]), get(xb, b[0]), get(xb, b[1]));
        // Cheap first: the two segments' boxes must overlap.
        let r = self.settings.contact.thickness;
        if (0..3).any(|d| a0[d].max(a1[d]) + r < b0[d].min(b1[d]) || b0[d].max(b1[d]) + r < a0[d].min(a1[d])) {
            return;
        }
        let (s, t) = closest_segments(a0, a1, b0, b1);
        if s <= 1e-6 || s >= 1.0 - 1e-6 || t <= 1e-6 || t >= 1.0 - 1e-6 {
            return; // an end point: the vertex–face test's business
        }
        let (pa, pb) = (lerp(a0, a1, s), lerp(b0, b1, t));
        if norm(sub(pa, pb)) >= self.cx.reach_now {
            return;
        }
        // The side at the start of the step.
        let (pra, prb) = (&self.prev[ba], &self.prev[bb]);
        let (c0, c1, d0, d1) = (get(pra, a[0]), get(pra, a[1]), get(prb, b[0]), get(prb, b[1]));
        let (s0, t0) = closest_segments(c0, c1, d0, d1);
        let before = sub(lerp(c0, c1, s0), lerp(d0, d1, t0));
        let len0 = norm(before);
        let n = if len0 > 1e-12 {
            scale(before, 1.0 / len0)
        } else {
            let now = sub(pa, pb);
            let l = norm(now);
            if l <= 1e-12 {
                return;
            }
            scale(now, 1.0 / l)
        };
        let gap = dot(sub(pa, pb), n);
        if gap >= 0.0 || gap < -self.cx.reach_now {
            return;
        }
        let w = |body: usize, v: usize| if self.bodies[body].is_pinned(v) { 0.0 } else { 1.0 / self.bodies[body].masses()[v] };
        let g = [(ba, a[0], 1.0 - s, 1.0), (ba, a[1], s, 1.0), (bb, b[0], 1.0 - t, -1.0), (bb, b[1], t, -1.0)];
        let wsum: f64 = g.iter().map(|&(body, v, gk, _)| gk * gk * w(body, v)).sum();
        if wsum == 0.0 {
            return;
        }
        let vel = |body: usize, v: usize| get(self.bodies[body].velocities(), v);
        let va = add(scale(vel(ba, a[0]), 1.0 - s), scale(vel(ba, a[1]), s));
        let vb = add(scale(vel(bb, b[0]), 1.0 - t), scale(vel(bb, b[1]), t));
        let impulse = super::contacts::contact_impulse(sub(va, vb), n, wsum, self.settings.contact.friction);
        // Closed to a hair's breadth (a thousandth of the thickness), not to zero: two edges left
        // exactly touching would have no side at the next step.
        let lambda = (-gap + 1e-3 * self.settings.contact.thickness) / wsum;
        let ws = g.map(|(body, v, _, _)| w(body, v));
        for (k, &(body, v, gk, sign)) in g.iter().enumerate() {
            let f = sign * gk * ws[k];
            self.bodies[body].nudge(v, scale(n, f * lambda), scale(impulse, f));
        }
    }
}

/// Whether two edges of one body were at least as far apart as the longer of them in the rest
/// shape (so they are not neighbours on the surface).
fn far_apart_at_rest(w: &World, b: usize, a: [usize; 2], c: [usize; 2]) -> bool {
    let x = w.bodies[b].frozen_positions();
    let (a0, a1, c0, c1) = (get(x, a[0]), get(x, a[1]), get(x, c[0]), get(x, c[1]));
    let (s, t) = closest_segments(a0, a1, c0, c1);
    let d = norm(sub(lerp(a0, a1, s), lerp(c0, c1, t)));
    d >= norm(sub(a1, a0)).max(norm(sub(c1, c0)))
}
