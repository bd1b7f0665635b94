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
    #[inline(never)]
    pub fn accumulate(&self, k: f64, cs: f64, x: &[f64], v: &[f64], f: &mut [f64]) {
        let n = 3 * self.vertex_count;
        assert!(x.len() >= n && v.len() >= n && f.len() >= n);
        let (ii, jj, rest) = (&self.i[..], &self.j[..self.i.len()], &self.rest[..self.i.len()]);
        for e in 0..ii.len() {
            let a = 3 * ii[e] as usize;
            let b = 3 * jj[e] as usize;
            // SAFETY: every index is below `vertex_count` (checked in `new`, never changed) and
            // the three arrays hold at least 3 · vertex_count values (asserted above).
            unsafe {
                let dx = *x.get_unchecked(b) - *x.get_unchecked(a);
                let dy = *x.get_unchecked(b + 1) - *x.get_unchecked(a + 1);
                let dz = *x.get_unchecked(b + 2) - *x.get_unchecked(a + 2);
                let len = (dx * dx + dy * dy + dz * dz).sqrt();
                let inv = 1.0 / len;
                let (ux, uy, uz) = (dx * inv, dy * inv, dz * inv);
                let dvn = (*v.get_unchecked(b) - *v.get_unchecked(a)) * ux
                    + (*v.get_unchecked(b + 1) - *v.get_unchecked(a + 1)) * uy
                    + (*v.get_unchecked(b + 2) - *v.get_unchecked(a + 2)) * uz;
                let fs = k * (len - rest[e]) + cs * dvn;
                let (sx, sy, sz) = (fs * ux, fs * uy, fs * uz);
                *f.get_unchecked_mut(a) += sx;
                *f.get_unchecked_mut(a + 1) += sy;
                *f.get_unchecked_mut(a + 2) += sz;
                *f.get_unchecked_mut(b) -= sx;
                *f.get_unchecked_mut(b + 1) -= sy;
                *f.get_unchecked_mut(b + 2) -= sz;
            }
        }
    }
}
