//! A hinged body's matrix as 3×3 blocks, row by row (block compressed sparse rows), for the
//! conjugate gradient's many products.
//!
//! The evaluation leaves the matrix A = M + dt D + dt² K in pieces (`system.rs`): per spring
//! entry its (a, b, d) (the block B = a I + b d dᵀ), per hinge its coefficient c_h and gradient
//! ∇θ (the rank-one c_h ∇θ ∇θᵀ over its four vertices), per vertex the scalar diagonal. A
//! product from those pieces takes, per row, the springs' coefficients, a pass over every hinge
//! for c_h (∇θ · p) and the hinge entries' gradients: measured on the modeler's mushroom
//! subdivided twice (5,762 vertices) after a grab, the product was 61 % of the step, a third
//! of it the hinges' pass. Here the pieces are summed once per Newton iteration into one block
//! per pair of vertices that a spring or a hinge couples,
//!
//!   A[i, i] = diag_i I + Σ_{springs at i} B + Σ_{hinges at i} c_h ∇_i θ ∇_i θᵀ
//!   A[i, j] = −Σ_{springs (i, j)} B + Σ_{hinges at i and j} c_h ∇_i θ ∇_j θᵀ          (kg)
//!
//! with diag_i = m_i (1 + dt c) + dt c_t + dt² k_t (mass, viscous damping, target springs)
//! (every pair of a hinge's vertices is an edge or its two opposite vertices, a bending pair:
//! 12 blocks and the diagonal on a row of valence 6), and a product is one block row times the
//! gathered p: q_i = Σ_j A[i, j] p_j. The same matrix as the pieces' up to rounding (the sums
//! are taken in another order); the gas's rank-one term, the ground's held rows, pins and
//! self-contacts are applied by the product as before (`System::product`).
//!
//! Only for hinged bodies: without hinges a row's springs are already one compact pass (5
//! numbers per spring against a block's 9). The blocks are summed when a conjugate gradient
//! runs long enough for them to pay (`System::prepare`, called by `Cg::solve`: see
//! `cg::BLOCKS_FROM`), so a body at rest, whose solves take one or two iterations, never pays
//! for them.

use super::adjacency::{HingeRows, SpringRows};
use crate::par::{chunk, Out, Threads};

/// A 3×3 block, row-major.
pub(crate) type Block = [f64; 9];

/// The block rows of a hinged body and where each piece of the matrix goes in them.
#[derive(Debug, Clone, Default)]
pub(crate) struct Blocks {
    /// Row i is `start[i]..start[i + 1]`; its first entry is the diagonal (`col` = i), the
    /// others its neighbours in increasing order.
    pub start: Vec<u32>,
    pub col: Vec<u32>,
    /// Per entry of the edges' and the bending springs' `SpringRows`: the block entry of the
    /// spring's other end in that row.
    eslot: Vec<u32>,
    bslot: Vec<u32>,
    /// Per entry of `HingeRows`: the block entries, in that row, of the hinge's four vertices
    /// (the row's own vertex: its diagonal).
    hslot: Vec<[u32; 4]>,
    pub blk: Vec<Block>,
    /// The blocks are those of the last evaluation (`System::prepare`; the evaluation clears it).
    pub ready: bool,
}

