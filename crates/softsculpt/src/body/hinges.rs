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
//! (positive semi-definite, rank one per hinge, `implicit/system/`) and drops
//! D w (θ − θ̄) ∇²θ, which is indefinite and vanishes at the rest angle.
//!
//! A face crushed below half its frozen height over the edge fades its hinge's force and matrix
//! part out (× Ψ, [`bend`]): there ∇θ and ∇²θ grow as 1/h and 1/h², and Newton could not finish
//! a step.

use crate::mesh::topology;
use crate::vec3::{cross, dot, get, norm, scale, sub, V3};

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
    /// Per hinge, for each of its two faces, the height over the edge relative to the edge,
    /// u = h / |e| = |n| / |e|², below which the face fades the hinge out ([`bend`]):
    /// [`FADE_BELOW`] × the frozen shape's (0: never).
    pub thin: Vec<[f64; 2]>,
}

/// A face thinner over a hinge's edge than this fraction of its frozen height fades the hinge
/// out ([`fade_of`], [`bend`]). Why: θ is the angle of a face about the edge, so ∇_k θ = −n̂₁ / h₁
/// and its curvature D w (θ − θ̄) ∇²θ grow as 1 / h₁² as the face collapses towards its edge:
/// measured on the modeler's mushroom pulled a metre by the strongest grab (BENCHMARKS.md), a
/// face crushed to h / |e| = 7e-4 under hinges bent by 1.8 rad made every Newton direction
/// overshoot 100–1000× along that one vertex, and no step finished even at dt / 16 (with
/// D = 0: 3 Newton iterations). Of nine such steps replayed (`bend`'s fade), a fade below 0.3
/// of the frozen height let 6 finish, below 0.5 all 9, in 5–8 Newton iterations. A face squashed
/// to under half its height over an edge is a crushed fold, where the bending of its edge means
/// little; the hinges of a body that is not crushed are exactly as before.
pub const FADE_BELOW: f64 = 0.5;

/// φ(u) = s √(3 − 2 s), s = u / u₀: the square root of the smoothstep s² (3 − 2 s), so that
/// φ² rises from 0 with slope 0 to 1 with slope 0; 1 from u₀ on or where u₀ = 0.
#[inline(always)]
fn root_smoothstep(u: f64, u0: f64) -> f64 {
    if !(u < u0) {
        return 1.0;
    }
    let s = (u / u0).max(0.0);
    s * (3.0 - 2.0 * s).sqrt()
}

/// A hinge's fade Φ = φ(u₁) φ(u₂) from each face's height over the edge relative to the edge,
/// `u` = h / |e| = |n| / |e|² ([`angle_gradient_heights`]), against `thin` ([`root_smoothstep`]),
/// or `None` where neither face is thinner than its `thin` (Φ = 1).
#[inline(always)]
fn fade_of(u: [f64; 2], thin: [f64; 2]) -> Option<f64> {
    if !(u[0] < thin[0] || u[1] < thin[1]) {
        return None;
    }
    Some(root_smoothstep(u[0], thin[0]) * root_smoothstep(u[1], thin[1]))
}

/// A hinge's bend r (rad) and the gradient g (1/m) its force and matrix use, at its four
/// vertices, or `None` where a face or the edge has no extent: r = θ − θ̄ and g = ∇θ
/// ([`angle_and_gradient`], [`excess`]), each × the fade Φ where a face is crushed ([`fade_of`]).
/// The hinge's force is −D w (r + τ ṙ) g with ṙ = g · v, i.e. −D w Ψ (θ − θ̄ + τ θ̇) ∇θ with
/// Ψ = Φ², and the implicit matrix's part D w g gᵀ = D w Ψ ∇θ ∇θᵀ, its Gauss–Newton part; its
/// energy is reported as ½ D w r².
///
/// Where a face is crushed that force is **not** conservative: it is the unfaded hinge's force
/// scaled by Ψ, without the −½ D w (θ − θ̄)² ∇Ψ an energy ½ D w (θ − θ̄)² Ψ would add. Why: that
/// term pulls a face further into its collapse (the faded energy is lower there), with a
/// stiffness of order D w (θ − θ̄)² / (u₀ |e|)² that the matrix does not have; measured with
/// it, the balloon preset on the octopus subdivided twice, whose tentacle tips crush on the
/// ground, did not converge within 100 Newton iterations (at step 5, and taking its
/// Gauss–Newton part into the matrix, at step 20). Without it the force at a crushed face is
/// bounded (Ψ |∇θ| ≤ 3 / (u₀ |e|) as h → 0), goes to 0 with the face, and still sums to zero
/// with no moment (a scalar times ∇θ). The work the left-out term would have done is
/// −∫ ½ D w (θ − θ̄)² dΨ: each passage of a face into or out of its fade gains or loses at most
/// the hinge's largest ½ D w (θ − θ̄)² on the way (Ψ changes by at most 1), and nothing while
/// no face is crushed.
#[inline(always)]
pub fn bend(x: &[f64], h: &[u32; 4], rest: f64, thin: [f64; 2]) -> Option<(f64, [V3; 4])> {
    bend_crushed(x, h, rest, thin, false).0
}

