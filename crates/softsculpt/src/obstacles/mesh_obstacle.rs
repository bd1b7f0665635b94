//! A static triangle mesh as an obstacle (a floor, a bowl, a tool loaded from a file).
//!
//! The triangles sit in a bounding-volume hierarchy (axis-aligned boxes, split at the median of
//! the longest axis, built once: the mesh never moves). Two queries serve the contact stage:
//! - `closest(p, reach)`: the nearest surface point within `reach`, with the signed distance:
//!   positive in front of the faces (the side their normals point to), negative behind. Where
//!   the nearest point is on an edge or a corner shared by several faces, the face whose normal
//!   is most aligned with p − q decides the side — right on both convex and concave edges;
//! - `first_hit(p0, p1)`: the first front face the segment p0 → p1 crosses (Möller–Trumbore),
//!   the continuous check that stops a fast vertex from passing between two samples.
//!
//! "Inside" is only looked for within `reach` behind a face (a quarter of the mean edge, at
//! least 1 mm): the sweep catches every entry, so the depth check only mops up rounding, and a
//! body placed wholly behind an open mesh (under a terrain) is left alone.

use crate::geometry::closest_on_triangle;
use crate::mesh::TriMesh;
use crate::vec3::{cross, dot, get, norm, scale, sub, V3};

#[derive(Clone, Copy)]
struct Node {
    lo: V3,
    hi: V3,
    /// Leaf: triangles `first..first + count` of `order`; inner: children `first`, `first + 1`.
    first: u32,
    count: u32,
}

pub struct MeshShape {
    positions: Vec<f64>,
    triangles: Vec<[u32; 3]>,
    /// Unit outward normals of the triangles.
    normals: Vec<V3>,
    order: Vec<u32>,
    nodes: Vec<Node>,
    /// Depth behind a face within which a point counts as inside (m).
    pub reach: f64,
}

impl std::fmt::Debug for MeshShape {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "MeshShape({} triangles)", self.triangles.len())
    }
}

const LEAF: usize = 4;

impl MeshShape {
    /// The mesh's degenerate triangles are dropped; an error if nothing is left or a
    /// coordinate is not finite.
    pub fn new(mesh: &TriMesh) -> Result<MeshShape, String> {
        if mesh.positions.iter().any(|p| !p.is_finite()) {
            return Err("the obstacle mesh has non-finite coordinates".into());
        }
        let x = &mesh.positions;
        let mut triangles = Vec::new();
        let mut normals = Vec::new();
        let mut edge_sum = 0.0;
        for t in &mesh.triangles {
            if t.iter().any(|&i| 3 * i as usize + 2 >= x.len()) {
                return Err("an obstacle face refers to a vertex that does not exist".into());
            }
            let (a, b, c) = (get(x, t[0] as usize), get(x, t[1] as usize), get(x, t[2] as usize));
            let n = cross(sub(b, a), sub(c, a));
            let len = norm(n);
            if len > 0.0 {
                triangles.push(*t);
                normals.push(scale(n, 1.0 / len));
                edge_sum += norm(sub(b, a)) + norm(sub(c, b)) + norm(sub(a, c));
            }
        }
        if triangles.is_empty() {
            return Err("the obstacle mesh has no faces of non-zero area".into());
        }
        let reach = (0.25 * edge_sum / (3 * triangles.len()) as f64).max(1e-3);
        let mut shape = MeshShape { positions: x.clone(), order: (0..triangles.len() as u32).collect(), triangles, normals, nodes: Vec::new(), reach };
        let n = shape.triangles.len();
        shape.nodes.push(Node { lo: [0.0; 3], hi: [0.0; 3], first: 0, count: n as u32 });
        shape.split(0, 0, n);
        Ok(shape)
    }

    /// The mesh (degenerate faces dropped): positions (m, flat xyz) and triangles.
    pub fn positions(&self) -> &[f64] {
        &self.positions
    }
    pub fn triangles(&self) -> &[[u32; 3]] {
        &self.triangles
    }

