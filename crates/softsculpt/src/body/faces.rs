//! Faces: the exact enclosed volume and its gradient, in one pass.
//!
//! For a closed outward mesh, V = Σ_faces xa · (xb × xc) / 6 (divergence theorem). Its gradient
//! with respect to a vertex is Σ over the faces around it of (xb × xc) / 6 which, summed around a
//! closed fan, equals Σ n_f / 6 with n_f = (xb − xa) × (xc − xa) = 2 · area · unit normal. So the
//! gas force P ∂V/∂xi is one third of P · area · normal of each face around i (Matyka & Ollila).
//! We accumulate g_i = Σ n_f (m²); the pressure stage multiplies by P / 6.

/// The triangles of a body, with indices checked once against its vertex count.
#[derive(Debug, Clone)]
pub struct Faces {
    tris: Vec<[u32; 3]>,
    vertex_count: usize,
}

impl Faces {
    pub fn new(tris: Vec<[u32; 3]>, vertex_count: usize) -> Self {
        assert!(tris.iter().flatten().all(|&i| (i as usize) < vertex_count));
        Faces { tris, vertex_count }
    }
    pub fn triangles(&self) -> &[[u32; 3]] {
        &self.tris
    }
    pub fn len(&self) -> usize {
        self.tris.len()
    }
    pub fn is_empty(&self) -> bool {
        self.tris.is_empty()
    }
    /// Stage "faces": return 6V (m³) and add n_f of every face to each of its three vertices in `g`.
    #[inline(never)]
    pub fn volume6_and_normals(&self, x: &[f64], g: &mut [f64]) -> f64 {
        assert!(x.len() >= 3 * self.vertex_count && g.len() >= 3 * self.vertex_count);
        volume6_and_normals(&self.tris, x, g)
    }
    /// 6V only (m³).
    pub fn volume6(&self, x: &[f64]) -> f64 {
        volume6(&self.tris, x)
    }
}

impl Faces {
    /// The faces stage for one chunk of vertices (`parforces.rs`): faces `ids` (their smallest
    /// corner in `vr`) add n_f into `g`, the chunk's accumulator (vertex `vr.start` at 0), when
    /// `normals`; n_f for a corner past the chunk goes to the next 3 values of `cross`, in face
    /// then corner order. Returns their part of 6V.
    pub(crate) fn volume6_and_normals_part(&self, ids: &[u32], x: &[f64], vr: std::ops::Range<usize>, g: &mut [f64], cross: &mut [f64], normals: bool) -> f64 {
        let (base, end) = (vr.start, vr.end);
        let mut six_v = 0.0;
        let mut slot = 0;
        for &f in ids {
            let t = self.tris[f as usize];
            let (a, b, c) = (3 * t[0] as usize, 3 * t[1] as usize, 3 * t[2] as usize);
            let (ax, ay, az) = (x[a], x[a + 1], x[a + 2]);
            let (e1x, e1y, e1z) = (x[b] - ax, x[b + 1] - ay, x[b + 2] - az);
            let (e2x, e2y, e2z) = (x[c] - ax, x[c + 1] - ay, x[c + 2] - az);
            let nx = e1y * e2z - e1z * e2y;
            let ny = e1z * e2x - e1x * e2z;
            let nz = e1x * e2y - e1y * e2x;
            six_v += ax * nx + ay * ny + az * nz;
            if normals {
                for &v in &t {
                    let v = v as usize;
                    if v < end {
                        let k = 3 * (v - base);
                        g[k] += nx;
                        g[k + 1] += ny;
                        g[k + 2] += nz;
                    } else {
                        cross[slot..slot + 3].copy_from_slice(&[nx, ny, nz]);
                        slot += 3;
                    }
                }
            }
        }
        six_v
    }
}

/// SAFETY contract: every index in `tris` is below `x.len() / 3` and `g.len() / 3` (guaranteed
/// by [`Faces::new`] and the assertion in [`Faces::volume6_and_normals`]).
#[inline(always)]
fn volume6_and_normals(tris: &[[u32; 3]], x: &[f64], g: &mut [f64]) -> f64 {
    let mut six_v = 0.0;
    for t in tris {
        let (a, b, c) = (3 * t[0] as usize, 3 * t[1] as usize, 3 * t[2] as usize);
        // SAFETY: see the function's contract.
        unsafe {
            let (ax, ay, az) = (*x.get_unchecked(a), *x.get_unchecked(a + 1), *x.get_unchecked(a + 2));
            let e1x = *x.get_unchecked(b) - ax;
            let e1y = *x.get_unchecked(b + 1) - ay;
            let e1z = *x.get_unchecked(b + 2) - az;
            let e2x = *x.get_unchecked(c) - ax;
            let e2y = *x.get_unchecked(c + 1) - ay;
            let e2z = *x.get_unchecked(c + 2) - az;
            let nx = e1y * e2z - e1z * e2y;
            let ny = e1z * e2x - e1x * e2z;
            let nz = e1x * e2y - e1y * e2x;
            six_v += ax * nx + ay * ny + az * nz; // xa · ((xb − xa) × (xc − xa)) = xa · (xb × xc)
            for &p in &[a, b, c] {
                *g.get_unchecked_mut(p) += nx;
                *g.get_unchecked_mut(p + 1) += ny;
                *g.get_unchecked_mut(p + 2) += nz;
            }
        }
    }
    six_v
}

fn volume6(tris: &[[u32; 3]], x: &[f64]) -> f64 {
    let mut six_v = 0.0;
    for t in tris {
        let (a, b, c) = (3 * t[0] as usize, 3 * t[1] as usize, 3 * t[2] as usize);
        let cx = x[b + 1] * x[c + 2] - x[b + 2] * x[c + 1];
        let cy = x[b + 2] * x[c] - x[b] * x[c + 2];
        let cz = x[b] * x[c + 1] - x[b + 1] * x[c];
        six_v += x[a] * cx + x[a + 1] * cy + x[a + 2] * cz;
    }
    six_v
}
