//! Projection back onto the input surface: the nearest point on the nearest input triangle,
//! found through a uniform grid of the triangles' bounding boxes.

use crate::vec3::{norm, sub, V3};

/// Closest point to `p` on triangle (a, b, c).
pub fn closest_on_triangle(p: V3, a: V3, b: V3, c: V3) -> V3 {
    crate::geometry::closest_on_triangle(p, a, b, c).1
}

/// The input surface, bucketed in a grid of cubic cells.
pub struct Surface {
    tris: Vec<[V3; 3]>,
    lo: V3,
    cell: f64,
    dims: [usize; 3],
    /// Triangles per cell (CSR).
    start: Vec<u32>,
    items: Vec<u32>,
}

impl Surface {
    pub fn new(positions: &[f64], triangles: &[[u32; 3]]) -> Self {
        let p = |i: u32| [positions[3 * i as usize], positions[3 * i as usize + 1], positions[3 * i as usize + 2]];
        let tris: Vec<[V3; 3]> = triangles.iter().map(|t| [p(t[0]), p(t[1]), p(t[2])]).collect();
        let (lo, hi) = super::super::bounds(positions);
        let size = sub(hi, lo);
        // About as many cells as triangles (at least a few per axis).
        let volume = size.iter().map(|s| s.max(1e-9 * norm(size))).product::<f64>();
        let cell = (volume / tris.len().max(1) as f64).cbrt().max(norm(size) / 256.0).max(1e-12);
        let dims = [0, 1, 2].map(|k| ((size[k] / cell).floor() as usize + 1).min(512));
        let cell_of = |x: f64, k: usize| (((x - lo[k]) / cell).floor().max(0.0) as usize).min(dims[k] - 1);
        let ncell = dims[0] * dims[1] * dims[2];
        let mut lists: Vec<Vec<u32>> = vec![Vec::new(); ncell];
        for (f, t) in tris.iter().enumerate() {
            let mut r = [[0usize; 2]; 3];
            for k in 0..3 {
                let (a, b) = (t.iter().map(|v| v[k]).fold(f64::INFINITY, f64::min), t.iter().map(|v| v[k]).fold(f64::NEG_INFINITY, f64::max));
                r[k] = [cell_of(a, k), cell_of(b, k)];
            }
            for i in r[0][0]..=r[0][1] {
                for j in r[1][0]..=r[1][1] {
                    for l in r[2][0]..=r[2][1] {
                        lists[(i * dims[1] + j) * dims[2] + l].push(f as u32);
                    }
                }
            }
        }
        let mut start = vec![0u32; ncell + 1];
        let mut items = Vec::new();
        for (c, l) in lists.iter().enumerate() {
            items.extend_from_slice(l);
            start[c + 1] = items.len() as u32;
        }
        Surface { tris, lo, cell, dims, start, items }
    }

    /// The nearest point of the surface to `p`: search shells of cells around p's cell until
    /// the best distance found is within the shell already covered.
    pub fn project(&self, p: V3) -> V3 {
        self.nearest(p).0
    }

    /// The nearest point and the index of the triangle it lies on.
    pub fn nearest(&self, p: V3) -> (V3, usize) {
        let (q, f, _) = self.search(p);
        (q, f)
    }

    /// The distance from `p` to the surface (m): infinite if the search found no triangle (a
    /// point farther than the grid's shells reach, or not finite), never 0 for want of one.
    pub fn distance(&self, p: V3) -> f64 {
        self.search(p).2
    }

    /// The nearest point, its triangle and its distance (p itself, 0, ∞ if none was found).
    fn search(&self, p: V3) -> (V3, usize, f64) {
        let c = [0, 1, 2].map(|k| ((p[k] - self.lo[k]) / self.cell).floor() as i64);
        let (mut best, mut best_d, mut best_f) = (p, f64::INFINITY, 0usize);
        let max_r = *self.dims.iter().max().unwrap() as i64 + 1;
        for r in 0..=max_r {
            for i in c[0] - r..=c[0] + r {
                for j in c[1] - r..=c[1] + r {
                    for l in c[2] - r..=c[2] + r {
                        let shell = (i - c[0]).abs() == r || (j - c[1]).abs() == r || (l - c[2]).abs() == r;
                        if !shell || i < 0 || j < 0 || l < 0 {
                            continue;
                        }
                        let (i, j, l) = (i as usize, j as usize, l as usize);
                        if i >= self.dims[0] || j >= self.dims[1] || l >= self.dims[2] {
                            continue;
                        }
                        let cell = (i * self.dims[1] + j) * self.dims[2] + l;
                        for &f in &self.items[self.start[cell] as usize..self.start[cell + 1] as usize] {
                            let t = &self.tris[f as usize];
                            let q = closest_on_triangle(p, t[0], t[1], t[2]);
                            let d = norm(sub(q, p));
                            if d < best_d {
                                best = q;
                                best_d = d;
                                best_f = f as usize;
                            }
                        }
                    }
                }
            }
            // Everything outside the cells searched so far is at least r·cell away.
            if best_d <= r as f64 * self.cell {
                break;
            }
        }
        (best, best_f, best_d)
    }
}
