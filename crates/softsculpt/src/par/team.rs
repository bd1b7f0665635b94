//! A team of threads for short passes: a fork/join that costs about a microsecond, not tens.
//!
//! Why not rayon's `install` for these passes: an explicit step at 10,242 vertices is ~0.1 ms of
//! work split into two passes; rayon's workers fall asleep a few microseconds after a pass, and
//! waking them through the kernel (tens of µs per pass, measured: 2 threads were slower than 1)
//! costs more than the pass. Here the caller is thread 0 and runs its own share; the other
//! threads spin on an epoch counter for up to [`SPIN`] after each pass (so back-to-back passes
//! and steps find them awake: a fork is one cache-line write, a join one counter), then park
//! (no CPU is burnt while the body is not stepping). The spinning uses the `pause` hint and
//! bounds itself in time, so a loaded machine loses at most [`SPIN`] of one core per pass.
//!
//! A worker takes part in a pass only if it joins before the caller has finished its own share:
//! the caller's share must then include all work left (it claims chunks until none remain,
//! `Threads::blocks`), and it closes the pass to latecomers instead of waiting for a worker the
//! system has not scheduled (on a loaded machine that wait was milliseconds).
//!
//! A panic on any thread is caught there; the caller waits for every thread that joined to
//! finish the pass (the job borrows the caller's stack) and then panics itself.

use std::cell::UnsafeCell;
use std::panic::{catch_unwind, resume_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering::*};
use std::sync::{Arc, Mutex};
use std::thread;
#[cfg(not(target_arch = "wasm32"))]
use std::time::{Duration, Instant};

/// Passes a worker (not a caller) took part in, over every team: what shows that the threads
/// work (the page's thread test reads it through `ss_thread_passes`).
pub(crate) static PASSES_HELPED: AtomicU64 = AtomicU64::new(0);

/// How long an idle thread spins before it parks.
#[cfg(not(target_arch = "wasm32"))]
const SPIN: Duration = Duration::from_micros(100);
/// WebAssembly has no clock in the core (`Instant` is not implemented on wasm32-unknown-unknown):
/// an idle thread spins this many epoch reads (about 100 µs: a read and a compare take ~1 ns)
/// before it parks.
#[cfg(target_arch = "wasm32")]
const SPIN_READS: u32 = 1 << 17;

type Job = dyn Fn(usize) + Sync;

struct Shared {
    /// Incremented by the caller for each pass (and to quit).
    epoch: AtomicU64,
    /// The pass: written by the caller before the epoch's increment, read by the workers after
    /// they see it, cleared after every worker reported done (so no worker reads it meanwhile).
    job: UnsafeCell<Option<*const Job>>,
    /// Workers done with the current pass.
    done: AtomicUsize,
    /// Per worker: 2e once it joined pass e, 2e + 1 once the caller closed pass e to it.
    joined: Vec<AtomicU64>,
    panicked: AtomicBool,
    quit: AtomicBool,
    /// Worker w (1..) is parked or about to park.
    sleeping: Vec<AtomicBool>,
    /// Worker w's thread, set when it starts (before it can park).
    threads: Vec<std::sync::OnceLock<thread::Thread>>,
    /// Workers that have returned (after `quit`).
    ended: AtomicUsize,
}

// SAFETY: `job` is only written while no worker can read it (see the field), and the job it
// points to is `Sync`.
unsafe impl Sync for Shared {}
unsafe impl Send for Shared {}

pub(crate) struct Team {
    shared: Arc<Shared>,
    /// Workers started (1..=workers).
    workers: usize,
    /// One pass at a time; a caller that finds the team busy runs the pass alone.
    gate: Mutex<()>,
}

impl Team {
    /// A team of `n` threads: the caller and `n − 1` workers. Errors if a thread cannot start.
    pub fn new(n: usize) -> std::io::Result<Team> {
        let shared = Arc::new(Shared {
            epoch: AtomicU64::new(0),
            job: UnsafeCell::new(None),
            done: AtomicUsize::new(0),
            joined: (0..n).map(|_| AtomicU64::new(0)).collect(),
            panicked: AtomicBool::new(false),
            quit: AtomicBool::new(false),
            sleeping: (0..n).map(|_| AtomicBool::new(false)).collect(),
            threads: (0..n).map(|_| Default::default()).collect(),
            ended: AtomicUsize::new(0),
        });
        let mut team = Team { shared: shared.clone(), workers: 0, gate: Mutex::new(()) };
        for w in 1..n {
            let sh = shared.clone();
            // `team` is dropped on error, which stops the workers already started.
            start(w, Box::new(move || worker(&sh, w)))?;
            team.workers += 1;
        }
        Ok(team)
    }

