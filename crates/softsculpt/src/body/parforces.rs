//! The explicit force stages in chunks of vertices: two passes per force evaluation, on two or
//! more threads, with the same bits on every number; on one thread, pass A and then plain
//! passes over every spring and every vertex ([`ParForces::serial_b`]), the same forces to
//! rounding.
//!
//! Split the vertices into chunks of consecutive indices (the chunk length depends on the
//! vertex count only, [`chunk_len`]; vertices are in Morton order, so a chunk is a patch of the
//! surface). A spring (i, j), i < j, and a face (its smallest corner) belong to the chunk of
//! their first vertex. A spring or face with every end in its chunk is *interior*; the others
//! *cross* into later chunks (about 5 % of the springs at 1,536 vertices per chunk).
//!
//! - **Pass A** (per chunk): the chunk's faces: their part of 6V, and Σ n_f into `g` for the
//!   corners in the chunk (n_f for a later corner into a crossing slot); the chunk's crossing
//!   springs: their force into a crossing slot each.
//! - Between the passes, on the calling thread: 6V summed over the chunks in chunk order, the
//!   gas scale s = (P − P_ref)/6, and the rare stages (wind, face pressures, targets) into `f`.
//! - **Pass B** (per chunk): the chunk's interior springs into an accumulator of the thread's
//!   own (+ on i, − on j), then its crossing springs' slots (+ on their end in the chunk), the
//!   slots of earlier chunks aimed at it (springs −, faces + into g), then the vertex stage on
//!   the chunk's vertices with f = F + s g + f_rare + f_user (`forces.rs`).
//!
//! Pass B reads and writes only its chunk's x and v (a crossing spring's far end is read in
//! pass A only, before any vertex moves), so the vertex stage fuses into it, and the spring
//! accumulator (one chunk, ~96 KB) stays in the thread's cache. Both ends of a crossing spring
//! get the same slot value, ±: momentum stays balanced exactly.
//!
//! Determinism: every value is written by one chunk (slots by their source chunk, vertices by
//! their own chunk), and each sum runs in an order fixed by the chunks (a vertex's spring forces
//! in spring order, then its crossing slots in slot order; g in face order, then slots): 2, 3 or
//! N threads give the same bits. Which thread runs which chunk is [`Threads::blocks`]' choice.
//! (Bodies of one chunk, and every body when one thread steps, take the one-thread path.)
//!
//! Built once per body (first explicit step) and kept in `Work`; allocates nothing per step
//! (the per-thread accumulators are resized only when the thread count changes).

use super::faces::LocalFaces;
use super::springs::LocalSprings;
use super::{Model, Springs};
use crate::par::{chunk, chunks, Out, Threads};

/// Vertices per chunk aimed at: a chunk's accumulator (24 B per vertex, ~96 KB) stays in the
/// L2 cache, two threads get two chunks each at 10,242 vertices, and the crossing springs and
/// faces (whose far ends are random reads: 4.6 % of the springs at 10,242 vertices and 5.5 % at
/// 163,842 with 1,536-vertex chunks, fewer with larger ones) stay few. 4096 and 1536 measured
/// within noise of each other on one thread (BENCHMARKS.md, "Explicit passes" section).
const TARGET_CHUNK: usize = 4096;

/// Vertices per thread below which a pass runs on one thread (a fork and join would cost more
/// than they save). With [`TARGET_CHUNK`] this leaves every body of one chunk (≤ 4,096
/// vertices) on one thread: at 2,562 vertices the rayon passes took 2× the one-thread time
/// (BENCHMARKS.md); 2 threads on the new passes were not measured below 10,242 vertices.
const MIN_PER_THREAD: usize = 2048;

