//! The tension that holds a shape: spring tensions t_e (N) that balance given loads f_i (N) at
//! every free vertex of the current shape, as small as possible (Σ t² / k). What
//! [`SoftBody::freeze_keeping_tension`](super::SoftBody) solves for, as the change of tension
//! that cancels the net force the current rest lengths leave (f = that net force).
//!
//! Spring e joins i and j, l_e = |x_j − x_i|, d_e = (x_j − x_i) / l_e, stiffness k_e (edge or
//! bending). A tension t_e = k_e (l_e − L_e) pulls i by +t_e d_e and j by −t_e d_e; in matrix
//! form the springs' forces are A t, with A (3n × E) holding +d_e in rows i and −d_e in rows j.
//! The problem (rows of pinned vertices, and the vertical rows of vertices resting on a
//! support, are dropped: the support takes those components):
//!
//!   minimise  Σ_e t_e² / (2 k_e)   (the elastic energy, J; = Σ ½ k_e (L_e − l_e)²)
//!   subject to  A t + f = 0          (every free row balanced)
//!
//! Its Lagrange conditions give t = K Aᵀ u for a multiplier u (3n, m) that solves
//!
//!   (A K Aᵀ) u = −f                                                   (N)
//!
//! A K Aᵀ = Σ_e k_e d_e d_eᵀ ⊗ [[1, −1], [−1, 1]] is the axial stiffness matrix of the spring
//! network (u reads as the displacement whose linear response is that tension). It is
//! symmetric positive semi-definite: rigid motions of an unsupported body and mechanisms (a
//! vertex whose springs all lie in a plane cannot be pushed across it by tensions) are its
//! null space. The loads of a closed body's gas have zero resultant force and moment, so they
//! are compatible with the rigid motions; a mechanism's share of a load cannot be balanced by
//! any tension and is what remains as the residual. Solved by the conjugate gradient with a
//! block-Jacobi preconditioner on A K Aᵀ + ε diag(A K Aᵀ) (ε = [`REGULARISATION`], which keeps
//! the mechanism directions bounded: they change u, never t = K Aᵀ u), to a relative residual
//! of [`TOLERANCE`]: the balance must be as exact as the spring forces' own rounding
//! (~ε k |x| per spring), since the implicit step takes anything above its rounding estimate
//! for motion to resolve, and Newton iterating on rounding does not converge.

use super::Springs;

/// Relative regularisation ε of the matrix's diagonal (dimensionless).
pub(crate) const REGULARISATION: f64 = 1e-15;
/// The conjugate gradient stops at ‖r‖ ≤ TOLERANCE ‖f‖ (dimensionless).
pub(crate) const TOLERANCE: f64 = 1e-15;
/// Most conjugate-gradient iterations.
pub(crate) const MAX_ITERATIONS: usize = 20_000;

/// One kind of springs and its stiffness (N/m); a zero stiffness carries nothing.
pub(crate) struct SpringSet<'a> {
    pub springs: &'a Springs,
    pub k: f64,
}

/// Tensions (N) per spring of each set, and the conjugate-gradient iterations taken.
pub(crate) struct Tensions {
    pub t: Vec<Vec<f64>>,
    pub iterations: usize,
}

