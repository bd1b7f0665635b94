//! A dense spatial hash (after Müller, "Ten Minute Physics"): the broad phase for contacts.
//!
//! Points go into cubic cells of size `spacing` (m); a cell (i, j, k) is hashed into a table of
//! at least `2 N` buckets (a power of two), and the points of each bucket are stored contiguously by a counting sort:
//! `start[b]..start[b + 1]` indexes `entries`. Building is two linear passes; a query visits the
//! cells overlapping a box, so finding all points within `spacing` of a point costs O(1) on
//! average. Hash collisions only add candidates: callers check distances themselves.
//! Nothing is allocated after the first build for a given number of points.

use crate::vec3::V3;

#[derive(Debug, Clone)]
pub struct SpatialHash {
    /// Cell size (m).
    spacing: f64,
    start: Vec<u32>,
    entries: Vec<u32>,
}

impl SpatialHash {
    pub fn new(spacing: f64) -> Self {
        assert!(spacing.is_finite() && spacing > 0.0, "cell size must be positive");
        SpatialHash { spacing, start: Vec::new(), entries: Vec::new() }
    }

    pub fn spacing(&self) -> f64 {
        self.spacing
    }

    /// Change the cell size (m), keeping the memory; rebuild afterwards.
    pub fn set_spacing(&mut self, spacing: f64) {
        assert!(spacing.is_finite() && spacing > 0.0, "cell size must be positive");
        self.spacing = spacing;
    }

    fn cell(&self, x: f64) -> i64 {
        (x / self.spacing).floor() as i64
    }

    fn bucket(&self, i: i64, j: i64, k: i64) -> usize {
        // Müller's hash: large primes, xor, folded into the table.
        let h = (i.wrapping_mul(92837111)) ^ (j.wrapping_mul(689287499)) ^ (k.wrapping_mul(283923481));
        (h as u64 & (self.start.len() as u64 - 2)) as usize
    }

    /// Index the points (flat xyz).
    pub fn build(&mut self, positions: &[f64]) {
        let n = positions.len() / 3;
        // A power of two at least 2 N, so the hash folds with a mask.
        let table = (2 * n.max(1)).next_power_of_two();
        self.start.clear();
        self.start.resize(table + 1, 0);
        self.entries.resize(n, 0);
        for p in positions.chunks_exact(3) {
            let b = self.bucket(self.cell(p[0]), self.cell(p[1]), self.cell(p[2]));
            self.start[b] += 1;
        }
        // Prefix sums, then fill from the back so each bucket ends where the next starts.
        let mut sum = 0;
        for s in self.start.iter_mut() {
            sum += *s;
            *s = sum;
        }
        for (i, p) in positions.chunks_exact(3).enumerate() {
            let b = self.bucket(self.cell(p[0]), self.cell(p[1]), self.cell(p[2]));
            self.start[b] -= 1;
            self.entries[self.start[b] as usize] = i as u32;
        }
    }

    /// Push into `out` every point whose cell overlaps the box [lo, hi] (a superset of the points
    /// inside it; duplicates are possible only through hash collisions and are removed).
    pub fn query_box(&self, lo: V3, hi: V3, out: &mut Vec<u32>) {
        out.clear();
        if self.start.len() < 2 {
            return;
        }
        let (c0, c1) = ([self.cell(lo[0]), self.cell(lo[1]), self.cell(lo[2])], [self.cell(hi[0]), self.cell(hi[1]), self.cell(hi[2])]);
        let mut seen_buckets: [usize; 27] = [usize::MAX; 27];
        let mut count = 0;
        for i in c0[0]..=c1[0] {
            for j in c0[1]..=c1[1] {
                for k in c0[2]..=c1[2] {
                    let b = self.bucket(i, j, k);
                    // The same bucket reached from two cells would list its points twice.
                    if count < 27 {
                        if seen_buckets[..count].contains(&b) {
                            continue;
                        }
                        seen_buckets[count] = b;
                        count += 1;
                    }
                    out.extend_from_slice(&self.entries[self.start[b] as usize..self.start[b + 1] as usize]);
                }
            }
        }
        if count >= 27 {
            out.sort_unstable();
            out.dedup();
        }
    }

    /// Candidates within `radius` of `p`. With `radius` ≤ spacing / 2 the box spans at most
    /// 2 × 2 × 2 cells: choose the spacing about twice the contact distance.
    pub fn query(&self, p: V3, radius: f64, out: &mut Vec<u32>) {
        self.query_box([p[0] - radius, p[1] - radius, p[2] - radius], [p[0] + radius, p[1] + radius, p[2] + radius], out);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A deterministic scatter of points (a simple LCG), some clustered, some far apart.
    fn points(n: usize) -> Vec<f64> {
        let mut s: u64 = 12345;
        let mut next = || {
            s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (s >> 11) as f64 / (1u64 << 53) as f64
        };
        (0..3 * n).map(|k| if k % 7 == 0 { 100.0 * next() } else { 3.0 * next() - 1.5 }).collect()
    }

    #[test]
    fn queries_find_every_point_within_the_radius() {
        let x = points(3000);
        let mut h = SpatialHash::new(0.1);
        h.build(&x);
        let mut out = Vec::new();
        for q in (0..3000).step_by(37) {
            let p = [x[3 * q], x[3 * q + 1], x[3 * q + 2]];
            h.query(p, 0.1, &mut out);
            let mut sorted = out.clone();
            sorted.sort_unstable();
            sorted.dedup();
            assert_eq!(sorted.len(), out.len(), "no duplicates");
            for i in 0..3000 {
                let d = ((x[3 * i] - p[0]).powi(2) + (x[3 * i + 1] - p[1]).powi(2) + (x[3 * i + 2] - p[2]).powi(2)).sqrt();
                if d <= 0.1 {
                    assert!(out.contains(&(i as u32)), "point {i} at {d} missed");
                }
            }
        }
    }

    #[test]
    fn rebuilding_reuses_its_memory() {
        let x = points(1000);
        let mut h = SpatialHash::new(0.2);
        h.build(&x);
        let (a, b) = (h.start.as_ptr(), h.entries.as_ptr());
        h.build(&x);
        assert_eq!((a, b), (h.start.as_ptr(), h.entries.as_ptr()));
    }
}
