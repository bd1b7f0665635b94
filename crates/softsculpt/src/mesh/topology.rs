//! Edges, boundary and non-manifold edges, orientation.

use crate::error::MeshError;
use crate::vec3::{cross, dot, get};

/// Unique undirected edges `(i, j)` with `i < j`, sorted by `(i, j)`.
pub fn edges(tris: &[[u32; 3]]) -> Vec<[u32; 2]> {
    let mut keys: Vec<u64> = Vec::with_capacity(tris.len() * 3);
    for t in tris {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            let (a, b) = if a < b { (a, b) } else { (b, a) };
            keys.push(((a as u64) << 32) | b as u64);
        }
    }
    keys.sort_unstable();
    keys.dedup();
    keys.into_iter().map(|k| [(k >> 32) as u32, k as u32]).collect()
}

/// Bending pairs: for every edge shared by exactly two faces, the two vertices opposite it
/// (i < j), sorted and without repeats. A spring between them resists folding across the edge.
pub fn bending_pairs(tris: &[[u32; 3]]) -> Vec<[u32; 2]> {
    let h = half_edges(tris);
    let opposite = |f: u32, key: u64| {
        let t = tris[f as usize];
        let (a, b) = ((key >> 32) as u32, key as u32);
        t.into_iter().find(|&v| v != a && v != b).unwrap_or(a)
    };
    let mut pairs: Vec<[u32; 2]> = groups(&h)
        .filter(|g| g.len() == 2)
        .map(|g| {
            let (c, d) = (opposite(g[0].1, g[0].0), opposite(g[1].1, g[1].0));
            if c < d { [c, d] } else { [d, c] }
        })
        .filter(|p| p[0] != p[1])
        .collect();
    pairs.sort_unstable();
    pairs.dedup();
    pairs
}

/// Hinges: for every edge shared by exactly two faces that traverse it in opposite directions,
/// `[i, j, k, l]` with face (i, j, k) and face (j, i, l) in their winding (i < j), sorted by
/// (i, j). Edges of inconsistently oriented or non-manifold neighbourhoods have none.
pub fn hinges(tris: &[[u32; 3]]) -> Vec<[u32; 4]> {
    let h = half_edges(tris);
    let opposite = |f: u32, a: u32, b: u32| tris[f as usize].into_iter().find(|&v| v != a && v != b);
    groups(&h)
        .filter(|g| g.len() == 2 && g[0].2 != g[1].2)
        .filter_map(|g| {
            let (a, b) = ((g[0].0 >> 32) as u32, g[0].0 as u32);
            // The face traversing a → b (forward) is face 1.
            let (f1, f2) = if g[0].2 { (g[0].1, g[1].1) } else { (g[1].1, g[0].1) };
            let (k, l) = (opposite(f1, a, b)?, opposite(f2, a, b)?);
            (k != l).then_some([a, b, k, l])
        })
        .collect()
}

/// Counts of the defects that matter for a closed body.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct EdgeCounts {
    /// Undirected edges.
    pub edges: usize,
    /// Edges used by exactly one face (holes).
    pub boundary: usize,
    /// Edges used by three or more faces.
    pub non_manifold: usize,
    /// Manifold edges whose two faces traverse them in the same direction.
    pub inconsistent: usize,
}

/// Half-edges as (undirected key, face, forward?) sorted by key.
fn half_edges(tris: &[[u32; 3]]) -> Vec<(u64, u32, bool)> {
    let mut h = Vec::with_capacity(tris.len() * 3);
    for (f, t) in tris.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            let fwd = a < b;
            let (a, b) = if fwd { (a, b) } else { (b, a) };
            h.push((((a as u64) << 32) | b as u64, f as u32, fwd));
        }
    }
    h.sort_unstable();
    h
}

/// Group sorted half-edges by key.
fn groups(h: &[(u64, u32, bool)]) -> impl Iterator<Item = &[(u64, u32, bool)]> {
    h.chunk_by(|a, b| a.0 == b.0)
}

pub fn count_edges(tris: &[[u32; 3]]) -> EdgeCounts {
    let h = half_edges(tris);
    let mut c = EdgeCounts::default();
    for g in groups(&h) {
        c.edges += 1;
        match g.len() {
            1 => c.boundary += 1,
            2 => {
                if g[0].2 == g[1].2 {
                    c.inconsistent += 1
                }
            }
            _ => c.non_manifold += 1,
        }
    }
    c
}

