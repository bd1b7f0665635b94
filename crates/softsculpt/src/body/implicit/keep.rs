//! The multigrid's coarse levels kept from step to step while a body is nearly at rest — as
//! state, so that a restored world takes the same steps bit for bit.
//!
//! **Why**: a body at rest solves almost the same problem every step (half a Newton iteration
//! and half a conjugate-gradient iteration per step on the modeler's 10,242-vertex sphere), and
//! the coarse levels' assembly (`multigrid.rs`) was a quarter of such a step's time. The coarse
//! levels only precondition: any symmetric positive definite cycle gives the same backward-Euler
//! step within the tolerance. Levels assembled a few steps ago, for the same held vertices,
//! parameters and dt, precondition a resting step as well as fresh ones (measured: the same
//! Newton and conjugate-gradient iterations, BENCHMARKS.md).
//!
//! **Rule**: the first assembly of a Newton solve is skipped, and the kept levels used, when
//! - the step starts within [`KEEP_WITHIN`] times the convergence threshold (its residual at
//!   v⁺ = v: nearly at rest), and
//! - the kept levels were assembled for this step's problem: the same vertices held by the
//!   ground, the same projection of compressed springs, and the same model inputs to the
//!   assembly ([`inputs`]: parameters, dt, masses, pins, rest lengths, hinge weights); no
//!   target springs (a grab changes them every step) and no self-contacts.
//!
//! Every other assembly is made afresh, and the last one of an accepted step is kept.
//!
//! **Why state**: what a step computes must depend only on what a snapshot keeps (docs/
//! snapshot.md). The coarse levels are scratch, but they are a pure function of [`Kept`]: the
//! positions x_t they were assembled at, the held vertices, the projection, and the model's
//! inputs, whose fingerprint [`Kept::inputs`] holds. `Kept` is part of the body's state and of a
//! snapshot (version 6). A world whose scratch levels are not those of its `Kept` (restored,
//! undone, rolled back, or cloned) assembles them again from `Kept` when it would use them
//! ([`super::Implicit::rebuild`]), and gets the same bits: the assembly reads the system's
//! coefficients, which depend on x_t, the held vertices, the projection and the model inputs,
//! not on v⁺.

use super::system::Frame;

/// A step starting within this many times the convergence threshold may use the kept coarse
/// levels (measured on the modeler's 10,242-vertex sphere landing: the same iterations as with
/// fresh levels in every window, BENCHMARKS.md).
pub(crate) const KEEP_WITHIN: f64 = 10.0;

/// Where the coarse levels a body's implicit steps keep were assembled (state; snapshot
/// version 6). Empty `xt`: none kept.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Kept {
    /// x_t = x + dt v⁺ at that assembly (m, flat xyz).
    pub xt: Vec<f64>,
    /// The vertices the ground held then (their y no unknown), ascending.
    pub held: Vec<u32>,
    /// Whether compressed springs entered by the absolute value of their transverse factor
    /// (`system.rs`).
    pub absolute: bool,
    /// [`inputs`] then.
    pub inputs: u64,
}

impl Kept {
    pub fn is_empty(&self) -> bool {
        self.xt.is_empty()
    }
}

/// The Fx hash (rustc's) over 64-bit words: one multiply per word (~0.1 ms for the 10,242-vertex
/// sphere's ~110,000 inputs).
struct Fx(u64);

impl Fx {
    fn word(&mut self, w: u64) {
        self.0 = (self.0.rotate_left(5) ^ w).wrapping_mul(0x517c_c1b7_2722_0a95);
    }
    fn all(&mut self, xs: &[f64]) {
        self.word(xs.len() as u64);
        for x in xs {
            self.word(x.to_bits());
        }
    }
}

/// A fingerprint of everything besides x_t, the held vertices and the projection that the
/// coarse levels' assembly reads: the stiffnesses, dampings, rigidity, dt, the masses and
/// pins, the springs' and bending springs' rest lengths, the hinges' weights (the system's
/// coefficients `system.rs` and the multigrid's `assemble`). (Targets and self-contacts also
/// enter the matrix; steps with them never keep levels.)
pub(crate) fn inputs(fr: &Frame) -> u64 {
    let (p, m) = (fr.p, fr.m);
    let mut h = Fx(0);
    for x in [p.stiffness, p.spring_damping, p.bending_stiffness, p.rigidity, p.retardation_time(), p.damping, fr.dt] {
        h.word(x.to_bits());
    }
    h.all(&m.mass);
    h.all(&m.inv_mass);
    h.all(&m.springs.rest);
    h.all(&m.bending.rest);
    h.all(&m.hinges.weight);
    h.0
}

#[cfg(test)]
mod tests {
    use super::Kept;
    use crate::delta::{Delta, StateScope};
    use crate::mesh::builtin::icosphere;
    use crate::{Material, SoftBody, World, WorldSettings};

    /// The modeler's 2,562-vertex sphere (hinged: its implicit steps precondition with the
    /// V-cycle, `multigrid::HINGED_FROM`) put on the ground and stepped `steps` times at 1/60 s.
    fn on_the_ground(steps: u64) -> World {
        let body = SoftBody::new(&icosphere(4, 0.5), 1.0, Material::default()).unwrap();
        let mut w = World::single(body, WorldSettings::default());
        w.apply_preset(0, "modeler").unwrap();
        let lowest = w.bodies[0].positions().chunks_exact(3).map(|p| p[1]).fold(f64::INFINITY, f64::min);
        let x: Vec<f64> = w.bodies[0].positions().chunks_exact(3).flat_map(|p| [p[0], p[1] - lowest, p[2]]).collect();
        let v = vec![0.0; x.len()];
        w.bodies[0].set_state(&x, &v).unwrap();
        w.step_n(steps).unwrap();
        w
    }

