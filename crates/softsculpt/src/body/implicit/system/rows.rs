//! The residual's vertex pass (`super::System::eval`): each vertex row gathers its springs', bending
//! springs', hinges', faces' and contacts' forces and 3×3 diagonal blocks at (x_t, v⁺), with the
//! per-hinge and per-face passes that run before it.

use super::super::adjacency::{FaceRows, HingeRows, SpringRows};
use super::super::super::hinges::{bend_crushed, rate, Hinges};
use super::{Frame, ECHUNK};
use crate::par::{chunk, chunks, Out, Threads};


/// The vertex pass's per-entry outputs for its rows: `ecoef`, `bcoef`, `hcoef`.
pub(super) type RowCoefs<'a> = (&'a mut [[f64; 5]], &'a mut [[f64; 5]], &'a mut [[f64; 3]]);

/// The vertex pass's inputs.
pub(super) struct Rows<'a> {
    pub(super) fr: &'a Frame<'a>,
    pub(super) s: f64,
    pub(super) gas: bool,
    pub(super) fext_on: bool,
    pub(super) edges: &'a SpringRows,
    pub(super) bends: &'a SpringRows,
    pub(super) faces: &'a FaceRows,
    pub(super) absolute: bool,
    pub(super) bending: bool,
    pub(super) hinged: bool,
    pub(super) hrows: &'a HingeRows,
    pub(super) hg: &'a [[f64; 12]],
    pub(super) hf: &'a [f64],
    pub(super) hc: &'a [f64],
    pub(super) nf: &'a [f64],
    pub(super) gamma: f64,
    pub(super) fext: &'a [f64],
    pub(super) contacts: bool,
    pub(super) cf: &'a [[f64; 4]],
    pub(super) cblk: &'a [[f64; 6]],
    pub(super) held: &'a [bool],
    pub(super) grounded: bool,
}

/// Add row `i` of a spring kind at (x_t, v⁺): Σ ±fs d into `f`, Σ (a I + b d dᵀ) into `blk`,
/// Σ|fs d| into `abs`, Σ ¼ k (l − L)² into `energy` (each spring's ½ k (l − L)², half in each of
/// its rows); each entry kk's (a, b, d) into `coef[kk − base]`. Each spring is evaluated
/// in both its ends' rows, always from its first end i to its second j (d = (x_j − x_i)/l), so
/// both rows get the same bits, the forces are exactly opposite (momentum is kept to the last
/// bit) and no pass over the springs has to write them for the rows to gather (measured on the
/// modeler's 10,242-vertex sphere landing: the same time within noise, on 1 and 2 threads, as
/// with that pass, whose arrays of 64 B per spring are gone; the same bits).
/// `(k, cs, absolute)`: stiffness, damping, and how a compressed spring's negative transverse
/// factor 1 − L/l enters the matrix (clamped at 0, or its absolute value).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(super) fn gather_springs(rows: &SpringRows, rest: &[f64], (k, cs, absolute): (f64, f64, bool), dt: f64, (xt, vp): (&[f64], &[f64]), i: usize, (f, blk, abs, energy): (&mut [f64; 3], &mut [f64; 6], &mut f64, &mut f64), coef: &mut [[f64; 5]], base: usize) {
    let (dt2k, dtcs) = (dt * dt * k, dt * cs);
    for kk in rows.start[i] as usize..rows.start[i + 1] as usize {
        let e = rows.spring[kk] as usize;
        let o = rows.other[kk] as usize;
        let (sign, lo, hi) = if o > i { (1.0, 3 * i, 3 * o) } else { (-1.0, 3 * o, 3 * i) };
        let dx = [xt[hi] - xt[lo], xt[hi + 1] - xt[lo + 1], xt[hi + 2] - xt[lo + 2]];
        let l = (dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2]).sqrt();
        let inv = 1.0 / l;
        let u = [dx[0] * inv, dx[1] * inv, dx[2] * inv];
        let dvn = (vp[hi] - vp[lo]) * u[0] + (vp[hi + 1] - vp[lo + 1]) * u[1] + (vp[hi + 2] - vp[lo + 2]) * u[2];
        let rest = rest[e];
        let fs = k * (l - rest) + cs * dvn;
        // ½ k (l − L)² per spring, half in each end's row.
        *energy += 0.25 * k * (l - rest) * (l - rest);
        let alpha = if absolute { (1.0 - rest * inv).abs() } else { (1.0 - rest * inv).max(0.0) };
        let (fx, fy, fz) = (fs * u[0], fs * u[1], fs * u[2]);
        f[0] += sign * fx;
        f[1] += sign * fy;
        f[2] += sign * fz;
        *abs += fx.abs() + fy.abs() + fz.abs();
        let (a, b) = (dt2k * alpha, dt2k * (1.0 - alpha) + dtcs);
        let [dx, dy, dz] = u;
        coef[kk - base] = [a, b, dx, dy, dz];
        blk[0] += a + b * dx * dx;
        blk[1] += a + b * dy * dy;
        blk[2] += a + b * dz * dz;
        blk[3] += b * dx * dy;
        blk[4] += b * dx * dz;
        blk[5] += b * dy * dz;
    }
}

