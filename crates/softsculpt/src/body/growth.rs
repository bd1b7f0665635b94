//! Local growth (the inflate brush, [`SoftBody::scale_rest_lengths_by_vertex`]): per-vertex
//! growth factors become rest-length factors, spread first where the mesh is too coarse to show
//! them, so that a brush a few edges wide raises a rounded bulge and not a spike.
//!
//! **The law.** Each vertex is asked to grow by the factor f_i (dimensionless, > 0; its growth
//! is f_i − 1). Each spring (i, j) — edge or bending spring — has its rest length multiplied by
//! the mean ½ (f_i + f_j) of its ends' factors. Before that, while the field is sharper than the
//! mesh can carry — two neighbours' factors differ by more than [`RESOLVED_JUMP`] × the largest
//! growth |f − 1| — it is spread by passes of an explicit diffusion on the edges,
//!   f_i += β Σ_j c_ij (f_j − f_i) / A_i,   β = ½,   c_ij = min(A_i / n_i, A_j / n_j)   (m²),
//! A_i a third of the area of vertex i's faces (m²) and n_i its number of edges, at most
//! [`MAX_PASSES`] passes. c is symmetric, so Σ A_i (f_i − 1) — half the area the growth adds,
//! to first order — is kept: the spread moves growth, it neither adds nor removes any; and
//! Σ_j c_ij ≤ A_i, so each pass makes every f_i a weighted mean of itself (weight ≥ ½) and its
//! neighbours: no new extremes, no shrinking where only growth was asked for, every f > 0. A
//! uniform field, or one smooth on the scale of the edges, is left exactly as it is (bit for
//! bit: the rest lengths change as they did before the spread existed).
//!
//! **Why** (issue #37): the modeler's inflate brush, weight (1 − (d/r)²)² of radius r = 0.35 m,
//! on the 362-vertex mushroom (edges ≈ 0.25 m) covers one vertex at weight 1 and two or three
//! more above 0.5: the growth lands on one vertex's star, whose edges lengthen far more than the
//! ring around it, and the only shape with those lengths is a cone — a pyramid of flat faces
//! (measured: held 2 s, the faces round it turned by up to 54° against their neighbours; the
//! same with the hinges off, so not their rest angles; 27° at 1,442 vertices). The same growth
//! spread over a brush of twice the radius turned them by 9–11°. The falloff's steepest slope is
//! 1.54 / r of its peak, so neighbours h apart differ by at most 1.54 h / r of it: a jump of
//! [`RESOLVED_JUMP`] = 0.6 is a brush of r ≥ 2.6 h, which is left alone (the 642-vertex sphere,
//! r ≈ 2.3–2.6 h, unchanged bit for bit), and a narrower one acts as if about that wide.

use crate::vec3::{cross, get, norm, sub};

/// The largest difference of two neighbours' factors, as a fraction of the largest growth
/// |f − 1|, of a field the mesh carries as it is (module documentation).
pub const RESOLVED_JUMP: f64 = 0.6;

/// At most this many passes of the spreading diffusion (each widens the field by about an edge).
pub const MAX_PASSES: usize = 8;

/// The share of its neighbours' difference a vertex's factor takes per pass (β).
const RATE: f64 = 0.5;

/// Spread the factors `f` (per vertex) over the mesh of triangles `tris` with edges
/// (`i`, `j`) at positions `x` (flat xyz, m), as the module documentation says.
pub fn spread(f: &mut [f64], tris: &[[u32; 3]], edges: (&[u32], &[u32]), x: &[f64]) {
    let n = f.len();
    let sharp = |f: &[f64]| {
        let peak = f.iter().fold(0.0f64, |m, v| m.max((v - 1.0).abs()));
        let jump = edges.0.iter().zip(edges.1).fold(0.0f64, |m, (&i, &j)| m.max((f[i as usize] - f[j as usize]).abs()));
        jump > RESOLVED_JUMP * peak
    };
    if !sharp(f) {
        return;
    }
    let mut area = vec![0.0; n];
    for t in tris {
        let (a, b, c) = (get(x, t[0] as usize), get(x, t[1] as usize), get(x, t[2] as usize));
        let third = norm(cross(sub(b, a), sub(c, a))) / 6.0;
        for &v in t {
            area[v as usize] += third;
        }
    }
    let mut degree = vec![0u32; n];
    for (&i, &j) in edges.0.iter().zip(edges.1) {
        degree[i as usize] += 1;
        degree[j as usize] += 1;
    }
    let c: Vec<f64> = edges.0.iter().zip(edges.1).map(|(&i, &j)| (area[i as usize] / degree[i as usize] as f64).min(area[j as usize] / degree[j as usize] as f64)).collect();
    let mut flux = vec![0.0; n];
    for pass in 0..MAX_PASSES {
        if pass > 0 && !sharp(f) {
            break;
        }
        flux.fill(0.0);
        for (e, (&i, &j)) in edges.0.iter().zip(edges.1).enumerate() {
            let q = c[e] * (f[j as usize] - f[i as usize]);
            flux[i as usize] += q;
            flux[j as usize] -= q;
        }
        for ((fi, q), a) in f.iter_mut().zip(&flux).zip(&area) {
            if *a > 0.0 {
                *fi += RATE * q / a;
            }
        }
    }
}
