//! Assembly of the coarse levels (`super`): level 1 from the fine springs and hinges, each
//! level below by the Galerkin product, the nodes' centres and offsets, and the hinges' node
//! blocks found once from the mesh.

use super::dense::*;
use super::{free, held, Level, BLOCK_PIVOT};
use super::super::aggregate::Shape;
use super::super::system::System;
use super::super::super::Model;

impl Level {
    /// Level 1: centres, offsets, then the springs' CSR entries row by row.
    pub(super) fn add_springs(&mut self, sys: &System, m: &Model, x: &[f64]) {
        let Level { s, a, c: centre, off, .. } = self;
        centres(s, |i| [x[3 * i], x[3 * i + 1], x[3 * i + 2]], centre, off);
        a.fill([0.0; 36]);
        for c in 0..s.n {
            let dpos = s.start[c] as usize;
            for &i in &s.member[s.mstart[c] as usize..s.mstart[c + 1] as usize] {
                let i = i as usize;
                if !free(m, i) {
                    continue;
                }
                spring_row(sys, m, s, off, a, i, dpos);
            }
        }
    }

    /// The hinges' rank-one blocks c ∇θ ∇θᵀ (`system/`): with w_q = P_qᵀ ∇_q θ = (g_q, r_q × g_q)
    /// (g_q's y zeroed where the ground holds the vertex; a pinned vertex is no unknown),
    /// Pᵀ (c ∇θ ∇θᵀ) P = c W Wᵀ with W_I = Σ_{q ∈ I} w_q summed per node first: block
    /// (I, J) gets c W_I W_Jᵀ, (J, I) its transpose (a hinge spans 1–4 nodes, ~2 on average:
    /// k(k + 1)/2 outer products for k nodes instead of the 16 vertex pairs'). Every pair of a hinge's vertices
    /// is an edge or its bending pair, so the level's sparsity has the block already.
    /// Without them the coarse levels did not see bending: at 10,242 vertices with the
    /// modeler's D = 0.05 J the conjugate gradient took 6× the iterations (BENCHMARKS.md).
    pub(super) fn add_hinges(&mut self, sys: &System, m: &Model, hpos: &[HingeNodes]) {
        for (h, hn) in hpos.iter().enumerate() {
            let c = sys.hc[h];
            if c == 0.0 {
                continue;
            }
            let w = hinge_node_weights(sys, m, &self.off, h, hn, c.sqrt());
            add_hinge_outer(&mut self.a, hn, &w);
        }
    }

    /// Every node's diagonal block inverted (a pseudo-inverse without the modes it cannot feel,
    /// [`BLOCK_PIVOT`]), and the matrix in single precision for the sweeps.
    pub(super) fn invert_diagonal(&mut self) {
        let mut f = [0.0; 36];
        let mut drop = [false; 6];
        let mut col = [0.0; 6];
        for (af, a) in self.af.iter_mut().zip(&self.a) {
            for q in 0..36 {
                af[q] = a[q] as f32;
            }
        }
        for c in 0..self.s.n {
            f.copy_from_slice(&self.a[self.s.start[c] as usize]);
            cholesky(&mut f, 6, &mut drop, BLOCK_PIVOT);
            for q in 0..6 {
                let mut e = [0.0; 6];
                e[q] = 1.0;
                cholesky_solve(&f, 6, &drop, &e, &mut col);
                for p in 0..6 {
                    self.dinv[c][6 * p + q] = col[p];
                }
            }
        }
    }
}

/// Row i of level 1 (`s`, offsets `off`, blocks `a`; i's node's diagonal block at `dpos`):
/// each spring block B of i (edges, and bending pairs if on) into the coupling with the
/// other end's node, and the diagonal P_iᵀ (dg I + Σ B) P_i, the 3×3 sum first.
pub(super) fn spring_row(sys: &System, m: &Model, s: &Shape, off: &[[f64; 3]], a: &mut [Blk], i: usize, dpos: usize) {
    let ri = off[i];
    // Row i's diagonal: P_iᵀ (dg I + Σ B) P_i, the 3×3 sum first.
    let dg = sys.diag[i];
    let mut sum = [[dg, 0.0, 0.0], [0.0, dg, 0.0], [0.0, 0.0, dg]];
    let kinds = [(&sys.edges, &sys.ecoef, &s.pos[0]), (&sys.bends, &sys.bcoef, &s.pos[1])];
    for (rows, coef, pos) in kinds.into_iter().take(if sys.bending { 2 } else { 1 }) {
        for k in rows.start[i] as usize..rows.start[i + 1] as usize {
            let j = rows.other[k] as usize;
            let [ca, cb, dx, dy, dz] = coef[k];
            let d = [dx, dy, dz];
            let bl = spring_block(ca, cb, &d);
            for p in 0..3 {
                for q in 0..3 {
                    sum[p][q] += bl[p][q];
                }
            }
            if free(m, j) {
                let rj = off[j];
                let blk = &mut a[pos[k] as usize];
                if held(sys, i) || held(sys, j) {
                    add_general(blk, -1.0, &without_y(bl, held(sys, i), held(sys, j)), &ri, &rj);
                } else {
                    add_spring(blk, -1.0, ca, cb, &d, &ri, &rj);
                }
            }
        }
    }
    let sum = without_y(sum, held(sys, i), held(sys, i));
    add_sandwich(&mut a[dpos], &sum, &ri);
}

