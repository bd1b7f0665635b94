//! Bulk data as typed-array views over wasm memory. `ss_body_views(w, b)` (`world.rs`) returns a
//! pointer to body b's layout table: [`LAYOUT_LEN`] u32,
//!
//! | slot | what | type, length |
//! |---|---|---|
//! | 0–3 | vertex, face, spring and bending-spring counts (n, f, s, k) | |
//! | 4 | positions (m), the engine's | f64, 3n |
//! | 5 | velocities (m/s), the engine's | f64, 3n |
//! | 6 | render positions (refreshed by `ss_sync`) | f32, 3n |
//! | 7 | triangles | u32, 3f |
//! | 8 | springs (ends) | u32, 2s |
//! | 9 | vertex masses (kg), the engine's | f64, n |
//! | 10 | pinned (1/0; refreshed by `ss_sync`, read by `ss_set_pins`) | u8, n |
//! | 11 | spring rest lengths (m), the engine's | f64, s |
//! | 12 | bending-spring rest lengths (m), the engine's | f64, k |
//! | 13 | staging: user forces (N), read by `ss_apply_loads` | f64, 3n |
//! | 14 | staging: face pressures (Pa), read by `ss_apply_loads` | f64, f |
//! | 15 | staging: vertex scratch, read by `ss_scale_rest`, `ss_set_masses` | f64, n |
//! | 16 | stats (refreshed by `ss_sync`): step, time, volume, pressure, kinetic, elastic, gas, gravity, total, momentum xyz, centre of mass xyz, max speed | f64, 16 |
//!
//! The engine's arrays are read-only for the page (write through the calls). Pointers stay
//! valid until a call replaces bodies (see the crate documentation); typed arrays over them must
//! be re-made after any call, since any call may grow memory.

use softsculpt::World;

/// Length of the layout table (u32).
pub const LAYOUT_LEN: usize = 17;

/// What the binding keeps for the page beside one body.
pub struct BodyViews {
    pub render: Vec<f32>,
    pub springs: Vec<u32>,
    pub pinned: Vec<u8>,
    pub user_forces: Vec<f64>,
    pub face_pressures: Vec<f64>,
    pub scratch: Vec<f64>,
    pub stats: [f64; 16],
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
            stats: [0.0; 16],
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
        let s = world.stats(i);
        self.stats = [
            s.step as f64,
            s.time,
            s.volume,
            s.pressure,
            s.kinetic_energy,
            s.elastic_energy,
            s.gas_energy,
            s.gravity_energy,
            s.total_energy,
            s.momentum[0],
            s.momentum[1],
            s.momentum[2],
            s.center_of_mass[0],
            s.center_of_mass[1],
            s.center_of_mass[2],
            s.max_speed,
        ];
    }

    /// The layout table of body `i` (pointers as they are now).
    pub fn layout(&mut self, world: &World, i: usize) -> *const u32 {
        let b = &world.bodies[i];
        let p = |ptr: *const u8| ptr as usize as u32;
        self.layout = [
            b.vertex_count() as u32,
            b.face_count() as u32,
            b.spring_count() as u32,
            b.bending_rest_lengths().len() as u32,
            p(b.positions().as_ptr().cast()),
            p(b.velocities().as_ptr().cast()),
            p(self.render.as_ptr().cast()),
            p(b.triangles().as_ptr().cast()),
            p(self.springs.as_ptr().cast()),
            p(b.masses().as_ptr().cast()),
            p(self.pinned.as_ptr()),
            p(b.rest_lengths().as_ptr().cast()),
            p(b.bending_rest_lengths().as_ptr().cast()),
            p(self.user_forces.as_ptr().cast()),
            p(self.face_pressures.as_ptr().cast()),
            p(self.scratch.as_ptr().cast()),
            p(self.stats.as_ptr().cast()),
        ];
        self.layout.as_ptr()
    }
}
