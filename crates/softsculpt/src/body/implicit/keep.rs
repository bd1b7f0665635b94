//! The multigrid's coarse levels kept from step to step while a body is nearly at rest — as
//! state, so that a restored world takes the same steps bit for bit.
//!
//! **Why**: a body at rest solves almost the same problem every step (half a Newton iteration
//! and half a conjugate-gradient iteration per step on the modeler's 10,242-vertex sphere), and
//! the coarse levels' assembly (`multigrid/`) was a quarter of such a step's time. The coarse
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
//!   target springs (a grab's; their stiffness is in the matrix but not in the fingerprint)
//!   and no self-contacts.
//!
//! Every other assembly is made afresh, and the last one of an accepted step is kept — unless
//! target springs acted in it (then the state keeps the older [`Kept`], and the scratch levels
//! are marked unknown, so the next resting step assembles from that state, as a restored world
//! would).
//!
//! **Why state**: what a step computes must depend only on what a snapshot keeps (docs/
//! snapshot.md). The coarse levels are scratch, but they are a pure function of [`Kept`]: the
//! positions x_t they were assembled at, the held vertices, the projection, and the model's
//! inputs, whose fingerprint [`Kept::inputs`] holds. `Kept` is part of the body's state and of a
//! snapshot (version 6). A world whose scratch levels are not those of its `Kept` (restored,
//! undone, rolled back, or cloned) assembles them again from `Kept` when it would use them
//! ([`super::Implicit::rebuild`]), and gets the same bits: without target springs the assembly
//! reads the system's coefficients that depend on x_t, the held vertices, the projection and
//! the model inputs only, not on v⁺. (Its evaluation at x_t cannot fail where the original's
//! did not: a collapsed or non-finite volume is a property of x_t alone.)

use super::system::Frame;

/// A step starting within this many times the convergence threshold may use the kept coarse
/// levels (measured on the modeler's 10,242-vertex sphere landing: the same iterations as with
/// fresh levels in every window, BENCHMARKS.md).
pub(crate) const KEEP_WITHIN: f64 = 10.0;

/// Where the coarse levels a body's implicit steps keep were assembled (state; snapshot
/// version 6). Empty `xt`: none kept.
#[derive(Debug, Default, PartialEq)]
pub struct Kept {
    /// x_t = x + dt v⁺ at that assembly (m, flat xyz).
    pub xt: Vec<f64>,
    /// The vertices the ground held then (their y no unknown), ascending.
    pub held: Vec<u32>,
    /// Whether compressed springs entered by the absolute value of their transverse factor
    /// (`system/`).
    pub absolute: bool,
    /// [`inputs`] then.
    pub inputs: u64,
}

/// By hand for `clone_from`, which keeps the buffers (the derived one allocates anew): the
/// rollback's backup and [`super::Implicit::rebuild`] copy a `Kept` into the same record step
/// after step.
impl Clone for Kept {
    fn clone(&self) -> Self {
        Kept { xt: self.xt.clone(), held: self.held.clone(), absolute: self.absolute, inputs: self.inputs }
    }

    fn clone_from(&mut self, o: &Self) {
        self.xt.clone_from(&o.xt);
        self.held.clone_from(&o.held);
        self.absolute = o.absolute;
        self.inputs = o.inputs;
    }
}

impl Kept {
    pub fn is_empty(&self) -> bool {
        self.xt.is_empty()
    }

    /// The same, bit for bit (x_t compared by its bits: −0 and 0 are not the same here).
    pub(crate) fn same(&self, o: &Kept) -> bool {
        self.xt.len() == o.xt.len() && self.xt.iter().zip(&o.xt).all(|(a, b)| a.to_bits() == b.to_bits()) && self.held == o.held && self.absolute == o.absolute && self.inputs == o.inputs
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
/// coefficients `system/` and the multigrid's `assemble`). (Target springs also enter the
/// coarse levels, through the diagonal: levels assembled with them are never kept, nor are
/// kept ones used while they act.)
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
    use crate::body::Target;
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
    /// each time) end within the tolerance's bound of each other. The bound, an estimate: each
    /// accepted step has ‖r‖_{M⁻¹} ≤ tol · ‖dt M g‖_{M⁻¹} (the floor dominates at rest), and
    /// its matrix A ≥ M (near a stable rest the true Jacobian is close to A), so its velocity's
    /// mass-weighted RMS error is ≤ tol dt g (1e-3 · 9.81 / 60 = 1.6e-4 m/s). Taken as never
    /// damped (the body's damping and the ground's friction only shrink it), the velocity error
    /// of step k moves the positions in each of the 31 − k steps from it on: Σ_k (31 − k) = 465
    /// steps of dt · 1.6e-4 m/s = 1.3e-3 m for one run, 2.5e-3 m between two. (Measured: 3e-11.)
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
        let bound = 2.0 * 465.0 * w.settings.dt * tol * w.settings.dt * w.settings.gravity;
        let gap = rms_gap(&w.bodies[0], &fresh.bodies[0]);
        assert!(differ, "the kept levels were never used");
        assert!(gap <= bound, "kept vs fresh levels after 30 steps: {gap:e} m RMS, bound {bound:e}");
    }

