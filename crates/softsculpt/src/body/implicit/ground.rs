//! The ground inside the backward-Euler solve: vertices resting on it are constrained.
//!
//! Without this the ground is only the world's after-step projection (`world/ground.rs`): each
//! step the solve lets gravity push a resting body's bottom into the plane by g dt² and the
//! projection puts it back. At dt = 1/60 s that is 2.7 mm per step, and the solve's upper body
//! follows the falling bottom: measured on the modeler's 642-vertex sphere on a frictionless
//! ground, it came to rest 3.0 cm lower (centre of mass 0.6007 m against 0.6308 m) and with 1.1 %
//! less volume than the explicit model's equilibrium (symplectic, dt = 2e-4 s: 0.6307 m). And
//! the solve at rest never met the same problem twice: 3 Newton iterations per step forever.
//!
//! **Constraints** (Baraff & Witkin 1998, §5.3: a constrained vertex's velocity is prescribed
//! along the constrained direction, which is filtered out of the conjugate gradient). At a
//! step's start, a free vertex with y ≤ h (on or in the plane, as the projection leaves it) that
//! is not moving up (v_y ≤ 0; a vertex bounced up by a restitution e > 0 is left free to leave)
//! gets v⁺_y = 0: it stays at its height, x⁺_y = x_y; x and z stay unknowns. Its residual's y
//! component is then the ground's impulse over the step: from M (v⁺ − v) = dt (f + F_g),
//! dt F_g,y = r_y(v⁺) (N·s). The vertices with r_y < 0 (the plane would have to pull them
//! down) are released for the rest of the step, and Newton goes on with them free (the set only
//! shrinks, so it cannot cycle; the tolerance still counts from the first residual): when Newton
//! has converged, and at Newton iterations 1, 2, 3, 4, then 8, 16, … ([`release_due`]: the
//! first iterations' releases let go at once the vertices the landing's prediction over-held,
//! so a stiff ball's patch peels in fewer Newton iterations than with releases at 2, 4, 8, …
//! only — stiff rubber's first second at 10,242 vertices 4,561 → 1,061; releasing at every
//! iteration instead cost clay 2.5×: docs/history/benchmarks-log.md, "Landing inside the
//! implicit step"). Measured on a 10,242-vertex sphere landing with the presets of `tests/presets.rs`: releasing only at convergence, a crumpling
//! cloth stalled for 100 iterations at a relative residual of ~1e-3 with 140 of its 327 held
//! vertices pulled down; releasing at every iterate, clay stalled at ~5e-3 (a few vertices let
//! go every iteration or two, each time a changed problem); the spaced releases let both
//! converge — but not every landing: a jelly (k = 60 N/m, no bending springs) stalled at
//! 1e-3–3e-2 between releases. So a step not converged after [`GIVE_UP`] Newton iterations is
//! solved again from v⁺ = v without the ground in the solve (the after-step projection alone,
//! as before it was part of the solve). Newton iterations (CG iterations) in the first second
//! of those landings, before → after: balloon 1042 (22.2k) → 349 (13.1k), jelly 1428 (25.0k) →
//! 641 (15.0k), clay 1051 (27.4k) → 475 (16.2k), cloth 1352 (32.9k) → 1290 (37.5k). Giving up
//! after 24, 32 or 48 iterations instead cost up to 4× more on clay; and going on from the
//! half-converged held iterate (as this did until the landing was held too) is slower than
//! starting again: with the landing held, the stiff rubber preset (k = 2000 N/m) at 10,242
//! vertices stalls in most steps of its landing, each step 64 held iterations, 36 more from
//! that iterate to the cap of 100, and a third solve without the ground; starting again at
//! 64 took its first second from 4,117 to 4,541 Newton iterations but 123k to 44k CG
//! iterations, 97 → 38 s (the other presets unchanged or faster: clay 5.3 → 4.3 s; the history
//! log, "Landing inside the implicit step"). Giving up at 32 or 48 then: rubber 29 / 34 s but
//! cloth 10.6 → 16–17 s. A body at rest on the ground is then an equilibrium of the solve: the plane
//! carries the bottom's weight, and v⁺ = v is already converged (measured: 0–1 Newton
//! iterations per step at rest, against 3).
//!
//! **Landing in the step**: without restitution, a vertex whose explicit prediction
//! x_y + dt v_y falls below the plane is held from the step's start too, with
//! v⁺_y = (h − x_y) / dt (it ends the step exactly on the plane), and so is a vertex a
//! not-yet-converged iterate x + dt v⁺ puts below it at Newton iterations 1, 2, 4, …,
//! [`ADD_UNTIL`] (each vertex at most once in a step: with the shrinking releases the set
//! cannot cycle; a step converged by then leaves the rest to the projection). All go through
//! the same release test as the resting vertices (a vertex the body would hold back above the
//! plane has r_y < 0 and is let go). After the accepted solve the landed vertices are at rest
//! along the normal on the plane ([`GroundSet::land`]), as the after-step projection leaves an
//! inelastic landing. Why: before, only vertices already on the plane were held, and the ring
//! landing in the step fell through it inside the solve, folded about the held bottom, and was
//! pushed back only by the projection. On a fine mesh that fold is as deep as the mesh is fine
//! (|v_y| dt = 2 cm at 1.3 m/s, one edge at 40,962 vertices on the modeler's 2.5 m sphere):
//! measured there, from step 12 of the drop the held attempt stalled at a relative residual of
//! 2e-3–3e-2 with 60–75 % of the residual on the ~600–1,200 vertices below the plane, 72–180
//! Newton iterations per step; with the landing held, 4–17 (45 steps of the drop: 2,327 → 383
//! Newton iterations, 138 → 22 s; the centre of mass 0.8–2.3 cm from a dt/4 reference run
//! this way, where the old way at dt was 1.0–3.8 cm from it; three times sampled). At 10,242
//! vertices, where the ring is half an edge deep, the landing's first second with the presets
//! of `tests/presets.rs` (docs/history/benchmarks-log.md, "Landing inside the implicit step"): k = k_b = 500
//! 2.7× faster; the default 1.1×, balloon 1.4×, jelly 1.2×, clay 1.5×, cloth 1.2–1.3× slower
//! (the prediction over-holds vertices the body stops above the plane, each release one more
//! Newton round); stiff rubber chaotic either way. With restitution the projection's bounce is
//! kept.
//!
//! **Friction** after the accepted solve, Coulomb with the normal impulse per unit mass
//! j = r_y / m (m/s; plus the landing's stop |v⁺_y| for a vertex landing in the step): the
//! tangential velocity loses up to μ j (stops if |v_t| ≤ μ j), as the
//! projection does with its j (`world/ground.rs`); positions are x + dt v⁺ from the solve.
//! Tried and dropped: stuck vertices held in all three directions, released to sliding where
//! |r_t| > μ r_y. While a body lands nearly every stuck vertex then flips to sliding within the
//! step, each flip another Newton round: 10–22 Newton iterations per step against 5–16.
//!
//! Not for self-colliding bodies (their ground stays the after-step projection): with held
//! vertices the crushed mushroom of `tests/self_contact.rs` had a vertex through its skin after
//! 8 s (also when the vertices of the step's self-contacts were not held); not investigated.
//!
//! The constraints depend only on the state at the step's start and the Newton iterates, so a
//! restored snapshot takes the same steps.