/// Hinge h's W_I = Σ_{q ∈ I} w_q per node (slot) of `hn`, w_q = (g_q, r_q × g_q) scaled by
/// √c (`cs`), so that the outer products carry c.
pub(super) fn hinge_node_weights(sys: &System, m: &Model, off: &[[f64; 3]], h: usize, hn: &HingeNodes, cs: f64) -> [[f64; 6]; 4] {
    let (g, hv) = (&sys.hg[h], &m.hinges.v[h]);
    let mut w = [[0.0; 6]; 4];
    for q in 0..4 {
        let v = hv[q] as usize;
        if !free(m, v) {
            continue; // a pinned vertex is no unknown: w_q = 0
        }
        let gq = [cs * g[3 * q], if held(sys, v) { 0.0 } else { cs * g[3 * q + 1] }, cs * g[3 * q + 2]];
        let rg = cross(&off[v], &gq);
        let wn = &mut w[hn.slot[q] as usize];
        for (e, x) in wn.iter_mut().zip([gq[0], gq[1], gq[2], rg[0], rg[1], rg[2]]) {
            *e += x;
        }
    }
    w
}

/// Block (I, J) += W_I W_Jᵀ and (J, I) its transpose, for each pair of the hinge's nodes.
pub(super) fn add_hinge_outer(blocks: &mut [Blk], hn: &HingeNodes, w: &[[f64; 6]; 4]) {
    let k = hn.nodes as usize;
    for a in 0..k {
        for b in a..k {
            let (ab, ba) = (hn.at[4 * a + b], hn.at[4 * b + a]);
            if ab == super::super::aggregate::NONE {
                continue;
            }
            let (wa, wb) = (&w[a], &w[b]);
            let mut o = [0.0; 36];
            for p in 0..6 {
                for t in 0..6 {
                    o[6 * p + t] = wa[p] * wb[t];
                }
            }
            let blk = &mut blocks[ab as usize];
            for q in 0..36 {
                blk[q] += o[q];
            }
            if a != b {
                let blk = &mut blocks[ba as usize];
                for p in 0..6 {
                    for t in 0..6 {
                        blk[6 * t + p] += o[6 * p + t];
                    }
                }
            }
        }
    }
}

/// Level l + 1 from level l, A_{l+1} = Pᵀ A_l P block by block, from level 1 (`first`) down.
pub(super) fn galerkin(first: &Level, rest: &mut [Level]) {
    let mut above = first;
    for lv in rest.iter_mut() {
        let s = &lv.s;
        centres(s, |u| above.c[u], &mut lv.c, &mut lv.off);
        lv.a.fill([0.0; 36]);
        for c in 0..s.n {
            for &u in &s.member[s.mstart[c] as usize..s.mstart[c + 1] as usize] {
                let ru = lv.off[u as usize];
                for e in above.s.start[u as usize] as usize..above.s.start[u as usize + 1] as usize {
                    let rw = lv.off[above.s.col[e] as usize];
                    add_galerkin(&mut lv.a[s.pos[0][e] as usize], &above.a[e], &ru, &rw);
                }
            }
        }
        above = lv;
    }
}

/// A hinge's vertices by level-1 node: `slot[q]` is vertex q's node among the hinge's
/// `nodes` distinct ones (in the order met), `at[4 a + b]` the level-1 block (`s`) of nodes
/// (a, b): the node's diagonal block for a = b, else the coupling's. Every pair of a hinge's
/// vertices is an edge or a bending pair (both always in the level's sparsity), so `NONE` does
/// not occur for a mesh's hinges: it is a guard.
/// Pins are not looked at (they change between assemblies; the assembly leaves a pinned vertex
/// out), so this depends on the mesh alone.
#[derive(Debug, Clone, Copy)]
pub(super) struct HingeNodes {
    slot: [u8; 4],
    nodes: u8,
    at: [u32; 16],
}

pub(super) fn hinge_blocks(s: &Shape, m: &Model) -> Vec<HingeNodes> {
    use super::super::aggregate::NONE;
    let block = |i: usize, j: usize| s.entry(i, j).unwrap_or(NONE);
    m.hinges
        .v
        .iter()
        .map(|hv| {
            let mut hn = HingeNodes { slot: [0; 4], nodes: 0, at: [NONE; 16] };
            let mut node = [0usize; 4];
            for (q, &v) in hv.iter().enumerate() {
                let p = s.parent[v as usize] as usize;
                let a = match node[..hn.nodes as usize].iter().position(|&x| x == p) {
                    Some(a) => a,
                    None => {
                        node[hn.nodes as usize] = p;
                        hn.nodes += 1;
                        hn.nodes as usize - 1
                    }
                };
                hn.slot[q] = a as u8;
            }
            for a in 0..hn.nodes as usize {
                for b in 0..hn.nodes as usize {
                    hn.at[4 * a + b] = block(node[a], node[b]);
                }
            }
            hn
        })
        .collect()
}

/// Each node's centre (the mean of its members' positions `pos`) into `c`, and each member's
/// offset from its node's centre into `off`.
pub(super) fn centres(s: &Shape, pos: impl Fn(usize) -> [f64; 3], c: &mut [[f64; 3]], off: &mut [[f64; 3]]) {
    for (node, cn) in c.iter_mut().enumerate().take(s.n) {
        let mem = &s.member[s.mstart[node] as usize..s.mstart[node + 1] as usize];
        let mut acc = [0.0; 3];
        for &u in mem {
            let p = pos(u as usize);
            for d in 0..3 {
                acc[d] += p[d];
            }
        }
        let inv = 1.0 / mem.len() as f64;
        *cn = [acc[0] * inv, acc[1] * inv, acc[2] * inv];
        for &u in mem {
            let p = pos(u as usize);
            off[u as usize] = [p[0] - cn[0], p[1] - cn[1], p[2] - cn[2]];
        }
    }
}
