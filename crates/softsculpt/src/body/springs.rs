//! Springs: one damped Hooke spring per mesh edge.
//!
//! Force on i from the spring (i, j), with l = |xj − xi|, d = (xj − xi) / l, L the rest length:
//!   f = [ k (l − L) + cs ((vj − vi) · d) ] d        (N)
//! and −f on j, so the pair conserves momentum exactly. The first term is the gradient of the
//! elastic energy ½ k (l − L)²; the second dissipates only the stretching rate, never rigid
//! motion (rotation leaves (vj − vi) · d = 0).

/// Edge springs as flat arrays (struct of arrays).
#[derive(Debug, Clone)]
pub struct Springs {
    /// First and second vertex of each spring (i < j), sorted by (i, j).
    pub i: Vec<u32>,
    pub j: Vec<u32>,
    /// Rest length L of each spring (m).
    pub rest: Vec<f64>,
    /// Number of vertices the indices refer to (all indices are below it).
    vertex_count: usize,
}

impl Springs {
    /// Springs on `edges`, with rest lengths measured in `x` (flat xyz).
    pub fn new(edges: &[[u32; 2]], x: &[f64]) -> Self {
        let vertex_count = x.len() / 3;
        assert!(edges.iter().all(|e| (e[0] as usize) < vertex_count && (e[1] as usize) < vertex_count));
        let mut s = Springs {
            i: edges.iter().map(|e| e[0]).collect(),
            j: edges.iter().map(|e| e[1]).collect(),
            rest: vec![0.0; edges.len()],
            vertex_count,
        };
        s.rest_to_current(x);
        s
    }

    /// Set every rest length to the spring's current length in `x`.
    pub fn rest_to_current(&mut self, x: &[f64]) {
        let mut rest = std::mem::take(&mut self.rest);
        rest.resize(self.i.len(), 0.0);
        self.lengths_into(x, |e, l| rest[e] = l);
        self.rest = rest;
    }

    pub fn len(&self) -> usize {
        self.i.len()
    }
    pub fn is_empty(&self) -> bool {
        self.i.is_empty()
    }

