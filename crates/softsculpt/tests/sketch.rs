//! Sketch a silhouette, get a balloon: an outline becomes a closed body that gas inflates.

use softsculpt::sketch::{outline, sketch, Outline};
use softsculpt::vec3::{cross, dot, get, sub, V3};
use softsculpt::TriMesh;
use std::f64::consts::PI;

/// A five-pointed star, outer radius 1 m, inner 0.45 m.
fn star() -> Vec<[f64; 2]> {
    (0..10).map(|k| { let r = if k % 2 == 0 { 1.0 } else { 0.45 }; let a = PI / 2.0 + PI * k as f64 / 5.0; [r * a.cos(), r * a.sin()] }).collect()
}

/// A crescent: the unit disk less a disk of radius 0.8 centred at (0.45, 0), as a polygon of 80
/// points (outer arc, then the inner arc back).
fn crescent() -> Vec<[f64; 2]> {
    // The circles meet where x² + y² = 1 and (x − 0.45)² + y² = 0.64: x = (1 − 0.64 + 0.2025) / 0.9.
    let xm: f64 = (1.0 - 0.64 + 0.2025) / 0.9;
    let (outer, inner) = ((1.0 - xm * xm).sqrt().atan2(xm), (1.0 - xm * xm).sqrt().atan2(xm - 0.45));
    let mut p = Vec::new();
    for k in 0..=40 {
        let a = outer + (2.0 * PI - 2.0 * outer) * k as f64 / 40.0;
        p.push([a.cos(), a.sin()]);
    }
    for k in 1..40 {
        let a = 2.0 * PI - inner - (2.0 * PI - 2.0 * inner) * k as f64 / 40.0;
        p.push([0.45 + 0.8 * a.cos(), 0.8 * a.sin()]);
    }
    p
}

/// Area of the body's shadow on the xy plane (m²): rasterized on a fine grid (cell h: the error
/// is below perimeter · h ≈ 0.3 % here).
fn silhouette_area(m: &TriMesh) -> f64 {
    let (lo, hi) = m.bounds();
    let n = 600usize;
    let h = (hi[0] - lo[0]).max(hi[1] - lo[1]) / n as f64;
    let (nx, ny) = (((hi[0] - lo[0]) / h) as usize + 2, ((hi[1] - lo[1]) / h) as usize + 2);
    let mut inside = vec![false; nx * ny];
    for t in &m.triangles {
        let p: Vec<V3> = t.iter().map(|&i| get(&m.positions, i as usize)).collect();
        let (x0, x1) = (p.iter().map(|q| q[0]).fold(f64::INFINITY, f64::min), p.iter().map(|q| q[0]).fold(f64::NEG_INFINITY, f64::max));
        let (y0, y1) = (p.iter().map(|q| q[1]).fold(f64::INFINITY, f64::min), p.iter().map(|q| q[1]).fold(f64::NEG_INFINITY, f64::max));
        let e = |a: V3, b: V3, x: f64, y: f64| (b[0] - a[0]) * (y - a[1]) - (b[1] - a[1]) * (x - a[0]);
        for i in ((x0 - lo[0]) / h) as usize..=((x1 - lo[0]) / h) as usize + 1 {
            for j in ((y0 - lo[1]) / h) as usize..=((y1 - lo[1]) / h) as usize + 1 {
                let (x, y) = (lo[0] + (i as f64 + 0.5) * h, lo[1] + (j as f64 + 0.5) * h);
                let (a, b, c) = (e(p[0], p[1], x, y), e(p[1], p[2], x, y), e(p[2], p[0], x, y));
                if i < nx && j < ny && ((a >= 0.0 && b >= 0.0 && c >= 0.0) || (a <= 0.0 && b <= 0.0 && c <= 0.0)) {
                    inside[i * ny + j] = true;
                }
            }
        }
    }
    inside.iter().filter(|&&b| b).count() as f64 * h * h
}

/// Does any edge pierce a triangle it does not touch? (Segment–triangle test: the segment's ends
/// on opposite sides of the plane, and the crossing inside all three edges.)
fn self_intersects(m: &TriMesh) -> bool {
    let p = |i: u32| get(&m.positions, i as usize);
    for e in softsculpt::mesh::topology::edges(&m.triangles) {
        let (a, b) = (p(e[0]), p(e[1]));
        for t in &m.triangles {
            if t.contains(&e[0]) || t.contains(&e[1]) {
                continue;
            }
            let (u, v, w) = (p(t[0]), p(t[1]), p(t[2]));
            let n = cross(sub(v, u), sub(w, u));
            let (da, db) = (dot(n, sub(a, u)), dot(n, sub(b, u)));
            if da * db >= 0.0 {
                continue;
            }
            let s = da / (da - db);
            let x = [a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1]), a[2] + s * (b[2] - a[2])];
            let side = |q: V3, r: V3| dot(cross(sub(r, q), sub(x, q)), n);
            if side(u, v) >= 0.0 && side(v, w) >= 0.0 && side(w, u) >= 0.0 {
                return true;
            }
        }
    }
    false
}

fn check_balloon(name: &str, points: &[[f64; 2]]) {
    let o = Outline::new(points).unwrap();
    let s = sketch(&o, None, None).unwrap();
    let m = &s.mesh;
    let c = m.edge_counts();
    let (area, shadow) = (o.area(), silhouette_area(m));
    let (lo, hi) = m.bounds();
    eprintln!(
        "{name}: L {:.4} m, {} vertices, {} faces, nRT {:.3} J, {} steps (rest {}), volume {:.4} -> {:.4} m³, thickness {:.3} m, outline {area:.4} m², silhouette {shadow:.4} m² ({:+.2} %)",
        s.edge, m.vertex_count(), m.triangles.len(), s.nrt, s.steps, s.at_rest, s.pillow.volume(), m.volume(), hi[2] - lo[2], 100.0 * (shadow / area - 1.0)
    );
    assert!(s.at_rest, "{name}: came to rest");
    assert!(c.boundary == 0 && c.non_manifold == 0 && c.inconsistent == 0, "{name}: {c:?}");
    assert!(m.volume() > 0.0, "{name}: outward with positive volume");
    assert!(m.volume() > s.pillow.volume(), "{name}: the gas inflated it");
    assert!(!self_intersects(m), "{name}: intersects itself");
    assert!((shadow / area - 1.0).abs() < 0.05, "{name}: silhouette {shadow} vs outline {area}");
}

#[test]
fn a_star_becomes_a_closed_inflated_balloon_of_its_silhouette() {
    check_balloon("star", &star());
}

#[test]
fn a_crescent_becomes_a_closed_inflated_balloon_of_its_silhouette() {
    check_balloon("crescent", &crescent());
}

#[test]
fn bad_outlines_are_refused_with_a_clear_message() {
    let cases: Vec<(Vec<[f64; 2]>, &str)> = vec![
        (vec![[0.0, 0.0], [1.0, 0.0]], "at least 3"),
        (vec![[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [0.0, 0.0]], "no area"),
        (vec![[0.0, 0.0], [1.0, 1.0], [1.0, 0.0], [0.0, 1.0]], "crosses itself"), // a bow tie
    ];
    for (p, says) in cases {
        let e = Outline::new(&p).unwrap_err().to_string();
        assert!(e.contains(says), "{p:?}: {e}");
    }
    let e = outline::parse("0 0\n1 0\n1 x\n").unwrap_err().to_string();
    assert!(e.contains("line 3") && e.contains("'x'"), "{e}");
    let e = outline::parse("0 0 0\n").unwrap_err().to_string();
    assert!(e.contains("two numbers"), "{e}");
}
