//! The preconditioned conjugate gradient on A δ = −r (A = M + dt D + dt² K, symmetric positive
//! definite after the projections of `system/`). Preconditioner (`multigrid/`): the inverse
//! of each vertex's 3×3 diagonal block (block Jacobi), or on large bodies an aggregation
//! multigrid V-cycle. A is applied row by row (`System::product`): matrix-free from the
//! evaluation's pieces, or from 3×3 blocks summed once a hinged body's solve runs long
//! ([`BLOCKS_AFTER`]).
//!
//! It stops when the mass-weighted norm of its residual ‖b − A δ‖_{M⁻¹} (with
//! ‖y‖²_{M⁻¹} = Σ_i |y_i|² / m_i) is at most η ‖b‖_{M⁻¹} — the Newton loop chooses η — or after
//! [`LINEAR_MAX`] iterations (Newton then goes on from the partial solution).

use super::multigrid::Multigrid;
use super::system::{System, VCHUNK};
use super::super::Model;
use crate::par::{chunk, Out, Threads};

/// Most conjugate-gradient iterations per Newton iteration.
pub(crate) const LINEAR_MAX: u32 = 2000;
/// Fine products (`System::product`, and the V-cycle's two residuals per iteration) of a
/// solve after which a hinged body's products take the matrix's blocks (`blocks.rs`), and the
/// Newton loop asks for them from the start of the next solve when its last one ran that
/// long. A rent-or-buy rule: summing the blocks costs ~6 products from the pieces (~15 block
/// products; measured at 10,242 vertices) and each block product saves ~0.6 of one, so the
/// blocks are summed once the pieces' products have cost about as much as summing them —
/// after 4 iterations with the V-cycle (3 products each, and 2 before the first), 12 with block
/// Jacobi (1 each: hinged bodies below `multigrid::HINGED_FROM`). (9, summing them from the
/// fourth V-cycle iteration, measured the same; with it, the presets test's balloon on the
/// twice-subdivided octopus met a step at t = 0.717 s that did not converge in 100 Newton
/// iterations — a step on the edge, which main and 0 or 12 here converge: the products agree
/// to 1e-16 there, only their rounding differs. See `BENCHMARKS.md`.) At rest a solve
/// takes 1–5 iterations, 2.2 on average (the 10,242-vertex sphere: 64 CG in 29 Newton
/// iterations over 60 steps; with the blocks summed for every solve 13 % of its time went to
/// summing them, 3–10 % slower steps); after a grab 12–26 per Newton iteration, where taking
/// them from the first, the second or the fourth iteration measured the same (`BENCHMARKS.md`).
pub(crate) const BLOCKS_AFTER: u32 = 12;

/// Vectors of the conjugate gradient (flat xyz), allocated once.
#[derive(Debug, Clone, Default)]
pub(crate) struct Cg {
    pub res: Vec<f64>,
    pub z: Vec<f64>,
    pub p: Vec<f64>,
    pub q: Vec<f64>,
    pub slots: Vec<[f64; 4]>,
}

impl Cg {
    pub fn new(n: usize, chunks: usize) -> Self {
        Cg { res: vec![0.0; 3 * n], z: vec![0.0; 3 * n], p: vec![0.0; 3 * n], q: vec![0.0; 3 * n], slots: vec![[0.0; 4]; chunks] }
    }

