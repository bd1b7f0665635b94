//! A hinged body's matrix as 3×3 blocks, row by row (block compressed sparse rows), for the
//! conjugate gradient's many products.
//!
//! The evaluation leaves the matrix A = M + dt D + dt² K in pieces (`system/`): per spring
//! entry its (a, b, d) (the block B = a I + b d dᵀ), per hinge its coefficient c_h and gradient
//! ∇θ (the rank-one c_h ∇θ ∇θᵀ over its four vertices), per vertex the scalar diagonal. A
//! product from those pieces takes, per row, the springs' coefficients, a pass over every hinge
//! for c_h (∇θ · p) and the hinge entries' gradients: measured on the modeler's mushroom
//! subdivided twice (5,762 vertices) after a grab, the product was 61 % of the step, a third
//! of it the hinges' pass. Here the pieces are summed, at most once per evaluation, into one
//! block per pair of vertices that a spring or a hinge couples,
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
//! `cg::BLOCKS_AFTER`), so a body at rest, whose solves take one or two iterations, seldom pays
//! for them. Memory: the sparsity ~300 B per vertex (with the hinge entries' slots) from the
//! first hinged evaluation, the blocks 13 × 72 B ≈ 940 B per vertex from the first sum
//! (~150 MB at 163,842 vertices).

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
        // The blocks themselves wait for the first sum (`assemble`).
        Blocks { start, col, eslot, bslot, hslot, blk: Vec::new(), ready: false }
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
        // Every row is summed: one slot per chunk of rows.
        assert_eq!(slots.len(), crate::par::chunks(n, vchunk), "one slot per chunk of rows");
        if self.blk.len() != self.col.len() {
            self.blk = vec![[0.0; 9]; self.col.len()];
        }
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

    /// q = Σ_j A[i, j] p_j over row i (the blocks summed: `ready`).
    ///
    /// # Safety
    /// `p.len() ≥ 3 n` (every column is a vertex of the body: built from its springs and
    /// hinges, whose indices are checked against the vertex count).
    #[inline(always)]
    pub unsafe fn row(&self, i: usize, p: &[f64]) -> [f64; 3] {
        let (s, e) = (self.start[i] as usize, self.start[i + 1] as usize);
        let mut q = [0.0; 3];
        for (&j, b) in self.col[s..e].iter().zip(&self.blk[s..e]) {
            let o = 3 * j as usize;
            // SAFETY: o + 2 < 3 n ≤ p.len() (the caller's contract).
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
    use crate::mesh::TriMesh;
    use crate::par::Threads;
    use crate::world::{Ground, Integrator, WorldSettings};

    fn rng(mut seed: u64) -> impl FnMut() -> f64 {
        move || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        }
    }

    /// The largest |a − b| over two vectors (NaN if either has one: never under a bound).
    fn max_diff(a: &[f64], b: &[f64]) -> f64 {
        a.iter().zip(b).map(|(x, y)| (x - y).abs()).fold(0.0, |m, d| if d.is_nan() || m.is_nan() { f64::NAN } else { m.max(d) })
    }

    /// The scratch of `body` evaluated at v⁺ = v (the ground's held vertices from the state)
    /// with dt = 1/60 s, compressed springs' transverse stiffness by its absolute value if
    /// `absolute`.
    fn evaluated(body: &SoftBody, p: &Material, w: &WorldSettings, absolute: bool) -> Implicit {
        let m = &body.model;
        let mut imp = Implicit::new(m);
        let fr = Frame { p, w, m, x: &body.state.x, v: &body.state.v, dt: 1.0 / 60.0, relax: crate::Relaxed::No };
        imp.sys.ground.find(m, w.ground.as_ref(), fr.x, fr.v, fr.dt);
        imp.vp.copy_from_slice(fr.v);
        imp.sys.ground.prescribe(&mut imp.vp);
        imp.sys.absolute = absolute;
        imp.eval(&Threads::single(), &fr).unwrap();
        imp
    }

    /// A p and b − A p from the pieces and from the blocks for a random p (0 on pinned vertices
    /// and held y components, as the solver's vectors are): (max difference, scale), scale the
    /// largest row's Σ |A_ij| times max |p|. Both sum the same ≤ ~40 products per entry (a row
    /// of valence 6: 13 blocks of 3; the pieces: 12 springs, 12 hinge entries, the diagonal) in
    /// other orders, so they differ by ≤ ~2 · 40 ε ≈ 2e-14 of the entry's absolute sum ≤ scale.
    fn compare(imp: &mut Implicit, m: &crate::body::Model, rnd: &mut impl FnMut() -> f64) -> (f64, f64) {
        let n = m.mass.len();
        let single = Threads::single();
        let mut u: Vec<f64> = (0..3 * n).map(|k| if m.inv_mass[k / 3] == 0.0 { 0.0 } else { rnd() }).collect();
        imp.sys.ground.filter(&mut u);
        let b: Vec<f64> = (0..3 * n).map(|k| if u[k] == 0.0 { 0.0 } else { rnd() }).collect();
        let gp: f64 = u.iter().zip(&imp.sys.g).map(|(a, b)| a * b).sum();
        let mut slots = vec![[0.0; 4]; imp.cg.slots.len()];
        let (mut q0, mut r0, mut q1, mut r1) = (vec![0.0; 3 * n], vec![0.0; 3 * n], vec![0.0; 3 * n], vec![0.0; 3 * n]);
        assert!(!imp.sys.blocks.ready);
        let pq0 = imp.sys.product(&single, m, &u, gp, &mut q0, &mut slots);
        imp.sys.residual(&single, m, &u, &b, &mut r0, &mut slots);
        imp.sys.prepare(&single, m);
        assert!(imp.sys.blocks.ready);
        let pq1 = imp.sys.product(&single, m, &u, gp, &mut q1, &mut slots);
        imp.sys.residual(&single, m, &u, &b, &mut r1, &mut slots);
        let bl = &imp.sys.blocks;
        let row_abs = (0..n).map(|i| bl.blk[bl.start[i] as usize..bl.start[i + 1] as usize].iter().flatten().map(|a| a.abs()).sum::<f64>()).fold(0.0, f64::max);
        let scale = row_abs * u.iter().fold(0.0f64, |a, b| a.max(b.abs()));
        assert!(q0.iter().all(|x| x.is_finite()) && scale > 0.0);
        let pq = if (pq0 - pq1).abs() <= 1e-12 * pq0.abs() { 0.0 } else { f64::NAN };
        (max_diff(&q0, &q1).max(max_diff(&r0, &r1)) + pq, scale)
    }

    /// The block product is the pieces' product: on a jittered, swirling 2,562-vertex sphere
    /// (two vertex chunks) with stretched and compressed springs, bending springs, bent hinges,
    /// gas, damping, a pinned vertex, grab-like target springs and its bottom held by the
    /// ground, A p and b − A p agree to rounding (`compare`: 1e-13 of the scale, ~5× the bound),
    /// p · A p to 1e-12; pinned and held rows are 0; and 1 and 2 threads give the same bits
    /// (each row is summed by one thread in a fixed order).
    #[test]
    fn the_block_product_is_the_product_of_the_springs_and_hinges() {
        let mut p = Material { stiffness: 300.0, spring_damping: 0.5, bending_stiffness: 50.0, rigidity: 0.05, damping: 1.0, ..Material::default() };
        p.set_nrt(2.0);
        let mut body = SoftBody::new(&icosphere(4, 1.0), 1.0, p.clone()).unwrap();
        let mut rnd = rng(99);
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
        let n = m.mass.len();
        let mut imp = evaluated(&body, &p, &w, false);
        assert!(imp.sys.hinged && imp.sys.ground.list.len() >= 10, "{} held", imp.sys.ground.list.len());
        let (err, scale) = compare(&mut imp, m, &mut rnd);
        assert!(err <= 1e-13 * scale, "max difference {err:e} of {scale:e}");
        // Pinned and held rows are 0 in the product; two threads: the blocks and the product,
        // bit for bit.
        let u: Vec<f64> = (0..3 * n).map(|k| if k / 3 == 7 { 0.0 } else { rnd() }).collect();
        let mut u = u;
        imp.sys.ground.filter(&mut u);
        let mut slots = vec![[0.0; 4]; imp.cg.slots.len()];
        let (mut q1, mut q2) = (vec![0.0; 3 * n], vec![0.0; 3 * n]);
        imp.sys.product(&Threads::single(), m, &u, 0.3, &mut q1, &mut slots);
        assert_eq!(&q1[21..24], &[0.0; 3]);
        assert!(imp.sys.ground.list.iter().all(|&i| q1[3 * i as usize + 1] == 0.0));
        let two = Threads::new(2).unwrap();
        let blk1 = imp.sys.blocks.blk.clone();
        imp.sys.blocks.ready = false;
        imp.sys.prepare(&two, m);
        assert!(imp.sys.blocks.blk == blk1);
        imp.sys.product(&two, m, &u, 0.3, &mut q2, &mut slots);
        assert!(q2 == q1);
    }

    /// Every evaluation makes the blocks stale: after blocks summed at one state, an evaluation
    /// at another (the body moved and turned) gives products from the new pieces, not the old
    /// blocks (a stale matrix would only slow Newton down, so no physics test would see it),
    /// and blocks summed again agree with them.
    #[test]
    fn an_evaluation_makes_the_blocks_stale() {
        let mut p = Material { stiffness: 300.0, spring_damping: 0.5, rigidity: 0.05, ..Material::default() };
        p.set_nrt(2.0);
        let mut body = SoftBody::new(&icosphere(3, 1.0), 1.0, p.clone()).unwrap();
        let w = WorldSettings { integrator: Integrator::Implicit, ..WorldSettings::default() };
        let mut rnd = rng(7);
        let mut imp = evaluated(&body, &p, &w, false);
        imp.sys.prepare(&Threads::single(), &body.model);
        assert!(imp.sys.blocks.ready);
        for x in body.state.x.iter_mut() {
            *x *= 1.0 + 0.1 * rnd();
        }
        for v in body.state.v.iter_mut() {
            *v = 2.0 * rnd();
        }
        let m = &body.model;
        let n = m.mass.len();
        let fr = Frame { p: &p, w: &w, m, x: &body.state.x, v: &body.state.v, dt: 1.0 / 60.0, relax: crate::Relaxed::No };
        imp.vp.copy_from_slice(fr.v);
        imp.eval(&Threads::single(), &fr).unwrap();
        assert!(!imp.sys.blocks.ready, "an evaluation left the blocks ready");
        let u: Vec<f64> = (0..3 * n).map(|_| rnd()).collect();
        let mut slots = vec![[0.0; 4]; imp.cg.slots.len()];
        let (mut q, mut q_new) = (vec![0.0; 3 * n], vec![0.0; 3 * n]);
        imp.sys.product(&Threads::single(), m, &u, 0.0, &mut q, &mut slots);
        imp.sys.prepare(&Threads::single(), m);
        imp.sys.product(&Threads::single(), m, &u, 0.0, &mut q_new, &mut slots);
        let scale = q.iter().fold(0.0f64, |a, b| a.max(b.abs()));
        assert!(max_diff(&q, &q_new) <= 1e-12 * scale, "{:e} of {scale:e}", max_diff(&q, &q_new));
    }

    /// The mesh with its faces turned outward (a positive divergence-theorem volume).
    fn outward(positions: Vec<f64>, mut triangles: Vec<[u32; 3]>) -> TriMesh {
        let mesh = TriMesh { positions, triangles: triangles.clone() };
        if mesh.volume() < 0.0 {
            for t in triangles.iter_mut() {
                t.swap(1, 2);
            }
        }
        TriMesh { positions: mesh.positions, triangles }
    }

    /// The same on meshes unlike an icosphere's rows: a tetrahedron (every bending pair is also
    /// an edge: one block per pair of vertices, both terms in it), a double cone whose apexes
    /// have valence 24, an open plate (boundary edges without hinges, rows of valence 2–6; no
    /// gas), an icosphere — each with bending springs on and off and compressed springs' matrix
    /// clamped and by its absolute value, jittered to have stretched and compressed springs.
    #[test]
    fn the_block_product_holds_on_odd_meshes() {
        let tetra = outward(vec![1.0, 1.0, 1.0, 1.0, -1.0, -1.0, -1.0, 1.0, -1.0, -1.0, -1.0, 1.0], vec![[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]]);
        let ring = 24u32;
        let mut cone = vec![0.0, 1.0, 0.0, 0.0, -1.0, 0.0];
        let mut ct = Vec::new();
        for k in 0..ring {
            let a = std::f64::consts::TAU * k as f64 / ring as f64;
            cone.extend([a.cos(), 0.0, a.sin()]);
            let (v, u) = (2 + k, 2 + (k + 1) % ring);
            ct.push([0, u, v]);
            ct.push([1, v, u]);
        }
        let cone = outward(cone, ct);
        let side = 7u32;
        let mut plate = Vec::new();
        let mut pt = Vec::new();
        for r in 0..side {
            for c in 0..side {
                plate.extend([c as f64 * 0.1, 0.0, r as f64 * 0.1]);
            }
        }
        for r in 0..side - 1 {
            for c in 0..side - 1 {
                let v = r * side + c;
                pt.push([v, v + side, v + 1]);
                pt.push([v + 1, v + side, v + side + 1]);
            }
        }
        let plate = TriMesh { positions: plate, triangles: pt };
        let w = WorldSettings { integrator: Integrator::Implicit, gravity: 9.81, ..WorldSettings::default() };
        let mut rnd = rng(2024);
        for (name, mesh, gas) in [("tetrahedron", tetra, true), ("double cone", cone, true), ("open plate", plate, false), ("icosphere", icosphere(2, 1.0), true)] {
            for bending in [0.0, 50.0] {
                for absolute in [false, true] {
                    let mut p = Material { stiffness: 200.0, spring_damping: 0.3, bending_stiffness: bending, rigidity: 0.05, damping: 0.5, ..Material::default() };
                    p.set_nrt(if gas { 1.0 } else { 0.0 });
                    let mut body = SoftBody::new(&mesh, 1.0, p.clone()).unwrap();
                    let size = if gas { 1.0 } else { 0.6 };
                    for x in body.state.x.iter_mut() {
                        *x += 0.05 * size * rnd();
                    }
                    for v in body.state.v.iter_mut() {
                        *v = 0.3 * rnd();
                    }
                    let mut imp = evaluated(&body, &p, &w, absolute);
                    assert!(imp.sys.hinged, "{name}");
                    let (err, scale) = compare(&mut imp, &body.model, &mut rnd);
                    assert!(err <= 1e-13 * scale, "{name}, k_b {bending}, absolute {absolute}: max difference {err:e} of {scale:e}");
                }
            }
        }
    }
}
