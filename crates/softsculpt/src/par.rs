//! Threads: the force stages and the implicit solver's passes split their vertices (or springs,
//! or faces) into chunks of a fixed size and hand the chunks to a pool of threads.
//!
//! Deterministic by construction: a chunk's work does not depend on which thread runs it, every
//! output value is written by exactly one chunk (per-vertex gathers, never scatters from two
//! chunks into one value), and reductions (volume, dot products, norms) are summed per chunk
//! into a slot of their own, then the slots in chunk order on the calling thread. The chunk size
//! does not depend on the thread count, so 1 and N threads give the same bits.
//!
//! Native builds use a rayon pool of their own (`Threads::new(n)`, n = 0: every core). On
//! wasm32 there is no pool: every chunk runs on the calling thread.

use std::marker::PhantomData;
use std::ops::Range;

/// A pool of threads (or none: the calling thread). Cheap to clone (shared).
#[derive(Clone, Default)]
pub struct Threads {
    #[cfg(not(target_arch = "wasm32"))]
    pool: Option<std::sync::Arc<rayon::ThreadPool>>,
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

    /// A pool of `n` threads; 0 means one per core. One thread is the caller's (no pool).
    pub fn new(n: usize) -> Result<Self, String> {
        #[cfg(not(target_arch = "wasm32"))]
        {
            let n = if n == 0 { std::thread::available_parallelism().map(|n| n.get()).unwrap_or(1) } else { n };
            if n <= 1 {
                return Ok(Threads::single());
            }
            let pool = rayon::ThreadPoolBuilder::new().num_threads(n).build().map_err(|e| format!("cannot start {n} threads: {e}"))?;
            Ok(Threads { pool: Some(std::sync::Arc::new(pool)) })
        }
        #[cfg(target_arch = "wasm32")]
        {
            let _ = n;
            Ok(Threads::single())
        }
    }

    /// Threads that work on a pass.
    pub fn count(&self) -> usize {
        #[cfg(not(target_arch = "wasm32"))]
        if let Some(p) = &self.pool {
            return p.current_num_threads();
        }
        1
    }

    /// Call `f(c, &mut slot[c])` for every chunk c, on the pool's threads (any order).
    pub(crate) fn each<R: Send>(&self, slots: &mut [R], f: impl Fn(usize, &mut R) + Sync + Send) {
        #[cfg(not(target_arch = "wasm32"))]
        if let Some(pool) = &self.pool {
            if slots.len() > 1 {
                use rayon::prelude::*;
                pool.install(|| slots.par_iter_mut().enumerate().for_each(|(c, r)| f(c, r)));
                return;
            }
        }
        for (c, r) in slots.iter_mut().enumerate() {
            f(c, r);
        }
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
