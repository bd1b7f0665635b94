//! The explicit force stages on several threads, deterministically.
//!
//! The one-thread stages scatter: every spring adds its force to both ends, every face its
//! normal to its three corners. Split the vertices into chunks of [`PCHUNK`] consecutive indices
//! (fixed, whatever the thread count; vertices are in Morton order, so a chunk is a patch of
//! the surface). A spring (i, j), i < j, and a face (owned by its smallest corner) belong to
//! the chunk of their first vertex, and that chunk's thread adds them to every end *inside the
//! chunk* directly — in one pass over its own items, as the one-thread stage does. The
//! contributions to ends in a later chunk (the chunk's border: about a tenth of the springs at
//! 2048 vertices per chunk) go to a buffer slot of their own; a second pass, per target chunk,
//! adds the slots in a fixed order. Every value is therefore written by one thread at a time
//! and summed in an order that depends on the chunks only: any number of threads ≥ 2 gives the
//! same bits, and against the one-thread stages only the summation order differs (the terms
//! are the same numbers, so the results agree to rounding: tested at 1e-12 relative).
//!
//! Built once per body (the first threaded explicit step) and kept in `Work`; allocates nothing
//! per step.

use super::{Model, Springs};
use crate::par::{chunk, chunks, Out, Threads};

/// Vertices per chunk.
pub(crate) const PCHUNK: usize = 2048;

/// Crossing contributions of one kind: slots in source order, and per target chunk the slots
/// (with their target vertex) in slot order.
#[derive(Debug, Clone, Default)]
struct Cross {
    /// Slots of source chunk c: `src[c]..src[c + 1]`.
    src: Vec<u32>,
    /// Entries for target chunk c: `tgt[c]..tgt[c + 1]` into `slot` / `vertex`.
    tgt: Vec<u32>,
    slot: Vec<u32>,
    vertex: Vec<u32>,
    /// 3 values per slot.
    buf: Vec<f64>,
}

impl Cross {
    /// From the crossing contributions in slot order: (source chunk, target vertex).
    fn new(nch: usize, list: &[(usize, u32)]) -> Self {
        let mut src = vec![0u32; nch + 1];
        let mut tgt = vec![0u32; nch + 1];
        for &(c, v) in list {
            src[c + 1] += 1;
            tgt[v as usize / PCHUNK + 1] += 1;
        }
        for c in 0..nch {
            src[c + 1] += src[c];
            tgt[c + 1] += tgt[c];
        }
        let mut fill = tgt.clone();
        let (mut slot, mut vertex) = (vec![0u32; list.len()], vec![0u32; list.len()]);
        for (s, &(_, v)) in list.iter().enumerate() {
            let t = &mut fill[v as usize / PCHUNK];
            slot[*t as usize] = s as u32;
            vertex[*t as usize] = v;
            *t += 1;
        }
        Cross { src, tgt, slot, vertex, buf: vec![0.0; 3 * list.len()] }
    }

    /// Add (sign ·) the slots aimed at chunk c's vertices into its accumulator `f` (chunk-local).
    fn apply(&self, c: usize, base: usize, sign: f64, f: &mut [f64]) {
        for k in self.tgt[c] as usize..self.tgt[c + 1] as usize {
            let (s, v) = (3 * self.slot[k] as usize, 3 * (self.vertex[k] as usize - base));
            for d in 0..3 {
                f[v + d] += sign * self.buf[s + d];
            }
        }
    }
}

/// Springs of one kind: per chunk the range of springs whose first end is in it.
#[derive(Debug, Clone, Default)]
struct SpringPart {
    range: Vec<u32>,
    cross: Cross,
}

impl SpringPart {
    /// None unless the springs are sorted by their first end (then each chunk's are contiguous).
    fn new(n: usize, sp: &Springs) -> Option<Self> {
        if sp.i.windows(2).any(|w| w[0] > w[1]) || sp.i.iter().zip(&sp.j).any(|(i, j)| i >= j) {
            return None;
        }
        let nch = chunks(n, PCHUNK);
        let mut range = vec![0u32; nch + 1];
        for &i in &sp.i {
            range[i as usize / PCHUNK + 1] += 1;
        }
        for c in 0..nch {
            range[c + 1] += range[c];
        }
        let list: Vec<(usize, u32)> =
            sp.i.iter().zip(&sp.j).filter(|(i, j)| **i as usize / PCHUNK != **j as usize / PCHUNK).map(|(&i, &j)| (i as usize / PCHUNK, j)).collect();
        Some(SpringPart { range, cross: Cross::new(nch, &list) })
    }
}

/// The partition of one body's springs, bending springs and faces.
#[derive(Debug, Clone, Default)]
pub(crate) struct ParForces {
    n: usize,
    springs: SpringPart,
    bending: SpringPart,
    /// Faces owned by chunk c (smallest corner in it): `face_ids[face_start[c]..face_start[c + 1]]`.
    face_start: Vec<u32>,
    face_ids: Vec<u32>,
    faces: Cross,
    slots: Vec<f64>,
}

