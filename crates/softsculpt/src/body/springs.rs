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

    /// Forces fs·u of springs e0..e0 + m (m ≤ BLOCK) into lanes 0..m of `l.s`, coordinate-major.
    #[inline(always)]
    fn block(&self, l: &mut Lanes, e0: usize, m: usize, k: f64, cs: f64, x: &[f64], v: &[f64]) {
        let (ii, jj) = (&self.i[..], &self.j[..self.i.len()]);
        assert!(e0 + m <= ii.len() && ii.len() <= self.rest.len());
        // SAFETY: e < ii.len() = jj.len() (asserted); every index is below `vertex_count`
        // (checked in `new`, never changed) and x and v hold at least 3 · vertex_count values
        // (asserted by the callers).
        unsafe { self.block_of(l, m, |t| (e0 + t, 3 * *ii.get_unchecked(e0 + t) as usize, 3 * *jj.get_unchecked(e0 + t) as usize), k, cs, x, v) }
    }

    /// Forces fs·u of the springs `ends(t) = (e, 3 a, 3 b)`, t < m ≤ BLOCK (spring e from
    /// vertex a to b of `x` and `v`), into lanes 0..m of `l.s`, coordinate-major.
    ///
    /// # Safety
    /// Every e is below `self.rest.len()`, every 3 a + 2 and 3 b + 2 below `x.len()` and `v.len()`.
    #[inline(always)]
    unsafe fn block_of(&self, l: &mut Lanes, m: usize, ends: impl Fn(usize) -> (usize, usize, usize), k: f64, cs: f64, x: &[f64], v: &[f64]) {
        let rest = &self.rest[..];
        let Lanes { d, dv, l0, s } = l;
        // Gather.
        for t in 0..m {
            let (e, a, b) = ends(t);
            // SAFETY: the caller's promise.
            unsafe {
                for c in 0..3 {
                    d[c][t] = *x.get_unchecked(b + c) - *x.get_unchecked(a + c);
                    dv[c][t] = *v.get_unchecked(b + c) - *v.get_unchecked(a + c);
                }
                l0[t] = *rest.get_unchecked(e);
            }
        }
        // Compute: s = [k (l − L) + cs (dv · u)] u with u = d / l. Padding lanes (t ≥ m) hold
        // an earlier block's springs (or d = 0) and are never scattered; their values, NaN
        // included, are harmless.
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
    }

    #[inline(always)]
    fn accumulate_blocks(&self, k: f64, cs: f64, x: &[f64], v: &[f64], f: &mut [f64]) {
        let (ii, jj) = (&self.i[..], &self.j[..self.i.len()]);
        let ne = ii.len();
        let mut e0 = 0;
        let mut l = Lanes::new();
        while e0 < ne {
            let m = BLOCK.min(ne - e0);
            self.block(&mut l, e0, m, k, cs, x, v);
            let s = &l.s;
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
    /// Pass A of the chunked stages (`parforces.rs`): the force fs·u on the first end of each
    /// spring of `ids` into `out` (3 values per spring, in order). Same arithmetic as
    /// [`Springs::accumulate`], so the same bits as the pass-B force of the same spring.
    pub(crate) fn forces_of(&self, k: f64, cs: f64, x: &[f64], v: &[f64], ids: &[u32], out: &mut [f64]) {
        let n = 3 * self.vertex_count;
        assert!(x.len() >= n && v.len() >= n && out.len() == 3 * ids.len());
        assert!(ids.iter().all(|&e| (e as usize) < self.len()) && self.len() <= self.rest.len());
        #[cfg(target_arch = "x86_64")]
        {
            if std::arch::is_x86_feature_detected!("avx2") && std::arch::is_x86_feature_detected!("fma") {
                // SAFETY: the CPU supports the features the function is compiled for.
                unsafe { self.forces_of_avx2(k, cs, x, v, ids, out) };
                return;
            }
        }
        self.forces_of_blocks(k, cs, x, v, ids, out);
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,fma")]
    unsafe fn forces_of_avx2(&self, k: f64, cs: f64, x: &[f64], v: &[f64], ids: &[u32], out: &mut [f64]) {
        self.forces_of_blocks(k, cs, x, v, ids, out);
    }

    #[inline(always)]
    fn forces_of_blocks(&self, k: f64, cs: f64, x: &[f64], v: &[f64], ids: &[u32], out: &mut [f64]) {
        let (ii, jj) = (&self.i[..], &self.j[..self.i.len()]);
        let mut l = Lanes::new();
        for (ids, out) in ids.chunks(BLOCK).zip(out.chunks_mut(3 * BLOCK)) {
            // SAFETY: every id is a spring (asserted by the caller); the rest as in `block`.
            unsafe {
                self.block_of(
                    &mut l,
                    ids.len(),
                    |t| {
                        let e = *ids.get_unchecked(t) as usize;
                        (e, 3 * *ii.get_unchecked(e) as usize, 3 * *jj.get_unchecked(e) as usize)
                    },
                    k,
                    cs,
                    x,
                    v,
                )
            };
            let s = &l.s;
            for (t, o) in out.chunks_exact_mut(3).enumerate() {
                o.copy_from_slice(&[s[0][t], s[1][t], s[2][t]]);
            }
        }
    }

    /// Pass B of the chunked stages (`parforces.rs`): chunk c's interior springs of `local`
    /// add their forces into `f`, the chunk's accumulator (`x`, `v` and `f` chunk-local):
    /// +s on i, −s on j.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn accumulate_local(&self, local: &LocalSprings, c: usize, k: f64, cs: f64, x: &[f64], v: &[f64], f: &mut [f64]) {
        let n3 = 3 * local.chunk_len[c] as usize;
        assert!(x.len() == n3 && v.len() == n3 && f.len() == n3 && local.count == self.len() && self.rest.len() >= self.len());
        let ends = &local.ends[local.start[c] as usize..local.start[c + 1] as usize];
        #[cfg(target_arch = "x86_64")]
        {
            if std::arch::is_x86_feature_detected!("avx2") && std::arch::is_x86_feature_detected!("fma") {
                // SAFETY: the CPU supports the features the function is compiled for; the
                // ends are in bounds (asserted lengths, `LocalSprings::new`).
                unsafe { self.local_avx2(k, cs, x, v, ends, f) };
                return;
            }
        }
        // SAFETY: as above.
        unsafe { self.local_blocks(k, cs, x, v, ends, f) };
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,fma")]
    unsafe fn local_avx2(&self, k: f64, cs: f64, x: &[f64], v: &[f64], ends: &[LocalEnd], f: &mut [f64]) {
        self.local_blocks(k, cs, x, v, ends, f);
    }

    /// # Safety
    /// Every (e, a, b) of `ends` has e below `self.rest.len()` and 3a + 2, 3b + 2 below the
    /// lengths of `x`, `v` and `f`.
    #[inline(always)]
    unsafe fn local_blocks(&self, k: f64, cs: f64, x: &[f64], v: &[f64], ends: &[LocalEnd], f: &mut [f64]) {
        let mut l = Lanes::new();
        for ends in ends.chunks(BLOCK) {
            let at = |t: usize| {
                let LocalEnd { e, a, b } = *ends.get_unchecked(t);
                (e as usize, 3 * a as usize, 3 * b as usize)
            };
            self.block_of(&mut l, ends.len(), at, k, cs, x, v);
            let s = &l.s;
            for t in 0..ends.len() {
                let (_, a, b) = at(t);
                for c in 0..3 {
                    *f.get_unchecked_mut(a + c) += s[c][t];
                    *f.get_unchecked_mut(b + c) -= s[c][t];
                }
            }
        }
    }
}

/// Springs in chunk-local form for [`Springs::accumulate_local`]: chunk c's springs are
/// `ends[start[c]..start[c + 1]]`, each (e, a, b) with a and b the chunk-local indices of its
/// ends (below `chunk_len[c]`, checked by `new`) and e its index (below `count`).
#[derive(Debug, Clone, Default)]
pub(crate) struct LocalSprings {
    start: Vec<u32>,
    ends: Vec<LocalEnd>,
    chunk_len: Vec<u32>,
    count: usize,
}

impl LocalSprings {
    /// For the chunks (first vertex, vertex count, springs with both ends in it) of `sp`.
    /// Panics if a spring has an end outside its chunk.
    pub fn new<'a>(sp: &Springs, chunks: impl Iterator<Item = (usize, usize, &'a [u32])>) -> Self {
        let mut l = LocalSprings { start: vec![0], count: sp.len(), ..Default::default() };
        for (base, len, ids) in chunks {
            for &e in ids {
                let (a, b) = ((sp.i[e as usize] as usize).wrapping_sub(base), (sp.j[e as usize] as usize).wrapping_sub(base));
                assert!(a < len && b < len && (e as usize) < sp.len(), "an interior spring has both ends in its chunk");
                l.ends.push(LocalEnd { e, a: u16::try_from(a).expect("chunks of at most 65,536 vertices"), b: u16::try_from(b).expect("chunks of at most 65,536 vertices") });
            }
            l.start.push(l.ends.len() as u32);
            l.chunk_len.push(len as u32);
        }
        l
    }
}

/// One interior spring of a chunk: its index e (for the rest length) and its ends' chunk-local
/// indices, 8 bytes (16-bit indices: chunks hold at most 65,536 vertices; `parforces.rs` makes
/// them ~4,096). Read once per spring and step, so its size is memory traffic.
#[derive(Debug, Clone, Copy)]
struct LocalEnd {
    e: u32,
    a: u16,
    b: u16,
}

/// Springs per block of the springs stage (a multiple of the widest vector, 8 f64 lanes).
const BLOCK: usize = 16;

/// One block's lanes: the gathered differences of positions and velocities, rest lengths and
/// forces. Kept from block to block of a stage (initialising them per block cost ~10 % of the
/// stage in stores), so a short last block's padding lanes hold earlier springs' values.
struct Lanes {
    d: [[f64; BLOCK]; 3],
    dv: [[f64; BLOCK]; 3],
    l0: [f64; BLOCK],
    s: [[f64; BLOCK]; 3],
}

impl Lanes {
    #[inline(always)]
    fn new() -> Self {
        Lanes { d: [[0.0; BLOCK]; 3], dv: [[0.0; BLOCK]; 3], l0: [1.0; BLOCK], s: [[0.0; BLOCK]; 3] }
    }
}