/// The least-energy tensions of `sets` at positions `x` (flat xyz) balancing the loads `f` (N,
/// flat xyz) on every row where `free` is true.
pub(crate) fn balance(sets: &[SpringSet], x: &[f64], f: &[f64], free: &[bool]) -> Tensions {
    let n3 = x.len();
    // Unit directions and lengths per spring.
    let dirs: Vec<Vec<[f64; 3]>> = sets
        .iter()
        .map(|s| {
            (0..s.springs.len())
                .map(|e| {
                    let (a, b) = (3 * s.springs.i[e] as usize, 3 * s.springs.j[e] as usize);
                    let d = [x[b] - x[a], x[b + 1] - x[a + 1], x[b + 2] - x[a + 2]];
                    let l = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
                    if l > 0.0 { [d[0] / l, d[1] / l, d[2] / l] } else { [0.0; 3] }
                })
                .collect()
        })
        .collect();
    // y = H u on the free rows (0 elsewhere), H = A K Aᵀ + ε diag.
    let apply = |u: &[f64], y: &mut [f64]| {
        y.fill(0.0);
        for (s, ds) in sets.iter().zip(&dirs) {
            if s.k == 0.0 {
                continue;
            }
            for (e, d) in ds.iter().enumerate() {
                let (a, b) = (3 * s.springs.i[e] as usize, 3 * s.springs.j[e] as usize);
                let mut w = 0.0;
                for c in 0..3 {
                    let ua = if free[a + c] { u[a + c] } else { 0.0 };
                    let ub = if free[b + c] { u[b + c] } else { 0.0 };
                    w += d[c] * (ua - ub);
                }
                let t = s.k * w;
                for c in 0..3 {
                    y[a + c] += t * d[c];
                    y[b + c] -= t * d[c];
                }
            }
        }
        for (yk, &fr) in y.iter_mut().zip(free) {
            if !fr {
                *yk = 0.0;
            }
        }
    };
    // Block-Jacobi preconditioner: the inverse of each vertex's 3×3 diagonal block (free rows).
    let n = n3 / 3;
    let mut blocks = vec![[[0.0f64; 3]; 3]; n];
    for (s, ds) in sets.iter().zip(&dirs) {
        for (e, d) in ds.iter().enumerate() {
            for v in [s.springs.i[e] as usize, s.springs.j[e] as usize] {
                for r in 0..3 {
                    for c in 0..3 {
                        blocks[v][r][c] += s.k * d[r] * d[c];
                    }
                }
            }
        }
    }
    let mut diag = vec![0.0; n3];
    let mut inv = vec![[[0.0f64; 3]; 3]; n];
    for v in 0..n {
        let mut b = blocks[v];
        for r in 0..3 {
            b[r][r] *= 1.0 + REGULARISATION;
            diag[3 * v + r] = REGULARISATION * blocks[v][r][r];
            for c in 0..3 {
                if !(free[3 * v + r] && free[3 * v + c]) {
                    b[r][c] = if r == c { 1.0 } else { 0.0 };
                }
            }
        }
        inv[v] = invert3(&b);
    }
    let precondition = |r: &[f64], z: &mut [f64]| {
        for v in 0..n {
            for a in 0..3 {
                z[3 * v + a] = if free[3 * v + a] { (0..3).map(|c| inv[v][a][c] * r[3 * v + c]).sum() } else { 0.0 };
            }
        }
    };
    // Conjugate gradient on H u = −f (free rows).
    let rhs: Vec<f64> = (0..n3).map(|k| if free[k] { -f[k] } else { 0.0 }).collect();
    let norm_b = dot(&rhs, &rhs).sqrt();
    let mut u = vec![0.0; n3];
    let mut r = rhs.clone();
    let mut z = vec![0.0; n3];
    precondition(&r, &mut z);
    let mut p = z.clone();
    let mut q = vec![0.0; n3];
    let mut rz = dot(&r, &z);
    let mut iterations = 0;
    while iterations < MAX_ITERATIONS && dot(&r, &r).sqrt() > TOLERANCE * norm_b {
        apply(&p, &mut q);
        for k in 0..n3 {
            q[k] += diag[k] * p[k];
        }
        let pq = dot(&p, &q);
        if !(pq > 0.0 && pq.is_finite()) {
            break;
        }
        let alpha = rz / pq;
        for k in 0..n3 {
            u[k] += alpha * p[k];
            r[k] -= alpha * q[k];
        }
        precondition(&r, &mut z);
        let rz_new = dot(&r, &z);
        let beta = rz_new / rz;
        rz = rz_new;
        for k in 0..n3 {
            p[k] = z[k] + beta * p[k];
        }
        iterations += 1;
    }
    // t = K Aᵀ u.
    let t = sets
        .iter()
        .zip(&dirs)
        .map(|(s, ds)| {
            ds.iter()
                .enumerate()
                .map(|(e, d)| {
                    let (a, b) = (3 * s.springs.i[e] as usize, 3 * s.springs.j[e] as usize);
                    let w: f64 = (0..3).map(|c| d[c] * ((if free[a + c] { u[a + c] } else { 0.0 }) - (if free[b + c] { u[b + c] } else { 0.0 }))).sum();
                    s.k * w
                })
                .collect()
        })
        .collect();
    Tensions { t, iterations }
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Inverse of a symmetric 3×3 matrix; a singular one gives its pseudo-inverse's stand-in 0.
fn invert3(m: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
    let c = [
        [m[1][1] * m[2][2] - m[1][2] * m[2][1], m[0][2] * m[2][1] - m[0][1] * m[2][2], m[0][1] * m[1][2] - m[0][2] * m[1][1]],
        [m[1][2] * m[2][0] - m[1][0] * m[2][2], m[0][0] * m[2][2] - m[0][2] * m[2][0], m[0][2] * m[1][0] - m[0][0] * m[1][2]],
        [m[1][0] * m[2][1] - m[1][1] * m[2][0], m[0][1] * m[2][0] - m[0][0] * m[2][1], m[0][0] * m[1][1] - m[0][1] * m[1][0]],
    ];
    let det = m[0][0] * c[0][0] + m[0][1] * c[1][0] + m[0][2] * c[2][0];
    if !(det.abs() > 0.0) || !det.is_finite() {
        let mut out = [[0.0; 3]; 3];
        for r in 0..3 {
            out[r][r] = if m[r][r] > 0.0 { 1.0 / m[r][r] } else { 0.0 };
        }
        return out;
    }
    let mut out = [[0.0; 3]; 3];
    for r in 0..3 {
        for k in 0..3 {
            out[r][k] = c[r][k] / det;
        }
    }
    out
}