impl ParForces {
    /// None where the springs are not sorted by first end (then the one-thread stages run).
    pub fn new(m: &Model) -> Option<Self> {
        let n = m.mass.len();
        let nch = chunks(n, PCHUNK);
        let (springs, bending) = (SpringPart::new(n, &m.springs)?, SpringPart::new(n, &m.bending)?);
        let tris = m.faces.triangles();
        let owner = |t: &[u32; 3]| *t.iter().min().expect("three corners") as usize / PCHUNK;
        let mut face_start = vec![0u32; nch + 1];
        for t in tris {
            face_start[owner(t) + 1] += 1;
        }
        for c in 0..nch {
            face_start[c + 1] += face_start[c];
        }
        let mut fill = face_start.clone();
        let mut face_ids = vec![0u32; tris.len()];
        for (f, t) in tris.iter().enumerate() {
            let c = &mut fill[owner(t)];
            face_ids[*c as usize] = f as u32;
            *c += 1;
        }
        let mut list = Vec::new();
        for c in 0..nch {
            for &f in &face_ids[face_start[c] as usize..face_start[c + 1] as usize] {
                for &v in &tris[f as usize] {
                    if v as usize / PCHUNK != c {
                        list.push((c, v));
                    }
                }
            }
        }
        Some(ParForces { n, springs, bending, face_start, face_ids, faces: Cross::new(nch, &list), slots: vec![0.0; nch] })
    }

    /// Built for `m` (same vertex, spring, bending and face counts).
    pub fn fits(&self, m: &Model) -> bool {
        self.n == m.mass.len()
            && self.springs.range.last() == Some(&(m.springs.len() as u32))
            && self.bending.range.last() == Some(&(m.bending.len() as u32))
            && self.face_ids.len() == m.faces.len()
    }

    /// Stage faces: 6V, and Σ n_f per vertex into `g` (zero on entry) when `normals`.
    pub fn faces(&mut self, th: &Threads, m: &Model, x: &[f64], g: &mut [f64], normals: bool) -> f64 {
        let n = self.n;
        let (ids, start) = (&self.face_ids, &self.face_start);
        let cross = Out::new(&mut self.faces.buf);
        let src = &self.faces.src;
        let go = Out::new(g);
        th.each(&mut self.slots, |c, slot| {
            let vr = chunk(c, PCHUNK, n);
            // SAFETY: chunk c writes its own vertices and its own crossing slots only.
            let (gl, cb) = unsafe { (go.range(3 * vr.start..3 * vr.end), cross.range(3 * src[c] as usize..3 * src[c + 1] as usize)) };
            let own = &ids[start[c] as usize..start[c + 1] as usize];
            *slot = m.faces.volume6_and_normals_part(own, x, vr, gl, cb, normals);
        });
        let six_v = self.slots.iter().sum();
        if normals {
            let faces = &self.faces;
            th.each(&mut self.slots, |c, _| {
                let vr = chunk(c, PCHUNK, n);
                // SAFETY: chunk c writes its own vertices only.
                faces.apply(c, vr.start, 1.0, unsafe { go.range(3 * vr.start..3 * vr.end) });
            });
        }
        six_v
    }

    /// Stage springs (and bending springs, stiffness `kb`, when `bend`): add the forces into `f`.
    #[allow(clippy::too_many_arguments)]
    pub fn springs(&mut self, th: &Threads, m: &Model, k: f64, kb: Option<f64>, cs: f64, x: &[f64], v: &[f64], f: &mut [f64]) {
        let n = self.n;
        let (bend, kb) = (kb.is_some(), kb.unwrap_or(0.0));
        let fo = Out::new(f);
        let (sp, bp) = (&mut self.springs, &mut self.bending);
        {
            let (scb, bcb) = (Out::new(&mut sp.cross.buf), Out::new(&mut bp.cross.buf));
            let (sr, ss, br, bs) = (&sp.range, &sp.cross.src, &bp.range, &bp.cross.src);
            th.each(&mut self.slots, |c, _| {
                let vr = chunk(c, PCHUNK, n);
                // SAFETY: chunk c writes its own vertices and its own crossing slots only.
                unsafe {
                    let fl = fo.range(3 * vr.start..3 * vr.end);
                    let cb = scb.range(3 * ss[c] as usize..3 * ss[c + 1] as usize);
                    m.springs.accumulate_part(k, cs, x, v, sr[c] as usize..sr[c + 1] as usize, vr.clone(), fl, cb);
                    if bend {
                        let cb = bcb.range(3 * bs[c] as usize..3 * bs[c + 1] as usize);
                        m.bending.accumulate_part(kb, cs, x, v, br[c] as usize..br[c + 1] as usize, vr, fl, cb);
                    }
                }
            });
        }
        let (sc, bc) = (&sp.cross, &bp.cross);
        th.each(&mut self.slots, |c, _| {
            let vr = chunk(c, PCHUNK, n);
            // SAFETY: chunk c writes its own vertices only.
            let fl = unsafe { fo.range(3 * vr.start..3 * vr.end) };
            sc.apply(c, vr.start, -1.0, fl);
            if bend {
                bc.apply(c, vr.start, -1.0, fl);
            }
        });
    }

    /// Call `f(range)` for every chunk of vertices, on the pool.
    pub fn vertices(&mut self, th: &Threads, f: impl Fn(std::ops::Range<usize>) + Sync + Send) {
        let n = self.n;
        th.each(&mut self.slots, |c, _| f(chunk(c, PCHUNK, n)));
    }
}