/// blk += c g gᵀ, blk a symmetric 3×3 as (xx, yy, zz, xy, xz, yz): a rank-one term's diagonal
/// block (the gas's γ g gᵀ, a hinge's c_h ∇θ ∇θᵀ).
#[inline(always)]
pub(super) fn add_outer(blk: &mut [f64; 6], c: f64, g: [f64; 3]) {
    blk[0] += c * g[0] * g[0];
    blk[1] += c * g[1] * g[1];
    blk[2] += c * g[2] * g[2];
    blk[3] += c * g[0] * g[1];
    blk[4] += c * g[0] * g[2];
    blk[5] += c * g[1] * g[2];
}

/// Inverse of the symmetric 3×3 (xx, yy, zz, xy, xz, yz) by its adjugate.
#[inline(always)]
pub(super) fn inverse_sym(m: &[f64; 6]) -> [f64; 6] {
    let [a, d, f, b, c, e] = *m; // [[a b c] [b d e] [c e f]]
    let (c00, c11, c22) = (d * f - e * e, a * f - c * c, a * d - b * b);
    let (c01, c02, c12) = (c * e - b * f, b * e - c * d, b * c - a * e);
    let det = a * c00 + b * c01 + c * c02;
    let inv = 1.0 / det;
    [c00 * inv, c11 * inv, c22 * inv, c01 * inv, c02 * inv, c12 * inv]
}