    /// Solve A δ = −r to relative accuracy `eta`; δ into `delta`. Returns the iterations taken
    /// and the fine products made. A hinged body's products switch to the matrix's blocks
    /// (`System::prepare`) from the start if `upfront`, else after [`BLOCKS_AFTER`] products.
    #[allow(clippy::too_many_arguments)]
    /// It also stops once `stop` says so (a deadline passed, an interrupt), after at least one
    /// iteration (the anytime step: any PCG iterate from δ = 0 minimizes A's quadratic model
    /// over a Krylov space containing 0, so r·δ ≤ −½ δᵀAδ < 0, a descent direction).
    pub fn solve(&mut self, th: &Threads, sys: &mut System, mg: &mut Multigrid, m: &Model, r: &[f64], eta: f64, upfront: bool, stop: &dyn Fn() -> bool, delta: &mut [f64]) -> (u32, u32) {
        if upfront {
            sys.prepare(th, m);
        }
        let n = m.mass.len();
        let Cg { res, z, p, q, slots } = self;
        // δ = 0, res = −r; rn = ‖res‖²_{M⁻¹}.
        {
            let (dl, rs) = (Out::new(delta), Out::new(res));
            th.each(slots, |c, slot| {
                let vr = chunk(c, VCHUNK, n);
                // SAFETY: chunk c writes vertices vr only.
                let (dl, rs) = unsafe { (dl.range(3 * vr.start..3 * vr.end), rs.range(3 * vr.start..3 * vr.end)) };
                let mut acc = [0.0; 4];
                for (li, i) in vr.enumerate() {
                    for d in 0..3 {
                        let ri = -r[3 * i + d];
                        dl[3 * li + d] = 0.0;
                        rs[3 * li + d] = ri;
                        acc[1] += ri * ri / m.mass[i];
                    }
                }
                *slot = acc;
            });
        }
        let mut rn = sum3(slots).1;
        let target = eta * eta * rn;
        if rn <= target || rn == 0.0 {
            return (0, 0);
        }
        // z = B res (the preconditioner), p = z; rz = res · z, gp = g · p.
        let mut rz = mg.apply(th, sys, m, res, z, slots);
        let gas = sys.gamma != 0.0;
        let mut gp = direction(th, sys, n, z, 0.0, p, slots);
        // Fine products per iteration (the conjugate gradient's, the V-cycle's two residuals),
        // and those made so far (the first V-cycle's).
        let per = if mg.cycles(sys, n) { 3 } else { 1 };
        let mut products = per - 1;
        for it in 0..LINEAR_MAX {
            if products >= BLOCKS_AFTER {
                sys.prepare(th, m);
            }
            products += per;
            let pq = sys.product(th, m, p, if gas { gp } else { 0.0 }, q, slots);
            if !(pq > 0.0 && pq.is_finite()) {
                return (it, products); // only rounding can do this: A is positive definite
            }
            let alpha = rz / pq;
            {
                let (dl, rs) = (Out::new(delta), Out::new(res));
                let (p, q) = (&*p, &*q);
                th.each(slots, |c, slot| {
                    let vr = chunk(c, VCHUNK, n);
                    // SAFETY: chunk c writes vertices vr only.
                    let (dl, rs) = unsafe { (dl.range(3 * vr.start..3 * vr.end), rs.range(3 * vr.start..3 * vr.end)) };
                    let mut acc = [0.0; 4];
                    for (li, i) in vr.enumerate() {
                        for d in 0..3 {
                            dl[3 * li + d] += alpha * p[3 * i + d];
                            let ri = rs[3 * li + d] - alpha * q[3 * i + d];
                            rs[3 * li + d] = ri;
                            acc[1] += ri * ri / m.mass[i];
                        }
                    }
                    *slot = acc;
                });
            }
            rn = sum3(slots).1;
            if rn <= target || rn == 0.0 || stop() {
                return (it + 1, products);
            }
            let rz_new = mg.apply(th, sys, m, res, z, slots);
            let beta = rz_new / rz;
            rz = rz_new;
            gp = direction(th, sys, n, z, beta, p, slots);
        }
        (LINEAR_MAX, products)
    }
}

/// p = z + β p; returns g · p.
fn direction(th: &Threads, sys: &System, n: usize, z: &[f64], beta: f64, p: &mut [f64], slots: &mut [[f64; 4]]) -> f64 {
    let pp = Out::new(p);
    th.each(slots, |c, slot| {
        let vr = chunk(c, VCHUNK, n);
        // SAFETY: chunk c writes vertices vr only.
        let pp = unsafe { pp.range(3 * vr.start..3 * vr.end) };
        let mut acc = [0.0; 4];
        for (li, i) in vr.enumerate() {
            for d in 0..3 {
                let v = z[3 * i + d] + beta * pp[3 * li + d];
                pp[3 * li + d] = v;
                acc[2] += v * sys.g[3 * i + d];
            }
        }
        *slot = acc;
    });
    sum3(slots).2
}

/// Sums of the first three reduction slots, in chunk order.
fn sum3(slots: &[[f64; 4]]) -> (f64, f64, f64) {
    slots.iter().fold((0.0, 0.0, 0.0), |a, s| (a.0 + s[0], a.1 + s[1], a.2 + s[2]))
}