    fn corners(&self, t: u32) -> [V3; 3] {
        let t = self.triangles[t as usize];
        [get(&self.positions, t[0] as usize), get(&self.positions, t[1] as usize), get(&self.positions, t[2] as usize)]
    }

    /// Fit node `k` around order[start..end] and split it while it holds more than LEAF faces.
    fn split(&mut self, k: usize, start: usize, end: usize) {
        let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for &t in &self.order[start..end] {
            for p in self.corners(t) {
                for d in 0..3 {
                    lo[d] = lo[d].min(p[d]);
                    hi[d] = hi[d].max(p[d]);
                }
            }
        }
        self.nodes[k] = Node { lo, hi, first: start as u32, count: (end - start) as u32 };
        if end - start <= LEAF {
            return;
        }
        let axis = (0..3).max_by(|&a, &b| (hi[a] - lo[a]).total_cmp(&(hi[b] - lo[b]))).unwrap_or(0);
        let mid = (start + end) / 2;
        let key = |s: &MeshShape, t: u32| s.corners(t).iter().map(|p| p[axis]).sum::<f64>();
        let mut part: Vec<(f64, u32)> = self.order[start..end].iter().map(|&t| (key(self, t), t)).collect();
        part.select_nth_unstable_by(mid - start, |a, b| a.0.total_cmp(&b.0));
        for (i, (_, t)) in part.into_iter().enumerate() {
            self.order[start + i] = t;
        }
        let child = self.nodes.len();
        self.nodes.push(Node { lo, hi, first: 0, count: 0 });
        self.nodes.push(Node { lo, hi, first: 0, count: 0 });
        self.nodes[k] = Node { lo, hi, first: child as u32, count: 0 };
        self.split(child, start, mid);
        self.split(child + 1, mid, end);
    }

    /// Depth-first over the hierarchy: into every node `enter` accepts, calling `leaf` on each
    /// triangle of the leaves reached.
    /// The stack lives on the call stack (no allocation per query: this runs for every vertex
    /// every step); the median split keeps the depth under log2(faces) + 1 < 64.
    fn visit(&self, enter: impl Fn(&Node) -> bool, mut leaf: impl FnMut(u32)) {
        let mut stack = [0usize; 64];
        let mut len = 1;
        while len > 0 {
            len -= 1;
            let n = &self.nodes[stack[len]];
            if !enter(n) {
                continue;
            }
            if n.count == 0 {
                stack[len] = n.first as usize;
                stack[len + 1] = n.first as usize + 1;
                len += 2;
                continue;
            }
            for &t in &self.order[n.first as usize..(n.first + n.count) as usize] {
                leaf(t);
            }
        }
    }

    fn box_distance2(n: &Node, p: V3) -> f64 {
        (0..3).map(|d| (n.lo[d] - p[d]).max(0.0).max(p[d] - n.hi[d])).map(|e| e * e).sum()
    }

    /// Signed distance to the nearest surface point within `reach` (m) and the normal there.
    pub fn closest(&self, p: V3, reach: f64) -> Option<(f64, V3)> {
        // (distance², alignment of p − q with the face normal, q), and that face's normal.
        let mut best: Option<(f64, f64, V3)> = None;
        let mut best_n = [0.0; 3];
        let best_d2 = std::cell::Cell::new(reach * reach);
        self.visit(
            |n| Self::box_distance2(n, p) <= best_d2.get() * (1.0 + 1e-12),
            |t| {
                let [a, b, c] = self.corners(t);
                let (_, q) = closest_on_triangle(p, a, b, c);
                let d = sub(p, q);
                let d2 = dot(d, d);
                let normal = self.normals[t as usize];
                let align = if d2 > 0.0 { dot(d, normal).abs() / d2.sqrt() } else { 1.0 };
                let better = match best {
                    None => d2 <= best_d2.get(),
                    // Equal distances (a shared edge or corner): the best-aligned face decides.
                    Some((bd2, balign, _)) if (d2 - bd2).abs() <= 1e-12 * (1.0 + bd2) => align > balign,
                    Some((bd2, _, _)) => d2 < bd2,
                };
                if better {
                    best_d2.set(d2);
                    best = Some((d2, align, q));
                    best_n = normal;
                }
            },
        );
        let (d2, _, q) = best?;
        let s = dot(sub(p, q), best_n);
        let sign = if s < 0.0 { -1.0 } else { 1.0 };
        Some((sign * d2.sqrt(), best_n))
    }

