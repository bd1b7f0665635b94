//! The conjugate gradient's preconditioner: one aggregation-multigrid V-cycle on A = M + dt D +
//! dt² K (`system.rs`), its coarse matrices built from the fine coefficients at the first
//! Newton iteration of every solve and again when the fine matrix changes its kind in it (the
//! ground releases vertices, compressed springs switch to the absolute value: `stale` in
//! `Implicit::newton`), or for a body nearly at rest kept from an earlier step (`keep.rs`). In
//! between the fine coefficients move with each Newton iterate and the coarse ones lag: the
//! preconditioner only has to be symmetric positive definite, not exact.
//!
//! **Why**: block Jacobi leaves every smooth error to the conjugate gradient, whose iterations
//! then grow with √(dt² k / m) and the resolution (142 per step at 40,962 vertices of the
//! standard workload). A V-cycle removes smooth error on coarser levels, so the iterations
//! stay ~flat in the resolution.
//!
//! **Levels** (`aggregate.rs`): level l + 1's nodes are aggregates of level l's. A coarse node
//! I has six unknowns, a translation t and a small rotation θ about its centre c_I (the mean of
//! its members' centres; a vertex's centre is its position): it moves member u by
//!
//!   u_u = t + θ × r_u,   r_u = c_u − c_I,   i.e. P_u = [I  −[r_u]×]   (3×6; 6×6 with the
//!   member's own rotation kept: [[I, −[r_u]×], [0, I]]).
//!
//! Translations alone (piecewise-constant prolongation) were measured first: the conjugate
//! gradient then still needed ~47 iterations per step at every resolution, whatever the
//! smoothing, aggregate size or cycle: a membrane's springs store nothing under a patch's rigid
//! rotation, and only the rigid modes make a coarse space for elasticity (Vaněk, Mandel &
//! Brezina 1996). The coarse matrix is the Galerkin product A_{l+1} = Pᵀ A_l P, 6×6 blocks
//!
//!   A_{l+1}[I, J] = Σ_{u ∈ I, w ∈ J} P_uᵀ A_l[u, w] P_w.
//!
//! On the finest level a spring block B = a I + b d dᵀ (see `system.rs`) between i ∈ I and
//! j ∈ J adds P_iᵀ B P_i to A[I, I] and −P_iᵀ B P_j to A[I, J] (from row i; row j the mirror),
//! with P_iᵀ B P_j = a P_iᵀ P_j + b w_i w_jᵀ, w_i = (d, r_i × d) and
//! P_iᵀ P_j = [[I, −[r_j]×], [[r_i]×, (r_i·r_j) I − r_j r_iᵀ]]. Left out of the coarse
//! matrices and of the cycle's own products: the gas's rank-one term γ g gᵀ (the conjugate
//! gradient, whose product has it, takes care of that one direction). A hinge's rank-one
//! c ∇θ ∇θᵀ adds c W_I W_Jᵀ to the blocks of its vertices' nodes, W_I = Σ_{q ∈ I} P_qᵀ ∇_q θ
//! (the sum per node first: a hinge on k nodes takes k(k + 1)/2 outer products, 3 for the
//! typical 2, instead of 16). Pinned vertices are no
//! part of the system: their springs count on the free end's diagonal only. Vertices the
//! ground holds have no y unknown (`ground.rs`): the fine matrix is F A F (F zeroes their y rows
//! and columns: the fine product zeroes the rows, and every vector it is given is 0 there), and a spring block touching one is F_i B F_j, added
//! as a general 3×3 block ([`add_general`]). Counting their y stiffness instead made the coarse
//! levels see a bottom stiffer than the cycle's fine level: measured on 10,242-vertex spheres
//! landing, 1.2–1.7× more iterations (cloth, clay, stiff rubber). A rotation a node
//! cannot feel (one vertex; an aggregate on a line) has a zero pivot: it is left out of that
//! node's solve (a pseudo-inverse), see [`cholesky`].
//!
//! **Cycle**: finest level, damped block Jacobi (ω = [`OMEGA`]) before and after the coarse
//! correction; coarse levels, a forward block Gauss–Seidel sweep before and a backward one
//! after (so the cycle is a symmetric positive definite operator, as the conjugate gradient
//! needs); the coarsest level (≤ [`COARSEST`] nodes) solved by a dense Cholesky factor. The
//! coarse matrices depend on the step's state only (kept ones on where they were assembled,
//! which is state: `keep.rs`), so a restored snapshot continues with the same bits. Coarse
//! levels run on the calling thread (a fixed order: the same bits for any thread count); the
//! finest level's passes are chunked like the
//! rest of the solver.

use super::aggregate::{Graph, Shape};
use super::system::{System, VCHUNK};
use super::super::Model;
use crate::par::{chunk, Out, Threads};

