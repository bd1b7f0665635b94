//! Compressed sparse rows (CSR) of a body's topology, built once per body: for every vertex,
//! the springs that end at it (with the other end) and the faces around it.
//!
//! The solver's passes gather per vertex through these lists instead of scattering per spring
//! or per face: every vertex's sums are then taken in one fixed order whatever the thread
//! count, and the vertices can be split between threads without two of them writing the same
//! value (`par.rs`).

/// Vertex → incident springs. Springs are (i, j) with i < j (`Springs`), so at vertex v the
/// spring's force points along +d when `other > v` (v is the spring's first end) and −d else.
#[derive(Debug, Clone, Default)]
pub(crate) struct SpringRows {
    /// Row v is `start[v]..start[v + 1]`.
    pub start: Vec<u32>,
    pub spring: Vec<u32>,
    pub other: Vec<u32>,
}

impl SpringRows {
    pub fn new(n: usize, ii: &[u32], jj: &[u32]) -> Self {
        let mut count = vec![0u32; n + 1];
        for (&i, &j) in ii.iter().zip(jj) {
            count[i as usize + 1] += 1;
            count[j as usize + 1] += 1;
        }
        for v in 0..n {
            count[v + 1] += count[v];
        }
        let start = count.clone();
        let total = start[n] as usize;
        let (mut spring, mut other) = (vec![0u32; total], vec![0u32; total]);
        let mut fill = start.clone();
        for (e, (&i, &j)) in ii.iter().zip(jj).enumerate() {
            for (a, b) in [(i, j), (j, i)] {
                let k = fill[a as usize] as usize;
                spring[k] = e as u32;
                other[k] = b;
                fill[a as usize] += 1;
            }
        }
        SpringRows { start, spring, other }
    }
}

/// Vertex → faces around it.
#[derive(Debug, Clone, Default)]
pub(crate) struct FaceRows {
    pub start: Vec<u32>,
    pub face: Vec<u32>,
}

impl FaceRows {
    pub fn new(n: usize, tris: &[[u32; 3]]) -> Self {
        let mut start = vec![0u32; n + 1];
        for t in tris {
            for &v in t {
                start[v as usize + 1] += 1;
            }
        }
        for v in 0..n {
            start[v + 1] += start[v];
        }
        let mut face = vec![0u32; start[n] as usize];
        let mut fill = start.clone();
        for (f, t) in tris.iter().enumerate() {
            for &v in t {
                face[fill[v as usize] as usize] = f as u32;
                fill[v as usize] += 1;
            }
        }
        FaceRows { start, face }
    }
}

/// Vertex → the hinges it belongs to (`body/hinges.rs`): each entry is 4 h + s, hinge h with
/// the vertex in its slot s (0, 1 the edge's ends; 2, 3 the opposite vertices).
#[derive(Debug, Clone, Default)]
pub(crate) struct HingeRows {
    pub start: Vec<u32>,
    pub entry: Vec<u32>,
}

impl HingeRows {
    pub fn new(n: usize, hinges: &[[u32; 4]]) -> Self {
        let mut start = vec![0u32; n + 1];
        for h in hinges {
            for &v in h {
                start[v as usize + 1] += 1;
            }
        }
        for v in 0..n {
            start[v + 1] += start[v];
        }
        let mut entry = vec![0u32; start[n] as usize];
        let mut fill = start.clone();
        for (k, h) in hinges.iter().enumerate() {
            for (s, &v) in h.iter().enumerate() {
                entry[fill[v as usize] as usize] = (4 * k + s) as u32;
                fill[v as usize] += 1;
            }
        }
        HingeRows { start, entry }
    }
}