impl Blocks {
    /// The sparsity of a body with these springs and hinges (`hinges`: each hinge's vertices).
    pub fn new(n: usize, edges: &SpringRows, bends: &SpringRows, hrows: &HingeRows, hinges: &[[u32; 4]]) -> Self {
        let mut start = Vec::with_capacity(n + 1);
        let mut col: Vec<u32> = Vec::new();
        let mut row: Vec<u32> = Vec::new();
        start.push(0u32);
        for i in 0..n {
            row.clear();
            let (e0, e1) = (edges.start[i] as usize, edges.start[i + 1] as usize);
            row.extend_from_slice(&edges.other[e0..e1]);
            if bends.start.len() == n + 1 {
                row.extend_from_slice(&bends.other[bends.start[i] as usize..bends.start[i + 1] as usize]);
            }
            for &e in &hrows.entry[hrows.start[i] as usize..hrows.start[i + 1] as usize] {
                row.extend(hinges[(e / 4) as usize].iter().copied());
            }
            row.retain(|&j| j as usize != i);
            row.sort_unstable();
            row.dedup();
            col.push(i as u32);
            col.extend_from_slice(&row);
            start.push(col.len() as u32);
        }
        // The entry of column j in row i (the diagonal first, then a binary search of the rest).
        let at = |i: usize, j: u32| -> u32 {
            let (s, e) = (start[i] as usize, start[i + 1] as usize);
            if j as usize == i {
                return s as u32;
            }
            let k = col[s + 1..e].binary_search(&j).expect("a spring's or hinge's vertex is a neighbour of the row");
            (s + 1 + k) as u32
        };
        let slots = |rows: &SpringRows| -> Vec<u32> {
            if rows.start.len() != n + 1 {
                return Vec::new();
            }
            (0..n).flat_map(|i| rows.other[rows.start[i] as usize..rows.start[i + 1] as usize].iter().map(move |&j| (i, j))).map(|(i, j)| at(i, j)).collect()
        };
        let (eslot, bslot) = (slots(edges), slots(bends));
        let mut hslot = vec![[0u32; 4]; hrows.entry.len()];
        for i in 0..n {
            for k in hrows.start[i] as usize..hrows.start[i + 1] as usize {
                let hv = &hinges[(hrows.entry[k] / 4) as usize];
                hslot[k] = [at(i, hv[0]), at(i, hv[1]), at(i, hv[2]), at(i, hv[3])];
            }
        }
        let total = col.len();
        Blocks { start, col, eslot, bslot, hslot, blk: vec![[0.0; 9]; total], ready: false }
    }

    /// Whether this was built for `n` vertices and `entries` hinge entries.
    pub fn fits(&self, n: usize, entries: usize) -> bool {
        self.start.len() == n + 1 && self.hslot.len() == entries
    }

    /// Sum the pieces into the blocks (see the module documentation), rows in chunks of
    /// `vchunk` vertices, each written by one thread: the same bits for any thread count.
    /// Pinned rows are left 0 (the product writes 0 there).
    pub fn assemble(&mut self, th: &Threads, vchunk: usize, pieces: &Pieces, slots: &mut [[f64; 4]]) {
        let n = self.start.len() - 1;
        let (start, eslot, bslot, hslot) = (&self.start, &self.eslot, &self.bslot, &self.hslot);
        let out = Out::new(&mut self.blk);
        th.each(slots, |c, _| {
            let vr = chunk(c, vchunk, n);
            // SAFETY: chunk c writes the entries of rows vr only; chunks are disjoint.
            let blk = unsafe { out.range(start[vr.start] as usize..start[vr.end] as usize) };
            let first = start[vr.start] as usize;
            for i in vr {
                let (s, e) = (start[i] as usize, start[i + 1] as usize);
                let row = &mut blk[s - first..e - first];
                row.fill([0.0; 9]);
                if pieces.inv_mass[i] == 0.0 {
                    continue;
                }
                let dg = pieces.diag[i];
                row[0][0] = dg;
                row[0][4] = dg;
                row[0][8] = dg;
                let mut springs = |rows: &SpringRows, coef: &[[f64; 5]], slot: &[u32]| {
                    for kk in rows.start[i] as usize..rows.start[i + 1] as usize {
                        let [a, b, dx, dy, dz] = coef[kk];
                        let d = [dx, dy, dz];
                        let j = slot[kk] as usize - s;
                        for p in 0..3 {
                            for q in 0..3 {
                                let v = b * d[p] * d[q] + if p == q { a } else { 0.0 };
                                row[0][3 * p + q] += v;
                                row[j][3 * p + q] -= v;
                            }
                        }
                    }
                };
                springs(pieces.edges, pieces.ecoef, eslot);
                if pieces.bending {
                    springs(pieces.bends, pieces.bcoef, bslot);
                }
                let hr = pieces.hrows;
                let ks = hr.start[i] as usize..hr.start[i + 1] as usize;
                for ((&e, gi), slots) in hr.entry[ks.clone()].iter().zip(&pieces.hcoef[ks.clone()]).zip(&hslot[ks]) {
                    let h = (e / 4) as usize;
                    let (ch, g) = (pieces.hc[h], &pieces.hg[h]);
                    let cg = [ch * gi[0], ch * gi[1], ch * gi[2]];
                    for (q, &slot) in slots.iter().enumerate() {
                        let b = &mut row[slot as usize - s];
                        for p in 0..3 {
                            for r in 0..3 {
                                b[3 * p + r] += cg[p] * g[3 * q + r];
                            }
                        }
                    }
                }
            }
        });
        self.ready = true;
    }

