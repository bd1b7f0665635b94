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

use std::sync::atomic::{AtomicUsize, Ordering::SeqCst};
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
