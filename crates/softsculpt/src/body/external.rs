//! External forces on faces: wind and user pressure. Both split a face force equally over its
//! three vertices. With n_f = (xb − xa) × (xc − xa) = 2 · area · n̂:
//!
//! Wind (linear drag, one-sided): a face whose outward normal meets the relative wind
//! u = w − v_face (v_face the mean of its vertex velocities) with u · n̂ < 0 receives
//!   F = cw · area · (u · n̂) n̂ = cw (u · n_f) n_f / (2 |n_f|)      (N)
//! pushing it inward; faces on the lee side (u · n̂ ≥ 0) receive nothing.
//!
//! User pressure p (Pa) on a face: F = −p · area · n̂ = −p n_f / 2 (N), along the inward normal.

use crate::vec3::{cross, dot, get, norm, sub};

pub fn wind(tris: &[[u32; 3]], x: &[f64], v: &[f64], w: [f64; 3], cw: f64, f: &mut [f64]) {
    for t in tris {
        let (a, b, c) = (t[0] as usize, t[1] as usize, t[2] as usize);
        let xa = get(x, a);
        let nf = cross(sub(get(x, b), xa), sub(get(x, c), xa));
        let len = norm(nf);
        if len == 0.0 {
            continue;
        }
        let (va, vb, vc) = (get(v, a), get(v, b), get(v, c));
        let u = [
            w[0] - (va[0] + vb[0] + vc[0]) / 3.0,
            w[1] - (va[1] + vb[1] + vc[1]) / 3.0,
            w[2] - (va[2] + vb[2] + vc[2]) / 3.0,
        ];
        let un = dot(u, nf);
        if un >= 0.0 {
            continue;
        }
        let s = cw * un / (2.0 * len) / 3.0;
        for &p in &[a, b, c] {
            for d in 0..3 {
                f[3 * p + d] += s * nf[d];
            }
        }
    }
}

/// Forces are added multiplied by `scale` (see `forces.rs`).
pub fn face_pressures(tris: &[[u32; 3]], x: &[f64], pressure: &[f64], scale: f64, f: &mut [f64]) {
    for (t, &p) in tris.iter().zip(pressure) {
        if p == 0.0 {
            continue;
        }
        let (a, b, c) = (t[0] as usize, t[1] as usize, t[2] as usize);
        let xa = get(x, a);
        let nf = cross(sub(get(x, b), xa), sub(get(x, c), xa));
        let s = -p / 6.0 * scale;
        for &q in &[a, b, c] {
            for d in 0..3 {
                f[3 * q + d] += s * nf[d];
            }
        }
    }
}
