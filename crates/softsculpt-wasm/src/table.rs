//! The table of live bodies and the last message. Single-threaded (wasm32 without threads).

use softsculpt::body::{Ground, SoftBody};
use std::cell::RefCell;

/// A body and the arrays the page views.
pub struct Entry {
    pub body: SoftBody,
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
    backup_x: Vec<f64>,
    backup_v: Vec<f64>,
    /// A one-body world for self-collision, made when first needed (it holds a stand-in body
    /// between steps; the real one is swapped in to step).
    world: Option<softsculpt::world::World>,
}

impl Entry {
    pub fn new(body: SoftBody) -> Self {
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
            ground: body.params.ground.unwrap_or(crate::default_ground()),
            backup_x: body.positions().to_vec(),
            backup_v: body.velocities().to_vec(),
            world: None,
            body,
        };
        e.sync();
        e
    }
    pub fn sync(&mut self) {
        for (r, &x) in self.render.iter_mut().zip(self.body.positions()) {
            *r = x as f32;
        }
    }
    pub fn checkpoint(&mut self) {
        self.backup_x.copy_from_slice(self.body.positions());
        self.backup_v.copy_from_slice(self.body.velocities());
    }
    /// One step of `dt` s: alone, or in a one-body world when the body collides with itself.
    /// The contact thickness there is a fifth of the mean rest edge length.
    pub fn step(&mut self, dt: f64) -> Result<(), softsculpt::SimError> {
        if !self.body.params.self_collision {
            return self.body.step(dt);
        }
        let rest = self.body.rest_lengths();
        let thickness = 0.2 * rest.iter().sum::<f64>() / rest.len().max(1) as f64;
        let world = self.world.get_or_insert_with(|| softsculpt::world::World::new(vec![self.body.clone()], thickness));
        world.thickness = thickness;
        std::mem::swap(&mut self.body, &mut world.bodies[0]);
        let r = world.step(dt);
        std::mem::swap(&mut self.body, &mut world.bodies[0]);
        r
    }

    pub fn rollback(&mut self) {
        // The backup was finite when taken, so this cannot fail.
        let _ = self.body.set_state(&self.backup_x, &self.backup_v);
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