    /// q = Σ_j A[i, j] p_j over row i.
    #[inline(always)]
    pub fn row(&self, i: usize, p: &[f64]) -> [f64; 3] {
        let (s, e) = (self.start[i] as usize, self.start[i + 1] as usize);
        let mut q = [0.0; 3];
        for (&j, b) in self.col[s..e].iter().zip(&self.blk[s..e]) {
            let o = 3 * j as usize;
            // SAFETY: every column is a vertex of the body (built from its springs and hinges)
            // and the product asserts p.len() ≥ 3 n.
            let pj = unsafe { [*p.get_unchecked(o), *p.get_unchecked(o + 1), *p.get_unchecked(o + 2)] };
            q[0] += b[0] * pj[0] + b[1] * pj[1] + b[2] * pj[2];
            q[1] += b[3] * pj[0] + b[4] * pj[1] + b[5] * pj[2];
            q[2] += b[6] * pj[0] + b[7] * pj[1] + b[8] * pj[2];
        }
        q
    }
}

/// The evaluation's pieces of the matrix that `Blocks::assemble` sums (`System`'s arrays).
pub(crate) struct Pieces<'a> {
    pub edges: &'a SpringRows,
    pub bends: &'a SpringRows,
    pub ecoef: &'a [[f64; 5]],
    pub bcoef: &'a [[f64; 5]],
    pub bending: bool,
    pub hrows: &'a HingeRows,
    pub hcoef: &'a [[f64; 3]],
    pub hg: &'a [[f64; 12]],
    pub hc: &'a [f64],
    pub diag: &'a [f64],
    pub inv_mass: &'a [f64],
}

#[cfg(test)]
mod tests {
    use super::super::system::Frame;
    use super::super::Implicit;
    use crate::body::{Material, SoftBody, Target};
    use crate::mesh::builtin::icosphere;
    use crate::par::Threads;
    use crate::world::{Ground, Integrator, WorldSettings};