    /// A parameter the assembly reads (the spring damping: at rest it changes no force, so the
    /// step still starts within the threshold) makes a resting body assemble afresh; so does a
    /// painted mass; a parameter it does not read (the gas) keeps the levels. Each at the same
    /// step as an unchanged copy's first solve, which keeps them (the steps before it converge
    /// without one, in every copy).
    #[test]
    fn a_change_the_coarse_levels_read_makes_a_resting_body_assemble_afresh() {
        let mut w = on_the_ground(210);
        run(&mut w, 10);
        let snap = w.snapshot();
        let control = run(&mut World::restore(&snap).unwrap(), 30);
        let k = control.iter().position(|s| s.0 > 0).expect("a step that solves");
        assert!(!control[k].1, "the unchanged copy keeps its levels: {control:?}");
        let changes: [(&str, fn(&mut World), bool); 3] = [
            ("a new spring damping", |w| w.set_param(0, "spring_damping", crate::params::Value::Number(0.2)).unwrap(), true),
            (
                "a painted mass",
                |w| {
                    let mut masses = w.bodies[0].model.mass.clone();
                    masses[5] *= 1.0 + 1e-9;
                    w.bodies[0].set_masses(&masses).unwrap();
                },
                true,
            ),
            ("a little more gas", |w| w.set_param(0, "gas.nrt", crate::params::Value::Number(30.0 * (1.0 + 1e-9))).unwrap(), false),
        ];
        for (what, change, fresh) in changes {
            let mut c = World::restore(&snap).unwrap();
            change(&mut c);
            let steps = run(&mut c, k + 1);
            assert!(steps[..k].iter().all(|s| s.0 == 0) && steps[k].0 > 0, "{what}: {steps:?}");
            assert_eq!(steps[k].1, fresh, "{what}: assembled afresh");
        }
    }

    /// A grab held still on a resting body, then let go: the grabbed steps' levels (their
    /// target springs in the diagonal) are not kept, and the world steps on bit for bit like one
    /// restored from a snapshot taken at the release. (Before targets were left out of the kept
    /// levels the original reused the grabbed levels there and the restored world did not.)
    #[test]
    fn levels_assembled_under_a_grab_are_not_kept() {
        let mut w = on_the_ground(210);
        let x = w.bodies[0].positions().to_vec();
        let grab: Vec<Target> = (0..40).map(|i| Target { vertex: i, anchor: [x[3 * i], x[3 * i + 1], x[3 * i + 2]], stiffness: 50.0, damping: 0.5 }).collect();
        w.bodies[0].set_targets(&grab).unwrap();
        let grabbed = run(&mut w, 20);
        assert!(grabbed.iter().any(|s| s.0 > 0), "the grabbed steps solve: {grabbed:?}");
        assert!(w.bodies[0].work.implicit.as_ref().unwrap().built.is_none(), "the grabbed levels are not kept");
        w.bodies[0].clear_targets();
        let mut r = World::restore(&w.snapshot()).unwrap();
        let after = run(&mut w, 30);
        assert!(after.iter().any(|s| s.0 > 0 && !s.1), "kept levels used after the release: {after:?}");
        assert_eq!(run(&mut r, 30), after);
        assert_eq!(r.snapshot(), w.snapshot());
    }

    /// A call of `step_n` that fails leaves the whole state as it was, the warm start and the
    /// kept levels too. On the resting world at a tolerance of 1e-5 giving up after one Newton
    /// iteration, a call whose first step takes at most one (x, v, the warm start and perhaps
    /// the kept levels change) and whose second needs more fails, and the world's snapshot is the
    /// one from before the call.
    #[test]
    fn a_rolled_back_call_leaves_the_warm_start_and_the_kept_levels_as_they_were() {
        let mut w = on_the_ground(210);
        w.settings.tolerance = 1e-5;
        let mut copy = World::restore(&w.snapshot()).unwrap();
        let newton: Vec<u32> = (0..60).map(|_| copy.step().map(|_| copy.bodies[0].solver_iterations().newton).unwrap()).collect();
        let j = (0..59).find(|&j| newton[j] <= 1 && newton[j + 1] > 1).unwrap_or_else(|| panic!("a step of at most one iteration before one of more: {newton:?}"));
        run(&mut w, j);
        let before = w.snapshot();
        let warm = w.bodies[0].state.warm.clone();
        let e = w.step_n_splitting(2, crate::world::GiveUp { stalled: 1, most: 1 }).expect_err("the second step needs more than one iteration");
        assert_eq!(e.time, w.settings.dt * (210 + j + 1) as f64, "the first step was taken: {e:?}");
        assert_eq!(w.bodies[0].state.warm, warm);
        assert_eq!(w.snapshot(), before);
    }
}
