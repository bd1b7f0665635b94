//! The mesh being remeshed and its three local operations: split an edge at its midpoint,
//! collapse an edge, flip an edge. Faces keep their counter-clockwise (outward) winding through
//! every operation, so a closed outward mesh stays closed and outward.
//!
//! Connectivity is kept as the faces around each vertex (`vf`); the faces of edge (a, b) are
//! those of `vf[a]` that contain b. An edge is *constrained* when it is on the border (one face)
//! or is a feature edge (a crease of the input, kept in `features`): constrained edges are never
//! flipped, collapse only along themselves, and their vertices are not relaxed.

use crate::vec3::{add, cross, dot, norm, scale, sub, V3};
use std::collections::HashSet;

pub(super) fn key(a: u32, b: u32) -> (u32, u32) {
    if a < b { (a, b) } else { (b, a) }
}

pub(super) struct Work {
    pub pos: Vec<V3>,
    pub tris: Vec<[u32; 3]>,
    pub face_alive: Vec<bool>,
    pub vf: Vec<Vec<u32>>,
    pub vertex_alive: Vec<bool>,
    /// Feature (crease) edges, as sorted pairs.
    pub features: HashSet<(u32, u32)>,
}

impl Work {
    pub fn new(positions: &[f64], tris: &[[u32; 3]], features: HashSet<(u32, u32)>) -> Self {
        let pos: Vec<V3> = positions.chunks_exact(3).map(|p| [p[0], p[1], p[2]]).collect();
        let mut vf = vec![Vec::new(); pos.len()];
        for (f, t) in tris.iter().enumerate() {
            for &v in t {
                vf[v as usize].push(f as u32);
            }
        }
        let vertex_alive = vf.iter().map(|f| !f.is_empty()).collect();
        Work { pos, tris: tris.to_vec(), face_alive: vec![true; tris.len()], vf, vertex_alive, features }
    }

    pub fn p(&self, v: u32) -> V3 {
        self.pos[v as usize]
    }

    pub fn length(&self, a: u32, b: u32) -> f64 {
        norm(sub(self.p(a), self.p(b)))
    }

    /// Faces of edge (a, b): one on the border, two inside.
    pub fn edge_faces(&self, a: u32, b: u32) -> Vec<u32> {
        self.vf[a as usize].iter().copied().filter(|&f| self.tris[f as usize].contains(&b)).collect()
    }

    /// Every live edge (a < b).
    pub fn edges(&self) -> Vec<(u32, u32)> {
        let mut e: Vec<(u32, u32)> = Vec::new();
        for (f, t) in self.tris.iter().enumerate() {
            if self.face_alive[f] {
                for k in 0..3 {
                    e.push(key(t[k], t[(k + 1) % 3]));
                }
            }
        }
        e.sort_unstable();
        e.dedup();
        e
    }

    /// Neighbouring vertices of v.
    pub fn neighbours(&self, v: u32) -> Vec<u32> {
        let mut n: Vec<u32> = self.vf[v as usize].iter().flat_map(|&f| self.tris[f as usize]).filter(|&w| w != v).collect();
        n.sort_unstable();
        n.dedup();
        n
    }

    pub fn is_constrained(&self, a: u32, b: u32) -> bool {
        self.features.contains(&key(a, b)) || self.edge_faces(a, b).len() == 1
    }

    /// Constrained edges at v (0 for a free vertex, 2 along a border or crease, more at a corner).
    pub fn constrained_count(&self, v: u32) -> usize {
        self.neighbours(v).into_iter().filter(|&w| self.is_constrained(v, w)).count()
    }

    pub fn on_border(&self, v: u32) -> bool {
        self.neighbours(v).into_iter().any(|w| self.edge_faces(v, w).len() == 1)
    }

    /// Target valence: 6 inside, 4 on the border (regular triangulation).
    fn valence_deviation(&self, v: u32, change: i64) -> i64 {
        let target = if self.on_border(v) { 4 } else { 6 };
        let d = self.neighbours(v).len() as i64 + change - target;
        d * d
    }

