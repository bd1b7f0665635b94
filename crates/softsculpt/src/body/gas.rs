//! Gas: the ideal-gas pressure P = nRT / V and its reference state.
//!
//! The force on vertex i is (P − P_ref) ∂V/∂xi (the faces stage gives ∂V/∂xi). P_ref is the
//! pressure of the surroundings: 0 (vacuum) until the first freeze. Freezing sets P_ref to the
//! current P, so that with springs at rest and gas at the surroundings' pressure nothing moves:
//! the frozen shape is an exact equilibrium. Adding gas (or heat) afterwards raises P above
//! P_ref and inflates; removing it deflates. Since P_ref is *set*, never added to, toggling or
//! freezing repeatedly cannot make the body grow (godot#123661).
//!
//! Potential energy of the gas (J), with V0 the volume at the last freeze (or at creation):
//!   E_gas = −nRT ln(V / V0) + P_ref (V − V0)
//! whose gradient −(nRT/V − P_ref) ∂V/∂x is the force above (exact volume mode). Before any
//! freeze P_ref = 0 and this is the textbook −nRT ln(V/V0).

use super::material::VolumeMode;
use std::f64::consts::PI;

/// State of the gas that is not a user parameter.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GasReference {
    /// Pressure of the surroundings P_ref (Pa), set by freeze.
    pub ambient_pressure: f64,
    /// Volume V0 (m³) at which the gas energy is zero.
    pub reference_volume: f64,
}

impl GasReference {
    /// V0 for a body whose volume is now `volume` (m³): that volume, or 1 m³ where there is no
    /// positive one (an open surface — a flat sheet's divergence-theorem volume is exactly 0 —
    /// or an inside-out mesh). Such a body has no gas (`gas.nrt` is refused on an open mesh), so
    /// V0 is then unused, but it must stay a valid reference: a non-positive V0 is refused by
    /// `SoftBody::set_gas_reference` and by a snapshot's restore.
    pub fn volume_for(volume: f64) -> f64 {
        if volume > 0.0 && volume.is_finite() { volume } else { 1.0 }
    }
}

/// The volume the gas law uses (m³): the exact one from the faces stage (`six_v` = 6V), or one
/// of the paper's bounding volumes computed from the positions `x` (flat xyz) and the faces
/// `tris` (the ellipsoid's axes).
pub fn measure(tris: &[[u32; 3]], mode: VolumeMode, six_v: f64, x: &[f64]) -> f64 {
    match mode {
        VolumeMode::Exact => six_v / 6.0,
        VolumeMode::Box => {
            let (lo, hi) = crate::mesh::bounds(x);
            (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2])
        }
        VolumeMode::Sphere => {
            let c = centroid(x);
            let mut r2: f64 = 0.0;
            for p in x.chunks_exact(3) {
                r2 = r2.max((p[0] - c[0]).powi(2) + (p[1] - c[1]).powi(2) + (p[2] - c[2]).powi(2));
            }
            4.0 / 3.0 * PI * r2.sqrt().powi(3)
        }
        VolumeMode::Ellipsoid => ellipsoid(tris, x),
    }
}

/// Mean of the vertices (m).
fn centroid(x: &[f64]) -> [f64; 3] {
    let n = (x.len() / 3).max(1) as f64;
    let mut c = [0.0; 3];
    for p in x.chunks_exact(3) {
        c[0] += p[0];
        c[1] += p[1];
        c[2] += p[2];
    }
    [c[0] / n, c[1] / n, c[2] / n]
}