/// Make face orientation consistent across manifold edges (flood fill per connected piece), then
/// flip every closed piece whose signed volume is negative so that normals point outward.
/// Returns the number of faces flipped. Fails if a piece cannot be oriented (Möbius-like).
pub fn orient_outward(tris: &mut [[u32; 3]], positions: &[f64]) -> Result<usize, MeshError> {
    let nf = tris.len();
    let h = half_edges(tris);
    // Adjacency through manifold edges: (neighbour, same_direction).
    let mut adj_start = vec![0u32; nf + 1];
    let mut pairs: Vec<(u32, u32, bool)> = Vec::new();
    let mut open_face = vec![false; nf];
    for g in groups(&h) {
        if g.len() == 2 {
            pairs.push((g[0].1, g[1].1, g[0].2 == g[1].2));
        } else {
            for e in g {
                open_face[e.1 as usize] = true;
            }
        }
    }
    for &(a, b, _) in &pairs {
        adj_start[a as usize + 1] += 1;
        adj_start[b as usize + 1] += 1;
    }
    for i in 0..nf {
        adj_start[i + 1] += adj_start[i];
    }
    let mut fill = adj_start.clone();
    let mut adj = vec![(0u32, false); 2 * pairs.len()];
    for &(a, b, same) in &pairs {
        adj[fill[a as usize] as usize] = (b, same);
        fill[a as usize] += 1;
        adj[fill[b as usize] as usize] = (a, same);
        fill[b as usize] += 1;
    }

    const UNSEEN: u8 = 2;
    let mut flip = vec![UNSEEN; nf];
    let mut conflicts = 0usize;
    let mut flipped = 0usize;
    let mut stack = Vec::new();
    let mut piece = Vec::new();
    for seed in 0..nf {
        if flip[seed] != UNSEEN {
            continue;
        }
        flip[seed] = 0;
        stack.push(seed as u32);
        piece.clear();
        let mut closed = true;
        while let Some(f) = stack.pop() {
            let f = f as usize;
            piece.push(f);
            closed &= !open_face[f];
            for &(g, same) in &adj[adj_start[f] as usize..adj_start[f + 1] as usize] {
                // Faces sharing an edge in the same direction disagree: one of them must flip.
                let want = flip[f] ^ same as u8;
                if flip[g as usize] == UNSEEN {
                    flip[g as usize] = want;
                    stack.push(g);
                } else if flip[g as usize] != want {
                    conflicts += 1;
                }
            }
        }
        let mut six_v = 0.0;
        for &f in &piece {
            if flip[f] == 1 {
                tris[f].swap(1, 2);
            }
            let t = tris[f];
            six_v += dot(get(positions, t[0] as usize), cross(get(positions, t[1] as usize), get(positions, t[2] as usize)));
        }
        let inside_out = closed && six_v < 0.0;
        for &f in &piece {
            if inside_out {
                tris[f].swap(1, 2);
            }
            if (flip[f] == 1) != inside_out {
                flipped += 1;
            }
        }
    }
    if conflicts > 0 {
        return Err(MeshError::NonOrientable { edges: conflicts / 2 });
    }
    Ok(flipped)
}

/// Connected pieces of a surface of `n` vertices: sets of triangles linked through shared
/// vertices. Vertices no triangle uses are not pieces.
pub fn count_pieces(tris: &[[u32; 3]], n: usize) -> usize {
    fn find(parent: &mut [u32], mut i: u32) -> u32 {
        while parent[i as usize] != i {
            parent[i as usize] = parent[parent[i as usize] as usize];
            i = parent[i as usize];
        }
        i
    }
    let mut parent: Vec<u32> = (0..n as u32).collect();
    let mut used = vec![false; n];
    for t in tris {
        for &v in t {
            used[v as usize] = true;
        }
        for k in 1..3 {
            let (a, b) = (find(&mut parent, t[0]), find(&mut parent, t[k]));
            if a != b {
                parent[a.max(b) as usize] = a.min(b);
            }
        }
    }
    (0..n as u32).filter(|&i| used[i as usize] && find(&mut parent, i) == i).count()
}

/// Signed volume `Σ xa · (xb × xc) / 6` (m³), exact for a closed outward mesh.
pub fn signed_volume(tris: &[[u32; 3]], positions: &[f64]) -> f64 {
    let mut six_v = 0.0;
    for t in tris {
        six_v += dot(get(positions, t[0] as usize), cross(get(positions, t[1] as usize), get(positions, t[2] as usize)));
    }
    six_v / 6.0
}