    /// Call `out(e, l)` with the current length l (m) of every spring.
    pub fn lengths_into(&self, x: &[f64], mut out: impl FnMut(usize, f64)) {
        for e in 0..self.i.len() {
            let (a, b) = (3 * self.i[e] as usize, 3 * self.j[e] as usize);
            let d = [x[b] - x[a], x[b + 1] - x[a + 1], x[b + 2] - x[a + 2]];
            out(e, (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt());
        }
    }

    /// Elastic energy Σ ½ k (l − L)² (J).
    pub fn energy(&self, k: f64, x: &[f64]) -> f64 {
        let mut sum = 0.0;
        self.lengths_into(x, |e, l| sum += (l - self.rest[e]).powi(2));
        0.5 * k * sum
    }

    /// Virial of the springs Σ k (l − L) l (J); equals 3 nRT at inflated equilibrium.
    pub fn virial(&self, k: f64, x: &[f64]) -> f64 {
        let mut sum = 0.0;
        self.lengths_into(x, |e, l| sum += (l - self.rest[e]) * l);
        k * sum
    }

    /// Stage "springs": add every spring's force to `f` (N, flat xyz).
    ///
    /// Springs go in blocks of [`BLOCK`]: gather the blocks' end positions and velocities, compute
    /// the forces in a loop the compiler vectorises (the square roots and divisions dominate the
    /// cost and run several per instruction), then scatter. On x86-64 CPUs with AVX2 and FMA the
    /// same code is compiled a second time for them and chosen at run time.
    #[inline(never)]
    pub fn accumulate(&self, k: f64, cs: f64, x: &[f64], v: &[f64], f: &mut [f64]) {
        let n = 3 * self.vertex_count;
        assert!(x.len() >= n && v.len() >= n && f.len() >= n);
        #[cfg(target_arch = "x86_64")]
        {
            if std::arch::is_x86_feature_detected!("avx2") && std::arch::is_x86_feature_detected!("fma") {
                // SAFETY: the CPU supports the features the function is compiled for.
                unsafe { self.accumulate_avx2(k, cs, x, v, f) };
                return;
            }
        }
        self.accumulate_blocks(k, cs, x, v, f);
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,fma")]
    unsafe fn accumulate_avx2(&self, k: f64, cs: f64, x: &[f64], v: &[f64], f: &mut [f64]) {
        self.accumulate_blocks(k, cs, x, v, f);
    }

    /// Forces fs·u of springs e0..e0 + m (m ≤ BLOCK) into lanes 0..m, coordinate-major.
    #[inline(always)]
    fn block(&self, e0: usize, m: usize, k: f64, cs: f64, x: &[f64], v: &[f64]) -> [[f64; BLOCK]; 3] {
        let (ii, jj, rest) = (&self.i[..], &self.j[..self.i.len()], &self.rest[..self.i.len()]);
        assert!(e0 + m <= ii.len());
        let mut d = [[0.0f64; BLOCK]; 3];
        let mut dv = [[0.0f64; BLOCK]; 3];
        let mut l0 = [1.0f64; BLOCK];
        // Gather.
        for t in 0..m {
            let e = e0 + t;
            // SAFETY: every index is below `vertex_count` (checked in `new`, never changed)
            // and the arrays hold at least 3 · vertex_count values (asserted by the callers).
            unsafe {
                let a = 3 * *ii.get_unchecked(e) as usize;
                let b = 3 * *jj.get_unchecked(e) as usize;
                for c in 0..3 {
                    d[c][t] = *x.get_unchecked(b + c) - *x.get_unchecked(a + c);
                    dv[c][t] = *v.get_unchecked(b + c) - *v.get_unchecked(a + c);
                }
                l0[t] = *rest.get_unchecked(e);
            }
        }
        // Compute: s = [k (l − L) + cs (dv · u)] u with u = d / l. Padding lanes (t ≥ m) hold
        // d = 0 and are never scattered; their NaN is harmless.
        let mut s = [[0.0f64; BLOCK]; 3];
        for t in 0..BLOCK {
            let len = (d[0][t] * d[0][t] + d[1][t] * d[1][t] + d[2][t] * d[2][t]).sqrt();
            let inv = 1.0 / len;
            let (ux, uy, uz) = (d[0][t] * inv, d[1][t] * inv, d[2][t] * inv);
            let dvn = dv[0][t] * ux + dv[1][t] * uy + dv[2][t] * uz;
            let fs = k * (len - l0[t]) + cs * dvn;
            s[0][t] = fs * ux;
            s[1][t] = fs * uy;
            s[2][t] = fs * uz;
        }
        s
    }

    #[inline(always)]
    fn accumulate_blocks(&self, k: f64, cs: f64, x: &[f64], v: &[f64], f: &mut [f64]) {
        let (ii, jj) = (&self.i[..], &self.j[..self.i.len()]);
        let ne = ii.len();
        let mut e0 = 0;
        while e0 < ne {
            let m = BLOCK.min(ne - e0);
            let s = self.block(e0, m, k, cs, x, v);
            // Scatter: +s on i, −s on j.
            for t in 0..m {
                let e = e0 + t;
                // SAFETY: as for the gather.
                unsafe {
                    let a = 3 * *ii.get_unchecked(e) as usize;
                    let b = 3 * *jj.get_unchecked(e) as usize;
                    for c in 0..3 {
                        *f.get_unchecked_mut(a + c) += s[c][t];
                        *f.get_unchecked_mut(b + c) -= s[c][t];
                    }
                }
            }
            e0 += m;
        }
    }
}

impl Springs {
    /// The springs stage for one chunk of vertices (`parforces.rs`): springs `e` (whose first
    /// ends are all in `vr`) add their forces into `f`, the chunk's accumulator (vertex
    /// `vr.start` at 0); a force on a second end past the chunk goes to the next 3 values of
    /// `cross` instead, in spring order. Same arithmetic as [`Springs::accumulate`].
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn accumulate_part(&self, k: f64, cs: f64, x: &[f64], v: &[f64], e: std::ops::Range<usize>, vr: std::ops::Range<usize>, f: &mut [f64], cross: &mut [f64]) {
        let n = 3 * self.vertex_count;
        assert!(x.len() >= n && v.len() >= n && f.len() == 3 * vr.len() && e.end <= self.i.len());
        #[cfg(target_arch = "x86_64")]
        {
            if std::arch::is_x86_feature_detected!("avx2") && std::arch::is_x86_feature_detected!("fma") {
                // SAFETY: the CPU supports the features the function is compiled for.
                unsafe { self.part_avx2(k, cs, x, v, e, vr, f, cross) };
                return;
            }
        }
        self.part_blocks(k, cs, x, v, e, vr, f, cross);
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,fma")]
    #[allow(clippy::too_many_arguments)]
    unsafe fn part_avx2(&self, k: f64, cs: f64, x: &[f64], v: &[f64], e: std::ops::Range<usize>, vr: std::ops::Range<usize>, f: &mut [f64], cross: &mut [f64]) {
        self.part_blocks(k, cs, x, v, e, vr, f, cross);
    }

    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn part_blocks(&self, k: f64, cs: f64, x: &[f64], v: &[f64], e: std::ops::Range<usize>, vr: std::ops::Range<usize>, f: &mut [f64], cross: &mut [f64]) {
        let (ii, jj) = (&self.i[..], &self.j[..self.i.len()]);
        let (base, end) = (3 * vr.start, vr.end as u32);
        let mut slot = 0;
        let mut e0 = e.start;
        while e0 < e.end {
            let m = BLOCK.min(e.end - e0);
            let s = self.block(e0, m, k, cs, x, v);
            // Scatter: +s on i (in the chunk), −s on j when in the chunk, else into `cross`.
            for t in 0..m {
                let e = e0 + t;
                let a = 3 * ii[e] as usize - base;
                let j = jj[e];
                for c in 0..3 {
                    f[a + c] += s[c][t];
                }
                if j < end {
                    let b = 3 * j as usize - base;
                    for c in 0..3 {
                        f[b + c] -= s[c][t];
                    }
                } else {
                    cross[slot..slot + 3].copy_from_slice(&[s[0][t], s[1][t], s[2][t]]);
                    slot += 3;
                }
            }
            e0 += m;
        }
    }
}

/// Springs per block of the springs stage (a multiple of the widest vector, 8 f64 lanes).
const BLOCK: usize = 16;
