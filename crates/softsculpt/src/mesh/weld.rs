//! Welding: merge vertices that coincide, so that UV seams and duplicated corners do not open
//! holes in the surface (a seam makes a pressurised body leak or burst in other engines).

use std::collections::HashMap;

/// Map every vertex to the first earlier vertex within `tol` (metres) of it, or to itself.
/// Returns `rep[i] <= i`. Uses a uniform hash grid of cell size `tol`, so the cost is linear.
pub fn weld(positions: &[f64], tol: f64) -> Vec<u32> {
    let n = positions.len() / 3;
    let mut rep: Vec<u32> = (0..n as u32).collect();
    if tol <= 0.0 || !tol.is_finite() {
        // Only exact duplicates can be merged.
        let mut seen: HashMap<[u64; 3], u32> = HashMap::with_capacity(n);
        for i in 0..n {
            let key = [positions[3 * i].to_bits(), positions[3 * i + 1].to_bits(), positions[3 * i + 2].to_bits()];
            rep[i] = *seen.entry(key).or_insert(i as u32);
        }
        return rep;
    }
    let inv = 1.0 / tol;
    let cell = |x: f64| (x * inv).floor() as i64; // saturates, never panics
    let mut grid: HashMap<[i64; 3], Vec<u32>> = HashMap::with_capacity(n);
    let tol2 = tol * tol;
    for i in 0..n {
        let p = &positions[3 * i..3 * i + 3];
        let c = [cell(p[0]), cell(p[1]), cell(p[2])];
        let mut found = None;
        'search: for dx in -1..=1i64 {
            for dy in -1..=1i64 {
                for dz in -1..=1i64 {
                    let key = [c[0].saturating_add(dx), c[1].saturating_add(dy), c[2].saturating_add(dz)];
                    if let Some(list) = grid.get(&key) {
                        for &j in list {
                            let q = &positions[3 * j as usize..3 * j as usize + 3];
                            let d2 = (p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2);
                            if d2 <= tol2 {
                                found = Some(j);
                                break 'search;
                            }
                        }
                    }
                }
            }
        }
        match found {
            Some(j) => rep[i] = j,
            None => grid.entry(c).or_default().push(i as u32),
        }
    }
    rep
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn merges_points_within_tolerance_only() {
        let p = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1e-12, 0.0, 0.0, 1.0 + 2e-9, 0.0, 0.0];
        assert_eq!(weld(&p, 1e-9), vec![0, 1, 0, 3]);
    }
}