    pub fn face_normal(&self, t: [u32; 3]) -> V3 {
        let (a, b, c) = (self.p(t[0]), self.p(t[1]), self.p(t[2]));
        cross(sub(b, a), sub(c, a))
    }

    /// Split edge (a, b) at its midpoint; returns the new vertex.
    pub fn split(&mut self, a: u32, b: u32) -> u32 {
        let m = self.pos.len() as u32;
        self.pos.push(scale(add(self.p(a), self.p(b)), 0.5));
        self.vertex_alive.push(true);
        self.vf.push(Vec::new());
        if self.features.remove(&key(a, b)) {
            self.features.insert(key(a, m));
            self.features.insert(key(m, b));
        }
        for f in self.edge_faces(a, b) {
            let t = self.tris[f as usize];
            let c = t.into_iter().find(|&v| v != a && v != b).expect("a face has three vertices");
            // The face keeps a's half (b → m); a new face takes b's half (a → m): both keep the
            // winding, since each replaces one corner in place.
            let first = t.map(|v| if v == b { m } else { v });
            let second = t.map(|v| if v == a { m } else { v });
            self.tris[f as usize] = first;
            let g = self.tris.len() as u32;
            self.tris.push(second);
            self.face_alive.push(true);
            self.vf[b as usize].retain(|&x| x != f);
            self.vf[b as usize].push(g);
            self.vf[c as usize].push(g);
            self.vf[m as usize].extend_from_slice(&[f, g]);
        }
        m
    }

    /// Collapse edge (a, b), removing `a` and moving `b` to `to`, if that keeps the surface a
    /// manifold, no new edge is longer than `max_len`, and no face turns over. Returns whether it
    /// collapsed.
    pub fn collapse(&mut self, a: u32, b: u32, to: V3, max_len: f64) -> bool {
        let faces = self.edge_faces(a, b);
        let (na, nb) = (self.neighbours(a), self.neighbours(b));
        // Link condition: the common neighbours of a and b are exactly the edge's opposite
        // vertices (else the collapse pinches the surface).
        let common: Vec<u32> = na.iter().copied().filter(|v| nb.contains(v)).collect();
        if common.len() != faces.len() {
            return false;
        }
        // Each opposite vertex loses an edge: keep it at three or more (two on the border).
        for &c in &common {
            let min = if self.on_border(c) { 3 } else { 4 };
            if self.neighbours(c).len() < min {
                return false;
            }
        }
        if na.len() + nb.len() < 6 + common.len() {
            return false; // a tetrahedron (or smaller) has nothing left to collapse
        }
        if na.iter().chain(&nb).any(|&v| v != a && v != b && norm(sub(self.p(v), to)) > max_len) {
            return false;
        }
        // No surviving face around a or b may turn over or become a sliver.
        for &f in self.vf[a as usize].iter().chain(&self.vf[b as usize]) {
            let t = self.tris[f as usize];
            if t.contains(&a) && t.contains(&b) {
                continue;
            }
            let before = self.face_normal(t);
            let moved = t.map(|v| if v == a { b } else { v });
            let after = {
                let q = |v: u32| if v == b { to } else { self.p(v) };
                cross(sub(q(moved[1]), q(moved[0])), sub(q(moved[2]), q(moved[0])))
            };
            if dot(before, after) <= 0.2 * norm(before) * norm(after) {
                return false; // turned by more than ~78°
            }
        }
        // Apply.
        for f in faces {
            self.face_alive[f as usize] = false;
            for v in self.tris[f as usize] {
                self.vf[v as usize].retain(|&x| x != f);
            }
        }
        for f in std::mem::take(&mut self.vf[a as usize]) {
            let t = &mut self.tris[f as usize];
            for v in t.iter_mut() {
                if *v == a {
                    *v = b;
                }
            }
            self.vf[b as usize].push(f);
        }
        for v in na {
            if self.features.remove(&key(a, v)) && v != b {
                self.features.insert(key(b, v));
            }
        }
        self.vertex_alive[a as usize] = false;
        self.pos[b as usize] = to;
        true
    }