/// [`bend`], and whether a face of the hinge is crushed (below its `thin`: the hinge fades).
/// `let_go`: a hinge with a crushed face gives nothing at all (`None`, as a degenerate one)
/// instead of its faded force: the implicit integrator's relaxed retry of a step it could not
/// finish (`implicit/mod.rs` `Relaxed`, [`crate::settings::WorldSettings::relax`]).
#[inline(always)]
pub fn bend_crushed(x: &[f64], h: &[u32; 4], rest: f64, thin: [f64; 2], let_go: bool) -> (Option<(f64, [V3; 4])>, bool) {
    let Some((theta, g, u)) = angle_gradient_heights(x, h) else {
        return (None, false);
    };
    let ex = excess(theta, rest);
    match fade_of(u, thin) {
        None => (Some((ex, g)), false),
        Some(_) if let_go => (None, true),
        Some(phi) => (Some((phi * ex, g.map(|gq| scale(gq, phi)))), true),
    }
}

/// A hinge's angle θ (rad) and its gradient ∇θ at its four vertices (1/m), or `None` where a
/// face or the edge has no extent.
#[inline(always)]
pub fn angle_and_gradient(x: &[f64], h: &[u32; 4]) -> Option<(f64, [V3; 4])> {
    angle_gradient_heights(x, h).map(|(theta, g, _)| (theta, g))
}