use super::super::Model;
use crate::settings::Ground;

/// The last Newton iteration at which vertices the iterate puts below the plane are taken into
/// the set (at 1, 2, 4, …, this): later the set only shrinks.
pub(crate) const ADD_UNTIL: u32 = 16;
/// Newton iterations after which a step still not converged with the ground's vertices held
/// is solved again without them.
pub(crate) const GIVE_UP: u32 = 64;
/// Releases at every Newton iteration up to this one, then at powers of two ([`release_due`]).
pub(crate) const RELEASE_EVERY_UNTIL: u32 = 4;

/// Whether the held vertices the plane would pull down are released after Newton iteration `k`
/// (besides at convergence): at 1, 2, …, [`RELEASE_EVERY_UNTIL`], then 8, 16, 32, … (see the
/// module doc, "Constraints").
pub(crate) fn release_due(k: u32) -> bool {
    k >= 1 && (k <= RELEASE_EVERY_UNTIL || k.is_power_of_two())
}

/// The vertices the ground holds in one step, and their impulses.
#[derive(Debug, Clone, Default)]
pub(crate) struct GroundSet {
    /// Indices of the held vertices, ascending.
    pub list: Vec<u32>,
    /// Per vertex: held this step (its v⁺_y prescribed: `target`).
    pub held: Vec<bool>,
    /// Per vertex, the residual's y component at a held vertex as the last evaluation found it,
    /// before it was zeroed: the ground's impulse dt F_g,y (N·s); stale at other vertices.
    pub react: Vec<f64>,
    /// Per vertex, its prescribed v⁺_y while held (m/s): 0 for a vertex resting on the plane,
    /// (h − y) / dt for one landing in this step (it ends the step on the plane); stale at
    /// other vertices.
    pub target: Vec<f64>,
    /// Per vertex: held at some time in this step (a released vertex is not taken again).
    pub was: Vec<bool>,
}

impl GroundSet {
    pub fn new(n: usize) -> Self {
        GroundSet { list: Vec::new(), held: vec![false; n], react: vec![0.0; n], target: vec![0.0; n], was: vec![false; n] }
    }

    /// Any vertex held this step.
    pub fn active(&self) -> bool {
        !self.list.is_empty()
    }