impl Rows<'_> {
    #[allow(clippy::too_many_arguments)]
    pub(super) fn run(&self, vr: std::ops::Range<usize>, vp: &[f64], xt: &[f64], (r, react): (&mut [f64], &mut [f64]), g: &mut [f64], diag: &mut [f64], pre: &mut [f64], coef: RowCoefs) -> [f64; 4] {
        let Frame { p, w, m, v, dt, .. } = *self.fr;
        let sys = self;
        let grav = [0.0, -w.gravity, 0.0];
        let c = p.damping;
        let targets = &m.targets;
        let (mut res2, mut noise2, mut energy) = (0.0, 0.0, 0.0);
        let (ecoef, bcoef, hcoef) = coef;
        let (ebase, bbase) = (sys.edges.start[vr.start] as usize, if sys.bending { sys.bends.start[vr.start] as usize } else { 0 });
        let hbase = if sys.hinged { sys.hrows.start[vr.start] as usize } else { 0 };
        for (li, i) in vr.enumerate() {
            let mi = m.mass[i];
            let mut f = [0.0; 3];
            let mut blk = [0.0; 6];
            let mut abs = 0.0;
            gather_springs(sys.edges, &m.springs.rest, (p.stiffness, p.spring_damping, sys.absolute), dt, (xt, vp), i, (&mut f, &mut blk, &mut abs, &mut energy), ecoef, ebase);
            if sys.bending {
                gather_springs(sys.bends, &m.bending.rest, (p.bending_stiffness, p.spring_damping, sys.absolute), dt, (xt, vp), i, (&mut f, &mut blk, &mut abs, &mut energy), bcoef, bbase);
            }
            if self.hinged {
                // Σ over the hinges around i: −D w (θ − θ̄ + τ θ̇) ∇_i θ, and c_h ∇_i θ ∇_i θᵀ.
                for k in sys.hrows.start[i] as usize..sys.hrows.start[i + 1] as usize {
                    let e = sys.hrows.entry[k];
                    let (h, s) = ((e / 4) as usize, 3 * (e % 4) as usize);
                    let g = &sys.hg[h][s..s + 3];
                    hcoef[k - hbase] = [g[0], g[1], g[2]];
                    let (fs, ch) = (sys.hf[h], sys.hc[h]);
                    f[0] += fs * g[0];
                    f[1] += fs * g[1];
                    f[2] += fs * g[2];
                    abs += fs.abs() * (g[0].abs() + g[1].abs() + g[2].abs());
                    add_outer(&mut blk, ch, [g[0], g[1], g[2]]);
                }
            }
            if self.gas {
                let mut gi = [0.0; 3];
                for k in sys.faces.start[i] as usize..sys.faces.start[i + 1] as usize {
                    let fidx = 3 * sys.faces.face[k] as usize;
                    gi[0] += sys.nf[fidx];
                    gi[1] += sys.nf[fidx + 1];
                    gi[2] += sys.nf[fidx + 2];
                }
                for d in 0..3 {
                    f[d] += self.s * gi[d];
                    g[3 * li + d] = gi[d];
                }
                abs += self.s.abs() * (gi[0].abs() + gi[1].abs() + gi[2].abs());
                add_outer(&mut blk, sys.gamma, gi);
            }
            if self.contacts {
                let (cf, cb) = (&self.cf[i], &self.cblk[i]);
                f[0] += cf[0];
                f[1] += cf[1];
                f[2] += cf[2];
                abs += cf[3];
                for q in 0..6 {
                    blk[q] += cb[q];
                }
            }
            let mut dg = mi * (1.0 + dt * c);
            let (kt, ct) = if targets.active() { (targets.k[i], targets.c[i]) } else { (0.0, 0.0) };
            if kt != 0.0 || ct != 0.0 {
                dg += dt * ct + dt * dt * kt;
            }
            // Rounding of the spring forces: k (l − L) loses ε |x| of l (x_j − x_i is rounded at the
            // scale of the positions), cs (Δv · d) ε |v|.
            let deg = (sys.edges.start[i + 1] - sys.edges.start[i]) as f64;
            let bdeg = if sys.bending { (sys.bends.start[i + 1] - sys.bends.start[i]) as f64 } else { 0.0 };
            let xa = xt[3 * i].abs() + xt[3 * i + 1].abs() + xt[3 * i + 2].abs();
            let va = vp[3 * i].abs() + vp[3 * i + 1].abs() + vp[3 * i + 2].abs();
            abs += (deg * p.stiffness + bdeg * p.bending_stiffness) * xa + (deg + bdeg) * p.spring_damping * va;
            let pinned = m.inv_mass[i] == 0.0;
            // Ground constraint: v⁺_y prescribed (`ground.rs`).
            let held = self.grounded && self.held[i];
            let mut r2 = 0.0;
            let mut scale = 0.0;
            for d in 0..3 {
                let k3 = 3 * i + d;
                let mut fd = f[d] + mi * grav[d] - c * mi * vp[k3];
                if m.external_active {
                    fd += m.external[k3];
                }
                if self.fext_on {
                    fd += sys.fext[k3];
                }
                if kt != 0.0 || ct != 0.0 {
                    fd += kt * (targets.anchor[k3] - xt[k3]) - ct * vp[k3];
                }
                let mut rd = if pinned { 0.0 } else { mi * (vp[k3] - v[k3]) - dt * fd };
                if held && d == 1 {
                    react[li] = rd;
                    rd = 0.0;
                }
                r[3 * li + d] = rd;
                r2 += rd * rd;
                scale += dt * fd.abs() + mi * (vp[k3].abs() + v[k3].abs());
            }
            scale += dt * abs;
            diag[li] = if pinned { 0.0 } else { dg };
            if pinned {
                pre[6 * li..6 * li + 6].fill(0.0);
            } else {
                blk[0] += dg;
                blk[1] += dg;
                blk[2] += dg;
                if held {
                    // The inverse of the x–z block alone: y's row and column removed.
                    (blk[1], blk[3], blk[5]) = (1.0, 0.0, 0.0);
                }
                let mut inv = inverse_sym(&blk);
                if held {
                    inv[1] = 0.0;
                }
                pre[6 * li..6 * li + 6].copy_from_slice(&inv);
                res2 += r2 / mi;
                // Rounding of r_i: a few ulps of the magnitudes summed into it.
                let nz = 16.0 * f64::EPSILON * scale;
                noise2 += nz * nz / mi;
            }
        }
        [res2, noise2, energy, 0.0]
    }
}

