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
        let tris: Vec<[u32; 3]> = self.tris.iter().map(|t| t.map(|v| 3 * v)).collect();
        // SAFETY: every corner is a vertex (`Faces::new`), asserted lengths.
        unsafe { volume6_and_normals_at::<true>(&tris, x, g) }
    }
    /// 6V only (m³).
    pub fn volume6(&self, x: &[f64]) -> f64 {
        volume6(&self.tris, x)
    }
}

impl Faces {
    /// Pass A of the chunked stages (`parforces.rs`) on chunk c of `local`, vertices `vr`:
    /// returns the part of 6V of its faces, interior (every corner in `vr`) and `crossing`
    /// (smallest corner in `vr`, another past it; global corners). With `normals`, sets `g`
    /// (the chunk's Σ n_f, vertex `vr.start` at 0) to the sum over these faces, and puts n_f
    /// for a corner past the chunk in the next 3 values of `cross` (face, then corner order).
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn volume6_and_normals_part(&self, local: &LocalFaces, c: usize, crossing: &[[u32; 3]], x: &[f64], vr: std::ops::Range<usize>, g: &mut [f64], cross: &mut [f64], normals: bool) -> f64 {
        let (base, len) = (vr.start, vr.len());
        assert!(x.len() >= 3 * self.vertex_count && g.len() == 3 * len && vr.end <= self.vertex_count && local.chunk_len[c] as usize == len);
        let xl = &x[3 * base..3 * vr.end];
        let interior = &local.tris[local.start[c] as usize..local.start[c + 1] as usize];
        let mut slot = 0;
        let mut six_c = 0.0;
        // 6V is summed in the same order with the same operations with or without normals (a
        // freeze and the step must agree on it to the bit, `SoftBody::step_volume`).
        if !normals {
            for t in crossing {
                six_c += normal(t.map(|v| 3 * v as usize), x).1;
            }
            // SAFETY: interior corners are below the chunk's length (`LocalFaces::new`).
            return unsafe { volume6_and_normals_at::<false>(interior, xl, &mut []) } + six_c;
        }
        g.fill(0.0);
        // SAFETY: as above; `g` has the chunk's length too.
        let six_v = unsafe { volume6_and_normals_at::<true>(interior, xl, g) };
        for t in crossing {
            let (n, six) = normal(t.map(|v| 3 * v as usize), x);
            six_c += six;
            for &v in t {
                let k = (v as usize).wrapping_sub(base);
                if k < len {
                    for d in 0..3 {
                        g[3 * k + d] += n[d];
                    }
                } else {
                    cross[slot..slot + 3].copy_from_slice(&n);
                    slot += 3;
                }
            }
        }
        six_v + six_c
    }
}

/// Faces in chunk-local form for [`Faces::volume6_and_normals_part`]: chunk c's interior faces
/// are `tris[start[c]..start[c + 1]]`, each corner as 3 × its chunk-local index (below
/// `chunk_len[c]`, checked by `new`).
#[derive(Debug, Clone, Default)]
pub(crate) struct LocalFaces {
    start: Vec<u32>,
    tris: Vec<[u32; 3]>,
    chunk_len: Vec<u32>,
}

impl LocalFaces {
    /// For the chunks (first vertex, vertex count, faces with every corner in it). Panics if a
    /// corner is outside its chunk.
    pub fn new<'a>(chunks: impl Iterator<Item = (usize, usize, &'a [[u32; 3]])>) -> Self {
        let mut l = LocalFaces { start: vec![0], ..Default::default() };
        for (base, len, tris) in chunks {
            for t in tris {
                let local = t.map(|v| (v as usize).wrapping_sub(base));
                assert!(local.iter().all(|&k| k < len), "an interior face has every corner in its chunk");
                l.tris.push(local.map(|k| 3 * k as u32));
            }
            l.start.push(l.tris.len() as u32);
            l.chunk_len.push(len as u32);
        }
        l
    }
}

/// n_f = (xb − xa) × (xc − xa) and xa · n_f (= 6 × the face's signed volume from the origin) of
/// the face with corners at `t` = (3a, 3b, 3c) in `x`.
#[inline(always)]
fn normal(t: [usize; 3], x: &[f64]) -> ([f64; 3], f64) {
    let [a, b, c] = t;
    let (ax, ay, az) = (x[a], x[a + 1], x[a + 2]);
    let (e1x, e1y, e1z) = (x[b] - ax, x[b + 1] - ay, x[b + 2] - az);
    let (e2x, e2y, e2z) = (x[c] - ax, x[c + 1] - ay, x[c + 2] - az);
    let nx = e1y * e2z - e1z * e2y;
    let ny = e1z * e2x - e1x * e2z;
    let nz = e1x * e2y - e1y * e2x;
    ([nx, ny, nz], ax * nx + ay * ny + az * nz)
}

/// 6V of `tris` (corners as 3 × vertex index) over `x`, and with `NORMALS` Σ n_f per vertex
/// added into `g`.
///
/// # Safety
/// Every corner + 2 is below `x.len()`, and with `NORMALS` below `g.len()`.
#[inline(always)]
unsafe fn volume6_and_normals_at<const NORMALS: bool>(tris: &[[u32; 3]], x: &[f64], g: &mut [f64]) -> f64 {
    let mut six_v = 0.0;
    for t in tris {
        let (a, b, c) = (t[0] as usize, t[1] as usize, t[2] as usize);
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
        if NORMALS {
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
