//! The multigrid hierarchy's topology, built once per body from its springs: aggregates of
//! vertices, aggregates of aggregates, …, and the sparsity of every level's matrix.
//!
//! **Aggregation** (greedy, Vaněk–Mandel–Brezina 1996, phase 1 and 2): in the vertices' order
//! (Morton order, `mesh/reorder.rs`, so aggregates come out compact and numbered along the
//! curve), a vertex whose neighbours are all still free starts an aggregate of itself and its
//! neighbours; then every vertex left over joins the aggregate of its first aggregated
//! neighbour (one without neighbours is an aggregate of its own). On a triangle mesh the
//! aggregates hold ~7 vertices, so each level has ~1/5–1/7 the nodes of the one above.
//!
//! **Sparsity**: node I of a level is coupled to node J when a spring (edge or bending spring)
//! or a coupling of the level above joins a member of I to a member of J. Each row lists its
//! diagonal first, then the other columns in increasing order. Per entry of the level above,
//! `pos` says where in this level's entries its block is summed (the Galerkin product Pᵀ A P,
//! 6×6 blocks of a translation and a rotation per node: `multigrid/`).

use super::adjacency::SpringRows;

/// An entry that is summed nowhere (a spring inside one aggregate of the finest level).
pub(crate) const NONE: u32 = u32::MAX;

/// A graph in compressed rows: row u's neighbours are `nbr[start[u]..start[u + 1]]` (may list
/// u itself, which is skipped where it matters).
#[derive(Clone, Copy)]
pub(crate) struct Graph<'a> {
    pub start: &'a [u32],
    pub nbr: &'a [u32],
}

impl<'a> From<&'a SpringRows> for Graph<'a> {
    fn from(r: &'a SpringRows) -> Self {
        Graph { start: &r.start, nbr: &r.other }
    }
}

/// One coarse level's topology.
#[derive(Debug, Clone, Default)]
pub(crate) struct Shape {
    pub n: usize,
    /// Node of this level for every node of the level above.
    pub parent: Vec<u32>,
    /// Members (nodes of the level above) of node I: `member[mstart[I]..mstart[I + 1]]`.
    pub mstart: Vec<u32>,
    pub member: Vec<u32>,
    /// Block rows: row I's columns are `col[start[I]..start[I + 1]]`, the diagonal first.
    pub start: Vec<u32>,
    pub col: Vec<u32>,
    /// Per graph of the level above (in the order given to [`Shape::coarsen`]) and per entry of
    /// it: the entry of this level its block is summed into, or [`NONE`].
    pub pos: Vec<Vec<u32>>,
}

/// Greedy aggregation of `g` (n nodes): (node → aggregate, aggregate count).
fn aggregate(n: usize, g: Graph) -> (Vec<u32>, usize) {
    let mut parent = vec![NONE; n];
    let mut count = 0u32;
    let row = |u: usize| g.nbr[g.start[u] as usize..g.start[u + 1] as usize].iter().map(|&w| w as usize).filter(move |&w| w != u);
    for u in 0..n {
        if parent[u] == NONE && row(u).all(|w| parent[w] == NONE) {
            parent[u] = count;
            for w in row(u) {
                parent[w] = count;
            }
            count += 1;
        }
    }
    for u in 0..n {
        if parent[u] == NONE {
            parent[u] = match row(u).find(|&w| parent[w] != NONE) {
                Some(w) => parent[w],
                None => {
                    count += 1;
                    count - 1
                }
            };
        }
    }
    (parent, count as usize)
}

/// The entry of (I, J) in rows `start`/`col` (diagonal first, then increasing columns).
fn entry(start: &[u32], col: &[u32], i: usize, j: usize) -> Option<u32> {
    let (r0, r1) = (start[i] as usize, start[i + 1] as usize);
    if i == j {
        return Some(r0 as u32);
    }
    col[r0 + 1..r1].binary_search(&(j as u32)).ok().map(|k| (r0 + 1 + k) as u32)
}

