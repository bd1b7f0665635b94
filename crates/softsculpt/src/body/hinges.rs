//! Hinges: bending by the dihedral angle at every interior edge, the same at any mesh
//! resolution (discrete shells: Grinspun et al. 2003; gradients as in Bridson et al. 2003 and
//! Tamstorf & Grinspun 2013).
//!
//! A hinge is an edge (i, j) with its two faces (i, j, k) and (j, i, l) in their winding. With
//! e = x_j − x_i, the faces' normals n₁ = e × (x_k − x_i), n₂ = (x_l − x_i) × e (|n| = twice the
//! face's area) and ê = e / |e|, its **dihedral angle** is the signed angle from n₁ to n₂ about ê:
//!
//!   θ = atan2((n₁ × n₂) · ê, n₁ · n₂)                 (rad; 0 where the faces are flat)
//!
//! **Energy** (J), with D the flexural rigidity (`Material::rigidity`, J = N·m) and θ̄, |ē|, Ā
//! the hinge's angle, edge length and two faces' area in the frozen shape:
//!
//!   E = Σ_hinges ½ D w (θ − θ̄)²,      w = |ē|² / Ā    (dimensionless)
//!
//! (the discrete-shells energy; Grinspun et al. write its weight 3 |ē|² / Ā with their own
//! constant). Why it does not depend on the resolution: on a surface of curvature κ a mesh of
//! edge h has angles θ = O(κ h) and each edge stands for O(h²) of area, so Σ w θ² per unit area
//! is O(κ²) whatever h — where bending springs' flexural rigidity goes as k_b h², 4× weaker per
//! subdivision. Why this w: a plate of near-equilateral faces rolled into a cylinder of radius
//! R with its rows of vertices along the axis keeps every face's normal radial (each face has
//! an edge parallel to the axis), so only the axis-parallel edges bend, each by θ = (√3/2) h / R
//! (the two faces' mid-lines are √3 h/2 apart around the cylinder), with w = h² / (√3 h²/2), one
//! per √3 h²/2 of area: Σ w θ² per unit area = (2/√3)(3/4)(h²/R²) / (√3 h²/2) = 1/R², and
//!
//!   E = ½ D A / R²,
//!
//! Kirchhoff's thin plate in cylindrical bending (D = Y t³ / 12 (1 − ν²) for Young's modulus Y,
//! thickness t). (On doubly curved shapes the mesh's sum has a Gaussian-curvature part with an
//! effective Poisson ratio of its own, not a chosen one.) Measured (`tests/hinges.rs`): that, and the same plate meshed across the axis,
//! at three resolutions each, to within the edges on the plate's ends (which have no hinge).
//!
//! **Gradient** of θ (m⁻¹): rotating face 1 about ê by φ moves x_k by φ h₁ n̂₁ (h₁ = |n₁| / |e|,
//! the height of k over the edge) and turns n̂₁ towards n̂₂ by φ, so ∇_k θ = −n̂₁ / h₁ =
//! −|e| n₁ / |n₁|²; likewise ∇_l θ = −|e| n₂ / |n₂|². θ does not change under a translation
//! (Σ ∇ = 0) or a rotation (Σ x × ∇ = 0), which fixes the edge's ends: with
//! t_k = (x_k − x_i) · e / |e|² and t_l likewise,
//!
//!   ∇_i θ = −(1 − t_k) ∇_k θ − (1 − t_l) ∇_l θ,    ∇_j θ = −t_k ∇_k θ − t_l ∇_l θ.
//!
//! **Force** f_v = −D w (θ − θ̄ + τ θ̇) ∇_v θ on the hinge's four vertices, θ̇ = Σ_u ∇_u θ · v_u:
//! it sums to zero and has no moment, so it conserves momentum and angular momentum. θ − θ̄ is
//! taken in (−π, π]. τ = c_s / k (s) is the material's retardation time, the same as its edges'
//! (a spring's damping c_s against its stiffness k): a Kelvin–Voigt solid, whose bending moment
//! D (κ + τ κ̇) relaxes with the membrane's time. Without it a fold's modes are damped only by
//! the viscous c, and forward Euler, whose amplification on an undamped mode of frequency ω is
//! √(1 + ω² dt²), had no usable step on the modeler's mushroom (1e-6 s); with it a mode is
//! damped at γ = τ ω² / 2, and forward Euler is stable for dt ≤ 2γ / (ω² + γ²), about τ where
//! τ ω ≲ 2 (the page's `stableDt` takes the bound). No τ where k = 0.
//!
//! The implicit integrator's matrix takes the Gauss–Newton part D w ∇θ ∇θᵀ of the Hessian
//! (positive semi-definite, rank one per hinge, `implicit/system.rs`) and drops
//! D w (θ − θ̄) ∇²θ, which is indefinite and vanishes at the rest angle.

use crate::mesh::topology;
use crate::vec3::{cross, dot, get, scale, sub, V3};