/// Vertices from which the V-cycle preconditions (below: block Jacobi). One cycle costs ~5
/// block-Jacobi iterations (two more fine products, the coarse levels), so it pays where block
/// Jacobi's iterations are many. Measured (BENCHMARKS.md, "Multigrid preconditioner" and "The
/// V-cycle where the modeler lands"), spheres landing with the modeler's materials: at 10,242
/// vertices 3.5–10× fewer iterations and 1.05–2.3× less time (the default material 2×; in
/// Chromium 1.8–3.3× closer to real time) except a collapsed cloth (1.2× more time); at 2,562,
/// the default material and clay faster, stiff rubber even, cloth 2× slower; at 40,962 the
/// default material even (72 Newton iterations per step there: the cycle's iterations cost what
/// they save), cloth 1.3× slower. The free-floating standard workload: 1.1–1.4× slower at
/// 10,242–40,962, 1.13–1.15× faster at 163,842. Bodies of 10,000–20,000 vertices, the modeler's
/// largest that can run near real time, decided it.
pub(crate) const MULTIGRID_FROM: usize = 8_000;
/// Vertices from which the V-cycle preconditions a body whose hinges are on (rigidity D > 0):
/// the hinges couple each vertex to its neighbours' neighbours, stiff and long-ranged, which
/// block Jacobi resolves slowly. Measured (BENCHMARKS.md, "A step that will not converge, found
/// out at once"), one thread, D = 0.05 J: the modeler's mushroom subdivided twice (5,762
/// vertices) grabbed and released, 1.7–2× less time (8× fewer CG iterations); the 2,562-vertex
/// sphere landing with each material preset 1.1–2.2× less time (clay at rest 0.9–1.0×); at 642
/// even. Without hinges the cycle did not pay there (cloth at 2,562: 1.5× slower; jelly at
/// 5,762: 1.4× slower), so `MULTIGRID_FROM` stays for them. The hierarchy is built from here
/// either way (the rigidity can change mid-run) and used where the hinges are on.
pub(crate) const HINGED_FROM: usize = 2_000;
/// Nodes of the coarsest level at most (solved densely: 6 n unknowns).
pub(crate) const COARSEST: usize = 24;
/// Levels below the finest at most.
const MAX_LEVELS: usize = 10;
/// Damping of the finest level's block Jacobi sweeps (λ_max(D⁻¹A) ≲ 2 on a triangle mesh's
/// spring matrix; 2/3 is the classic choice for smoothing).
const OMEGA: f64 = 0.7;
/// A pivot of the coarsest level's dense factor below this fraction of its diagonal is a mode
/// the level cannot feel (a rotation of a one-vertex node, …): solved as 0.
const PIVOT: f64 = 1e-10;
/// The same for the 6×6 diagonal block of a coarse node, which the Gauss–Seidel sweeps invert
/// while reading the off-diagonal blocks in single precision (`Level::af`: rounding u = 2⁻²⁴ ≈
/// 6e-8 of each entry). A mode the node barely feels (pivot ratio ρ) has an exactly tiny
/// coupling to its neighbours, which their rounded blocks replace by ~u of the entries: the
/// sweep multiplies that by ~1/ρ. Found on a stiff ball's contact patch (`ground.rs`): a node
/// of five held vertices (no y unknown, offsets' y ≈ 0 on the plane) and two released ones
/// feels its tilts about horizontal axes only through the two, pivot ratios 6.8e-8 and 2.6e-9
/// (kept at 1e-10): u/ρ ≈ 23, the cycle was no longer positive definite and every conjugate
/// gradient after that assembly ran to its cap of `LINEAR_MAX` (the stiff rubber preset at
/// 10,242 vertices landing: 64,598 iterations in one step). At 1e-5 the amplification is at
/// most 0.6 %, and dropping a mode felt at 1e-5 of its diagonal costs the preconditioner
/// nothing measurable (BENCHMARKS.md: the other presets' landings take the same iterations;
/// 1e-6 measured alike).
const BLOCK_PIVOT: f64 = 1e-5;
/// Gauss–Seidel sweeps before and after the coarse correction on levels 2 and below (level 1,
/// the largest coarse level, gets one): measured at 40,962 vertices, 1 → 3 sweeps there took
/// the conjugate gradient from 37 to 30 iterations per step for little cost.
const COARSE_SWEEPS: usize = 3;

/// A 6×6 block, row-major.
type Blk = [f64; 36];

/// y = B x (6).
#[inline(always)]
fn mul6(b: &Blk, x: &[f64; 6]) -> [f64; 6] {
    let mut y = [0.0; 6];
    for p in 0..6 {
        let row = &b[6 * p..6 * p + 6];
        y[p] = row[0] * x[0] + row[1] * x[1] + row[2] * x[2] + row[3] * x[3] + row[4] * x[4] + row[5] * x[5];
    }
    y
}

/// y = B x (6), B in single precision.
#[inline(always)]
fn mul6f(b: &[f32; 36], x: &[f64; 6]) -> [f64; 6] {
    let mut y = [0.0; 6];
    for p in 0..6 {
        let mut s = 0.0;
        for q in 0..6 {
            s += b[6 * p + q] as f64 * x[q];
        }
        y[p] = s;
    }
    y
}

