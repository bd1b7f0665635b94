//! The preconditioned conjugate gradient on A δ = −r (A = M + dt D + dt² K, symmetric positive
//! definite after the projections of `system.rs`; block-Jacobi preconditioner: the inverse of
//! each vertex's 3×3 diagonal block). Matrix-free: A is applied row by row (`System::product`).
//!
//! It stops when the mass-weighted norm of its residual ‖b − A δ‖_{M⁻¹} (with
//! ‖y‖²_{M⁻¹} = Σ_i |y_i|² / m_i) is at most η ‖b‖_{M⁻¹} — the Newton loop chooses η — or after
//! [`LINEAR_MAX`] iterations (Newton then goes on from the partial solution).

use super::system::{System, VCHUNK};
use super::super::Model;
use crate::par::{chunk, Out, Threads};

/// Most conjugate-gradient iterations per Newton iteration.
pub(crate) const LINEAR_MAX: u32 = 2000;

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
    pub fn solve(&mut self, th: &Threads, sys: &System, m: &Model, r: &[f64], eta: f64, delta: &mut [f64]) -> u32 {
        let n = m.mass.len();
        let Cg { res, z, p, q, slots } = self;
        // δ = 0, res = −r, z = P res, p = z; rz = res · z, rn = ‖res‖²_{M⁻¹}, gp = g · p.
        {
            let (dl, rs, zz, pp) = (Out::new(delta), Out::new(res), Out::new(z), Out::new(p));
            th.each(slots, |c, slot| {
                let vr = chunk(c, VCHUNK, n);
                // SAFETY: chunk c writes vertices vr only.
                let (dl, rs, zz, pp) = unsafe { (dl.range(3 * vr.start..3 * vr.end), rs.range(3 * vr.start..3 * vr.end), zz.range(3 * vr.start..3 * vr.end), pp.range(3 * vr.start..3 * vr.end)) };
                let mut acc = [0.0; 4];
                for (li, i) in vr.enumerate() {
                    let ri = [-r[3 * i], -r[3 * i + 1], -r[3 * i + 2]];
                    let zi = sys.precondition(i, &ri);
                    for d in 0..3 {
                        dl[3 * li + d] = 0.0;
                        rs[3 * li + d] = ri[d];
                        zz[3 * li + d] = zi[d];
                        pp[3 * li + d] = zi[d];
                        acc[0] += ri[d] * zi[d];
                        acc[1] += ri[d] * ri[d] / m.mass[i];
                        acc[2] += zi[d] * sys.g[3 * i + d];
                    }
                }
                *slot = acc;
            });
        }
        let (mut rz, mut rn, mut gp) = sum3(slots);
        let target = eta * eta * rn;
        let gas = sys.gamma != 0.0;
        for it in 0..LINEAR_MAX {
            if rn <= target || rn == 0.0 {
                return it;
            }
            let pq = sys.product(th, m, p, if gas { gp } else { 0.0 }, q, slots);
            if !(pq > 0.0 && pq.is_finite()) {
                return it; // only rounding can do this: A is positive definite
            }
            let alpha = rz / pq;
            {
                let (dl, rs, zz) = (Out::new(delta), Out::new(res), Out::new(z));
                let (p, q) = (&*p, &*q);
                th.each(slots, |c, slot| {
                    let vr = chunk(c, VCHUNK, n);
                    // SAFETY: chunk c writes vertices vr only.
                    let (dl, rs, zz) = unsafe { (dl.range(3 * vr.start..3 * vr.end), rs.range(3 * vr.start..3 * vr.end), zz.range(3 * vr.start..3 * vr.end)) };
                    let mut acc = [0.0; 4];
                    for (li, i) in vr.enumerate() {
                        let mut ri = [0.0; 3];
                        for d in 0..3 {
                            dl[3 * li + d] += alpha * p[3 * i + d];
                            ri[d] = rs[3 * li + d] - alpha * q[3 * i + d];
                            rs[3 * li + d] = ri[d];
                        }
                        let zi = sys.precondition(i, &ri);
                        for d in 0..3 {
                            zz[3 * li + d] = zi[d];
                            acc[0] += ri[d] * zi[d];
                            acc[1] += ri[d] * ri[d] / m.mass[i];
                        }
                    }
                    *slot = acc;
                });
            }
            let (rz_new, rn_new, _) = sum3(slots);
            let beta = rz_new / rz;
            rz = rz_new;
            rn = rn_new;
            {
                let pp = Out::new(p);
                let z = &*z;
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
            }
            gp = sum3(slots).2;
        }
        LINEAR_MAX
    }
}

/// Sums of the first three reduction slots, in chunk order.
fn sum3(slots: &[[f64; 4]]) -> (f64, f64, f64) {
    slots.iter().fold((0.0, 0.0, 0.0), |a, s| (a.0 + s[0], a.1 + s[1], a.2 + s[2]))
}
