//! Closest points and small transforms shared by the contact stages (obstacles, mesh
//! obstacles, bodies in a world) and by scene placement.

use crate::vec3::{add, cross, dot, scale, sub, V3};

/// Closest point on triangle (a, b, c) to p, as barycentric weights (Ericson, Real-Time
/// Collision Detection, 5.1.5).
pub fn closest_barycentric(p: V3, a: V3, b: V3, c: V3) -> [f64; 3] {
    let (ab, ac, ap) = (sub(b, a), sub(c, a), sub(p, a));
    let (d1, d2) = (dot(ab, ap), dot(ac, ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return [1.0, 0.0, 0.0];
    }
    let bp = sub(p, b);
    let (d3, d4) = (dot(ab, bp), dot(ac, bp));
    if d3 >= 0.0 && d4 <= d3 {
        return [0.0, 1.0, 0.0];
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let v = d1 / (d1 - d3);
        return [1.0 - v, v, 0.0];
    }
    let cp = sub(p, c);
    let (d5, d6) = (dot(ab, cp), dot(ac, cp));
    if d6 >= 0.0 && d5 <= d6 {
        return [0.0, 0.0, 1.0];
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let w = d2 / (d2 - d6);
        return [1.0 - w, 0.0, w];
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return [0.0, 1.0 - w, w];
    }
    let denom = 1.0 / (va + vb + vc);
    let (v, w) = (vb * denom, vc * denom);
    [1.0 - v - w, v, w]
}

/// The closest point on triangle (a, b, c) to p: its barycentric weights and the point.
pub fn closest_on_triangle(p: V3, a: V3, b: V3, c: V3) -> ([f64; 3], V3) {
    let w = closest_barycentric(p, a, b, c);
    (w, add(add(scale(a, w[0]), scale(b, w[1])), scale(c, w[2])))
}

/// Closest points of segments p0p1 and q0q1: parameters (s, t) ∈ [0, 1]² (Ericson, Real-Time
/// Collision Detection, 5.1.9).
pub fn closest_segments(p0: V3, p1: V3, q0: V3, q1: V3) -> (f64, f64) {
    let (d1, d2, r) = (sub(p1, p0), sub(q1, q0), sub(p0, q0));
    let (a, e, f) = (dot(d1, d1), dot(d2, d2), dot(d2, r));
    if a <= 1e-300 && e <= 1e-300 {
        return (0.0, 0.0);
    }
    if a <= 1e-300 {
        return (0.0, (f / e).clamp(0.0, 1.0));
    }
    let c = dot(d1, r);
    if e <= 1e-300 {
        return ((-c / a).clamp(0.0, 1.0), 0.0);
    }
    let b = dot(d1, d2);
    let denom = a * e - b * b;
    let mut s = if denom > 0.0 { ((b * f - c * e) / denom).clamp(0.0, 1.0) } else { 0.0 };
    let mut t = (b * s + f) / e;
    if t < 0.0 {
        t = 0.0;
        s = (-c / a).clamp(0.0, 1.0);
    } else if t > 1.0 {
        t = 1.0;
        s = ((b - c) / a).clamp(0.0, 1.0);
    }
    (s, t)
}

/// The point a fraction s of the way from a to b.
pub fn lerp(a: V3, b: V3, s: f64) -> V3 {
    add(a, scale(sub(b, a), s))
}

/// v turned by the angle whose sine and cosine are (sin, cos) about the unit axis k
/// (Rodrigues' formula: v cos + (k × v) sin + k (k · v)(1 − cos)).
pub fn rotate(v: V3, k: V3, sin: f64, cos: f64) -> V3 {
    add(add(scale(v, cos), scale(cross(k, v), sin)), scale(k, dot(k, v) * (1.0 - cos)))
}