impl Shape {
    /// Aggregate the n nodes of the level above along `agg` and couple the aggregates through
    /// every graph of `couplings`. An entry inside one aggregate goes to the diagonal when
    /// `inner_to_diagonal`, else to [`NONE`].
    pub fn coarsen(n: usize, agg: Graph, couplings: &[Graph], inner_to_diagonal: bool) -> Shape {
        let (parent, nc) = aggregate(n, agg);
        let mut mstart = vec![0u32; nc + 1];
        for &p in &parent {
            mstart[p as usize + 1] += 1;
        }
        for c in 0..nc {
            mstart[c + 1] += mstart[c];
        }
        let mut member = vec![0u32; n];
        let mut fill = mstart.clone();
        for (u, &p) in parent.iter().enumerate() {
            member[fill[p as usize] as usize] = u as u32;
            fill[p as usize] += 1;
        }
        let (mut start, mut col) = (vec![0u32; nc + 1], Vec::new());
        let mut row = Vec::new();
        for c in 0..nc {
            row.clear();
            for &u in &member[mstart[c] as usize..mstart[c + 1] as usize] {
                for g in couplings {
                    for &w in &g.nbr[g.start[u as usize] as usize..g.start[u as usize + 1] as usize] {
                        let pw = parent[w as usize];
                        if pw != c as u32 {
                            row.push(pw);
                        }
                    }
                }
            }
            row.sort_unstable();
            row.dedup();
            col.push(c as u32);
            col.extend_from_slice(&row);
            start[c + 1] = col.len() as u32;
        }
        let pos = couplings
            .iter()
            .map(|g| {
                let mut pos = vec![NONE; g.nbr.len()];
                for u in 0..n {
                    let pu = parent[u] as usize;
                    let r0 = start[pu] as usize;
                    for k in g.start[u] as usize..g.start[u + 1] as usize {
                        let pw = parent[g.nbr[k] as usize];
                        pos[k] = if pw as usize == pu {
                            if inner_to_diagonal { r0 as u32 } else { NONE }
                        } else {
                            // Present by construction: the row was built from these entries.
                            entry(&start, &col, pu, pw as usize).expect("coupling in the row")
                        };
                    }
                }
                pos
            })
            .collect();
        Shape { n: nc, parent, mstart, member, start, col, pos }
    }

    /// The entry of block (I, J) of this level's matrix (I's diagonal for I = J), if coupled.
    pub fn entry(&self, i: usize, j: usize) -> Option<u32> {
        entry(&self.start, &self.col, i, j)
    }

    /// This level's rows as a graph (for coarsening it in turn).
    pub fn graph(&self) -> Graph<'_> {
        Graph { start: &self.start, nbr: &self.col }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A ring of 12 nodes: every node is in exactly one aggregate, aggregates are runs of
    /// neighbours (3 nodes: a seed and its two neighbours), and the coarse ring couples each
    /// aggregate to its two neighbours only.
    #[test]
    fn a_ring_aggregates_into_a_coarser_ring() {
        let n = 12;
        let mut start = vec![0u32];
        let mut nbr = Vec::new();
        for u in 0..n {
            nbr.push(((u + n - 1) % n) as u32);
            nbr.push(((u + 1) % n) as u32);
            start.push(nbr.len() as u32);
        }
        let g = Graph { start: &start, nbr: &nbr };
        let s = Shape::coarsen(n, g, &[g], false);
        assert_eq!(s.n, 4);
        for c in 0..s.n {
            let row = &s.col[s.start[c] as usize..s.start[c + 1] as usize];
            assert_eq!(row.len(), 3, "itself and two neighbours");
            assert_eq!(row[0] as usize, c);
        }
        // Entries inside an aggregate go nowhere; the rest to a column that is their parent.
        for u in 0..n {
            for k in start[u] as usize..start[u + 1] as usize {
                let (pu, pw) = (s.parent[u], s.parent[nbr[k] as usize]);
                let p = s.pos[0][k];
                if pu == pw {
                    assert_eq!(p, NONE);
                } else {
                    assert_eq!(s.col[p as usize], pw);
                    assert!(s.start[pu as usize] < p && p < s.start[pu as usize + 1]);
                }
            }
        }
    }
}
