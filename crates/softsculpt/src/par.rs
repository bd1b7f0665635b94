//! Threads: the force stages and the implicit solver's passes split their vertices (or springs,
//! or faces) into chunks of a fixed size and hand the chunks to a pool of threads.
//!
//! Deterministic by construction: a chunk's work does not depend on which thread runs it, every
//! output value is written by exactly one chunk (per-vertex gathers, never scatters from two
//! chunks into one value), and reductions (volume, dot products, norms) are summed per chunk
//! into a slot of their own, then the slots in chunk order on the calling thread. The chunk size
//! does not depend on the thread count, so 1 and N threads give the same bits — except the
//! explicit stages on one thread, which take plain passes in spring and vertex order
//! (`body/parforces.rs` `serial_b`: faster on one core) and agree with N threads to rounding.
//!
//! Native builds use a rayon pool of their own (`Threads::new(n)`, n = 0: every core) for
//! [`Threads::each`], and a team of spinning threads (`par/team.rs`, started on first use) for
//! [`Threads::blocks`], the explicit step's two short passes. WebAssembly built with atomics
//! (`scripts/wasm_threads.sh`) runs both on the team, whose threads are helpers the page started
//! (`par/host.rs`); built without, there is no pool: every chunk runs on the calling thread.

use std::marker::PhantomData;
use std::ops::Range;

#[cfg(all(target_arch = "wasm32", target_feature = "atomics"))]
mod host;
#[cfg(any(not(target_arch = "wasm32"), target_feature = "atomics"))]
mod team;
#[cfg(all(target_arch = "wasm32", target_feature = "atomics"))]
pub use host::{helpers, serve, trapped_flag};

/// A pool of threads (or none: the calling thread). Cheap to clone (shared).
#[derive(Clone, Default)]
pub struct Threads {
    #[cfg(any(not(target_arch = "wasm32"), target_feature = "atomics"))]
    pool: Option<std::sync::Arc<Pool>>,
}

#[cfg(any(not(target_arch = "wasm32"), target_feature = "atomics"))]
struct Pool {
    #[cfg(not(target_arch = "wasm32"))]
    rayon: rayon::ThreadPool,
    /// Started on first use; `None` if its threads could not start.
    team: std::sync::OnceLock<Option<team::Team>>,
    n: usize,
}

#[cfg(any(not(target_arch = "wasm32"), target_feature = "atomics"))]
impl Pool {
    fn team(&self) -> Option<&team::Team> {
        self.team.get_or_init(|| team::Team::new(self.n).ok()).as_ref()
    }
}

impl std::fmt::Debug for Threads {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Threads({})", self.count())
    }
}

impl Threads {
    /// One thread: the caller's.
    pub fn single() -> Self {
        Threads::default()
    }

    /// A pool of `n` threads; 0 means one per core ([`max_threads`]). One thread is the
    /// caller's (no pool). More threads than cores are allowed here (the tests check the same
    /// bits on 2 and 3); the command line refuses them (`softsculpt-cli` `args::threads`).
    pub fn new(n: usize) -> Result<Self, String> {
        #[cfg(not(target_arch = "wasm32"))]
        {
            let n = if n == 0 { max_threads() } else { n };
            if n <= 1 {
                return Ok(Threads::single());
            }
            let rayon = rayon::ThreadPoolBuilder::new().num_threads(n).build().map_err(|e| format!("cannot start {n} threads: {e}"))?;
            Ok(Threads { pool: Some(std::sync::Arc::new(Pool { rayon, team: Default::default(), n })) })
        }
        #[cfg(all(target_arch = "wasm32", target_feature = "atomics"))]
        {
            // The team takes n − 1 of the page's helpers; they must be serving already.
            let n = if n == 0 { max_threads() } else { n };
            if n <= 1 {
                return Ok(Threads::single());
            }
            if n > max_threads() {
                return Err(format!("{n} threads asked for, but the page started {} helper threads", helpers()));
            }
            let pool = Pool { team: Default::default(), n };
            if pool.team().is_none() {
                return Err(format!("cannot start {n} threads: too few idle helper threads"));
            }
            Ok(Threads { pool: Some(std::sync::Arc::new(pool)) })
        }
        #[cfg(all(target_arch = "wasm32", not(target_feature = "atomics")))]
        {
            let _ = n;
            Ok(Threads::single())
        }
    }

    /// Threads that work on a pass.
    pub fn count(&self) -> usize {
        #[cfg(any(not(target_arch = "wasm32"), target_feature = "atomics"))]
        if let Some(p) = &self.pool {
            return p.n;
        }
        1
    }

    /// Call `f(c, &mut slot[c])` for every chunk c, on the pool's threads (any order).
    pub(crate) fn each<R: Send>(&self, slots: &mut [R], f: impl Fn(usize, &mut R) + Sync + Send) {
        #[cfg(not(target_arch = "wasm32"))]
        if let Some(pool) = &self.pool {
            if slots.len() > 1 {
                use rayon::prelude::*;
                pool.rayon.install(|| slots.par_iter_mut().enumerate().for_each(|(c, r)| f(c, r)));
                return;
            }
        }
        #[cfg(all(target_arch = "wasm32", target_feature = "atomics"))]
        if let Some(team) = self.pool.as_ref().filter(|_| slots.len() > 1).and_then(|p| p.team()) {
            // Every thread claims chunks one at a time until none remain (the caller's share
            // takes whatever the others have not: `Team::run`).
            let next = std::sync::atomic::AtomicUsize::new(0);
            let out = Out::new(slots);
            return team.run(&|_| loop {
                let c = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                if c >= out.len() {
                    break;
                }
                // SAFETY: chunk c is claimed by one thread only.
                f(c, unsafe { &mut out.range(c..c + 1)[0] });
            });
        }
        for (c, r) in slots.iter_mut().enumerate() {
            f(c, r);
        }
    }
}

