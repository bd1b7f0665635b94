//! The product A p and the preconditioner's diagonal for the conjugate gradient
//! (`super::System`), matrix-free from the pieces or from a hinged body's summed blocks.

use super::super::adjacency::SpringRows;
use super::super::super::Model;
use super::{System, VCHUNK};
use crate::par::{chunk, Out, Threads};


/// The product and the preconditioner, for the conjugate gradient: matrix-free from the
/// pieces, or from a hinged body's blocks once summed.
impl System {
    /// out = A p, A = M + dt D + dt² K (see the module documentation); `gp` = g · p. Pinned
    /// rows are 0 (p is 0 there too), and so are the ground-held vertices' y rows (the callers'
    /// vectors are 0 there too: with both, the product is F A F, `ground.rs`).
    pub fn product(&self, th: &Threads, m: &Model, p: &[f64], gp: f64, out: &mut [f64], slots: &mut [[f64; 4]]) -> f64 {
        self.rows_pass::<false>(th, m, p, self.gamma * gp, &[], out, slots)
    }

    /// out = b − A' p, A' = A without the gas's rank-one term (the multigrid cycle's residual:
    /// `multigrid/`). Pinned rows are 0 (b and p are 0 there too).
    pub fn residual(&self, th: &Threads, m: &Model, p: &[f64], b: &[f64], out: &mut [f64], slots: &mut [[f64; 4]]) {
        assert!(b.len() >= 3 * m.mass.len());
        self.rows_pass::<true>(th, m, p, 0.0, b, out, slots);
    }