/// Every hinge of a mesh, with its rest angle and weight (struct of arrays).
#[derive(Debug, Clone, Default)]
pub struct Hinges {
    /// `[i, j, k, l]`: the edge (i, j), i < j, and the vertices opposite it in face (i, j, k)
    /// and face (j, i, l) (`topology::hinges`).
    pub v: Vec<[u32; 4]>,
    /// Rest angle θ̄ (rad), the angle in the frozen shape.
    pub rest: Vec<f64>,
    /// w = |ē|² / Ā in the frozen shape (dimensionless; 0 for a degenerate hinge there).
    pub weight: Vec<f64>,
}

/// A hinge's angle θ (rad) and its gradient ∇θ at its four vertices (1/m), or `None` where a
/// face or the edge has no extent.
#[inline(always)]
pub fn angle_and_gradient(x: &[f64], h: &[u32; 4]) -> Option<(f64, [V3; 4])> {
    let [xi, xj, xk, xl] = h.map(|v| get(x, v as usize));
    let e = sub(xj, xi);
    let e2 = dot(e, e);
    let n1 = cross(e, sub(xk, xi));
    let n2 = cross(sub(xl, xi), e);
    let (a1, a2) = (dot(n1, n1), dot(n2, n2));
    if !(e2 > 0.0 && a1 > 0.0 && a2 > 0.0) {
        return None;
    }
    let le = e2.sqrt();
    let theta = (dot(cross(n1, n2), e) / le).atan2(dot(n1, n2));
    let gk = scale(n1, -le / a1);
    let gl = scale(n2, -le / a2);
    let tk = dot(sub(xk, xi), e) / e2;
    let tl = dot(sub(xl, xi), e) / e2;
    let gi = [-(1.0 - tk) * gk[0] - (1.0 - tl) * gl[0], -(1.0 - tk) * gk[1] - (1.0 - tl) * gl[1], -(1.0 - tk) * gk[2] - (1.0 - tl) * gl[2]];
    let gj = [-tk * gk[0] - tl * gl[0], -tk * gk[1] - tl * gl[1], -tk * gk[2] - tl * gl[2]];
    Some((theta, [gi, gj, gk, gl]))
}

/// θ̇ = Σ_u ∇_u θ · v_u (rad/s) from the gradient `g` and the velocities `v` (flat xyz).
#[inline(always)]
pub fn rate(g: &[V3; 4], h: &[u32; 4], v: &[f64]) -> f64 {
    let mut r = 0.0;
    for (q, &u) in h.iter().enumerate() {
        r += dot(g[q], get(v, u as usize));
    }
    r
}

/// θ − θ̄ in (−π, π] (rad).
#[inline(always)]
pub fn excess(theta: f64, rest: f64) -> f64 {
    let d = theta - rest;
    if d > std::f64::consts::PI {
        d - 2.0 * std::f64::consts::PI
    } else if d <= -std::f64::consts::PI {
        d + 2.0 * std::f64::consts::PI
    } else {
        d
    }
}

impl Hinges {
    /// The hinges of `tris` (rest angles and weights still zero: [`Hinges::rest_to`]).
    pub fn new(tris: &[[u32; 3]]) -> Self {
        let v = topology::hinges(tris);
        let n = v.len();
        Hinges { v, rest: vec![0.0; n], weight: vec![0.0; n] }
    }

    pub fn len(&self) -> usize {
        self.v.len()
    }
    pub fn is_empty(&self) -> bool {
        self.v.is_empty()
    }

    /// Rest angles and weights from the shape `x` (the frozen shape).
    pub fn rest_to(&mut self, x: &[f64]) {
        for (h, hv) in self.v.iter().enumerate() {
            let [xi, xj, xk, xl] = hv.map(|v| get(x, v as usize));
            let e = sub(xj, xi);
            let area = 0.5 * (crate::vec3::norm(cross(e, sub(xk, xi))) + crate::vec3::norm(cross(sub(xl, xi), e)));
            let w = dot(e, e) / area;
            self.weight[h] = if w.is_finite() { w } else { 0.0 };
            self.rest[h] = angle_and_gradient(x, hv).map_or(0.0, |(t, _)| t);
        }
    }

    /// Bending energy Σ ½ D w (θ − θ̄)² (J) at `x`, D in J.
    pub fn energy(&self, b: f64, x: &[f64]) -> f64 {
        let mut sum = 0.0;
        for (h, hv) in self.v.iter().enumerate() {
            if let Some((t, _)) = angle_and_gradient(x, hv) {
                sum += self.weight[h] * excess(t, self.rest[h]).powi(2);
            }
        }
        0.5 * b * sum
    }