/// Volume (m³) of the bounding ellipsoid along the principal axes of the body (`tris` over `x`).
///
/// With μ the centroid and C the covariance (m²) of the *solid* the faces enclose, the
/// ellipsoid E_s = { y : (y − μ)ᵀ C⁻¹ (y − μ) ≤ s² } has the body's principal axes, semi-axes
/// s √λk (λk the eigenvalues of C) and volume 4/3 π s³ √det C. The smallest s that encloses
/// every vertex is s² = max_i (xi − μ)ᵀ C⁻¹ (xi − μ). With the Cholesky factor C = L Lᵀ that is
/// max |L⁻¹ (xi − μ)|² and √det C = L00 L11 L22, so no eigenvectors are needed (nothing jumps
/// when two axes swap order). A solid ellipsoid has C = A Aᵀ / 5 for semi-axes matrix A, so for
/// any mesh whose vertices lie on an ellipsoid the result is that ellipsoid, however unevenly
/// the vertices are spread (a vertex-cloud covariance is biased by where vertices crowd: 36 %
/// too large on a latitude–longitude sphere). Homogeneous of degree 3 in the positions like
/// every volume; never smaller than the minimum-volume enclosing ellipsoid.
///
/// The solid's moments, by the divergence theorem over tetrahedra (o, a, b, c) from a point o
/// near the body (the vertex mean, for rounding): with V_t = a · (b × c) / 6 (a, b, c relative
/// to o),  ∫ y dV = V_t (a + b + c) / 4,  ∫ y yᵀ dV = V_t / 20 [a aᵀ + b bᵀ + c cᵀ + (a+b+c)(a+b+c)ᵀ].
/// O(faces + vertices), one pass each, like the sphere mode. A body of no volume or a flat one
/// (C not positive definite) reports 0, which the gas stage reports as a collapse.
///
/// Why not Khachiyan's minimum-volume enclosing ellipsoid: it iterates (hundreds of passes for a
/// 1e-3 volume tolerance) inside every force evaluation, and its result depends on where the
/// iteration stops. See docs/model.md.
fn ellipsoid(tris: &[[u32; 3]], x: &[f64]) -> f64 {
    let o = centroid(x);
    let at = |i: u32| {
        let k = 3 * i as usize;
        [x[k] - o[0], x[k + 1] - o[1], x[k + 2] - o[2]]
    };
    let (mut vol, mut m1, mut m2) = (0.0, [0.0; 3], [0.0; 6]);
    for t in tris {
        let (a, b, c) = (at(t[0]), at(t[1]), at(t[2]));
        let vt = (a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) + a[2] * (b[0] * c[1] - b[1] * c[0])) / 6.0;
        let s = [a[0] + b[0] + c[0], a[1] + b[1] + c[1], a[2] + b[2] + c[2]];
        vol += vt;
        for d in 0..3 {
            m1[d] += vt * s[d] / 4.0;
        }
        let w = vt / 20.0;
        for (k, (i, j)) in [(0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2)].into_iter().enumerate() {
            m2[k] += w * (a[i] * a[j] + b[i] * b[j] + c[i] * c[j] + s[i] * s[j]);
        }
    }
    if !(vol > 0.0) {
        return 0.0;
    }
    let mu = m1.map(|v| v / vol);
    // Covariance about the centroid (upper triangle: xx, xy, xz, yy, yz, zz).
    let m = [
        m2[0] / vol - mu[0] * mu[0],
        m2[1] / vol - mu[0] * mu[1],
        m2[2] / vol - mu[0] * mu[2],
        m2[3] / vol - mu[1] * mu[1],
        m2[4] / vol - mu[1] * mu[2],
        m2[5] / vol - mu[2] * mu[2],
    ];
    // Cholesky C = L Lᵀ.
    let l00 = m[0].sqrt();
    let l10 = m[1] / l00;
    let l20 = m[2] / l00;
    let l11 = (m[3] - l10 * l10).sqrt();
    let l21 = (m[4] - l20 * l10) / l11;
    let l22 = (m[5] - l20 * l20 - l21 * l21).sqrt();
    let det_sqrt = l00 * l11 * l22;
    if !(det_sqrt > 0.0 && det_sqrt.is_finite()) {
        return 0.0;
    }
    // s² = max |L⁻¹ (xi − μ)|², by forward substitution.
    let mut s2: f64 = 0.0;
    for p in x.chunks_exact(3) {
        let d = [p[0] - o[0] - mu[0], p[1] - o[1] - mu[1], p[2] - o[2] - mu[2]];
        let z0 = d[0] / l00;
        let z1 = (d[1] - l10 * z0) / l11;
        let z2 = (d[2] - l20 * z0 - l21 * z1) / l22;
        s2 = s2.max(z0 * z0 + z1 * z1 + z2 * z2);
    }
    4.0 / 3.0 * PI * s2 * s2.sqrt() * det_sqrt
}

/// Gas pressure P = nRT / V (Pa); 0 without gas.
pub fn pressure(nrt: f64, volume: f64) -> f64 {
    if nrt == 0.0 {
        0.0
    } else {
        nrt / volume
    }
}

/// Potential energy of the gas (J), see the module comment.
pub fn energy(nrt: f64, volume: f64, r: &GasReference) -> f64 {
    let log_term = if nrt == 0.0 { 0.0 } else { -nrt * (volume / r.reference_volume).ln() };
    log_term + r.ambient_pressure * (volume - r.reference_volume)
}