    /// Threads in the team, the caller included.
    pub fn len(&self) -> usize {
        self.workers + 1
    }

    /// Run `f(0)` on the calling thread and `f(t)` on each worker t (1..len()) that joins the
    /// pass before `f(0)` returns; return when those are done. `f(0)` must leave no work undone
    /// (it takes whatever the others have not claimed).
    pub fn run(&self, f: &(dyn Fn(usize) + Sync)) {
        let Ok(_gate) = self.gate.try_lock() else {
            // Another caller has the team (or this is a nested call): the same work, alone.
            return (0..self.len()).for_each(f);
        };
        let sh = &*self.shared;
        // SAFETY: the lifetime is erased for storage only; the job is cleared below after every
        // worker reported done, before `f`'s borrow ends (also when a thread panicked).
        let job: *const Job = unsafe { std::mem::transmute::<*const (dyn Fn(usize) + Sync + '_), *const Job>(f as *const _) };
        // SAFETY: no worker reads `job` between passes.
        unsafe { *sh.job.get() = Some(job) };
        sh.done.store(0, Relaxed);
        sh.panicked.store(false, Relaxed);
        let epoch = sh.epoch.fetch_add(1, SeqCst) + 1;
        self.wake();
        let mine = catch_unwind(AssertUnwindSafe(|| f(0)));
        // Close the pass to the workers that have not joined; wait for those that have.
        let joined = (1..self.len()).filter(|&w| !close(&sh.joined[w], epoch)).count();
        let mut spins = 0u32;
        while sh.done.load(Acquire) < joined {
            #[cfg(target_arch = "wasm32")]
            if super::host::trapped() {
                panic!("a helper thread of the engine stopped during a pass (host.rs, 'A helper that traps')");
            }
            spins += 1;
            if spins < 1 << 14 {
                std::hint::spin_loop();
            } else {
                thread::yield_now();
            }
        }
        // SAFETY: every worker that joined is done with the pass; the others never will.
        unsafe { *sh.job.get() = None };
        if let Err(p) = mine {
            resume_unwind(p);
        }
        if sh.panicked.load(Acquire) {
            panic!("a thread of the pool panicked during a pass");
        }
    }

    fn wake(&self) {
        for w in 1..self.len() {
            if self.shared.sleeping[w].load(SeqCst) {
                // A worker sets `sleeping` only after its thread is recorded.
                if let Some(t) = self.shared.threads[w].get() {
                    t.unpark();
                }
            }
        }
    }
}

impl Drop for Team {
    fn drop(&mut self) {
        self.shared.quit.store(true, SeqCst);
        self.shared.epoch.fetch_add(1, SeqCst);
        self.wake();
        // Every worker returns (it borrows nothing of the caller's; waiting keeps a dropped
        // team's threads from outliving it, and on wasm32 frees their helpers for the next).
        while self.shared.ended.load(Acquire) < self.workers {
            #[cfg(target_arch = "wasm32")]
            if super::host::trapped() {
                return; // a trapped helper never ends; the others are not waited for either
            }
            self.wake();
            thread::yield_now();
        }
    }
}

/// Start worker `w` running `f`: a named thread natively, a host's helper on wasm32 (`host.rs`).
fn start(w: usize, f: Box<dyn FnOnce() + Send>) -> std::io::Result<()> {
    #[cfg(not(target_arch = "wasm32"))]
    return thread::Builder::new().name(format!("softsculpt-{w}")).spawn(f).map(drop);
    #[cfg(target_arch = "wasm32")]
    {
        let _ = w;
        super::host::spawn(f)
    }
}

fn worker(sh: &Shared, w: usize) {
    let _ = sh.threads[w].set(thread::current());
    let mut seen = 0u64;
    loop {
        wait(sh, w, seen);
        seen = sh.epoch.load(Acquire);
        if sh.quit.load(Acquire) {
            sh.ended.fetch_add(1, Release);
            return;
        }
        if !join(&sh.joined[w], seen) {
            continue; // The caller finished the pass without this worker.
        }
        PASSES_HELPED.fetch_add(1, Relaxed);
        // SAFETY: the caller wrote the job before the epoch we saw and clears it only after
        // this worker's `done` below.
        let job = unsafe { (*sh.job.get()).expect("a pass with every epoch") };
        // SAFETY: the caller keeps the job alive until every worker is done.
        if catch_unwind(AssertUnwindSafe(|| unsafe { (*job)(w) })).is_err() {
            sh.panicked.store(true, Release);
        }
        sh.done.fetch_add(1, Release);
    }
}

/// The worker takes part in pass `epoch` (false: the caller closed it first).
fn join(slot: &AtomicU64, epoch: u64) -> bool {
    let old = slot.load(Acquire);
    old < 2 * epoch && slot.compare_exchange(old, 2 * epoch, AcqRel, Acquire).is_ok()
}

/// The caller closes pass `epoch` to a worker: true if it had not joined (it never will).
fn close(slot: &AtomicU64, epoch: u64) -> bool {
    let old = slot.load(Acquire);
    old < 2 * epoch && slot.compare_exchange(old, 2 * epoch + 1, AcqRel, Acquire).is_ok()
}

/// Until the epoch differs from `seen`: spin for up to [`SPIN`], then park.
fn wait(sh: &Shared, w: usize, seen: u64) {
    #[cfg(not(target_arch = "wasm32"))]
    let mut since: Option<Instant> = None;
    let mut spins = 0u32;
    while sh.epoch.load(Acquire) == seen {
        spins = spins.wrapping_add(1);
        #[cfg(not(target_arch = "wasm32"))]
        let spin = !spins.is_multiple_of(64) || since.get_or_insert_with(Instant::now).elapsed() < SPIN;
        #[cfg(target_arch = "wasm32")]
        let spin = spins < SPIN_READS;
        if spin {
            std::hint::spin_loop();
            continue;
        }
        // Park. The caller increments the epoch, then reads `sleeping`; we set `sleeping`,
        // then read the epoch (both SeqCst): at least one of us sees the other's write, so a
        // pass never waits for a parked worker. A spurious or stale unpark only loops.
        sh.sleeping[w].store(true, SeqCst);
        if sh.epoch.load(SeqCst) == seen {
            thread::park();
        }
        sh.sleeping[w].store(false, SeqCst);
        #[cfg(not(target_arch = "wasm32"))]
        {
            since = None;
        }
        spins = 0;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_callers_share_runs_every_pass_and_a_worker_at_most_once() {
        let team = Team::new(3).unwrap();
        let hits: Vec<AtomicUsize> = (0..3).map(|_| AtomicUsize::new(0)).collect();
        for pass in 0..1000 {
            if pass % 100 == 0 {
                // Long enough for the workers to park: the pass must not wait for them.
                thread::sleep(SPIN * 3);
            }
            let seen: Vec<AtomicUsize> = (0..3).map(|_| AtomicUsize::new(0)).collect();
            team.run(&|t| {
                seen[t].fetch_add(1, Relaxed);
                hits[t].fetch_add(1, Relaxed);
            });
            assert_eq!(seen[0].load(Relaxed), 1);
            assert!(seen.iter().all(|s| s.load(Relaxed) <= 1));
        }
        assert_eq!(hits[0].load(Relaxed), 1000);
    }

    #[test]
    fn workers_that_join_are_waited_for() {
        let team = Team::new(2).unwrap();
        for _ in 0..200 {
            let done = AtomicUsize::new(0);
            team.run(&|t| {
                if t == 0 {
                    // Give the worker time to join, then return before it is done.
                    thread::sleep(Duration::from_micros(20));
                } else {
                    thread::sleep(Duration::from_micros(200));
                    done.fetch_add(1, Relaxed);
                }
            });
            // Whatever joined has finished: nothing runs after `run` returns.
            let d = done.load(Relaxed);
            thread::sleep(Duration::from_micros(300));
            assert_eq!(done.load(Relaxed), d);
        }
    }

    #[test]
    fn a_panic_on_a_worker_reaches_the_caller_and_the_team_still_works() {
        let team = Team::new(2).unwrap();
        // The caller waits for the worker to join (so that it fails), then fails itself if not.
        let joined = AtomicBool::new(false);
        let r = catch_unwind(AssertUnwindSafe(|| {
            team.run(&|t| {
                if t == 0 {
                    let t0 = Instant::now();
                    while !joined.load(SeqCst) && t0.elapsed() < Duration::from_secs(5) {
                        std::hint::spin_loop();
                    }
                } else {
                    joined.store(true, SeqCst);
                    panic!("worker fails");
                }
            })
        }));
        assert!(r.is_err());
        let n = AtomicUsize::new(0);
        team.run(&|_| {
            n.fetch_add(1, Relaxed);
        });
        assert_eq!(n.load(Relaxed), 2);
    }
}