/// Chunk length for `n` vertices: an even number of chunks of equal length (so two threads get
/// equal halves), about [`TARGET_CHUNK`] each. A function of `n` only.
fn chunk_len(n: usize) -> usize {
    let nch = n.div_ceil(TARGET_CHUNK).max(1);
    let nch = if nch > 1 { nch.next_multiple_of(2) } else { 1 };
    n.div_ceil(nch).max(1)
}

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
    fn new(nch: usize, len: usize, list: &[(usize, u32)]) -> Self {
        let mut src = vec![0u32; nch + 1];
        let mut tgt = vec![0u32; nch + 1];
        for &(c, v) in list {
            src[c + 1] += 1;
            tgt[v as usize / len + 1] += 1;
        }
        for c in 0..nch {
            src[c + 1] += src[c];
            tgt[c + 1] += tgt[c];
        }
        let mut fill = tgt.clone();
        let (mut slot, mut vertex) = (vec![0u32; list.len()], vec![0u32; list.len()]);
        for (s, &(_, v)) in list.iter().enumerate() {
            let t = &mut fill[v as usize / len];
            slot[*t as usize] = s as u32;
            vertex[*t as usize] = v;
            *t += 1;
        }
        Cross { src, tgt, slot, vertex, buf: vec![0.0; 3 * list.len()] }
    }

    /// Source chunk c's slots (3 values each).
    fn source(&self, c: usize) -> std::ops::Range<usize> {
        3 * self.src[c] as usize..3 * self.src[c + 1] as usize
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

/// Springs of one kind: per chunk its interior springs (chunk-local, `local`) and its crossing
/// springs (`ids[cross.src[c]..cross.src[c + 1]]`, one slot each), both in spring order.
#[derive(Debug, Clone, Default)]
struct SpringPart {
    local: LocalSprings,
    ids: Vec<u32>,
    cross: Cross,
    count: usize,
}

impl SpringPart {
    fn new(n: usize, len: usize, sp: &Springs) -> Self {
        let nch = chunks(n, len);
        let owner = |e: usize| sp.i[e].min(sp.j[e]) as usize / len;
        let crossing = |e: usize| sp.i[e] as usize / len != sp.j[e] as usize / len;
        let mut inner_by: Vec<Vec<u32>> = vec![Vec::new(); nch];
        let mut cross_by: Vec<Vec<u32>> = vec![Vec::new(); nch];
        for e in 0..sp.len() {
            if crossing(e) { &mut cross_by[owner(e)] } else { &mut inner_by[owner(e)] }.push(e as u32);
        }
        let local = LocalSprings::new(sp, inner_by.iter().enumerate().map(|(c, ids)| (chunk(c, len, n).start, chunk(c, len, n).len(), &ids[..])));
        let ids = cross_by.concat();
        // The far end of each crossing spring, in slot order.
        let far = |e: u32| sp.i[e as usize].max(sp.j[e as usize]);
        let list: Vec<(usize, u32)> = ids.iter().map(|&e| (owner(e as usize), far(e))).collect();
        SpringPart { local, ids, cross: Cross::new(nch, len, &list), count: sp.len() }
    }

    /// Pass A: chunk c's crossing springs into their slots (the force on their end in c).
    fn crossing(&self, c: usize, sp: &Springs, k: f64, cs: f64, x: &[f64], v: &[f64], buf: &Out<f64>) {
        let ids = &self.ids[self.cross.src[c] as usize..self.cross.src[c + 1] as usize];
        // SAFETY: chunk c writes its own slots only.
        let out = unsafe { buf.range(self.cross.source(c)) };
        sp.forces_of(k, cs, x, v, ids, out);
        // `forces_of` gives the force on i; the chunk's end is j where j < i.
        for (o, &e) in out.chunks_exact_mut(3).zip(ids) {
            if sp.i[e as usize] > sp.j[e as usize] {
                o.iter_mut().for_each(|a| *a = -*a);
            }
        }
    }

    /// Pass B: chunk c's interior springs into `f` (its accumulator, vertex `base` at 0, `x` and
    /// `v` its positions and velocities), then the crossing slots: + on the chunk's own ends
    /// of its crossing springs, − on the far ends in it of earlier chunks'.
    #[allow(clippy::too_many_arguments)]
    fn local(&self, c: usize, base: usize, sp: &Springs, k: f64, cs: f64, x: &[f64], v: &[f64], f: &mut [f64]) {
        sp.accumulate_local(&self.local, c, k, cs, x, v, f);
        for (s, &e) in self.cross.source(c).step_by(3).zip(&self.ids[self.cross.src[c] as usize..]) {
            let a = 3 * (sp.i[e as usize].min(sp.j[e as usize]) as usize - base);
            for d in 0..3 {
                f[a + d] += self.cross.buf[s + d];
            }
        }
        self.cross.apply(c, base, -1.0, f);
    }
}

/// What one force evaluation needs from the model and material.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Coefficients {
    /// Spring stiffness, bending stiffness (None: no bending springs), spring damping.
    pub k: f64,
    pub kb: Option<f64>,
    pub cs: f64,
    /// Σ n_f per vertex is needed (a gas is active).
    pub normals: bool,
    /// The gas scale s = (P − P_ref)/6 (Pa) of f = F + s g, known after pass A (0 before).
    pub scale: f64,
}