    /// Flip the interior edge (a, b) if that brings the four vertices' valences closer to their
    /// targets, neither new face turns over, and the new pair's worst triangle is at least half
    /// as good as the old pair's (no sliver). Returns whether it flipped.
    pub fn flip_if_better(&mut self, a: u32, b: u32) -> bool {
        if self.features.contains(&key(a, b)) {
            return false;
        }
        let faces = self.edge_faces(a, b);
        if faces.len() != 2 {
            return false;
        }
        // Orient: f1 traverses a → b (opposite c), f2 traverses b → a (opposite d).
        let forward = |t: [u32; 3]| (0..3).any(|k| t[k] == a && t[(k + 1) % 3] == b);
        let (f1, f2) = if forward(self.tris[faces[0] as usize]) { (faces[0], faces[1]) } else { (faces[1], faces[0]) };
        let opp = |f: u32| self.tris[f as usize].into_iter().find(|&v| v != a && v != b).expect("three vertices");
        let (c, d) = (opp(f1), opp(f2));
        if c == d || self.neighbours(c).contains(&d) {
            return false;
        }
        if self.neighbours(a).len() <= 3 || self.neighbours(b).len() <= 3 {
            return false;
        }
        let before = self.valence_deviation(a, 0) + self.valence_deviation(b, 0) + self.valence_deviation(c, 0) + self.valence_deviation(d, 0);
        let after = self.valence_deviation(a, -1) + self.valence_deviation(b, -1) + self.valence_deviation(c, 1) + self.valence_deviation(d, 1);
        if after >= before {
            return false;
        }
        // The quad a → d → b → c becomes (a, d, c) and (d, b, c).
        let (t1, t2) = ([a, d, c], [d, b, c]);
        let old = add(self.face_normal(self.tris[f1 as usize]), self.face_normal(self.tris[f2 as usize]));
        let (n1, n2) = (self.face_normal(t1), self.face_normal(t2));
        // Both new faces face the same side as the old pair, within ~60° (no fold created).
        if dot(n1, old) <= 0.5 * norm(n1) * norm(old) || dot(n2, old) <= 0.5 * norm(n2) * norm(old) {
            return false;
        }
        // Nor a sliver (docs/meshing.md): the new pair's worst triangle at least half as good as the old pair's
        // (quality |n| / l_max², twice the area over the longest edge squared: √3/2 equilateral,
        // 0 for three points on a line). Valence alone flipped the quad of three collinear
        // vertices on a box's flat top, kept with its creases, into a face of angles 0°, 180°,
        // 0° (measured on the imported 8-vertex tower, sagged a little, at L/4 with creases).
        let quality = |t: [u32; 3]| {
            let longest = (0..3).map(|k| norm(sub(self.p(t[(k + 1) % 3]), self.p(t[k])))).fold(0.0, f64::max);
            norm(self.face_normal(t)) / (longest * longest)
        };
        if quality(t1).min(quality(t2)) < 0.5 * quality(self.tris[f1 as usize]).min(quality(self.tris[f2 as usize])) {
            return false;
        }
        self.tris[f1 as usize] = t1;
        self.tris[f2 as usize] = t2;
        self.vf[b as usize].retain(|&x| x != f1);
        self.vf[a as usize].retain(|&x| x != f2);
        self.vf[d as usize].push(f1);
        self.vf[c as usize].push(f2);
        true
    }

    /// The live mesh, compacted: positions and triangles.
    pub fn compact(&self) -> (Vec<f64>, Vec<[u32; 3]>) {
        let mut index = vec![u32::MAX; self.pos.len()];
        let mut positions = Vec::new();
        for (v, p) in self.pos.iter().enumerate() {
            if self.vertex_alive[v] && !self.vf[v].is_empty() {
                index[v] = (positions.len() / 3) as u32;
                positions.extend_from_slice(p);
            }
        }
        let tris = self.tris.iter().zip(&self.face_alive).filter(|(_, &a)| a).map(|(t, _)| t.map(|v| index[v as usize])).collect();
        (positions, tris)
    }
}
