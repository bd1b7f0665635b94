//! The conjugate gradient's preconditioner: one aggregation-multigrid V-cycle on A = M + dt D +
//! dt² K (`system/`), its coarse matrices built from the fine coefficients at the first
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
//! On the finest level a spring block B = a I + b d dᵀ (see `system/`) between i ∈ I and
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

mod assemble;
mod dense;
#[cfg(test)]
mod tests;

use assemble::{galerkin, hinge_blocks, HingeNodes};
use dense::*;

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
