//! The outline of a sketch: a closed polygon in the plane, read from text (`x y` per line,
//! metres), checked (enough points, an area, no self-intersection) and resampled to a spacing.

use crate::error::MeshError;

/// A closed polygon, counter-clockwise, without a repeated closing point.
#[derive(Debug, Clone, PartialEq)]
pub struct Outline {
    pub points: Vec<[f64; 2]>,
}

/// Parse `x y` lines (blank lines and `#` comments skipped; commas count as spaces); a last
/// point equal to the first closes the polygon and is dropped.
pub fn parse(text: &str) -> Result<Vec<[f64; 2]>, MeshError> {
    let mut pts = Vec::new();
    for (k, line) in text.lines().enumerate() {
        let line = line.split('#').next().unwrap_or("").replace(',', " ");
        let fields: Vec<&str> = line.split_whitespace().collect();
        if fields.is_empty() {
            continue;
        }
        let bad = |m: String| MeshError::Parse { line: k + 1, message: m };
        if fields.len() != 2 {
            return Err(bad(format!("expected two numbers 'x y', got {} fields", fields.len())));
        }
        let mut p = [0.0; 2];
        for (i, f) in fields.iter().enumerate() {
            p[i] = f.parse::<f64>().ok().filter(|v| v.is_finite()).ok_or_else(|| bad(format!("'{f}' is not a finite number")))?;
        }
        pts.push(p);
    }
    Ok(pts)
}

/// Twice the signed area (positive counter-clockwise).
fn twice_area(p: &[[f64; 2]]) -> f64 {
    (0..p.len()).map(|i| { let (a, b) = (p[i], p[(i + 1) % p.len()]); a[0] * b[1] - b[0] * a[1] }).sum()
}

pub fn area(p: &[[f64; 2]]) -> f64 {
    0.5 * twice_area(p).abs()
}

fn orient(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

/// Do segments ab and cd cross or touch (sharing no endpoint by index)?
fn segments_meet(a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> bool {
    let (d1, d2, d3, d4) = (orient(c, d, a), orient(c, d, b), orient(a, b, c), orient(a, b, d));
    if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0)) && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0)) {
        return true;
    }
    let on = |p: [f64; 2], q: [f64; 2], r: [f64; 2]| r[0] >= p[0].min(q[0]) && r[0] <= p[0].max(q[0]) && r[1] >= p[1].min(q[1]) && r[1] <= p[1].max(q[1]);
    (d1 == 0.0 && on(c, d, a)) || (d2 == 0.0 && on(c, d, b)) || (d3 == 0.0 && on(a, b, c)) || (d4 == 0.0 && on(a, b, d))
}

impl Outline {
    /// Check and orient a polygon: repeated consecutive points dropped, at least 3 points left, an
    /// area above 1e-6 of its bounding box's (not a line), no two non-adjacent edges meeting.
    pub fn new(points: &[[f64; 2]]) -> Result<Outline, MeshError> {
        let mut p: Vec<[f64; 2]> = Vec::with_capacity(points.len());
        for &q in points {
            if p.last() != Some(&q) {
                p.push(q);
            }
        }
        while p.len() > 1 && p.first() == p.last() {
            p.pop();
        }
        if p.len() < 3 {
            return Err(MeshError::Invalid(format!("an outline needs at least 3 distinct points, got {}", p.len())));
        }
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for q in &p {
            for k in 0..2 {
                lo[k] = lo[k].min(q[k]);
                hi[k] = hi[k].max(q[k]);
            }
        }
        let (w, h) = (hi[0] - lo[0], hi[1] - lo[1]);
        let n = p.len();
        for i in 0..n {
            for j in i + 1..n {
                let adjacent = j == i + 1 || (i == 0 && j == n - 1);
                if !adjacent && segments_meet(p[i], p[(i + 1) % n], p[j], p[(j + 1) % n]) {
                    return Err(MeshError::Invalid(format!(
                        "the outline crosses itself: edge {} ({:.3}, {:.3})–({:.3}, {:.3}) m meets edge {} (points are numbered from 1)",
                        i + 1, p[i][0], p[i][1], p[(i + 1) % n][0], p[(i + 1) % n][1], j + 1
                    )));
                }
            }
        }
        let a = area(&p);
        if !(a > 1e-6 * (w.max(h) * w.max(h))) || !(a > 0.0) {
            return Err(MeshError::Invalid(format!("the outline encloses (almost) no area ({a:.3e} m² in a {w:.3} × {h:.3} m box): draw a closed shape")));
        }
        if twice_area(&p) < 0.0 {
            p.reverse();
        }
        Ok(Outline { points: p })
    }

    pub fn area(&self) -> f64 {
        area(&self.points)
    }

    pub fn perimeter(&self) -> f64 {
        let p = &self.points;
        (0..p.len()).map(|i| dist(p[i], p[(i + 1) % p.len()])).sum()
    }

    /// The outline at spacing about `edge`: points closer than edge/2 to the last kept one are
    /// dropped (a mouse stroke's dense samples), then every edge longer than `edge` is cut into
    /// equal pieces. The kept points are the polygon's own, so its corners stay.
    pub fn resampled(&self, edge: f64) -> Vec<[f64; 2]> {
        let mut kept: Vec<[f64; 2]> = Vec::new();
        for &q in &self.points {
            if kept.last().is_none_or(|&l| dist(l, q) >= 0.5 * edge) {
                kept.push(q);
            }
        }
        while kept.len() > 3 && dist(kept[kept.len() - 1], kept[0]) < 0.5 * edge {
            kept.pop();
        }
        if kept.len() < 3 {
            kept = self.points.clone();
        }
        let mut out = Vec::new();
        for i in 0..kept.len() {
            let (a, b) = (kept[i], kept[(i + 1) % kept.len()]);
            let pieces = (dist(a, b) / edge).ceil().max(1.0) as usize;
            for k in 0..pieces {
                let t = k as f64 / pieces as f64;
                out.push([a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]);
            }
        }
        out
    }
}

pub fn dist(a: [f64; 2], b: [f64; 2]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt()
}