/// The partition of one body's springs, bending springs and faces, and the passes' buffers.
#[derive(Debug, Clone, Default)]
pub(crate) struct ParForces {
    n: usize,
    /// Vertices per chunk (the last may be shorter).
    len: usize,
    springs: SpringPart,
    bending: SpringPart,
    /// Faces by owner chunk (smallest corner): the interior ones chunk-local, the crossing ones
    /// of chunk c `cross_tris[cross_start[c]..cross_start[c + 1]]`, each in face order.
    local_faces: LocalFaces,
    cross_tris: Vec<[u32; 3]>,
    cross_start: Vec<u32>,
    face_count: usize,
    faces: Cross,
    /// Σ n_f per vertex (m², flat xyz), written by pass A, read by pass B.
    pub g: Vec<f64>,
    /// 6V per chunk.
    slots: Vec<f64>,
    /// One spring accumulator per thread (3 · len values each).
    scratch: Vec<f64>,
    /// One thread's spring forces F (N, flat xyz) when they are not folded into `g` (see
    /// [`ParForces::serial_b`]); zero between passes, sized on first use.
    serial_f: Vec<f64>,
}

impl ParForces {
    pub fn new(m: &Model) -> Self {
        let n = m.mass.len();
        let len = chunk_len(n);
        let nch = chunks(n, len);
        let all = m.faces.triangles();
        let owner = |t: &[u32; 3]| *t.iter().min().expect("three corners") as usize / len;
        let interior = |t: &[u32; 3]| t.iter().all(|&v| v as usize / len == owner(t));
        let (mut inner_by, mut cross_by) = (vec![Vec::new(); nch], vec![Vec::new(); nch]);
        for t in all {
            if interior(t) { &mut inner_by[owner(t)] } else { &mut cross_by[owner(t)] }.push(*t);
        }
        let local_faces = LocalFaces::new(inner_by.iter().enumerate().map(|(c, t)| (chunk(c, len, n).start, chunk(c, len, n).len(), &t[..])));
        let mut cross_start = vec![0u32];
        for t in &cross_by {
            cross_start.push(cross_start.last().unwrap() + t.len() as u32);
        }
        let cross_tris = cross_by.concat();
        let list: Vec<(usize, u32)> = cross_tris.iter().flat_map(|t| t.iter().filter(|&&v| v as usize / len != owner(t)).map(|&v| (owner(t), v))).collect();
        ParForces {
            n,
            len,
            springs: SpringPart::new(n, len, &m.springs),
            bending: SpringPart::new(n, len, &m.bending),
            local_faces,
            cross_tris,
            cross_start,
            face_count: all.len(),
            faces: Cross::new(nch, len, &list),
            g: vec![0.0; 3 * n],
            slots: vec![0.0; nch],
            scratch: Vec::new(),
            serial_f: Vec::new(),
        }
    }

    /// Built for `m` (same vertex, spring, bending and face counts).
    pub fn fits(&self, m: &Model) -> bool {
        self.n == m.mass.len() && self.springs.count == m.springs.len() && self.bending.count == m.bending.len() && self.face_count == m.faces.len()
    }

