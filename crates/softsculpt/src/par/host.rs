//! Threads the host starts (WebAssembly with atomics): `std::thread::spawn` cannot start a thread
//! on wasm32-unknown-unknown, so the page's worker starts Web Workers that instantiate the same
//! module on the same shared memory (each with its own stack and thread-local block,
//! `web/src/engine/threads.ts`) and call [`serve`], which never returns: it runs the closures
//! [`spawn`] hands it, one after another. A team (`team.rs`) takes one helper per extra thread
//! for as long as it lives; a dropped team's helpers go back to serving.
//!
//! A helper waits on a condition variable (`memory.atomic.wait32`, allowed in a Worker), so an
//! idle helper burns no CPU. [`spawn`] refuses when no helper is idle (the caller then runs its
//! passes on one thread) instead of queueing work no one may ever take.
//!
//! **A helper that traps.** WebAssembly panics abort: a panic on a helper traps its instance in
//! the middle of a pass, and the team's caller would wait for it forever. So the helper's
//! JavaScript, when `ss_thread_serve` throws, sets [`TRAPPED`] (its address: [`trapped_flag`])
//! in the shared memory, and the team's waits ([`trapped`]) panic on the calling thread instead
//! — a trap of the engine's call, which the page reports and restarts from the autosave, as
//! it does any engine failure.

use std::sync::atomic::{AtomicU32, AtomicUsize, Ordering::SeqCst};
use std::sync::{Condvar, Mutex};

type Task = Box<dyn FnOnce() + Send>;

struct Queue {
    tasks: Vec<Task>,
    /// Helpers waiting in [`serve`] for a task.
    idle: usize,
}

static QUEUE: Mutex<Queue> = Mutex::new(Queue { tasks: Vec::new(), idle: 0 });
static READY: Condvar = Condvar::new();
/// Helpers that have entered [`serve`].
static HELPERS: AtomicUsize = AtomicUsize::new(0);
/// Non-zero once a helper trapped (set by its JavaScript, `web/src/engine/helper.ts`).
static TRAPPED: AtomicU32 = AtomicU32::new(0);

/// The address of the trap flag (a u32 in the shared memory, for `Atomics.store`).
pub fn trapped_flag() -> *const AtomicU32 {
    &TRAPPED
}

/// Whether a helper trapped: a pass it joined will never finish.
pub(crate) fn trapped() -> bool {
    TRAPPED.load(SeqCst) != 0
}

/// Run `f` on an idle helper; an error if none is idle.
pub(crate) fn spawn(f: Task) -> std::io::Result<()> {
    let mut q = QUEUE.lock().unwrap_or_else(|e| e.into_inner());
    if q.idle <= q.tasks.len() {
        return Err(std::io::Error::other("no idle helper thread (the page started too few Web Workers)"));
    }
    q.tasks.push(f);
    READY.notify_one();
    Ok(())
}

/// A helper's whole life: take the tasks [`spawn`] hands out, forever.
pub fn serve() -> ! {
    HELPERS.fetch_add(1, SeqCst);
    loop {
        let task = {
            let mut q = QUEUE.lock().unwrap_or_else(|e| e.into_inner());
            q.idle += 1;
            while q.tasks.is_empty() {
                q = READY.wait(q).unwrap_or_else(|e| e.into_inner());
            }
            q.idle -= 1;
            q.tasks.remove(0)
        };
        task();
    }
}

/// Helpers that have started serving.
pub fn helpers() -> usize {
    HELPERS.load(SeqCst)
}
