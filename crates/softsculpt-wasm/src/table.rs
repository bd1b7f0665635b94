//! The table of live bodies and the last message. Single-threaded (wasm32 without threads).

use softsculpt::body::SoftBody;
use softsculpt::world::{Ground, World};
use std::cell::RefCell;

/// A body in its one-body world, and the arrays the page views.
pub struct Entry {
    /// One body; its world parameters (`ss_get`/`ss_set`) are this world's settings.
    pub world: World,
    pub render: Vec<f32>,
    pub triangles: Vec<u32>,
    pub springs: Vec<u32>,
    pub pinned: Vec<u8>,
    pub user_forces: Vec<f64>,
    pub face_pressures: Vec<f64>,
    pub scratch: Vec<f64>,
    pub vectors: Vec<f64>,
    pub stats: [f64; 16],
    /// Ground settings kept while the ground is off.
    pub ground: Ground,
}

impl Entry {
    pub fn new(world: World) -> Self {
        let body = &world.bodies[0];
        let n = body.vertex_count();
        let (si, sj) = body.spring_ends();
        let springs = si.iter().zip(sj).flat_map(|(&a, &b)| [a, b]).collect();
        let mut e = Entry {
            render: vec![0.0; 3 * n],
            triangles: body.triangles().iter().flatten().copied().collect(),
            springs,
            pinned: (0..n).map(|i| body.is_pinned(i) as u8).collect(),
            user_forces: vec![0.0; 3 * n],
            face_pressures: vec![0.0; body.face_count()],
            scratch: vec![0.0; n],
            vectors: vec![0.0; 3 * n],
            stats: [0.0; 16],
            ground: world.settings.ground.unwrap_or(crate::default_ground()),
            world,
        };
        e.sync();
        e
    }
    pub fn body(&self) -> &SoftBody {
        &self.world.bodies[0]
    }
    pub fn sync(&mut self) {
        for (r, &x) in self.render.iter_mut().zip(self.world.bodies[0].positions()) {
            *r = x as f32;
        }
    }
    /// `substeps` steps of `dt` s, or none (the world rolls back on failure). With
    /// self-collision the contact thickness is a fifth of the mean rest edge length.
    pub fn step(&mut self, dt: f64, substeps: u32) -> Result<(), String> {
        self.world.settings.dt = dt;
        if self.body().material.self_collision {
            let rest = self.body().rest_lengths();
            self.world.settings.contact.thickness = 0.2 * rest.iter().sum::<f64>() / rest.len().max(1) as f64;
        }
        self.world.step_n(substeps as u64).map_err(|e| e.to_string())
    }
}

#[derive(Default)]
pub struct Table {
    entries: Vec<Option<Entry>>,
}

impl Table {
    pub fn insert(&mut self, e: Entry) -> u32 {
        self.entries.push(Some(e));
        self.entries.len() as u32
    }
    pub fn remove(&mut self, h: u32) {
        if let Some(slot) = (h as usize).checked_sub(1).and_then(|i| self.entries.get_mut(i)) {
            *slot = None;
        }
    }
    pub fn get(&mut self, h: u32) -> Option<&mut Entry> {
        (h as usize).checked_sub(1).and_then(|i| self.entries.get_mut(i)).and_then(|s| s.as_mut())
    }
}

thread_local! {
    static TABLE: RefCell<Table> = RefCell::new(Table::default());
    static MESSAGE: RefCell<String> = const { RefCell::new(String::new()) };
}

pub fn with_table<R>(f: impl FnOnce(&mut Table) -> R) -> R {
    TABLE.with(|t| f(&mut t.borrow_mut()))
}

/// Run `f` on the entry of handle `h`, or return `missing` (with a message) if there is none.
pub fn with<R>(h: u32, missing: R, f: impl FnOnce(&mut Entry) -> R) -> R {
    with_table(|t| match t.get(h) {
        Some(e) => f(e),
        None => {
            set_message(&format!("no body with handle {h}"));
            missing
        }
    })
}

/// 0 if `f` succeeded, 1 (with the message) otherwise.
pub fn status(h: u32, f: impl FnOnce(&mut Entry) -> Result<(), String>) -> u32 {
    match with(h, Err(format!("no body with handle {h}")), f) {
        Ok(()) => 0,
        Err(m) => {
            set_message(&m);
            1
        }
    }
}

pub fn set_message(m: &str) {
    MESSAGE.with(|s| {
        let mut s = s.borrow_mut();
        s.clear();
        s.push_str(m);
    });
}

pub fn fail(m: String) -> u32 {
    set_message(&m);
    0
}

pub fn message_ptr() -> *const u8 {
    MESSAGE.with(|s| s.borrow().as_ptr())
}
pub fn message_len() -> usize {
    MESSAGE.with(|s| s.borrow().len())
}