    /// Stage "hinges": add f_v = −D w (θ − θ̄ + τ θ̇) ∇_v θ (N) to `f` (flat xyz), hinge by
    /// hinge; D in J, τ in s.
    pub fn add_forces(&self, b: f64, tau: f64, x: &[f64], v: &[f64], f: &mut [f64]) {
        for (h, hv) in self.v.iter().enumerate() {
            if let Some((t, g)) = angle_and_gradient(x, hv) {
                let s = -b * self.weight[h] * (excess(t, self.rest[h]) + tau * rate(&g, hv, v));
                for (q, &v) in hv.iter().enumerate() {
                    for d in 0..3 {
                        f[3 * v as usize + d] += s * g[q][d];
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A bent, skewed hinge (no symmetry to hide a sign or a swapped vertex).
    fn hinge_x() -> Vec<f64> {
        vec![0.1, -0.05, 0.02, 1.1, 0.2, -0.1, 0.4, 0.9, 0.3, 0.7, -0.6, 0.5]
    }

    /// ∇θ against central differences of θ: the truncation error is h² θ‴ / 6 ≈ 1e-12 at
    /// h = 1e-6 and unit-sized geometry, the rounding ε θ / h ≈ 1e-10; we allow 1e-7.
    #[test]
    fn the_angle_gradient_matches_finite_differences() {
        let x = hinge_x();
        let h = [0u32, 1, 2, 3];
        let (_, g) = angle_and_gradient(&x, &h).unwrap();
        for k in 0..12 {
            let (mut xp, mut xm) = (x.clone(), x.clone());
            xp[k] += 1e-6;
            xm[k] -= 1e-6;
            let fd = (angle_and_gradient(&xp, &h).unwrap().0 - angle_and_gradient(&xm, &h).unwrap().0) / 2e-6;
            assert!((fd - g[k / 3][k % 3]).abs() < 1e-7, "coordinate {k}: {fd} against {}", g[k / 3][k % 3]);
        }
    }

    /// The angle is 0 for a flat hinge, and ± the fold for a folded one: faces (i, j, k) and
    /// (j, i, l) folded by 90° about the edge.
    #[test]
    fn the_angle_is_the_fold_between_the_faces() {
        let flat = vec![0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.5, 1.0, 0.0, 0.5, -1.0, 0.0];
        assert!(angle_and_gradient(&flat, &[0, 1, 2, 3]).unwrap().0.abs() < 1e-15);
        let folded = vec![0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.5, 1.0, 0.0, 0.5, 0.0, 1.0];
        let t = angle_and_gradient(&folded, &[0, 1, 2, 3]).unwrap().0;
        assert!((t.abs() - std::f64::consts::FRAC_PI_2).abs() < 1e-14, "{t}");
    }

    /// Forces sum to zero and have no moment about the origin: translation and rotation leave
    /// θ unchanged. Rounding of sums of terms of size |x| |f| ≈ 10: we allow 1e-12.
    #[test]
    fn hinge_forces_have_no_net_force_or_moment() {
        let x = hinge_x();
        let hn = Hinges { v: vec![[0, 1, 2, 3]], rest: vec![0.3], weight: vec![1.7] };
        let mut f = vec![0.0; 12];
        let v: Vec<f64> = (0..12).map(|k| 0.1 * (k as f64).sin()).collect();
        hn.add_forces(2.0, 0.01, &x, &v, &mut f);
        let (mut sum, mut moment) = ([0.0; 3], [0.0; 3]);
        for v in 0..4 {
            let (xv, fv) = (get(&x, v), get(&f, v));
            let m = cross(xv, fv);
            for d in 0..3 {
                sum[d] += fv[d];
                moment[d] += m[d];
            }
        }
        assert!(sum.iter().chain(&moment).all(|c| c.abs() < 1e-12), "{sum:?} {moment:?}");
        assert!(f.iter().any(|c| c.abs() > 0.1), "a bent hinge pushes");
    }

    /// A hinge frozen with a face of no area gets a finite weight and rest angle (0 if both
    /// faces have none), and one whose face has no area at a step pushes nothing: nothing
    /// becomes NaN.
    #[test]
    fn a_degenerate_hinge_is_harmless() {
        // Face (i, j, k) with k on the edge: no area.
        let x = vec![0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.5, 0.0, 0.0, 0.5, -1.0, 0.3];
        let mut hn = Hinges { v: vec![[0, 1, 2, 3]], rest: vec![0.0], weight: vec![0.0] };
        hn.rest_to(&x);
        assert!(hn.weight[0].is_finite() && hn.rest[0].is_finite());
        let mut f = vec![0.0; 12];
        hn.add_forces(1.0, 0.01, &hinge_x(), &[0.1; 12], &mut f);
        assert!(f.iter().all(|c| c.is_finite()));
        let (mut f, v) = (vec![0.0; 12], vec![0.1; 12]);
        let healthy = Hinges { v: vec![[0, 1, 2, 3]], rest: vec![0.2], weight: vec![1.0] };
        healthy.add_forces(1.0, 0.01, &x, &v, &mut f);
        assert_eq!(f, vec![0.0; 12], "a hinge without area now pushes nothing");
        assert_eq!(healthy.energy(1.0, &x), 0.0);
    }
}