    /// The first front face the segment p0 → p1 enters, as the fraction t ∈ [0, 1] of the way.
    pub fn first_hit(&self, p0: V3, p1: V3) -> Option<f64> {
        let dir = sub(p1, p0);
        let (lo, hi) = ([p0[0].min(p1[0]), p0[1].min(p1[1]), p0[2].min(p1[2])], [p0[0].max(p1[0]), p0[1].max(p1[1]), p0[2].max(p1[2])]);
        let mut best: Option<f64> = None;
        self.visit(
            |n| (0..3).all(|d| n.hi[d] >= lo[d] && n.lo[d] <= hi[d]),
            |t| {
                if dot(dir, self.normals[t as usize]) >= 0.0 {
                    return; // leaving or grazing: not an entry
                }
                let [a, b, c] = self.corners(t);
                // Möller–Trumbore: p0 + t dir = a + u (b − a) + v (c − a).
                let (e1, e2) = (sub(b, a), sub(c, a));
                let h = cross(dir, e2);
                let det = dot(e1, h);
                if det.abs() < 1e-300 {
                    return;
                }
                let inv = 1.0 / det;
                let s = sub(p0, a);
                let u = inv * dot(s, h);
                let q = cross(s, e1);
                let v = inv * dot(dir, q);
                let eps = 1e-12;
                if u < -eps || v < -eps || u + v > 1.0 + eps {
                    return;
                }
                let tt = inv * dot(e2, q);
                if (0.0..=1.0).contains(&tt) && best.is_none_or(|b| tt < b) {
                    best = Some(tt);
                }
            },
        );
        best
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_closest_point_and_side_of_a_closed_mesh() {
        let m = crate::mesh::builtin::icosphere(2, 1.0);
        let s = MeshShape::new(&m).unwrap();
        let (d, n) = s.closest([0.0, 1.5, 0.0], 1.0).unwrap();
        assert!((d - 0.5).abs() < 0.02 && n[1] > 0.9, "{d} {n:?}");
        let (d, _) = s.closest([0.0, 0.97, 0.0], 1.0).unwrap();
        assert!(d < 0.0, "inside: {d}");
        assert!(s.closest([0.0, 3.0, 0.0], 1.0).is_none());
        // Brute force agrees on the distance at many points.
        for k in 0..200 {
            let p = [(k as f64 * 0.37).sin() * 1.3, (k as f64 * 0.71).cos() * 1.3, (k as f64 * 0.13).sin()];
            let brute = m.triangles.iter().map(|t| {
                let (a, b, c) = (get(&m.positions, t[0] as usize), get(&m.positions, t[1] as usize), get(&m.positions, t[2] as usize));
                norm(sub(p, closest_on_triangle(p, a, b, c).1))
            });
            let brute = brute.fold(f64::INFINITY, f64::min);
            let (d, _) = s.closest(p, 10.0).unwrap();
            assert!((d.abs() - brute).abs() < 1e-12, "{p:?}: {d} vs {brute}");
        }
    }

    #[test]
    fn a_segment_through_the_mesh_hits_the_front_face_first() {
        let s = MeshShape::new(&crate::mesh::builtin::icosphere(2, 1.0)).unwrap();
        let t = s.first_hit([0.0, 3.0, 0.0], [0.0, -3.0, 0.0]).unwrap();
        assert!((t - 1.0 / 3.0).abs() < 0.01, "{t}");
        assert!(s.first_hit([0.0, 0.0, 0.0], [0.0, 3.0, 0.0]).is_none(), "leaving is not entering");
    }
}
