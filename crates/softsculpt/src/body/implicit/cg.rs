//! The preconditioned conjugate gradient on A δ = −r (A = M + dt D + dt² K, symmetric positive
//! definite after the projections of `system.rs`). Preconditioner (`multigrid.rs`): the inverse
//! of each vertex's 3×3 diagonal block (block Jacobi), or on large bodies an aggregation
//! multigrid V-cycle. Matrix-free: A is applied row by row (`System::product`).
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
/// The iteration (from 0) of a solve from which a hinged body's products take the matrix's blocks
/// (`blocks.rs`), and the iterations of the last solve above which the Newton loop asks for
/// them from the start. Summing the blocks costs ~15 block products (~6 of the pieces';
/// measured at 10,242 vertices), and a block product is ~0.4 of one from the pieces, so they
/// pay from ~3 iterations on (each iteration is up to 3 products: the CG's and the V-cycle's
/// two residuals). At rest a solve takes about one iteration (the 10,242-vertex sphere: 30
/// Newton and 32 CG iterations in 60 steps; with the blocks summed for every solve 13 % of its
/// time went to summing them, 3–10 % slower steps); after a grab 12–26, where taking them
/// from the first, the second or the fourth iteration measured the same (`BENCHMARKS.md`).
pub(crate) const BLOCKS_FROM: u32 = 3;

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

    /// Solve A δ = −r to relative accuracy `eta`; δ into `delta`. Returns the iterations taken.
    /// A hinged body's products switch to the matrix's blocks (`System::prepare`) from the
    /// start if `upfront`, else from iteration [`BLOCKS_FROM`].
    #[allow(clippy::too_many_arguments)]
    pub fn solve(&mut self, th: &Threads, sys: &mut System, mg: &mut Multigrid, m: &Model, r: &[f64], eta: f64, upfront: bool, delta: &mut [f64]) -> u32 {
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
            return 0;
        }
        // z = B res (the preconditioner), p = z; rz = res · z, gp = g · p.
        let mut rz = mg.apply(th, sys, m, res, z, slots);
        let gas = sys.gamma != 0.0;
        let mut gp = direction(th, sys, n, z, 0.0, p, slots);
        for it in 0..LINEAR_MAX {
            if it == BLOCKS_FROM {
                sys.prepare(th, m);
            }
            let pq = sys.product(th, m, p, if gas { gp } else { 0.0 }, q, slots);
            if !(pq > 0.0 && pq.is_finite()) {
                return it; // only rounding can do this: A is positive definite
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
            if rn <= target || rn == 0.0 {
                return it + 1;
            }
            let rz_new = mg.apply(th, sys, m, res, z, slots);
            let beta = rz_new / rz;
            rz = rz_new;
            gp = direction(th, sys, n, z, beta, p, slots);
        }
        LINEAR_MAX
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
