//! Dense 6×6 block algebra for the coarse levels (`super`): products, the spring, hinge and
//! Galerkin block updates, and the small dense Cholesky factor of the coarsest level.

/// A 6×6 block, row-major.
pub(super) type Blk = [f64; 36];

/// y = B x (6).
#[inline(always)]
pub(super) fn mul6(b: &Blk, x: &[f64; 6]) -> [f64; 6] {
    let mut y = [0.0; 6];
    for p in 0..6 {
        let row = &b[6 * p..6 * p + 6];
        y[p] = row[0] * x[0] + row[1] * x[1] + row[2] * x[2] + row[3] * x[3] + row[4] * x[4] + row[5] * x[5];
    }
    y
}

/// y = B x (6), B in single precision.
#[inline(always)]
pub(super) fn mul6f(b: &[f32; 36], x: &[f64; 6]) -> [f64; 6] {
    let mut y = [0.0; 6];
    for p in 0..6 {
        let mut s = 0.0;
        for q in 0..6 {
            s += b[6 * p + q] as f64 * x[q];
        }
        y[p] = s;
    }
    y
}

#[inline(always)]
pub(super) fn cross(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

/// [r]× (3×3, row-major): [r]× v = r × v.
#[inline(always)]
pub(super) fn skew(r: &[f64; 3]) -> [[f64; 3]; 3] {
    [[0.0, -r[2], r[1]], [r[2], 0.0, -r[0]], [-r[1], r[0], 0.0]]
}

/// blk += s (a P_iᵀ P_j + b w_i w_jᵀ) for a spring (a, b, d) seen from offsets r_i, r_j.
#[inline(always)]
pub(super) fn add_spring(blk: &mut Blk, s: f64, a: f64, b: f64, d: &[f64; 3], ri: &[f64; 3], rj: &[f64; 3]) {
    let (wi, wj) = (cross(ri, d), cross(rj, d));
    let vi = [d[0], d[1], d[2], wi[0], wi[1], wi[2]];
    let vj = [d[0], d[1], d[2], wj[0], wj[1], wj[2]];
    let sb = s * b;
    for p in 0..6 {
        for q in 0..6 {
            blk[6 * p + q] += sb * vi[p] * vj[q];
        }
    }
    if a != 0.0 {
        add_ptp(blk, s * a, ri, rj);
    }
}

/// blk += s P_iᵀ P_j.
#[inline(always)]
pub(super) fn add_ptp(blk: &mut Blk, s: f64, ri: &[f64; 3], rj: &[f64; 3]) {
    let (si, sj) = (skew(ri), skew(rj));
    let rr = ri[0] * rj[0] + ri[1] * rj[1] + ri[2] * rj[2];
    for p in 0..3 {
        blk[6 * p + p] += s;
        for q in 0..3 {
            blk[6 * p + 3 + q] -= s * sj[p][q];
            blk[6 * (3 + p) + q] += s * si[p][q];
            blk[6 * (3 + p) + 3 + q] += s * ((if p == q { rr } else { 0.0 }) - rj[p] * ri[q]);
        }
    }
}

/// A spring's 3×3 block B = a I + b d dᵀ (`system/`).
#[inline(always)]
pub(super) fn spring_block(a: f64, b: f64, d: &[f64; 3]) -> [[f64; 3]; 3] {
    std::array::from_fn(|p| std::array::from_fn(|q| b * d[p] * d[q] + if p == q { a } else { 0.0 }))
}

/// F_i S F_j: the y row zeroed where `row` (vertex i held by the ground), the y column where
/// `col` (vertex j held).
#[inline(always)]
pub(super) fn without_y(mut sm: [[f64; 3]; 3], row: bool, col: bool) -> [[f64; 3]; 3] {
    if row {
        sm[1] = [0.0; 3];
    }
    if col {
        for r in sm.iter_mut() {
            r[1] = 0.0;
        }
    }
    sm
}

/// blk += s P_iᵀ S P_j for a general 3×3 S: [[S, −S R_j], [R_i S, −R_i S R_j]], R = [r]×.
pub(super) fn add_general(blk: &mut Blk, s: f64, sm: &[[f64; 3]; 3], ri: &[f64; 3], rj: &[f64; 3]) {
    let (ri, rj) = (skew(ri), skew(rj));
    let mm = |x: &[[f64; 3]; 3], y: &[[f64; 3]; 3]| {
        let mut z = [[0.0; 3]; 3];
        for p in 0..3 {
            for q in 0..3 {
                z[p][q] = x[p][0] * y[0][q] + x[p][1] * y[1][q] + x[p][2] * y[2][q];
            }
        }
        z
    };
    let (sr, rs) = (mm(sm, &rj), mm(&ri, sm));
    let rsr = mm(&rs, &rj);
    for p in 0..3 {
        for q in 0..3 {
            blk[6 * p + q] += s * sm[p][q];
            blk[6 * p + 3 + q] -= s * sr[p][q];
            blk[6 * (3 + p) + q] += s * rs[p][q];
            blk[6 * (3 + p) + 3 + q] -= s * rsr[p][q];
        }
    }
}

/// blk += P_iᵀ S P_i for a symmetric 3×3 S: [[S, −S R], [R S, −R S R]], R = [r_i]×.
pub(super) fn add_sandwich(blk: &mut Blk, sm: &[[f64; 3]; 3], r: &[f64; 3]) {
    add_general(blk, 1.0, sm, r, r);
}

/// blk += P_uᵀ A P_w, P = [[I, −[r]×], [0, I]] (coarse to coarser).
pub(super) fn add_galerkin(blk: &mut Blk, a: &Blk, ru: &[f64; 3], rw: &[f64; 3]) {
    // X = A P_w: columns 0..3 as A's; columns 3..6: A[:, 3..6] − A[:, 0..3] [r_w]×.
    let sw = skew(rw);
    let mut x = *a;
    for p in 0..6 {
        for q in 0..3 {
            let mut s = 0.0;
            for k in 0..3 {
                s += a[6 * p + k] * sw[k][q];
            }
            x[6 * p + 3 + q] -= s;
        }
    }
    // Pᵀ X: rows 0..3 as X's; rows 3..6: X[3..6, :] + [r_u]× X[0..3, :].
    let su = skew(ru);
    for p in 0..3 {
        for q in 0..6 {
            let mut s = x[6 * (3 + p) + q];
            for k in 0..3 {
                s += su[p][k] * x[6 * k + q];
            }
            blk[6 * (3 + p) + q] += s;
            blk[6 * p + q] += x[6 * p + q];
        }
    }
}

/// In-place Cholesky factor (lower triangle) of the symmetric positive semi-definite n×n
/// matrix `l` (row-major). A pivot at most `pivot` times its diagonal ([`PIVOT`],
/// [`BLOCK_PIVOT`]) is an unknown the matrix does not see: it is marked in `drop` and solved as
/// 0 (a pseudo-inverse on the rest).
pub(super) fn cholesky(l: &mut [f64], n: usize, drop: &mut [bool], pivot: f64) {
    for k in 0..n {
        let diag = l[k * n + k];
        let mut d = diag;
        for q in 0..k {
            d -= l[k * n + q] * l[k * n + q];
        }
        drop[k] = !(d > pivot * diag.abs() && d.is_finite());
        let d = if drop[k] { 0.0 } else { d.sqrt() };
        l[k * n + k] = if drop[k] { 1.0 } else { d };
        for r in k + 1..n {
            if drop[k] {
                l[r * n + k] = 0.0;
                continue;
            }
            let mut s = l[r * n + k];
            for q in 0..k {
                s -= l[r * n + q] * l[k * n + q];
            }
            l[r * n + k] = s / d;
        }
    }
}

/// x = (L Lᵀ)⁺ b with a factor from [`cholesky`].
pub(super) fn cholesky_solve(l: &[f64], n: usize, drop: &[bool], b: &[f64], x: &mut [f64]) {
    for r in 0..n {
        let mut s = b[r];
        for q in 0..r {
            s -= l[r * n + q] * x[q];
        }
        x[r] = if drop[r] { 0.0 } else { s / l[r * n + r] };
    }
    for r in (0..n).rev() {
        let mut s = x[r];
        for q in r + 1..n {
            s -= l[q * n + r] * x[q];
        }
        x[r] = if drop[r] { 0.0 } else { s / l[r * n + r] };
    }
}
