//! The table of world handles (a world and what the binding keeps beside it: its bodies' views,
//! the mark, the open scene), and the calls that make, free and find worlds and set the threads
//! they step on. Every call on a world finds it here ([`with_world`], [`with_body`]).
//! Single-threaded (wasm32 without threads).

use crate::abi::exports;
use crate::views::BodyViews;
use crate::{index, Fail, Res};
use softsculpt::scene::SceneSpec;
use softsculpt::{SoftBody, World, WorldSettings};
use std::cell::RefCell;

/// A world and what the binding keeps beside it.
pub struct Handle {
    pub world: World,
    /// One per body, in body order (`views.rs`).
    pub views: Vec<BodyViews>,
    /// The world as `ss_mark` saw it (`ss_delta` compares with it).
    pub mark: Option<World>,
    /// The open scene's names, file and length, for `ss_save_scene` (`scene.rs`).
    pub scene: Option<SceneInfo>,
}

impl Handle {
    fn new(world: World) -> Self {
        let mut h = Handle {
            world,
            views: Vec::new(),
            mark: None,
            scene: None,
        };
        h.rebuild_views();
        h
    }
    /// New views for every body (after bodies were replaced).
    pub fn rebuild_views(&mut self) {
        self.views = (0..self.world.bodies.len())
            .map(|i| BodyViews::new(&self.world, i))
            .collect();
    }
    /// Body `b`'s index, checked.
    pub fn body(&self, b: u32) -> Res<usize> {
        let n = self.world.bodies.len();
        if (b as usize) < n {
            Ok(b as usize)
        } else {
            Err(Fail::usage(format!(
                "there is no body {b} (the world has {n})"
            )))
        }
    }
    /// Add `body` to the world, with its views; its index.
    pub fn add(&mut self, body: SoftBody) -> usize {
        let i = self.world.add_body(body);
        self.views.push(BodyViews::new(&self.world, i));
        i
    }
}

thread_local! {
    static WORLDS: RefCell<Vec<Option<Handle>>> = const { RefCell::new(Vec::new()) };
    /// The page's one pool (`ss_use_threads`), shared by every world: single until then.
    static THREADS: RefCell<softsculpt::par::Threads> = RefCell::new(softsculpt::par::Threads::single());
}

fn insert(world: World) -> usize {
    WORLDS.with(|t| {
        let mut t = t.borrow_mut();
        t.push(Some(Handle::new(world)));
        t.len()
    })
}

/// Run `f` on the world of handle `w`.
pub fn with_world<R>(w: u32, f: impl FnOnce(&mut Handle) -> Res<R>) -> Res<R> {
    WORLDS.with(|t| {
        let mut t = t.borrow_mut();
        match (w as usize)
            .checked_sub(1)
            .and_then(|i| t.get_mut(i))
            .and_then(Option::as_mut)
        {
            Some(h) => {
                // Every world steps on the page's pool, also one a call replaced (a restore, a
                // scene, an undo): a clone of the pool is one reference count.
                THREADS.with(|p| h.world.share_threads(&p.borrow()));
                f(h)
            }
            None => Err(Fail::usage(format!("there is no world with handle {w}"))),
        }
    })
}

/// Run `f` on body `b` of world `w` (its index checked).
pub fn with_body<R>(w: u32, b: u32, f: impl FnOnce(&mut Handle, usize) -> Res<R>) -> Res<R> {
    with_world(w, |h| {
        let i = h.body(b)?;
        f(h, i)
    })
}

/// What a world handle keeps of the scene it opened.
pub struct SceneInfo {
    /// The file as parsed: its obstacles and events are written back on save.
    pub spec: SceneSpec,
    /// Body names, in body order.
    pub names: Vec<String>,
    /// Length of the run (s).
    pub duration: f64,
}

exports! {
    /// An empty world with the parameter table's defaults.
    pub fn ss_world_new() -> i32 {
        index(|| Ok(insert(World::new(Vec::new(), WorldSettings::default()))))
    }

    pub fn ss_world_free(w: u32) {
        WORLDS.with(|t| {
            if let Some(slot) = (w as usize)
                .checked_sub(1)
                .and_then(|i| t.borrow_mut().get_mut(i).map(Option::take))
            {
                drop(slot);
            }
        });
    }

    /// Step every world on `n` threads: the caller and n − 1 of the helper threads the page started
    /// (`ss_thread_serve`; 0: all of them). Returns the count in use; −1 (error) when the build has
    /// no threads (n > 1 without atomics) or too few helpers serve. 1 goes back to one thread.
    pub fn ss_use_threads(n: u32) -> i32 {
        index(|| {
            if n > 1 && softsculpt::par::max_threads() < n as usize {
                return Err(Fail::usage(format!(
                    "{n} threads asked for; this build runs {} (the threaded build needs the page cross-origin isolated)",
                    softsculpt::par::max_threads()
                )));
            }
            // The old pool is dropped first, so its helpers serve the new one.
            THREADS.with(|p| *p.borrow_mut() = softsculpt::par::Threads::single());
            WORLDS.with(|t| t.borrow_mut().iter_mut().flatten().for_each(|h| h.world.share_threads(&softsculpt::par::Threads::single())));
            let pool = softsculpt::par::Threads::new(n as usize).map_err(Fail::usage)?;
            let count = pool.count();
            THREADS.with(|p| *p.borrow_mut() = pool);
            Ok(count)
        })
    }

    /// A helper thread's life (a Web Worker on the same module and shared memory, its stack and
    /// thread-local block set up: `web/src/engine/threads.ts`): serve the pool's passes; never
    /// returns. Threaded builds only; elsewhere it returns at once.
    pub fn ss_thread_serve() {
        #[cfg(all(target_arch = "wasm32", target_feature = "atomics"))]
        softsculpt::par::serve();
    }

    /// Passes a helper thread took part in so far (`softsculpt::par::passes_helped`), as f64.
    pub fn ss_thread_passes() -> f64 {
        softsculpt::par::passes_helped() as f64
    }

    /// The address of the flag a helper's JavaScript sets (`Atomics.store`, u32) when its
    /// `ss_thread_serve` traps, so a pass waiting for it fails instead of waiting forever
    /// (`softsculpt::par::host`). 0 in builds without threads.
    pub fn ss_thread_trapped_flag() -> usize {
        #[cfg(all(target_arch = "wasm32", target_feature = "atomics"))]
        return softsculpt::par::trapped_flag() as usize;
        #[cfg(not(all(target_arch = "wasm32", target_feature = "atomics")))]
        0
    }

    /// Threads the worlds step on (1 until `ss_use_threads`).
    pub fn ss_threads() -> u32 {
        THREADS.with(|p| p.borrow().count() as u32)
    }

    /// The standard benchmark workload at an icosphere level (see `softsculpt::workload`).
    pub fn ss_workload(level: u32) -> i32 {
        index(|| {
            if level > 8 {
                return Err(Fail::usage(format!(
                    "level {level} is too large (at most 8)"
                )));
            }
            Ok(insert(softsculpt::workload::world(level)))
        })
    }
}
