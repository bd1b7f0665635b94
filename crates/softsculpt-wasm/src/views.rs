//! Bulk data as typed-array views over wasm memory. `ss_body_views(w, b)` (`world.rs`) returns a
//! pointer to body b's layout table: [`LAYOUT_LEN`] u32, one per [`Slot`], in the order of the `slots!` list below (its doc comments say what each
//! holds, its type and length): the four counts (n, f, s, k), then pointers to the engine's
//! f64 arrays and to the arrays the binding keeps for the page (f32 render positions, u32
//! springs, u8 pins, f64 staging, the stats block: [`STATS`], in the order of the `stats!`
//! list). The page's slot numbers and stats order are written from these two lists
//! (`web/src/engine/abi.ts`, by `tests/abi.rs`), never matched by hand.
//!
//! The engine's arrays are read-only for the page (write through the calls). Pointers stay
//! valid until a call replaces bodies (see the crate documentation); typed arrays over them must
//! be re-made after any call, since any call may grow memory.

use softsculpt::{Stats, World};

/// The slots of the layout table, each once, in order: the enum the binding fills the table by
/// (`Slot::Positions as usize`) and the list [`SLOTS`] the page's `SLOT` is written from
/// (`web/src/engine/abi.ts`, by `tests/abi.rs`; names in lowerCamelCase: `BendingRest` →
/// `bendingRest`).
macro_rules! slots {
    ($($(#[doc = $d:literal])* $slot:ident,)*) => {
        /// A slot of the layout table (see the module documentation).
        #[derive(Clone, Copy, Debug, PartialEq, Eq)]
        pub enum Slot { $($(#[doc = $d])* $slot,)* }
        /// Every slot's name and doc comment, in slot order.
        pub const SLOTS: &[(&str, &str)] = &[$((stringify!($slot), concat!($($d, "\n",)* ""))),*];
    };
}
slots! {
    /// Vertex count n.
    N,
    /// Face count f.
    F,
    /// Spring count s.
    S,
    /// Bending-spring count k.
    K,
    /// Positions (m), the engine's: f64, 3n.
    Positions,
    /// Velocities (m/s), the engine's: f64, 3n.
    Velocities,
    /// Render positions (refreshed by `ss_sync`): f32, 3n.
    Render,
    /// Triangles: u32, 3f.
    Triangles,
    /// Springs (ends): u32, 2s.
    Springs,
    /// Vertex masses (kg), the engine's: f64, n.
    Masses,
    /// Pinned (1/0; refreshed by `ss_sync`, read by `ss_set_pins`): u8, n.
    Pinned,
    /// Spring rest lengths (m), the engine's: f64, s.
    Rest,
    /// Bending-spring rest lengths (m), the engine's: f64, k.
    BendingRest,
    /// Staging: user forces (N), read by `ss_apply_loads`: f64, 3n.
    UserForces,
    /// Staging: face pressures (Pa), read by `ss_apply_loads`: f64, f.
    FacePressures,
    /// Staging: vertex scratch, read by `ss_scale_rest`, `ss_set_masses`: f64, n.
    Scratch,
    /// Stats (refreshed by `ss_sync`): f64, `STATS_LEN` (the stats block, `STATS`).
    Stats,
}

/// Length of the layout table (u32).
pub const LAYOUT_LEN: usize = SLOTS.len();

/// One entry of the stats block: the page's key, how many f64 it takes, its doc comment.
#[derive(Debug)]
pub struct Stat {
    pub name: &'static str,
    pub width: usize,
    pub doc: &'static str,
}

/// The stats block, each entry once, in order: the list [`STATS`] (the page's `Stats` and
/// `readStats` are written from it, `tests/abi.rs`) and the function that fills the block from
/// the core's [`Stats`] (`$s`: its name in the expressions), an expression per f64.
macro_rules! stats {
    ($s:ident => $($(#[doc = $d:literal])* $name:literal: [$($e:expr),+],)*) => {
        /// Every entry of the stats block, in order.
        pub const STATS: &[Stat] = &[$(Stat { name: $name, width: [$(stringify!($e)),+].len(), doc: concat!($($d, "\n",)* "") }),*];
        /// The stats block of `s`.
        fn stats_block($s: &Stats) -> [f64; STATS_LEN] {
            [$($($e),+),*]
        }
    };
}
stats! { s =>
    /// Steps taken.
    "step": [s.step as f64],
    /// Simulated time (s).
    "time": [s.time],
    /// The volume the pressure uses (m³).
    "volume": [s.volume],
    /// Gas pressure (Pa).
    "pressure": [s.pressure],
    /// Kinetic energy (J).
    "kinetic": [s.kinetic_energy],
    /// Elastic energy (J).
    "elastic": [s.elastic_energy],
    /// Gas energy (J).
    "gas": [s.gas_energy],
    /// Gravitational energy (J).
    "gravity": [s.gravity_energy],
    /// The sum of the four energies (J).
    "total": [s.total_energy],
    /// Momentum (kg·m/s).
    "momentum": [s.momentum[0], s.momentum[1], s.momentum[2]],
    /// Centre of mass (m).
    "centerOfMass": [s.center_of_mass[0], s.center_of_mass[1], s.center_of_mass[2]],
    /// Largest speed (m/s).
    "maxSpeed": [s.max_speed],
}

/// Length of the stats block (f64): the entries' widths summed.
pub const STATS_LEN: usize = {
    let (mut n, mut i) = (0, 0);
    while i < STATS.len() {
        n += STATS[i].width;
        i += 1;
    }
    n
};

/// What the binding keeps for the page beside one body.
pub struct BodyViews {
    pub render: Vec<f32>,
    pub springs: Vec<u32>,
    pub pinned: Vec<u8>,
    pub user_forces: Vec<f64>,
    pub face_pressures: Vec<f64>,
    pub scratch: Vec<f64>,
    pub stats: [f64; STATS_LEN],
    layout: [u32; LAYOUT_LEN],
}

impl BodyViews {
    /// Views of body `i` of `world`, synced.
    pub fn new(world: &World, i: usize) -> Self {
        let b = &world.bodies[i];
        let n = b.vertex_count();
        let (si, sj) = b.spring_ends();
        let mut v = BodyViews {
            render: vec![0.0; 3 * n],
            springs: si.iter().zip(sj).flat_map(|(&a, &c)| [a, c]).collect(),
            pinned: vec![0; n],
            user_forces: vec![0.0; 3 * n],
            face_pressures: vec![0.0; b.face_count()],
            scratch: vec![0.0; n],
            stats: [0.0; STATS_LEN],
            layout: [0; LAYOUT_LEN],
        };
        v.sync(world, i);
        v
    }

    /// Render positions, pins and stats from body `i`'s state.
    pub fn sync(&mut self, world: &World, i: usize) {
        let b = &world.bodies[i];
        for (r, &x) in self.render.iter_mut().zip(b.positions()) {
            *r = x as f32;
        }
        for (v, p) in self.pinned.iter_mut().enumerate() {
            *p = b.is_pinned(v) as u8;
        }
        self.stats = stats_block(&world.stats(i));
    }

    /// The layout table of body `i` (pointers as they are now).
    pub fn layout(&mut self, world: &World, i: usize) -> *const u32 {
        let b = &world.bodies[i];
        let p = |ptr: *const u8| ptr as usize as u32;
        let slots: [(Slot, u32); LAYOUT_LEN] = [
            (Slot::N, b.vertex_count() as u32),
            (Slot::F, b.face_count() as u32),
            (Slot::S, b.spring_count() as u32),
            (Slot::K, b.bending_rest_lengths().len() as u32),
            (Slot::Positions, p(b.positions().as_ptr().cast())),
            (Slot::Velocities, p(b.velocities().as_ptr().cast())),
            (Slot::Render, p(self.render.as_ptr().cast())),
            (Slot::Triangles, p(b.triangles().as_ptr().cast())),
            (Slot::Springs, p(self.springs.as_ptr().cast())),
            (Slot::Masses, p(b.masses().as_ptr().cast())),
            (Slot::Pinned, p(self.pinned.as_ptr())),
            (Slot::Rest, p(b.rest_lengths().as_ptr().cast())),
            (Slot::BendingRest, p(b.bending_rest_lengths().as_ptr().cast())),
            (Slot::UserForces, p(self.user_forces.as_ptr().cast())),
            (Slot::FacePressures, p(self.face_pressures.as_ptr().cast())),
            (Slot::Scratch, p(self.scratch.as_ptr().cast())),
            (Slot::Stats, p(self.stats.as_ptr().cast())),
        ];
        for (slot, value) in slots {
            self.layout[slot as usize] = value;
        }
        self.layout.as_ptr()
    }
}