    /// Per step of `steps`: (CG iterations, assembled afresh).
    fn run(w: &mut World, steps: usize) -> Vec<(u32, bool)> {
        (0..steps)
            .map(|_| {
                w.step().unwrap();
                let b = &w.bodies[0];
                (b.solver_iterations().linear, b.work.implicit.as_ref().unwrap().assembled)
            })
            .collect()
    }

    /// The mass-weighted RMS distance between two bodies' positions (m).
    fn rms_gap(a: &SoftBody, b: &SoftBody) -> f64 {
        let (xa, xb, m) = (a.positions(), b.positions(), &a.model.mass);
        let total: f64 = m.iter().sum();
        let s: f64 = m.iter().enumerate().map(|(i, mi)| mi * (0..3).map(|d| (xa[3 * i + d] - xb[3 * i + d]).powi(2)).sum::<f64>()).sum();
        (s / total).sqrt()
    }

    /// At rest on the ground (from 3 s on) the steps keep their coarse levels: most steps that
    /// run the conjugate gradient assemble nothing (measured: none of the 30 after 3.5 s does).
    /// A world restored from a snapshot taken then, whose scratch levels are gone, assembles
    /// them again from the kept state and takes the same steps: the same iterations, the same
    /// bits, the same snapshot after 30 steps. So does a world taken back by an undo delta.
    #[test]
    fn a_resting_body_keeps_its_coarse_levels_and_a_restored_world_steps_bit_for_bit() {
        let mut w = on_the_ground(210);
        let at_rest = w.snapshot();
        let steps = run(&mut w, 30);
        let kept = steps.iter().filter(|s| s.0 > 0 && !s.1).count();
        let solved = steps.iter().filter(|s| s.0 > 0).count();
        assert!(solved >= 5 && 2 * kept >= solved, "{kept} of {solved} steps kept their levels");
        assert!(!w.bodies[0].state.kept.is_empty());

        let mut r = World::restore(&at_rest).unwrap();
        assert!(r.bodies[0].work.implicit.is_none());
        assert_eq!(run(&mut r, 30), steps);
        assert_eq!(r.bodies[0].positions(), w.bodies[0].positions());
        assert_eq!(r.bodies[0].velocities(), w.bodies[0].velocities());
        assert_eq!(r.snapshot(), w.snapshot());

        // Undo of 30 steps (the whole state kept): the world at rest again, then the same steps.
        let before = World::restore(&at_rest).unwrap();
        let undo = Delta::between(&before, &w, StateScope::All);
        let mut u = World::restore(&w.snapshot()).unwrap();
        run(&mut u, 3);
        undo.apply(&mut u).unwrap();
        assert_eq!(u.snapshot(), at_rest);
        assert_eq!(run(&mut u, 30), steps);
        assert_eq!(u.snapshot(), w.snapshot());
    }

    /// Steps with kept levels are backward-Euler steps within the tolerance, as steps with fresh
    /// ones: 30 resting steps each way (the kept state cleared before every step: fresh levels
    /// each time) end within the tolerance's bound of each other. Each accepted step has
    /// ‖r‖_{M⁻¹} ≤ tol · ‖dt M g‖_{M⁻¹} (the floor dominates at rest), and A ≥ M, so its
    /// velocity's mass-weighted RMS error is ≤ tol dt g (1e-3 · 9.81 / 60 = 1.6e-4 m/s) and its
    /// position's ≤ dt times that (2.7e-6 m); 30 steps of a damped body add at most 30 of them,
    /// and the two runs' errors at most double that: 1.6e-4 m. (Measured: 3e-11 m.)
    #[test]
    fn steps_with_kept_levels_are_the_backward_euler_steps_within_the_tolerance() {
        let mut w = on_the_ground(210);
        let mut fresh = World::restore(&w.snapshot()).unwrap();
        let mut differ = false;
        for _ in 0..30 {
            fresh.bodies[0].state.kept = Kept::default();
            fresh.step().unwrap();
            w.step().unwrap();
            differ |= fresh.bodies[0].positions() != w.bodies[0].positions();
        }
        let tol = w.settings.tolerance;
        let bound = 2.0 * 30.0 * w.settings.dt * tol * w.settings.dt * w.settings.gravity;
        let gap = rms_gap(&w.bodies[0], &fresh.bodies[0]);
        assert!(differ, "the kept levels were never used");
        assert!(gap <= bound, "kept vs fresh levels after 30 steps: {gap:e} m RMS, bound {bound:e}");
    }

    /// A parameter the assembly reads (the spring damping: at rest it changes no force, so the
    /// step still starts within the threshold) makes the next step assemble afresh; so does a
    /// painted mass. A parameter it does not read (the gas) keeps the levels.
    #[test]
    fn a_change_the_coarse_levels_read_makes_a_resting_body_assemble_afresh() {
        let mut w = on_the_ground(210);
        run(&mut w, 10);
        let first_solve = |w: &mut World| run(w, 30).into_iter().find(|s| s.0 > 0).expect("a step that solves");
        let mut gas = World::restore(&w.snapshot()).unwrap();
        run(&mut gas, 1);
        gas.set_param(0, "gas.nrt", crate::params::Value::Number(30.0 * (1.0 + 1e-9))).unwrap();
        assert!(!first_solve(&mut gas).1, "a change the levels do not read");
        w.set_param(0, "spring_damping", crate::params::Value::Number(0.2)).unwrap();
        assert!(first_solve(&mut w).1, "a new spring damping");
        run(&mut w, 10);
        let mut masses = w.bodies[0].model.mass.clone();
        masses[5] *= 1.0 + 1e-9;
        w.bodies[0].set_masses(&masses).unwrap();
        assert!(first_solve(&mut w).1, "a painted mass");
    }
}