/// Per hinge at (x_t, v⁺): its bend's gradient ∇r, the force scale −D w (r + τ ṙ) and the
/// matrix coefficient (dt² + dt τ) D w (`(b, tau)` = D in J, τ in s), with r = θ − θ̄ and
/// ∇r = ∇θ, each × the fade Φ where a face is crushed (`hinges::bend`); a degenerate hinge (a
/// face without area), or with `let_go` a hinge with a crushed face, gets zeros. Returns
/// whether any hinge has a crushed face. The damping's dependence on x through ∇r is dropped, as the
/// springs' is.
#[allow(clippy::type_complexity)]
pub(super) fn hinge_pass(th: &Threads, hn: &Hinges, (b, tau, let_go): (f64, f64, bool), dt: f64, (xt, vp): (&[f64], &[f64]), (hg, hf, hc, he): (&mut [[f64; 12]], &mut [f64], &mut [f64], &mut [f64]), slots: &mut [f64]) -> bool {
    let nh = hn.v.len();
    let nch = chunks(nh, ECHUNK);
    let (go, fo, co, eo) = (Out::new(hg), Out::new(hf), Out::new(hc), Out::new(he));
    th.each(&mut slots[..nch], |c, slot| {
        let hr = chunk(c, ECHUNK, nh);
        // SAFETY: chunk c writes hinges hr only.
        let (hg, hf, hc, he) = unsafe { (go.range(hr.clone()), fo.range(hr.clone()), co.range(hr.clone()), eo.range(hr.clone())) };
        let mut crushed = false;
        for (lh, h) in hr.enumerate() {
            let (bent, flat) = bend_crushed(xt, &hn.v[h], hn.rest[h], hn.thin[h], let_go);
            crushed |= flat;
            match bent {
                Some((r, g)) => {
                    let bw = b * hn.weight[h];
                    for (q, gq) in g.iter().enumerate() {
                        hg[lh][3 * q..3 * q + 3].copy_from_slice(gq);
                    }
                    hf[lh] = -bw * (r + tau * rate(&g, &hn.v[h], vp));
                    hc[lh] = (dt * dt + dt * tau) * bw;
                    he[lh] = 0.5 * bw * r * r;
                }
                None => {
                    hg[lh] = [0.0; 12];
                    hf[lh] = 0.0;
                    hc[lh] = 0.0;
                    he[lh] = 0.0;
                }
            }
        }
        *slot = if crushed { 1.0 } else { 0.0 };
    });
    slots[..nch].iter().any(|&c| c != 0.0)
}

/// Per face n_f into `nf`; returns 6V = Σ x_a · n_f (per-chunk sums added in chunk order).
pub(super) fn face_pass(th: &Threads, tris: &[[u32; 3]], x: &[f64], nf: &mut [f64], slots: &mut [f64]) -> f64 {
    let n = tris.len();
    let out = Out::new(nf);
    th.each(slots, |c, slot| {
        let fr = chunk(c, ECHUNK, n);
        // SAFETY: chunk c writes faces fr only.
        let nf = unsafe { out.range(3 * fr.start..3 * fr.end) };
        let mut six_v = 0.0;
        for (lf, t) in tris[fr].iter().enumerate() {
            let (a, b, cc) = (3 * t[0] as usize, 3 * t[1] as usize, 3 * t[2] as usize);
            let e1 = [x[b] - x[a], x[b + 1] - x[a + 1], x[b + 2] - x[a + 2]];
            let e2 = [x[cc] - x[a], x[cc + 1] - x[a + 1], x[cc + 2] - x[a + 2]];
            let n3 = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]];
            six_v += x[a] * n3[0] + x[a + 1] * n3[1] + x[a + 2] * n3[2];
            nf[3 * lf..3 * lf + 3].copy_from_slice(&n3);
        }
        *slot = six_v;
    });
    slots.iter().sum()
}