    /// The chunked pass of `product` (SUB = false) and `residual` (SUB = true): out = A p or
    /// b − A p, gg = γ (g · p); returns p · A p.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn rows_pass<const SUB: bool>(&self, th: &Threads, m: &Model, p: &[f64], gg: f64, b: &[f64], out: &mut [f64], slots: &mut [[f64; 4]]) -> f64 {
        let n = m.mass.len();
        assert!(p.len() >= 3 * n && self.diag.len() >= n && self.g.len() >= 3 * n && m.inv_mass.len() >= n);
        if self.hinged && !self.block_products() {
            // Per hinge c_h (∇θ · p), in as many ranges of hinges as there are vertex chunks
            // (each hinge's value is the same whatever the split).
            let (nh, nc) = (m.hinges.v.len(), slots.len());
            th.each(slots, |c, _| {
                for h in c * nh / nc..(c + 1) * nh / nc {
                    let (g, hv) = (&self.hg[h], &m.hinges.v[h]);
                    let mut s = 0.0;
                    for (q, &v) in hv.iter().enumerate() {
                        let o = 3 * v as usize;
                        s += g[3 * q] * p[o] + g[3 * q + 1] * p[o + 1] + g[3 * q + 2] * p[o + 2];
                    }
                    self.hp.set(h, self.hc[h] * s);
                }
            });
        }
        let o = Out::new(out);
        th.each(slots, |c, slot| {
            let vr = chunk(c, VCHUNK, n);
            // SAFETY: chunk c writes vertices vr only.
            let out = unsafe { o.range(3 * vr.start..3 * vr.end) };
            slot[0] = self.product_rows::<SUB>(m, vr, p, gg, b, out);
        });
        let mut pq: f64 = slots.iter().map(|s| s[0]).sum();
        if m.self_contacts.active() {
            // The self-contacts' rank-one terms, scattered in list order after the chunks.
            pq += self.contact.product::<SUB>(&m.self_contacts, &m.inv_mass, p, out);
            self.ground.filter(out);
        }
        pq
    }

    /// Rows `vr` of the product into `out`; returns their part of p · A p. On x86-64 with AVX2
    /// the same code is compiled a second time for it (VEX encoding; no FMA contraction, so the
    /// bits are the same either way) and chosen at run time, as in `springs.rs`.
    pub(super) fn product_rows<const SUB: bool>(&self, m: &Model, vr: std::ops::Range<usize>, p: &[f64], gg: f64, b: &[f64], out: &mut [f64]) -> f64 {
        #[cfg(target_arch = "x86_64")]
        {
            if std::arch::is_x86_feature_detected!("avx2") {
                // SAFETY: the CPU supports the feature the function is compiled for.
                return unsafe { self.product_rows_avx2::<SUB>(m, vr, p, gg, b, out) };
            }
        }
        self.product_rows_plain::<SUB>(m, vr, p, gg, b, out)
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn product_rows_avx2<const SUB: bool>(&self, m: &Model, vr: std::ops::Range<usize>, p: &[f64], gg: f64, b: &[f64], out: &mut [f64]) -> f64 {
        self.product_rows_plain::<SUB>(m, vr, p, gg, b, out)
    }

    #[inline(always)]
    pub(super) fn product_rows_plain<const SUB: bool>(&self, m: &Model, vr: std::ops::Range<usize>, p: &[f64], gg: f64, b: &[f64], out: &mut [f64]) -> f64 {
        let mut pq = 0.0;
        let grounded = self.ground.active();
        let blocks = self.block_products();
        for (li, i) in vr.enumerate() {
            if m.inv_mass[i] == 0.0 {
                out[3 * li..3 * li + 3].fill(0.0);
                continue;
            }
            let pi = [p[3 * i], p[3 * i + 1], p[3 * i + 2]];
            let mut q = if blocks {
                // SAFETY: `rows_pass` asserts p.len() ≥ 3 n.
                unsafe { self.blocks.row(i, p) }
            } else {
                let dg = self.diag[i];
                let mut q = [dg * pi[0], dg * pi[1], dg * pi[2]];
                row_product(&self.edges, &self.ecoef, i, p, &pi, &mut q);
                if self.bending {
                    row_product(&self.bends, &self.bcoef, i, p, &pi, &mut q);
                }
                q
            };
            if self.hinged && !blocks {
                let (k0, k1) = (self.hrows.start[i] as usize, self.hrows.start[i + 1] as usize);
                for (&e, g) in self.hrows.entry[k0..k1].iter().zip(&self.hcoef[k0..k1]) {
                    let c = self.hp.get((e / 4) as usize);
                    q[0] += c * g[0];
                    q[1] += c * g[1];
                    q[2] += c * g[2];
                }
            }
            if gg != 0.0 {
                for d in 0..3 {
                    q[d] += gg * self.g[3 * i + d];
                }
            }
            if grounded && self.ground.held[i] {
                q[1] = 0.0;
            }
            pq += q[0] * pi[0] + q[1] * pi[1] + q[2] * pi[2];
            if SUB {
                for d in 0..3 {
                    q[d] = b[3 * i + d] - q[d]; // b is 0 where q is held at 0
                }
            }
            out[3 * li..3 * li + 3].copy_from_slice(&q);
        }
        pq
    }

    /// z_i = P_i⁻¹ r_i.
    #[inline(always)]
    pub fn precondition(&self, i: usize, r: &[f64; 3]) -> [f64; 3] {
        let b = &self.pre[6 * i..6 * i + 6];
        [b[0] * r[0] + b[3] * r[1] + b[4] * r[2], b[3] * r[0] + b[1] * r[1] + b[5] * r[2], b[4] * r[0] + b[5] * r[1] + b[2] * r[2]]
    }
}

#[inline(always)]
pub(super) fn row_product(rows: &SpringRows, coef: &[[f64; 5]], i: usize, p: &[f64], pi: &[f64; 3], q: &mut [f64; 3]) {
    let (k0, k1) = (rows.start[i] as usize, rows.start[i + 1] as usize);
    for (&other, c) in rows.other[k0..k1].iter().zip(&coef[k0..k1]) {
        let o = 3 * other as usize;
        // SAFETY: `other` is a vertex of the body (the springs' indices are checked against the
        // vertex count when built) and `product` asserts p.len() ≥ 3 n.
        let pj = unsafe { [*p.get_unchecked(o), *p.get_unchecked(o + 1), *p.get_unchecked(o + 2)] };
        let dl = [pi[0] - pj[0], pi[1] - pj[1], pi[2] - pj[2]];
        let [a, b, dx, dy, dz] = *c;
        let t = b * (dx * dl[0] + dy * dl[1] + dz * dl[2]);
        q[0] += a * dl[0] + t * dx;
        q[1] += a * dl[1] + t * dy;
        q[2] += a * dl[2] + t * dz;
    }
}