    /// Threads for a pass on `th`.
    fn threads(&self, th: &Threads) -> usize {
        th.for_chunks(self.slots.len(), self.len, MIN_PER_THREAD)
    }

    /// Pass A: returns 6V (m³); Σ n_f per vertex into `self.g` when `q.normals`; on several
    /// threads the crossing springs into their slots. 6V and g are the same sums, in the same
    /// order, on any thread count.
    pub fn pass_a(&mut self, th: &Threads, m: &Model, q: &Coefficients, x: &[f64], v: &[f64]) -> f64 {
        let (n, len, t) = (self.n, self.len, self.threads(th));
        let serial = t == 1;
        let (lf, ctris, cstart) = (&self.local_faces, &self.cross_tris, &self.cross_start);
        // The slot buffers, out of their parts while the pass writes them.
        let (mut sbuf, mut bbuf) = (std::mem::take(&mut self.springs.cross.buf), std::mem::take(&mut self.bending.cross.buf));
        let (fcross, scross, bcross) = (Out::new(&mut self.faces.buf), Out::new(&mut sbuf), Out::new(&mut bbuf));
        let (fsrc, sp, bp) = (&self.faces.src, &self.springs, &self.bending);
        let (go, so) = (Out::new(&mut self.g), Out::new(&mut self.slots));
        th.blocks(so.len(), t, |_, c| {
            let vr = chunk(c, len, n);
            // SAFETY: chunk c writes its own vertices, slots and 6V only.
            let (g, cb, six_v) = unsafe { (go.range(3 * vr.start..3 * vr.end), fcross.range(3 * fsrc[c] as usize..3 * fsrc[c + 1] as usize), &mut so.range(c..c + 1)[0]) };
            let crossing = &ctris[cstart[c] as usize..cstart[c + 1] as usize];
            *six_v = m.faces.volume6_and_normals_part(lf, c, crossing, x, vr, g, cb, q.normals);
            if serial {
                return;
            }
            sp.crossing(c, &m.springs, q.k, q.cs, x, v, &scross);
            if let Some(kb) = q.kb {
                bp.crossing(c, &m.bending, kb, q.cs, x, v, &bcross);
            }
        });
        (self.springs.cross.buf, self.bending.cross.buf) = (sbuf, bbuf);
        if serial && q.normals {
            // One thread's pass B reads g whole: complete it here with the faces' crossing
            // slots, as the chunked pass B does chunk by chunk (the same sums in the same order).
            for c in 0..self.slots.len() {
                let vr = chunk(c, len, n);
                self.faces.apply(c, vr.start, 1.0, &mut self.g[3 * vr.start..3 * vr.end]);
            }
        }
        self.slots.iter().sum()
    }

    /// Pass B: for every chunk, the spring forces F (N) of its vertices, completed by the
    /// crossing slots, and g completed likewise; then `vertex(range, F, g, a, x, v)` with the
    /// chunk's F (the thread's buffer, free to overwrite), g (empty without normals), a = 1
    /// (the force is a F + s g) and positions and velocities (free to update: no other chunk
    /// reads them in this pass). On one thread: [`ParForces::serial_b`].
    pub fn pass_b(&mut self, th: &Threads, m: &Model, q: &Coefficients, x: &mut [f64], v: &mut [f64], vertex: impl Fn(std::ops::Range<usize>, &mut [f64], &[f64], f64, &mut [f64], &mut [f64]) + Sync) {
        let (n, len, t) = (self.n, self.len, self.threads(th));
        assert!(x.len() == 3 * n && v.len() == 3 * n);
        if t == 1 {
            return self.serial_b(m, q, x, v, vertex);
        }
        let per = 3 * len;
        if self.scratch.len() < t * per {
            self.scratch = vec![0.0; t * per];
        }
        let (sp, bp, faces) = (&self.springs, &self.bending, &self.faces);
        let (fo, go, xo, vo) = (Out::new(&mut self.scratch), Out::new(&mut self.g), Out::new(x), Out::new(v));
        th.blocks(self.slots.len(), t, |b, c| {
            let vr = chunk(c, len, n);
            let r3 = 3 * vr.start..3 * vr.end;
            // SAFETY: thread b uses its own accumulator; chunk c reads and writes its own
            // vertices of g, x and v only.
            let (f, g, x, v) = unsafe { (&mut fo.range(b * per..(b + 1) * per)[..r3.len()], go.range(r3.clone()), xo.range(r3.clone()), vo.range(r3)) };
            f.fill(0.0);
            sp.local(c, vr.start, &m.springs, q.k, q.cs, x, v, f);
            if let Some(kb) = q.kb {
                bp.local(c, vr.start, &m.bending, kb, q.cs, x, v, f);
            }
            if q.normals {
                faces.apply(c, vr.start, 1.0, g);
            }
            vertex(vr, f, if q.normals { g } else { &[] }, 1.0, x, v);
        });
    }
}