#[inline(always)]
fn cross(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

/// [r]× (3×3, row-major): [r]× v = r × v.
#[inline(always)]
fn skew(r: &[f64; 3]) -> [[f64; 3]; 3] {
    [[0.0, -r[2], r[1]], [r[2], 0.0, -r[0]], [-r[1], r[0], 0.0]]
}

/// blk += s (a P_iᵀ P_j + b w_i w_jᵀ) for a spring (a, b, d) seen from offsets r_i, r_j.
#[inline(always)]
fn add_spring(blk: &mut Blk, s: f64, a: f64, b: f64, d: &[f64; 3], ri: &[f64; 3], rj: &[f64; 3]) {
    let (wi, wj) = (cross(ri, d), cross(rj, d));
    let vi = [d[0], d[1], d[2], wi[0], wi[1], wi[2]];
    let vj = [d[0], d[1], d[2], wj[0], wj[1], wj[2]];
    let sb = s * b;
    for p in 0..6 {
        for q in 0..6 {
            blk[6 * p + q] += sb * vi[p] * vj[q];
        }
    }
    if a != 0.0 {
        add_ptp(blk, s * a, ri, rj);
    }
}

/// blk += s P_iᵀ P_j.
#[inline(always)]
fn add_ptp(blk: &mut Blk, s: f64, ri: &[f64; 3], rj: &[f64; 3]) {
    let (si, sj) = (skew(ri), skew(rj));
    let rr = ri[0] * rj[0] + ri[1] * rj[1] + ri[2] * rj[2];
    for p in 0..3 {
        blk[6 * p + p] += s;
        for q in 0..3 {
            blk[6 * p + 3 + q] -= s * sj[p][q];
            blk[6 * (3 + p) + q] += s * si[p][q];
            blk[6 * (3 + p) + 3 + q] += s * ((if p == q { rr } else { 0.0 }) - rj[p] * ri[q]);
        }
    }
}

/// A spring's 3×3 block B = a I + b d dᵀ (`system.rs`).
#[inline(always)]
fn spring_block(a: f64, b: f64, d: &[f64; 3]) -> [[f64; 3]; 3] {
    std::array::from_fn(|p| std::array::from_fn(|q| b * d[p] * d[q] + if p == q { a } else { 0.0 }))
}

/// F_i S F_j: the y row zeroed where `row` (vertex i held by the ground), the y column where
/// `col` (vertex j held).
#[inline(always)]
fn without_y(mut sm: [[f64; 3]; 3], row: bool, col: bool) -> [[f64; 3]; 3] {
    if row {
        sm[1] = [0.0; 3];
    }
    if col {
        for r in sm.iter_mut() {
            r[1] = 0.0;
        }
    }
    sm
}

/// blk += s P_iᵀ S P_j for a general 3×3 S: [[S, −S R_j], [R_i S, −R_i S R_j]], R = [r]×.
fn add_general(blk: &mut Blk, s: f64, sm: &[[f64; 3]; 3], ri: &[f64; 3], rj: &[f64; 3]) {
    let (ri, rj) = (skew(ri), skew(rj));
    let mm = |x: &[[f64; 3]; 3], y: &[[f64; 3]; 3]| {
        let mut z = [[0.0; 3]; 3];
        for p in 0..3 {
            for q in 0..3 {
                z[p][q] = x[p][0] * y[0][q] + x[p][1] * y[1][q] + x[p][2] * y[2][q];
            }
        }
        z
    };
    let (sr, rs) = (mm(sm, &rj), mm(&ri, sm));
    let rsr = mm(&rs, &rj);
    for p in 0..3 {
        for q in 0..3 {
            blk[6 * p + q] += s * sm[p][q];
            blk[6 * p + 3 + q] -= s * sr[p][q];
            blk[6 * (3 + p) + q] += s * rs[p][q];
            blk[6 * (3 + p) + 3 + q] -= s * rsr[p][q];
        }
    }
}

/// blk += P_iᵀ S P_i for a symmetric 3×3 S: [[S, −S R], [R S, −R S R]], R = [r_i]×.
fn add_sandwich(blk: &mut Blk, sm: &[[f64; 3]; 3], r: &[f64; 3]) {
    add_general(blk, 1.0, sm, r, r);
}

/// blk += P_uᵀ A P_w, P = [[I, −[r]×], [0, I]] (coarse to coarser).
fn add_galerkin(blk: &mut Blk, a: &Blk, ru: &[f64; 3], rw: &[f64; 3]) {
    // X = A P_w: columns 0..3 as A's; columns 3..6: A[:, 3..6] − A[:, 0..3] [r_w]×.
    let sw = skew(rw);
    let mut x = *a;
    for p in 0..6 {
        for q in 0..3 {
            let mut s = 0.0;
            for k in 0..3 {
                s += a[6 * p + k] * sw[k][q];
            }
            x[6 * p + 3 + q] -= s;
        }
    }
    // Pᵀ X: rows 0..3 as X's; rows 3..6: X[3..6, :] + [r_u]× X[0..3, :].
    let su = skew(ru);
    for p in 0..3 {
        for q in 0..6 {
            let mut s = x[6 * (3 + p) + q];
            for k in 0..3 {
                s += su[p][k] * x[6 * k + q];
            }
            blk[6 * (3 + p) + q] += s;
            blk[6 * p + q] += x[6 * p + q];
        }
    }
}

/// In-place Cholesky factor (lower triangle) of the symmetric positive semi-definite n×n
/// matrix `l` (row-major). A pivot at most `pivot` times its diagonal ([`PIVOT`],
/// [`BLOCK_PIVOT`]) is an unknown the matrix does not see: it is marked in `drop` and solved as
/// 0 (a pseudo-inverse on the rest).
fn cholesky(l: &mut [f64], n: usize, drop: &mut [bool], pivot: f64) {
    for k in 0..n {
        let diag = l[k * n + k];
        let mut d = diag;
        for q in 0..k {
            d -= l[k * n + q] * l[k * n + q];
        }
        drop[k] = !(d > pivot * diag.abs() && d.is_finite());
        let d = if drop[k] { 0.0 } else { d.sqrt() };
        l[k * n + k] = if drop[k] { 1.0 } else { d };
        for r in k + 1..n {
            if drop[k] {
                l[r * n + k] = 0.0;
                continue;
            }
            let mut s = l[r * n + k];
            for q in 0..k {
                s -= l[r * n + q] * l[k * n + q];
            }
            l[r * n + k] = s / d;
        }
    }
}

/// x = (L Lᵀ)⁺ b with a factor from [`cholesky`].
fn cholesky_solve(l: &[f64], n: usize, drop: &[bool], b: &[f64], x: &mut [f64]) {
    for r in 0..n {
        let mut s = b[r];
        for q in 0..r {
            s -= l[r * n + q] * x[q];
        }
        x[r] = if drop[r] { 0.0 } else { s / l[r * n + r] };
    }
    for r in (0..n).rev() {
        let mut s = x[r];
        for q in r + 1..n {
            s -= l[q * n + r] * x[q];
        }
        x[r] = if drop[r] { 0.0 } else { s / l[r * n + r] };
    }
}

/// One coarse level: topology, matrix, geometry and vectors (6 per node).
#[derive(Debug, Clone, Default)]
struct Level {
    s: Shape,
    a: Vec<Blk>,
    /// `a` in single precision, as the sweeps read it (half the memory traffic; the cycle is
    /// a preconditioner, any symmetric positive definite approximation serves).
    af: Vec<[f32; 36]>,
    dinv: Vec<Blk>,
    /// Centre of each node.
    c: Vec<[f64; 3]>,
    /// Per node of the level above: its centre minus its parent's centre here.
    off: Vec<[f64; 3]>,
    b: Vec<[f64; 6]>,
    x: Vec<[f64; 6]>,
    r: Vec<[f64; 6]>,
}

/// The hierarchy below the finest level (empty for bodies of ≤ [`COARSEST`] vertices: block
/// Jacobi alone), the coarsest level's dense factor, and the finest level's scratch.
#[derive(Debug, Clone, Default)]
pub(crate) struct Multigrid {
    levels: Vec<Level>,
    /// Vertices from which the cycle is used without hinges (`HINGED_FROM`); 0 in `new`.
    pub unhinged_from: usize,
    /// Per hinge, its level-1 nodes and their blocks, found on the first assembly with hinges
    /// (from the mesh alone).
    hpos: Vec<HingeNodes>,
    chol: Vec<f64>,
    drop: Vec<bool>,
    t: Vec<f64>,
}

/// A fine vertex is an unknown of the system (a pinned one is not).
fn free(m: &Model, i: usize) -> bool {
    m.inv_mass[i] != 0.0
}

/// The ground's held vertices have no y unknown (`ground.rs`): the cycle's fine level is
/// F A F (F zeroes their y rows and columns), and so are the coarse ones.
fn held(sys: &System, i: usize) -> bool {
    sys.ground.active() && sys.ground.held[i]
}

impl Level {
    /// Level 1: centres, offsets, then the springs' CSR entries row by row.
    fn add_springs(&mut self, sys: &System, m: &Model, x: &[f64]) {
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

    /// The hinges' rank-one blocks c ∇θ ∇θᵀ (`system.rs`): with w_q = P_qᵀ ∇_q θ = (g_q, r_q × g_q)
    /// (g_q's y zeroed where the ground holds the vertex; a pinned vertex is no unknown),
    /// Pᵀ (c ∇θ ∇θᵀ) P = c W Wᵀ with W_I = Σ_{q ∈ I} w_q summed per node first: block
    /// (I, J) gets c W_I W_Jᵀ, (J, I) its transpose (a hinge spans 1–4 nodes, ~2 on average:
    /// k(k + 1)/2 outer products for k nodes instead of the 16 vertex pairs'). Every pair of a hinge's vertices
    /// is an edge or its bending pair, so the level's sparsity has the block already.
    /// Without them the coarse levels did not see bending: at 10,242 vertices with the
    /// modeler's D = 0.05 J the conjugate gradient took 6× the iterations (BENCHMARKS.md).
    fn add_hinges(&mut self, sys: &System, m: &Model, hpos: &[HingeNodes]) {
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
    fn invert_diagonal(&mut self) {
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
fn spring_row(sys: &System, m: &Model, s: &Shape, off: &[[f64; 3]], a: &mut [Blk], i: usize, dpos: usize) {
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
fn hinge_node_weights(sys: &System, m: &Model, off: &[[f64; 3]], h: usize, hn: &HingeNodes, cs: f64) -> [[f64; 6]; 4] {
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
fn add_hinge_outer(blocks: &mut [Blk], hn: &HingeNodes, w: &[[f64; 6]; 4]) {
    let k = hn.nodes as usize;
    for a in 0..k {
        for b in a..k {
            let (ab, ba) = (hn.at[4 * a + b], hn.at[4 * b + a]);
            if ab == super::aggregate::NONE {
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
fn galerkin(first: &Level, rest: &mut [Level]) {
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

impl Multigrid {
    /// The hierarchy of a body of n vertices, used when n ≥ `from` (else block Jacobi alone).
    pub fn new(sys: &System, n: usize, from: usize) -> Self {
        let mut levels: Vec<Level> = Vec::new();
        if n > COARSEST && n >= from {
            let fine = [Graph::from(&sys.edges), Graph::from(&sys.bends)];
            let mut s = Shape::coarsen(n, fine[0], &fine, true);
            loop {
                let above = levels.last().map_or(n, |l| l.s.n);
                let done = s.n <= COARSEST || 10 * s.n > 9 * above || levels.len() + 1 >= MAX_LEVELS;
                let nn = s.n;
                let next = if done { None } else { Some(Shape::coarsen(nn, s.graph(), &[s.graph()], true)) };
                let nnz = s.col.len();
                let v = vec![[0.0; 6]; nn];
                levels.push(Level { s, a: vec![[0.0; 36]; nnz], af: vec![[0.0; 36]; nnz], dinv: vec![[0.0; 36]; nn], c: vec![[0.0; 3]; nn], off: vec![[0.0; 3]; above], b: v.clone(), x: v.clone(), r: v });
                match next {
                    Some(ns) => s = ns,
                    None => break,
                }
            }
        }
        let nc = levels.last().map_or(0, |l| 6 * l.s.n);
        Multigrid { levels, unhinged_from: 0, hpos: Vec::new(), chol: vec![0.0; nc * nc], drop: vec![false; nc], t: vec![0.0; 3 * n] }
    }

    /// Coarse matrices from the system's current coefficients (after `System::eval`) and the
    /// positions `x` (flat xyz) they were taken at: level 1 from the fine springs and hinges,
    /// each level below by the Galerkin product, then every node's diagonal inverse and the
    /// coarsest level's dense factor.
    pub fn assemble(&mut self, sys: &System, m: &Model, x: &[f64]) {
        if !self.cycles(sys, m.mass.len()) {
            return;
        }
        if sys.hinged && self.hpos.len() != m.hinges.v.len() {
            if let Some(first) = self.levels.first() {
                self.hpos = hinge_blocks(&first.s, m);
            }
        }
        let Multigrid { levels, hpos, .. } = self;
        let Some((first, rest)) = levels.split_first_mut() else { return };
        first.add_springs(sys, m, x);
        if sys.hinged {
            first.add_hinges(sys, m, hpos);
        }
        galerkin(first, rest);
        for lv in self.levels.iter_mut() {
            lv.invert_diagonal();
        }
        self.factor();
    }

    /// Dense factor of the coarsest matrix.
    fn factor(&mut self) {
        let lv = self.levels.last().expect("a level");
        let n = 6 * lv.s.n;
        let l = &mut self.chol;
        l.fill(0.0);
        for c in 0..lv.s.n {
            for e in lv.s.start[c] as usize..lv.s.start[c + 1] as usize {
                let j = lv.s.col[e] as usize;
                for p in 0..6 {
                    for q in 0..6 {
                        l[(6 * c + p) * n + 6 * j + q] = lv.a[e][6 * p + q];
                    }
                }
            }
        }
        cholesky(l, n, &mut self.drop, PIVOT);
    }

    /// r = b − A x on a coarse level (`skip_diagonal`: without the diagonal block, for the
    /// Gauss–Seidel update) for node c.
    #[inline(always)]
    fn row(lv: &Level, c: usize, skip_diagonal: bool) -> [f64; 6] {
        let s = &lv.s;
        let mut r = lv.b[c];
        let (e0, e1) = (s.start[c] as usize + skip_diagonal as usize, s.start[c + 1] as usize);
        for (a, &j) in lv.af[e0..e1].iter().zip(&s.col[e0..e1]) {
            let q = mul6f(a, &lv.x[j as usize]);
            for d in 0..6 {
                r[d] -= q[d];
            }
        }
        r
    }

    /// One block Gauss–Seidel sweep on x, forward or backward; on x86-64 with AVX2 the same
    /// code compiled a second time for it (no FMA contraction: the same bits), as
    /// `System::product_rows`.
    fn sweep(lv: &mut Level, forward: bool) {
        #[cfg(target_arch = "x86_64")]
        {
            if std::arch::is_x86_feature_detected!("avx2") {
                // SAFETY: the CPU supports the feature the function is compiled for.
                return unsafe { Self::sweep_avx2(lv, forward) };
            }
        }
        Self::sweep_plain(lv, forward)
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn sweep_avx2(lv: &mut Level, forward: bool) {
        Self::sweep_plain(lv, forward)
    }

    /// r = b − A x on every node of a coarse level (dispatched as [`Self::sweep`]).
    fn residual(lv: &mut Level) {
        #[cfg(target_arch = "x86_64")]
        {
            if std::arch::is_x86_feature_detected!("avx2") {
                // SAFETY: the CPU supports the feature the function is compiled for.
                return unsafe { Self::residual_avx2(lv) };
            }
        }
        Self::residual_plain(lv)
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn residual_avx2(lv: &mut Level) {
        Self::residual_plain(lv)
    }

    #[inline(always)]
    fn residual_plain(lv: &mut Level) {
        for c in 0..lv.s.n {
            lv.r[c] = Self::row(lv, c, false);
        }
    }

    #[inline(always)]
    fn sweep_plain(lv: &mut Level, forward: bool) {
        let n = lv.s.n;
        for k in 0..n {
            let c = if forward { k } else { n - 1 - k };
            let r = Self::row(lv, c, true);
            lv.x[c] = mul6(&lv.dinv[c], &r);
        }
    }

    /// V-cycle from coarse level `levels[0]` down: x ≈ A⁻¹ b.
    fn cycle(levels: &mut [Level], chol: &[f64], drop: &[bool], depth: usize) {
        let (lv, below) = levels.split_first_mut().expect("a level");
        if below.is_empty() {
            cholesky_solve(chol, 6 * lv.s.n, drop, lv.b.as_flattened(), lv.x.as_flattened_mut());
            return;
        }
        lv.x.fill([0.0; 6]);
        let nu = if depth == 0 { 1 } else { COARSE_SWEEPS };
        for _ in 0..nu {
            Self::sweep(lv, true);
        }
        Self::residual(lv);
        // Restrict: B_C = Σ_u P_uᵀ r_u = Σ (t_u, θ_u + r_u × t_u).
        let nb = &mut below[0];
        for c in 0..nb.s.n {
            let mut acc = [0.0; 6];
            for &u in &nb.s.member[nb.s.mstart[c] as usize..nb.s.mstart[c + 1] as usize] {
                let u = u as usize;
                let ru = &lv.r[u];
                let w = cross(&nb.off[u], &[ru[0], ru[1], ru[2]]);
                for d in 0..3 {
                    acc[d] += ru[d];
                    acc[3 + d] += ru[3 + d] + w[d];
                }
            }
            nb.b[c] = acc;
        }
        Self::cycle(below, chol, drop, depth + 1);
        // Prolong: x_u += (T + Θ × r_u, Θ).
        let nb = &below[0];
        for (u, &p) in nb.s.parent.iter().enumerate() {
            let xp = &nb.x[p as usize];
            let w = cross(&[xp[3], xp[4], xp[5]], &nb.off[u]);
            for d in 0..3 {
                lv.x[u][d] += xp[d] + w[d];
                lv.x[u][3 + d] += xp[3 + d];
            }
        }
        for _ in 0..nu {
            Self::sweep(lv, false);
        }
    }

    /// Whether the V-cycle preconditions this body of `n` vertices now (its hinges on or off:
    /// [`HINGED_FROM`]).
    pub(crate) fn cycles(&self, sys: &System, n: usize) -> bool {
        !self.levels.is_empty() && (sys.hinged || n >= self.unhinged_from)
    }

    /// z = B res, B the V-cycle (block Jacobi alone when there are no coarse levels); returns
    /// res · z. `slots`: one reduction slot per vertex chunk.
    pub fn apply(&mut self, th: &Threads, sys: &System, m: &Model, res: &[f64], z: &mut [f64], slots: &mut [[f64; 4]]) -> f64 {
        let n = m.mass.len();
        if !self.cycles(sys, n) {
            return jacobi(th, sys, n, 1.0, res, None, z, slots);
        }
        let Multigrid { levels, chol, drop, t, .. } = self;
        // Pre-smoothing from 0: z = ω P res; then t = res − A z, restricted: (Σ t_i, Σ r_i × t_i).
        jacobi(th, sys, n, OMEGA, res, None, z, slots);
        sys.residual(th, m, z, res, t, slots);
        let l1 = &mut levels[0];
        for c in 0..l1.s.n {
            let mut acc = [0.0; 6];
            for &i in &l1.s.member[l1.s.mstart[c] as usize..l1.s.mstart[c + 1] as usize] {
                let i = i as usize;
                let ti = [t[3 * i], t[3 * i + 1], t[3 * i + 2]];
                let w = cross(&l1.off[i], &ti);
                for d in 0..3 {
                    acc[d] += ti[d];
                    acc[3 + d] += w[d];
                }
            }
            l1.b[c] = acc;
        }
        Self::cycle(levels, chol, drop, 0);
        // z += P x₁ (0 on pinned vertices), then post-smoothing on t = res − A z.
        let l1 = &levels[0];
        {
            let zo = Out::new(z);
            th.each(slots, |c, _| {
                let vr = chunk(c, VCHUNK, n);
                // SAFETY: chunk c writes vertices vr only.
                let z = unsafe { zo.range(3 * vr.start..3 * vr.end) };
                for (li, i) in vr.enumerate() {
                    if m.inv_mass[i] != 0.0 {
                        let xp = &l1.x[l1.s.parent[i] as usize];
                        let w = cross(&[xp[3], xp[4], xp[5]], &l1.off[i]);
                        for d in 0..3 {
                            z[3 * li + d] += xp[d] + w[d];
                        }
                    }
                }
            });
        }
        // The coarse correction moves ground-held components too: take them out (`ground.rs`),
        // so that the cycle stays symmetric on the free components.
        sys.ground.filter(z);
        sys.residual(th, m, z, res, t, slots);
        jacobi(th, sys, n, OMEGA, t, Some(res), z, slots)
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
struct HingeNodes {
    slot: [u8; 4],
    nodes: u8,
    at: [u32; 16],
}

fn hinge_blocks(s: &Shape, m: &Model) -> Vec<HingeNodes> {
    use super::aggregate::NONE;
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
fn centres(s: &Shape, pos: impl Fn(usize) -> [f64; 3], c: &mut [[f64; 3]], off: &mut [[f64; 3]]) {
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

/// Block Jacobi on the finest level: z = ω P t, or z += ω P t when `res` is given (then the
/// post-smoothing, and the returned value is res · z; else t · z).
#[allow(clippy::too_many_arguments)]
fn jacobi(th: &Threads, sys: &System, n: usize, omega: f64, t: &[f64], res: Option<&[f64]>, z: &mut [f64], slots: &mut [[f64; 4]]) -> f64 {
    let zo = Out::new(z);
    th.each(slots, |c, slot| {
        let vr = chunk(c, VCHUNK, n);
        // SAFETY: chunk c writes vertices vr only.
        let z = unsafe { zo.range(3 * vr.start..3 * vr.end) };
        let mut acc = 0.0;
        for (li, i) in vr.enumerate() {
            let ti = [t[3 * i], t[3 * i + 1], t[3 * i + 2]];
            let y = sys.precondition(i, &ti);
            for d in 0..3 {
                let zi = if res.is_some() { z[3 * li + d] + omega * y[d] } else { omega * y[d] };
                z[3 * li + d] = zi;
                acc += res.map_or(ti[d], |r| r[3 * i + d]) * zi;
            }
        }
        slot[0] = acc;
    });
    slots.iter().map(|s| s[0]).sum()
}

#[cfg(test)]
mod tests {
    use super::super::Implicit;
    use super::*;
    use crate::body::{Material, SoftBody};
    use crate::mesh::builtin::icosphere;
    use crate::world::{Ground, Integrator, WorldSettings};
    use super::super::system::Frame;

    /// One tight implicit step of a swirled, inflated sphere (2,562 vertices in two chunks of the
    /// vertex passes, the standard workload's ω dt ≈ 27 per spring, far
    /// outside explicit stability), once preconditioned by the V-cycle and once by block Jacobi.
    /// Both solve the same backward-Euler equations to ‖r‖_{M⁻¹} ≤ 1e-12 ‖r_0‖_{M⁻¹}; with
    /// A ⪰ M the velocity error of each is ≤ ‖r‖_{M⁻¹}/√m ≈ 1e-12 ‖r_0‖_{M⁻¹}/√m, ~1e-10 of the
    /// velocities here: they must agree to 1e-8 relative. And the V-cycle must need fewer
    /// conjugate-gradient iterations (that is its point).
    #[test]
    fn the_multigrid_preconditioner_reaches_the_same_step_in_fewer_iterations() {
        let mut p = Material { stiffness: 1000.0, spring_damping: 1.0, ..Material::default() };
        p.set_nrt(2.0);
        let mut body = SoftBody::new(&icosphere(4, 1.0), 1.0, p.clone()).unwrap();
        let n = body.model.mass.len();
        for i in 0..n {
            let x = &body.state.x[3 * i..3 * i + 3];
            let (vx, vy, vz) = (-x[1], x[0] + 0.3 * x[2], 0.5 * x[0] * x[1]);
            body.state.v[3 * i..3 * i + 3].copy_from_slice(&[vx, vy, vz]);
        }
        let w = WorldSettings { integrator: Integrator::Implicit, tolerance: 1e-12, gravity: 9.81, ..WorldSettings::default() };
        let run = |from: usize, th: &Threads| {
            let mut s = body.state.clone();
            let mut imp = Implicit::new(&body.model);
            imp.mg = Multigrid::new(&imp.sys, n, from);
            assert_eq!(imp.mg.levels.is_empty(), from > n);
            let it = imp.step(th, &p, &w, &body.model, &mut s, 1.0 / 60.0).unwrap();
            (s.v, it.linear)
        };
        let one = Threads::single();
        let (vm, itm) = run(0, &one);
        let (vj, itj) = run(usize::MAX, &one);
        // The cycle's coarse levels run on the calling thread and its fine passes in fixed
        // chunks: two threads give the same bits.
        assert_eq!(run(0, &Threads::new(2).unwrap()).0, vm);
        let scale = vj.iter().fold(0.0f64, |a, b| a.max(b.abs()));
        let err = vm.iter().zip(&vj).fold(0.0f64, |a, (x, y)| a.max((x - y).abs()));
        assert!(err <= 1e-8 * scale, "max |Δv| = {err:e} of {scale}");
        assert!(2 * itm < itj, "V-cycle {itm} vs block Jacobi {itj} CG iterations");
    }

    /// The implicit scratch of `body` with the V-cycle at any size, its system evaluated at
    /// v⁺ = v (the ground's held vertices from the state, their v⁺_y prescribed) with dt = 1/60 s
    /// and the coarse levels assembled from it.
    fn assembled(body: &SoftBody, p: &Material, w: &WorldSettings) -> Implicit {
        let m = &body.model;
        let mut imp = Implicit::new(m);
        imp.mg = Multigrid::new(&imp.sys, m.mass.len(), 0);
        let fr = Frame { p, w, m, x: &body.state.x, v: &body.state.v, dt: 1.0 / 60.0, relax: crate::Relaxed::No };
        imp.sys.ground.find(m, w.ground.as_ref(), fr.x, fr.v, fr.dt);
        imp.vp.copy_from_slice(fr.v);
        imp.sys.ground.prescribe(&mut imp.vp);
        imp.eval(&Threads::single(), &fr).unwrap();
        imp.mg.assemble(&imp.sys, m, &imp.xt);
        imp
    }

    /// The coarse matrix is the Galerkin product of the fine one the cycle works on: for any
    /// coarse vector x₁ (six unknowns per node of level 1), A₁ x₁ = Pᵀ F A F P x₁, F zeroing
    /// the ground-held vertices' y components (the fine product's rows and the cycle's vectors
    /// are 0 there, `ground.rs`). On a jittered sphere (compressed and stretched springs,
    /// bending springs, bent hinges, damping, one pinned vertex) whose bottom rests on the ground. Both sides
    /// sum the same products of the same coefficients in other orders: they agree to rounding,
    /// ~1e-15 of the largest term per entry times the ~100 terms an entry sums; 1e-11 of
    /// max |A₁ x₁| leaves room for that. A coarse matrix that counts the held vertices' y
    /// stiffness misses by O(1) of it on the bottom's nodes.
    #[test]
    fn the_coarse_matrix_is_the_galerkin_product_of_the_fine_one_with_the_ground_holding_vertices() {
        let mut p = Material { stiffness: 300.0, spring_damping: 0.5, bending_stiffness: 50.0, rigidity: 0.05, ..Material::default() };
        p.set_nrt(2.0);
        let mut body = SoftBody::new(&icosphere(3, 1.0), 1.0, p.clone()).unwrap();
        let n = body.model.mass.len();
        let mut seed = 12345u64;
        let mut rnd = move || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        for x in body.state.x.iter_mut() {
            *x += 0.02 * rnd();
        }
        for v in body.state.v.iter_mut() {
            *v = 0.1 * rnd();
        }
        body.set_pinned(7, true).unwrap();
        let w = WorldSettings { integrator: Integrator::Implicit, gravity: 9.81, ground: Some(Ground::at(-0.85)), ..WorldSettings::default() };
        let th = Threads::single();
        let imp = assembled(&body, &p, &w);
        let m = &body.model;
        assert!(imp.sys.ground.list.len() >= 10, "{} held", imp.sys.ground.list.len());
        let l1 = &imp.mg.levels[0];
        let mut slots = vec![[0.0; 4]; imp.cg.slots.len()];
        for _ in 0..3 {
            let x1: Vec<[f64; 6]> = (0..l1.s.n).map(|_| std::array::from_fn(|_| rnd())).collect();
            // u = F P x₁ on the free vertices; q = A u.
            let mut u = vec![0.0; 3 * n];
            for i in 0..n {
                if m.inv_mass[i] != 0.0 {
                    let xp = &x1[l1.s.parent[i] as usize];
                    let wv = cross(&[xp[3], xp[4], xp[5]], &l1.off[i]);
                    for d in 0..3 {
                        u[3 * i + d] = xp[d] + wv[d];
                    }
                }
            }
            imp.sys.ground.filter(&mut u);
            let mut q = vec![0.0; 3 * n];
            imp.sys.product(&th, m, &u, 0.0, &mut q, &mut slots);
            // Pᵀ q against A₁ x₁.
            let mut ptq = vec![[0.0; 6]; l1.s.n];
            for i in 0..n {
                let qi = [q[3 * i], q[3 * i + 1], q[3 * i + 2]];
                let wv = cross(&l1.off[i], &qi);
                let acc = &mut ptq[l1.s.parent[i] as usize];
                for d in 0..3 {
                    acc[d] += qi[d];
                    acc[3 + d] += wv[d];
                }
            }
            let mut scale = 0.0f64;
            let mut err = 0.0f64;
            for c in 0..l1.s.n {
                let mut y = [0.0; 6];
                for e in l1.s.start[c] as usize..l1.s.start[c + 1] as usize {
                    let t = mul6(&l1.a[e], &x1[l1.s.col[e] as usize]);
                    for d in 0..6 {
                        y[d] += t[d];
                    }
                }
                for d in 0..6 {
                    scale = scale.max(y[d].abs());
                    err = err.max((y[d] - ptq[c][d]).abs());
                }
            }
            assert!(err <= 1e-11 * scale, "max |A₁x₁ − PᵀFAFPx₁| = {err:e} of {scale:e}");
        }
    }

    /// The coarse sweeps and residuals dispatched at run time (AVX2 where the CPU has it) give
    /// the same bits as the plain code: the second compilation only widens the encoding (no FMA
    /// contraction, no reordered sums), so any difference at all is a fault. Forward and backward
    /// sweeps then a residual, on every coarse level of an assembled 2,562-vertex hierarchy.
    #[test]
    fn the_dispatched_coarse_sweeps_give_the_same_bits_as_the_plain_ones() {
        let mut p = Material { stiffness: 1000.0, spring_damping: 1.0, bending_stiffness: 100.0, ..Material::default() };
        p.set_nrt(2.0);
        let body = SoftBody::new(&icosphere(4, 1.0), 1.0, p.clone()).unwrap();
        let w = WorldSettings { integrator: Integrator::Implicit, ..WorldSettings::default() };
        let mut imp = assembled(&body, &p, &w);
        assert!(imp.mg.levels.len() >= 2);
        for (l, lv) in imp.mg.levels.iter_mut().enumerate() {
            for (c, b) in lv.b.iter_mut().enumerate() {
                *b = std::array::from_fn(|d| ((7 * c + 3 * d + l) % 11) as f64 - 5.0);
            }
            lv.x.fill([0.0; 6]);
            let mut plain = lv.clone();
            for forward in [true, false] {
                Multigrid::sweep(lv, forward);
                Multigrid::sweep_plain(&mut plain, forward);
            }
            Multigrid::residual(lv);
            Multigrid::residual_plain(&mut plain);
            let bits = |v: &[[f64; 6]]| v.iter().flatten().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&lv.x), bits(&plain.x), "level {l}: sweeps differ");
            assert_eq!(bits(&lv.r), bits(&plain.r), "level {l}: residuals differ");
        }
    }
}