    /// The block product is the pieces' product: on a jittered, swirling 2,562-vertex sphere
    /// (two vertex chunks) with stretched and compressed springs, bending springs, bent hinges,
    /// gas, damping, a pinned vertex, grab-like target springs and its bottom held by the
    /// ground, A p from the blocks against A p from the springs' and hinges' own coefficients,
    /// for random p (0 on the pinned vertex and the held y components, as the solver's vectors
    /// are), and the residual b − A p alike. Both sum the same ~40 products per entry in other
    /// orders: they differ by at most ~2 · 40 ε of the entry's absolute sum, ≤ 1e-14 of
    /// `scale` (the largest row's Σ |A_ij| times max |p|); 1e-13 leaves room. And 1 and 2
    /// threads give the same bits (each row is summed by one thread in a fixed order).
    #[test]
    fn the_block_product_is_the_product_of_the_springs_and_hinges() {
        let mut p = Material { stiffness: 300.0, spring_damping: 0.5, bending_stiffness: 50.0, rigidity: 0.05, damping: 1.0, ..Material::default() };
        p.set_nrt(2.0);
        let mut body = SoftBody::new(&icosphere(4, 1.0), 1.0, p.clone()).unwrap();
        let n = body.model.mass.len();
        let mut seed = 99u64;
        let mut rnd = move || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        for x in body.state.x.iter_mut() {
            *x *= 1.0 + 0.03 * rnd();
        }
        for v in body.state.v.iter_mut() {
            *v = 0.1 * rnd();
        }
        body.set_pinned(7, true).unwrap();
        let targets: Vec<Target> = (100..130).map(|i| Target { vertex: i, anchor: [0.0, 2.0, 0.0], stiffness: 50.0, damping: 0.1 }).collect();
        body.set_targets(&targets).unwrap();
        let w = WorldSettings { integrator: Integrator::Implicit, gravity: 9.81, ground: Some(Ground::at(-0.95)), ..WorldSettings::default() };
        let m = &body.model;
        let mut imp = Implicit::new(m);
        let fr = Frame { p: &p, w: &w, m, x: &body.state.x, v: &body.state.v, dt: 1.0 / 60.0 };
        let single = Threads::single();
        imp.sys.ground.find(m, w.ground.as_ref(), fr.x, fr.v, fr.dt);
        imp.vp.copy_from_slice(fr.v);
        imp.sys.ground.prescribe(&mut imp.vp);
        imp.eval(&single, &fr).unwrap();
        assert!(imp.sys.hinged && imp.sys.ground.list.len() >= 10, "{} held", imp.sys.ground.list.len());
        let mut u: Vec<f64> = (0..3 * n).map(|_| rnd()).collect();
        u[21..24].fill(0.0);
        imp.sys.ground.filter(&mut u);
        let b: Vec<f64> = (0..3 * n).map(|k| if u[k] == 0.0 { 0.0 } else { rnd() }).collect();
        let gp: f64 = u.iter().zip(&imp.sys.g).map(|(a, b)| a * b).sum();
        let mut slots = vec![[0.0; 4]; imp.cg.slots.len()];
        let (mut q0, mut r0) = (vec![0.0; 3 * n], vec![0.0; 3 * n]);
        let pq0 = imp.sys.product(&single, m, &u, gp, &mut q0, &mut slots);
        imp.sys.residual(&single, m, &u, &b, &mut r0, &mut slots);
        imp.sys.prepare(&single, m);
        assert!(imp.sys.blocks.ready);
        let (mut q1, mut r1) = (vec![0.0; 3 * n], vec![0.0; 3 * n]);
        let pq1 = imp.sys.product(&single, m, &u, gp, &mut q1, &mut slots);
        imp.sys.residual(&single, m, &u, &b, &mut r1, &mut slots);
        let bl = &imp.sys.blocks;
        let row_abs = (0..n).map(|i| bl.blk[bl.start[i] as usize..bl.start[i + 1] as usize].iter().flatten().map(|a| a.abs()).sum::<f64>()).fold(0.0, f64::max);
        let scale = row_abs * u.iter().fold(0.0f64, |a, b| a.max(b.abs()));
        for (name, x, y) in [("A p", &q0, &q1), ("b − A p", &r0, &r1)] {
            let err = x.iter().zip(y.iter()).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
            assert!(err <= 1e-13 * scale, "{name}: max difference {err:e} of {scale:e}");
        }
        assert!((pq0 - pq1).abs() <= 1e-12 * pq0.abs(), "p·Ap {pq0} against {pq1}");
        // Pinned and held rows are 0 in the product.
        assert_eq!(&q1[21..24], &[0.0; 3]);
        assert!(imp.sys.ground.list.iter().all(|&i| q1[3 * i as usize + 1] == 0.0));
        // Two threads: the blocks and the product, bit for bit.
        let two = Threads::new(2).unwrap();
        let blk1 = imp.sys.blocks.blk.clone();
        imp.sys.blocks.ready = false;
        imp.sys.prepare(&two, m);
        assert!(imp.sys.blocks.blk == blk1);
        let mut q2 = vec![0.0; 3 * n];
        imp.sys.product(&two, m, &u, gp, &mut q2, &mut slots);
        assert!(q2 == q1);
    }
}