/// [`angle_and_gradient`], and each face's height over the edge relative to the edge,
/// u = |n| / |e|² (for [`fade_of`]; from the same normals).
#[inline(always)]
fn angle_gradient_heights(x: &[f64], h: &[u32; 4]) -> Option<(f64, [V3; 4], [f64; 2])> {
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
    Some((theta, [gi, gj, gk, gl], [a1.sqrt() / e2, a2.sqrt() / e2]))
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

/// The rest angle a hinge takes from the shape `x`: its angle there, 0 where it has none.
fn rest_angle(x: &[f64], hv: &[u32; 4]) -> f64 {
    angle_and_gradient(x, hv).map_or(0.0, |(t, _)| t)
}

impl Hinges {
    /// The hinges of `tris` (rest angles and weights still zero: [`Hinges::rest_to`]).
    pub fn new(tris: &[[u32; 3]]) -> Self {
        let v = topology::hinges(tris);
        let n = v.len();
        Hinges { v, rest: vec![0.0; n], weight: vec![0.0; n], thin: vec![[0.0; 2]; n] }
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
            let e2 = dot(e, e);
            // |n| of each face: twice its area.
            let n = [norm(cross(e, sub(xk, xi))), norm(cross(sub(xl, xi), e))];
            let w = e2 / (0.5 * (n[0] + n[1]));
            self.weight[h] = if w.is_finite() { w } else { 0.0 };
            self.rest[h] = rest_angle(x, hv);
            self.thin[h] = n.map(|n| n / e2).map(|u| if u.is_finite() { FADE_BELOW * u } else { 0.0 });
        }
    }

    /// Stage "plastic" of the hinges (`plastic.rs`, "Bending"): where a hinge is bent from its
    /// rest angle by more than its yield angle θ_y = κ_y Ā / |e| (κ_y the yield curvature in
    /// 1/m; Ā / |e| at the shape `x`: the two faces' area over the edge, so that θ_y is the angle
    /// a surface of curvature κ_y makes at this hinge, as in the module documentation's
    /// cylinder, θ = κ Ā / |ē|), its rest angle moves the fraction `a` of the way to the angle
    /// that leaves exactly θ_y: with r = θ − θ̄,
    ///   r' = r − a (r − θ_y sign r),     θ̄' = θ − r'.
    /// A hinge with a crushed face (in its fade, [`bend`]) or none (no angle) does not flow: a
    /// crushed fold is no shape to keep. Returns the bending energy released at `x`,
    /// Σ ½ D w (r² − r'²) (J, ≥ 0: |r'| < |r|), D in J.
    pub(crate) fn flow(&mut self, d: f64, kappa_y: f64, a: f64, x: &[f64]) -> f64 {
        let mut released = 0.0;
        for (h, hv) in self.v.iter().enumerate() {
            let w = self.weight[h];
            let Some((theta, _, u)) = angle_gradient_heights(x, hv) else { continue };
            if w == 0.0 || fade_of(u, self.thin[h]).is_some() {
                continue;
            }
            // Ā / |e| = ½ (|n₁| + |n₂|) / |e| = ½ (u₁ + u₂) |e|  (u = |n| / |e|²).
            let le = norm(sub(get(x, hv[1] as usize), get(x, hv[0] as usize)));
            let theta_y = kappa_y * 0.5 * (u[0] + u[1]) * le;
            let r = excess(theta, self.rest[h]);
            if !(r.abs() > theta_y) {
                continue;
            }
            let r2 = r - a * (r - theta_y.copysign(r));
            released += 0.5 * d * w * (r * r - r2 * r2);
            self.rest[h] = excess(theta - r2, 0.0);
        }
        released
    }

    /// Whether every rest angle is the one [`Hinges::rest_to`] gives the shape `x`, bit for bit
    /// (no plastic flow moved them since), without copying anything.
    pub(crate) fn rest_is_of(&self, x: &[f64]) -> bool {
        self.v.iter().zip(&self.rest).all(|(hv, r)| rest_angle(x, hv).to_bits() == r.to_bits())
    }

    /// Bending energy Σ ½ D w r² (J) at `x` (r = θ − θ̄, faded at a crushed face: [`bend`]),
    /// D in J.
    pub fn energy(&self, b: f64, x: &[f64]) -> f64 {
        let mut sum = 0.0;
        for (h, hv) in self.v.iter().enumerate() {
            if let Some((r, _)) = bend(x, hv, self.rest[h], self.thin[h]) {
                sum += self.weight[h] * r * r;
            }
        }
        0.5 * b * sum
    }

    /// Stage "hinges": add f_v = −D w (r + τ ṙ) ∇_v r (N) to `f` (flat xyz), hinge by hinge,
    /// with r = θ − θ̄ (faded at a crushed face: [`bend`]) and ṙ = Σ_u ∇_u r · v_u; D in J, τ
    /// in s.
    pub fn add_forces(&self, b: f64, tau: f64, x: &[f64], v: &[f64], f: &mut [f64]) {
        for (h, hv) in self.v.iter().enumerate() {
            if let Some((r, g)) = bend(x, hv, self.rest[h], self.thin[h]) {
                let s = -b * self.weight[h] * (r + tau * rate(&g, hv, v));
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
    use crate::vec3::add;

    /// Φ of hinge `h` at `x` (`bend`'s fade), `None` where it does not fade or has no angle.
    fn fade(x: &[f64], h: &[u32; 4], thin: [f64; 2]) -> Option<f64> {
        angle_gradient_heights(x, h).and_then(|(_, _, u)| fade_of(u, thin))
    }

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
        let hn = Hinges { v: vec![[0, 1, 2, 3]], rest: vec![0.3], weight: vec![1.7], thin: vec![[0.0; 2]] };
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
        let mut hn = Hinges { v: vec![[0, 1, 2, 3]], rest: vec![0.0], weight: vec![0.0], thin: vec![[0.0; 2]] };
        hn.rest_to(&x);
        assert!(hn.weight[0].is_finite() && hn.rest[0].is_finite());
        let mut f = vec![0.0; 12];
        hn.add_forces(1.0, 0.01, &hinge_x(), &[0.1; 12], &mut f);
        assert!(f.iter().all(|c| c.is_finite()));
        let (mut f, v) = (vec![0.0; 12], vec![0.1; 12]);
        let healthy = Hinges { v: vec![[0, 1, 2, 3]], rest: vec![0.2], weight: vec![1.0], thin: vec![[0.0; 2]] };
        healthy.add_forces(1.0, 0.01, &x, &v, &mut f);
        assert_eq!(f, vec![0.0; 12], "a hinge without area now pushes nothing");
        assert_eq!(healthy.energy(1.0, &x), 0.0);
    }

    /// The hinges' plastic flow (`Hinges::flow`): a hinge bent within its yield angle keeps its
    /// rest angle bit for bit; one bent beyond it moves its rest angle the fraction `a` of the
    /// way to the angle that leaves exactly the yield angle (a = 1: exactly there), on either
    /// side, and releases ½ D w (r² − r'²). θ_y = κ_y Ā / |e| is computed from the hinge's own
    /// shape here to check the formula; tolerances: a few ulps of angles of order 1 rad (1e-14)
    /// and of energies of order 1 J (1e-13).
    #[test]
    fn a_hinge_bent_past_its_yield_angle_flows_toward_it() {
        let x = hinge_x();
        let hv = [0u32, 1, 2, 3];
        let (theta, _) = angle_and_gradient(&x, &hv).unwrap();
        let (e, n1, n2) = {
            let [xi, xj, xk, xl] = hv.map(|v| get(&x, v as usize));
            let e = sub(xj, xi);
            (norm(e), norm(cross(e, sub(xk, xi))), norm(cross(sub(xl, xi), e)))
        };
        let kappa_y = 0.4;
        let theta_y = kappa_y * 0.5 * (n1 + n2) / e;
        let (d, w) = (2.0, 1.7);
        for (bend, a) in [(0.3, 0.25), (-0.5, 0.25), (0.9, 1.0), (0.5 * theta_y, 1.0)] {
            let mut hn = Hinges { v: vec![hv], rest: vec![theta - bend], weight: vec![w], thin: vec![[0.0; 2]] };
            let released = hn.flow(d, kappa_y, a, &x);
            let r2 = excess(theta, hn.rest[0]);
            if bend.abs() <= theta_y {
                assert_eq!(hn.rest[0], theta - bend, "within the yield angle nothing flows");
                assert_eq!(released, 0.0);
                continue;
            }
            let want = bend - a * (bend - theta_y.copysign(bend));
            assert!((r2 - want).abs() < 1e-14, "bend {bend}, a {a}: r' = {r2}, want {want}");
            assert!((released - 0.5 * d * w * (bend * bend - want * want)).abs() < 1e-13, "released {released} J");
            assert!(released > 0.0);
        }
    }

    /// A hinge frozen from `hinge_x` (each face's height over the edge about 0.9 of the edge),
    /// then face (i, j, k) crushed: x_k moved towards the edge's line to `u` of the edge.
    fn crushed(u: f64) -> (Hinges, Vec<f64>) {
        let mut hn = Hinges::new(&[[0, 1, 2], [1, 0, 3]]);
        let x = hinge_x();
        hn.rest_to(&x);
        assert_eq!(hn.v, vec![[0, 1, 2, 3]]);
        let mut y = x.clone();
        // x_k = its foot on the edge + u |e| along its height direction (keeps θ of the rest).
        let (xi, xj, xk) = (get(&x, 0), get(&x, 1), get(&x, 2));
        let e = sub(xj, xi);
        let foot = add(xi, scale(e, dot(sub(xk, xi), e) / dot(e, e)));
        let up = sub(xk, foot);
        let k = add(foot, scale(up, u * norm(e) / norm(up)));
        y[6..9].copy_from_slice(&k);
        (hn, y)
    }

    /// Above half its frozen height a face leaves its hinge as it was (no fade at all); in
    /// the fade the force is the unfaded hinge's × Ψ = Φ², with no net force or moment, and it
    /// stays bounded as the face collapses where the unfaded one grows as 1 / h. Tolerances:
    /// Ψ × f is the same product as the faded force up to the rounding of Φ² against Φ · Φ
    /// (a few ulps of forces of order 10 N here), so 1e-12 N; sums of four forces of order
    /// 10 N (moments: × positions of order 1 m) round to ~1e-14, so 1e-12 there too.
    #[test]
    fn a_crushed_face_scales_its_hinges_force_down_and_keeps_it_bounded() {
        let (hn, x) = crushed(0.7);
        assert!(hn.thin[0][0] > 0.05 && hn.thin[0][1] > 0.05, "{:?}", hn.thin[0]);
        assert!(fade(&hinge_x(), &hn.v[0], hn.thin[0]).is_none() && fade(&x, &hn.v[0], hn.thin[0]).is_none());
        let mut hn = hn;
        hn.rest[0] += 1.3; // bent by 1.3 rad from its rest angle.
        let mut unfaded = hn.clone();
        unfaded.thin[0] = [0.0; 2];
        let v: Vec<f64> = (0..12).map(|k| 0.1 * (k as f64).cos()).collect();
        let mut largest = [0.0f64; 2];
        for u in [0.06, 0.03, 0.005, 1e-4] {
            let (_, x) = crushed(u);
            let phi = fade(&x, &hn.v[0], hn.thin[0]).expect("crushed below half its height");
            assert!(phi > 0.0 && phi < 1.0, "u = {u}: Φ = {phi}");
            let (mut f, mut f0) = (vec![0.0; 12], vec![0.0; 12]);
            hn.add_forces(2.0, 0.01, &x, &v, &mut f);
            unfaded.add_forces(2.0, 0.01, &x, &v, &mut f0);
            for c in 0..12 {
                assert!((f[c] - phi * phi * f0[c]).abs() < 1e-12, "u = {u}, coordinate {c}: {} against Ψ × {}", f[c], f0[c]);
            }
            let (mut sum, mut moment) = ([0.0; 3], [0.0; 3]);
            for q in 0..4 {
                let fq = get(&f, q);
                sum = add(sum, fq);
                moment = add(moment, cross(get(&x, q), fq));
            }
            assert!(sum.iter().chain(&moment).all(|c| c.abs() < 1e-12), "u = {u}: net force {sum:?}, moment {moment:?}");
            largest[0] = largest[0].max(norm(get(&f, 2)));
            largest[1] = largest[1].max(norm(get(&f0, 2)));
        }
        // The crushed apex: unfaded, |f| ∝ 1 / h, 574 N at u = 1e-4; faded, 6.4 N at most
        // (bounded: Ψ |∇θ| ≤ 3 / (u₀ |e|)); asserted with margins of ~2× and ~5×.
        assert!(largest[1] > 300.0 && largest[0] < 30.0, "largest force on the apex: faded {} N, unfaded {} N", largest[0], largest[1]);
    }

    /// Through its face's collapse (x_k crossing the edge's line, where θ jumps by π) a faded
    /// hinge's energy is continuous: it goes to 0 there. Without the fade it jumps by about
    /// ½ D w (π² − ...) at the crossing, over 1 J at D = 2; with it the largest change between
    /// samples 1e-4 of the edge apart is below 1e-2 J: E ≤ ½ D w π² ≈ 20 J and, within the
    /// ±0.02 of the edge sampled here, ψ' ≤ 6 u / u₀² ≈ 0.6 (u₀ ≈ 0.45), so at most
    /// 20 · 0.6 · 1e-4 ≈ 1.2e-3 J.
    #[test]
    fn a_faded_hinges_energy_is_continuous_through_its_faces_collapse() {
        let (mut hn, _) = crushed(0.5);
        hn.rest[0] += 1.3;
        let mut unfaded = hn.clone();
        unfaded.thin[0] = [0.0; 2];
        let (mut jump, mut jump0) = (0.0f64, 0.0f64);
        let mut last: Option<(f64, f64)> = None;
        for q in -200..=200 {
            let (_, x) = crushed(q as f64 * 1e-4);
            let (e, e0) = (hn.energy(2.0, &x), unfaded.energy(2.0, &x));
            if let Some((l, l0)) = last {
                jump = jump.max((e - l).abs());
                jump0 = jump0.max((e0 - l0).abs());
            }
            last = Some((e, e0));
        }
        assert!(jump0 > 1.0, "without the fade the energy jumps: {jump0} J");
        assert!(jump < 1e-2, "with it, at most {jump} J between samples");
    }
}