/// Passes a thread other than the caller took part in, since the program started (0 on one
/// thread): the evidence that a pool's threads work, for tests and the page's thread check.
pub fn passes_helped() -> u64 {
    #[cfg(any(not(target_arch = "wasm32"), target_feature = "atomics"))]
    return team::PASSES_HELPED.load(std::sync::atomic::Ordering::Relaxed);
    #[cfg(all(target_arch = "wasm32", not(target_feature = "atomics")))]
    0
}

/// Threads this machine runs at once (its available parallelism; in WebAssembly the caller and
/// the helpers the page started, 1 without atomics, where the passes run on the calling thread).
pub fn max_threads() -> usize {
    #[cfg(not(target_arch = "wasm32"))]
    return std::thread::available_parallelism().map(|n| n.get()).unwrap_or(1);
    #[cfg(all(target_arch = "wasm32", target_feature = "atomics"))]
    return 1 + helpers();
    #[cfg(all(target_arch = "wasm32", not(target_feature = "atomics")))]
    1
}

/// A thread count a caller may ask for: 0 (every core) up to [`max_threads`]. More would only
/// take turns (1,000 threads ran ~500× slower on 2 cores) and thousands stopped the machine, so
/// the command line and the Python package refuse them up front with this message.
pub fn check_threads(n: u64) -> Result<(), String> {
    let most = max_threads();
    if n > most as u64 {
        return Err(format!("this machine runs {most} threads at once: give at most {most} (0 or absent: every core)"));
    }
    Ok(())
}

impl Threads {
    /// Threads that [`Threads::blocks`] uses for `n` chunks of `min_len` items or more: one
    /// below `min_len` items per thread (a pass that short costs less than a fork and join).
    pub(crate) fn for_chunks(&self, chunks: usize, chunk_len: usize, min_len: usize) -> usize {
        let by_size = (chunks * chunk_len / min_len.max(1)).max(1);
        self.count().min(chunks).min(by_size).max(1)
    }

    /// Chunks 0..n in `t` contiguous blocks, block b to thread b: `f(b, c)` for every chunk c,
    /// with b the thread that runs it (below `t`). Each thread runs its own block in order,
    /// then helps with the others' (claiming chunks one at a time), so a thread the system
    /// stalled does not stall the pass. On a quiet machine a thread takes the same block in
    /// every pass with the same (n, t), so data a pass leaves in its cache is there for the next.
    pub(crate) fn blocks(&self, n: usize, t: usize, f: impl Fn(usize, usize) + Sync) {
        #[cfg(any(not(target_arch = "wasm32"), target_feature = "atomics"))]
        if let Some(pool) = self.pool.as_ref().filter(|_| t > 1) {
            if let Some(team) = pool.team() {
                /// A claim counter on a cache line of its own.
                #[repr(align(64))]
                struct Next(std::sync::atomic::AtomicUsize);
                const MAX: usize = 16;
                let t = t.min(MAX).min(team.len());
                let next: [Next; MAX] = std::array::from_fn(|b| Next((b * n / t).into()));
                return team.run(&|b| {
                    if b >= t {
                        return;
                    }
                    for k in 0..t {
                        let block = (b + k) % t;
                        let end = (block + 1) * n / t;
                        loop {
                            let c = next[block].0.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                            if c >= end {
                                break;
                            }
                            f(b, c);
                        }
                    }
                });
            }
        }
        let _ = t; // one thread (or the team could not start)
        (0..n).for_each(|c| f(0, c));
    }
}

/// Chunk `c` of `n` items in chunks of `size`.
#[inline]
pub(crate) fn chunk(c: usize, size: usize, n: usize) -> Range<usize> {
    c * size..((c + 1) * size).min(n)
}

/// Number of chunks of `size` covering `n` items (at least one).
pub(crate) fn chunks(n: usize, size: usize) -> usize {
    n.div_ceil(size).max(1)
}

/// A mutable slice that several chunks write, each only its own disjoint range.
pub(crate) struct Out<'a, T> {
    ptr: *mut T,
    len: usize,
    _life: PhantomData<&'a mut [T]>,
}

// SAFETY: the slice is only reached through `range`, whose callers promise disjoint ranges.
unsafe impl<T: Send> Send for Out<'_, T> {}
unsafe impl<T: Send> Sync for Out<'_, T> {}

impl<'a, T> Out<'a, T> {
    pub fn new(s: &'a mut [T]) -> Self {
        Out { ptr: s.as_mut_ptr(), len: s.len(), _life: PhantomData }
    }
    pub fn len(&self) -> usize {
        self.len
    }
    /// The values in `r`.
    ///
    /// # Safety
    /// No two live results may overlap (each chunk takes its own range).
    #[allow(clippy::mut_from_ref)]
    pub unsafe fn range(&self, r: Range<usize>) -> &mut [T] {
        assert!(r.start <= r.end && r.end <= self.len);
        std::slice::from_raw_parts_mut(self.ptr.add(r.start), r.end - r.start)
    }
}