impl ParForces {
    /// Pass B on one thread (what WebAssembly runs): the springs stage over every spring in
    /// spring order, then the vertex stage over every vertex: two streams over the arrays, as
    /// the explicit stages ran before the chunked passes. The chunks' pass B costs one thread
    /// 10–25 % more (BENCHMARKS.md, "One thread: plain passes again").
    ///
    /// F is folded into g: the springs add F / s to g (stiffness and damping divided by the gas
    /// scale s once), and the vertex stage gets g + F / s with a = s, so the force is
    /// s (g + F / s) = F + s g to a few ulps: one accumulator, the one pass A has just written
    /// (still in cache), instead of a second one of 3n values read and cleared every step.
    /// Without a gas, or with s = 0 (P = P_ref right after a freeze), F goes to `serial_f`.
    ///
    /// Against the chunked pass B only the summation order differs (F sums each vertex's
    /// springs in spring order, with the chunk-crossing ones among them, not last; the
    /// division by s): one thread and several agree to rounding (tests/threads.rs).
    fn serial_b(&mut self, m: &Model, q: &Coefficients, x: &mut [f64], v: &mut [f64], vertex: impl Fn(std::ops::Range<usize>, &mut [f64], &[f64], f64, &mut [f64], &mut [f64])) {
        let n = self.n;
        // |s| below this is not divided by (F / s would overflow); such a gas force is nil.
        const SCALE_MIN: f64 = 1e-200;
        let fold = q.normals && q.scale.is_finite() && q.scale.abs() >= SCALE_MIN;
        let inv = if fold { 1.0 / q.scale } else { 1.0 };
        if !fold && self.serial_f.len() != 3 * n {
            self.serial_f = vec![0.0; 3 * n];
        }
        let f = if fold { &mut self.g } else { &mut self.serial_f };
        m.springs.accumulate(q.k * inv, q.cs * inv, x, v, f);
        if let Some(kb) = q.kb {
            m.bending.accumulate(kb * inv, q.cs * inv, x, v, f);
        }
        if fold {
            vertex(0..n, &mut self.g, &[], q.scale, x, v);
        } else {
            vertex(0..n, &mut self.serial_f, if q.normals { &self.g } else { &[] }, 1.0, x, v);
            self.serial_f.fill(0.0);
        }
    }
}

impl super::SoftBody {
    /// The volume the gas uses (m³) as the explicit step computes it: 6V summed chunk by chunk
    /// (pass A), so a freeze that sets P_ref = nRT / V from it leaves P − P_ref = 0 exactly in
    /// the steps that follow (`SoftBody::volume` sums in face order: the same value to rounding).
    pub(crate) fn step_volume(&mut self) -> f64 {
        let (m, w, x, v) = (&self.model, &mut self.work, &self.state.x, &self.state.v);
        if !w.par.as_ref().is_some_and(|q| q.fits(m)) {
            w.par = Some(Box::new(ParForces::new(m)));
        }
        let q = Coefficients { k: 0.0, kb: None, cs: 0.0, normals: false, scale: 0.0 };
        let six_v = w.par.as_mut().expect("built above").pass_a(&Threads::single(), m, &q, x, v);
        super::gas::measure(m.faces.triangles(), self.material.volume_mode, six_v, x)
    }
}