    /// The held vertices from the step's start (x, v): those resting on the plane (v⁺_y = 0)
    /// and, without restitution, those the explicit prediction x_y + dt v_y puts below it
    /// (v⁺_y = (h − x_y) / dt: they land in this step).
    pub fn find(&mut self, m: &Model, ground: Option<&Ground>, x: &[f64], v: &[f64], dt: f64) {
        self.release_all();
        self.was.fill(false);
        let Some(g) = ground else { return };
        let predict = g.restitution == 0.0;
        for (i, (p, u)) in x.chunks_exact(3).zip(v.chunks_exact(3)).enumerate() {
            if m.inv_mass[i] == 0.0 || u[1] > 0.0 {
                continue;
            }
            if p[1] <= g.height {
                self.take(i, 0.0);
            } else if predict && p[1] + dt * u[1] < g.height {
                self.take(i, (g.height - p[1]) / dt);
            }
        }
    }

    /// Hold vertex `i` with v⁺_y = `target` for the rest of the step (once: `was`).
    fn take(&mut self, i: usize, target: f64) {
        self.held[i] = true;
        self.was[i] = true;
        self.target[i] = target;
        self.list.push(i as u32);
    }

    /// Without restitution: take the vertices the iterate x_t = x + dt v⁺ puts below the plane
    /// that have not been held in this step yet (so each is taken at most once: no cycling with
    /// `release`), v⁺_y = (h − x_y) / dt. Returns whether any was taken.
    pub fn add(&mut self, m: &Model, g: &Ground, dt: f64, x: &[f64], xt: &[f64]) -> bool {
        if g.restitution != 0.0 {
            return false;
        }
        let before = self.list.len();
        for i in 0..m.inv_mass.len() {
            if !self.was[i] && m.inv_mass[i] != 0.0 && xt[3 * i + 1] < g.height {
                // A vertex already below the plane (moving up at the step's start) is held at
                // its height, as `find` holds one resting there: never pushed up by the solve.
                self.take(i, ((g.height - x[3 * i + 1]) / dt).min(0.0));
            }
        }
        if self.list.len() == before {
            return false;
        }
        self.list.sort_unstable();
        true
    }

    /// Put the prescribed v⁺_y of the held vertices into `vp`.
    pub fn prescribe(&self, vp: &mut [f64]) {
        for &i in &self.list {
            vp[3 * i as usize + 1] = self.target[i as usize];
        }
    }

    /// After the accepted solve (and `friction`): the held vertices that landed in the step
    /// (v⁺_y = (h − x_y) / dt < 0) end it exactly on the plane and at rest along its normal, as
    /// the after-step projection leaves an inelastic landing (`world/ground.rs`).
    pub fn land(&self, h: f64, xt: &mut [f64], vp: &mut [f64]) {
        for &i in &self.list {
            let i = i as usize;
            if self.target[i] < 0.0 {
                xt[3 * i + 1] = h;
                vp[3 * i + 1] = 0.0;
            }
        }
    }

    /// Let every held vertex go (the rest of the step as without the ground in the solve).
    pub fn release_all(&mut self) {
        for &i in &self.list {
            self.held[i as usize] = false;
        }
        self.list.clear();
    }

    /// Zero the held components of a vector of the conjugate gradient (v⁺'s prescribed
    /// components: [`GroundSet::prescribe`]).
    pub fn filter(&self, y: &mut [f64]) {
        for &i in &self.list {
            y[3 * i as usize + 1] = 0.0;
        }
    }

    /// On the impulses the last evaluation left in `react`: release the vertices the plane
    /// would have to pull down. Returns whether any was released.
    pub fn release(&mut self) -> bool {
        let GroundSet { list, held, react, .. } = self;
        let before = list.len();
        list.retain(|&i| {
            let keep = react[i as usize] >= 0.0;
            held[i as usize] = keep;
            keep
        });
        list.len() != before
    }

    /// Coulomb friction on the held vertices of the accepted v⁺, with the normal impulse per
    /// unit mass j = r_y / m − v⁺_y (the solve's, and for a vertex landing in the step the
    /// stop of its v⁺_y = (h − x_y) / dt by `land`): |v_t| loses up to μ j.
    pub fn friction(&self, m: &Model, friction: f64, vp: &mut [f64]) {
        for &i in &self.list {
            let i = i as usize;
            let j = self.react[i].max(0.0) / m.mass[i] - self.target[i].min(0.0);
            let (vx, vz) = (vp[3 * i], vp[3 * i + 2]);
            let vt = vx.hypot(vz);
            let drop = friction * j;
            let keep = if vt <= drop { 0.0 } else { 1.0 - drop / vt };
            vp[3 * i] = vx * keep;
            vp[3 * i + 2] = vz * keep;
        }
    }
}
