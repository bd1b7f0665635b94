//! How time advances (`World::advance`, `world/advance.rs`): frames under a budget, the anytime
//! implicit step (`WorldSettings::deadline`) and the explicit stable step (`World::stable_dt`).
//!
//! The clocks here are not the machine's: a test that waits on the wall clock measures the
//! machine. `late` reads later at every call, so every deadline has passed by the time a
//! solve first looks at it (the worst budget: a frame that had no time at all); `never`
//! stands still, so no deadline ever passes.

mod common;
use common::*;
use softsculpt::body::{Material, SoftBody};
use softsculpt::mesh::builtin::icosphere;
use softsculpt::world::{Budget, Ground, Integrator, World, WorldSettings};
use std::cell::Cell;

thread_local! { static TICKS: Cell<f64> = const { Cell::new(0.0) }; }
/// A clock one second later at every reading.
fn late() -> f64 {
    TICKS.with(|t| {
        t.set(t.get() + 1.0);
        t.get()
    })
}
/// A clock that never moves.
fn never() -> f64 {
    0.0
}

const FRAME: f64 = 1.0 / 60.0;

/// The modeler's 642-vertex sphere (`modeler` preset, implicit, 1/60 s) dropped from 0.5 m
/// above the ground.
fn dropped_sphere() -> World {
    let mut mesh = icosphere(3, 1.0);
    for p in mesh.positions.chunks_exact_mut(3) {
        p[1] += 1.5;
    }
    let body = SoftBody::new(&mesh, 1.0, Material::default()).unwrap();
    let mut w = World::single(body, WorldSettings { ground: Some(Ground::at(0.0)), ..WorldSettings::default() });
    w.apply_preset(0, "modeler").unwrap();
    assert_eq!(w.settings.integrator, Integrator::Implicit);
    w
}

fn lowest(w: &World) -> f64 {
    w.bodies[0].positions().chunks_exact(3).map(|p| p[1]).fold(f64::INFINITY, f64::min)
}

fn highest(w: &World) -> f64 {
    w.bodies[0].positions().chunks_exact(3).map(|p| p[1]).fold(f64::NEG_INFINITY, f64::max)
}

/// Under *converge*, a frame is the steps it holds, bit for bit: `advance` only decides how
/// many (frame / dt, rounded) — for the implicit integrator (one 1/60 s step per frame) and an
/// explicit one (167 steps of 1e-4 s per frame). And a real-time budget whose deadline never
/// passes is the converged step too: the deadline only ever stops a solve, never starts one.
#[test]
fn a_frame_under_converge_is_its_steps_bit_for_bit() {
    let mut a = dropped_sphere();
    let mut b = a.clone();
    let mut c = a.clone();
    let never_late = Budget::real_time(1.0, never);
    for f in 0..40 {
        let done = a.advance(FRAME, &Budget::converge()).unwrap();
        assert_eq!((done.steps, done.splits, done.early), (1, 0, 0));
        b.step_n(1).unwrap();
        c.advance(FRAME, &never_late).unwrap();
        assert_eq!(a.bodies[0].positions(), b.bodies[0].positions(), "frame {f}");
        assert_eq!(a.bodies[0].velocities(), b.bodies[0].velocities(), "frame {f}");
        assert_eq!(a.bodies[0].positions(), c.bodies[0].positions(), "frame {f}");
        // The residual reported is what the step converged to.
        assert!(done.residual <= a.settings.tolerance, "frame {f}: {}", done.residual);
    }
    assert!(c.settings.deadline.is_none() && !c.settings.relax && c.settings.give_up.is_none(), "the caller's settings are back after a real-time frame");

    let mut e = rooted_mushroom();
    e.settings.integrator = Integrator::Symplectic;
    e.settings.dt = 1e-4;
    let mut f = e.clone();
    let done = e.advance(FRAME, &Budget::converge()).unwrap();
    assert_eq!(done.steps, 167);
    f.step_n(167).unwrap();
    assert_eq!(e.bodies[0].positions(), f.bodies[0].positions());
}

/// A step whose deadline has passed stops after its first Newton iteration whose iterate is
/// within the budget's accuracy, says so, and reports that accuracy: on the hard pull of
/// `tests/implicit.rs` (2 m in 0.4 s at ω = 600 1/s), where converged steps take several.
#[test]
fn past_its_deadline_a_step_ends_at_the_first_iterate_within_its_accuracy() {
    let (mut a, pull) = pulled_sphere();
    let (mut converged_newton, mut newton, mut early) = (0, 0, 0);
    let mut b = a.clone();
    let budget = Budget::real_time(0.0, late);
    let accept = budget.real_time.unwrap().min_accuracy;
    for s in 0..40 {
        a.bodies[0].set_targets(&pull(s)).unwrap();
        b.bodies[0].set_targets(&pull(s)).unwrap();
        let done = a.advance(FRAME, &budget).unwrap();
        let it = a.bodies[0].solver_iterations();
        (newton, early) = (newton + it.newton, early + done.early);
        assert!(it.residual <= accept, "step {s}: accepted at {} > {accept}", it.residual);
        assert_eq!(done.residual, it.residual);
        if it.early {
            assert_eq!(done.early, 1);
        } else {
            // Converged before the deadline was looked at again: within the tolerance.
            assert!(it.residual <= a.settings.tolerance, "step {s}");
        }
        b.advance(FRAME, &Budget::converge()).unwrap();
        converged_newton += b.bodies[0].solver_iterations().newton;
        assert!(a.bodies[0].is_finite());
    }
    assert!(converged_newton > 40, "the converged pull takes more than one Newton iteration a step ({converged_newton})");
    // The deadline did stop steps, and saved iterations: a step the deadline stops is accepted
    // at its first iterate within the accuracy, so it takes at most the converged step's.
    assert!(early > 0 && newton < converged_newton, "{early} steps stopped early, {newton} Newton iterations against {converged_newton}");
}

/// Anytime steps lose energy as converged ones do and come to rest where they do. The sphere
/// dropped 0.5 m onto the ground, every step stopped at its first Newton iterate within
/// `MIN_ACCURACY` (the worst budget): the total energy (kinetic, elastic, gas, gravity) never
/// rises above where it started — nothing but gravity does work, the ground takes energy
/// (inelastic) and backward Euler damps, so a rise would be the solver's own energy — within
/// 1e-6 of the sphere's weight times its size (the converged step's rounding; the anytime
/// step's error is a smaller move, which damps more). After 4 s both rest: the top's height and
/// the gas volume agree within 1 % (the accuracy goal for real-time frames).
#[test]
fn anytime_steps_of_a_drop_lose_energy_and_rest_where_converged_steps_do() {
    let mut any = dropped_sphere();
    let mut conv = any.clone();
    let e0 = any.total_energy();
    let scale = 1.0 * 9.81 * 1.0;
    let budget = Budget::real_time(0.0, late);
    let mut early = 0;
    for f in 0..240 {
        early += any.advance(FRAME, &budget).unwrap().early;
        conv.advance(FRAME, &Budget::converge()).unwrap();
        let e = any.total_energy();
        assert!(e <= e0 + 1e-6 * scale, "frame {f}: energy {e} above the start's {e0}");
        assert!(lowest(&any) > -0.01, "frame {f}: through the ground ({})", lowest(&any));
    }
    assert!(early > 20, "the drop's steps were stopped early ({early})");
    let (ha, hc) = (highest(&any), highest(&conv));
    let (va, vc) = (any.stats(0).volume, conv.stats(0).volume);
    assert!((ha - hc).abs() <= 0.01 * hc, "height {ha} against {hc}");
    assert!((va - vc).abs() <= 0.01 * vc, "volume {va} against {vc}");
}

/// `stable_dt` is the Courant-like bound of its documentation: for a sphere of 642 vertices of
/// 1/642 kg with springs only (k = 100 N/m, c_s = 0.1 N·s/m), ω² = 12 k / m, 0.3 · 2/ω =
/// 2.16e-3 s and the damping's 0.3 · 2 m / (24 c_s) = 3.9e-4 s: the damping's, rounded down to
/// 2e-4 s; forward Euler a quarter of it, 9.75e-5 s, rounded down to 5e-5 s; none for the
/// implicit integrator. And the symplectic
/// steps it gives keep a swirled ball's energy bounded (it oscillates, within 1 %).
#[test]
fn the_stable_step_keeps_an_explicit_body_bounded() {
    let mat = Material { stiffness: 100.0, spring_damping: 0.1, ..bare() };
    let mut body = sphere_body(3, 1.0, mat);
    swirl(&mut body, 0.5);
    let mut w = alone(body, still());
    let m = 1.0 / 642.0;
    let by_damping: f64 = 0.3 * 2.0 * m / (12.0 * 0.2);
    assert!((by_damping - 3.9e-4).abs() < 1e-5);
    assert_eq!(w.stable_dt(Integrator::Symplectic), Some(2e-4));
    assert_eq!(w.stable_dt(Integrator::Euler), Some(5e-5));
    assert_eq!(w.stable_dt(Integrator::Implicit), None);
    w.settings.dt = w.stable_dt(Integrator::Symplectic).unwrap();
    let e0 = w.total_energy();
    for _ in 0..60 {
        w.advance(FRAME, &Budget::converge()).unwrap();
        assert!(w.total_energy() <= 1.01 * e0);
    }
}

thread_local! { static ASKED: Cell<u32> = const { Cell::new(0) }; }
/// An interrupt that answers yes from its fifth question on (mid-solve: a step asks once per
/// Newton iteration and once per conjugate-gradient iteration).
fn fifth() -> bool {
    ASKED.with(|a| {
        a.set(a.get() + 1);
        a.get() >= 5
    })
}

/// An interrupted step is abandoned with the world exactly as before it (the page's Undo or
/// new model never waits for a slow step, and loses nothing); the same step asked again without
/// the interrupt is the step it would have been.
#[test]
fn an_interrupted_step_leaves_the_world_as_it_was() {
    let (mut a, pull) = pulled_sphere();
    a.bodies[0].set_targets(&pull(12)).unwrap();
    let mut b = a.clone();
    let (x, v) = (a.bodies[0].positions().to_vec(), a.bodies[0].velocities().to_vec());
    let time = a.time();
    a.settings.interrupt = Some(softsculpt::world::Interrupt(fifth));
    let e = a.advance(FRAME, &Budget::converge()).expect_err("interrupted");
    assert!(matches!(e.error, softsculpt::SimError::Interrupted { .. }), "{e}");
    assert_eq!(a.bodies[0].positions(), &x[..]);
    assert_eq!(a.bodies[0].velocities(), &v[..]);
    assert_eq!(a.time(), time);
    a.settings.interrupt = None;
    a.advance(FRAME, &Budget::converge()).unwrap();
    b.advance(FRAME, &Budget::converge()).unwrap();
    assert_eq!(a.bodies[0].positions(), b.bodies[0].positions());
}

/// Explicit steps under a real-time budget run while it lasts, at least one: with no time at
/// all (the `late` clock) a frame of 167 steps takes one, and says so in `simulated`.
#[test]
fn explicit_steps_under_an_exhausted_budget_take_one_step_and_say_so() {
    let mut w = rooted_mushroom();
    w.settings.integrator = Integrator::Symplectic;
    w.settings.dt = 1e-4;
    let done = w.advance(FRAME, &Budget::real_time(0.0, late)).unwrap();
    assert_eq!(done.steps, 1);
    assert!((done.simulated - 1e-4).abs() < 1e-15);
}

/// Implicit steps under a real-time budget run while it lasts, at least one: with no time at
/// all (the `late` clock) a frame of four steps of FRAME / 4 takes one, says so in `simulated`,
/// and the world's dt and settings are as they were.
#[test]
fn implicit_steps_under_an_exhausted_budget_take_one_step_and_say_so() {
    let mut w = dropped_sphere();
    w.settings.dt = FRAME / 4.0;
    let t0 = w.time();
    let done = w.advance(FRAME, &Budget::real_time(0.0, late)).unwrap();
    assert_eq!(done.steps, 1);
    assert_eq!(done.simulated, FRAME / 4.0);
    assert_eq!(w.time() - t0, FRAME / 4.0);
    assert_eq!(w.settings.dt, FRAME / 4.0);
    // With time to spare (a clock that stands still) the frame is whole.
    let done = w.advance(FRAME, &Budget::real_time(1.0, never)).unwrap();
    assert_eq!(done.steps, 4);
}

/// A step the solver refuses is taken as two of half its length, split again as needed, up to
/// the budget's `splits`: on the hard pull of `tests/implicit.rs` with the Newton cap cut to
/// NEWTON_CAP iterations, the first frames' steps are refused under *converge* (an error, the
/// world untouched), and with three splits every frame covers its 1/60 s exactly (the pieces'
/// lengths are FRAME / 2^k, exact in binary, so their sum is too) in 1 + splits steps (each
/// split turns one step into two).
#[test]
fn a_refused_step_is_split_and_its_pieces_cover_the_frame() {
    const NEWTON_CAP: u32 = 5;
    let (mut a, pull) = pulled_sphere();
    a.settings.newton_iterations = NEWTON_CAP;
    let mut refused = a.clone();
    let budget = Budget { splits: 3, ..Budget::converge() };
    let (mut frames_split, mut was_refused) = (0, 0);
    for s in 0..30 {
        a.bodies[0].set_targets(&pull(s)).unwrap();
        refused.clone_from(&a);
        let before = refused.bodies[0].positions().to_vec();
        if refused.advance(FRAME, &Budget::converge()).is_err() {
            was_refused += 1;
            assert_eq!(refused.bodies[0].positions(), &before[..], "a refused step leaves the world as it was");
        }
        let t0 = a.time();
        let done = a.advance(FRAME, &budget).unwrap_or_else(|e| panic!("frame {s}: {e}"));
        assert_eq!(done.simulated, FRAME, "frame {s}");
        assert!((a.time() - t0 - FRAME).abs() < 1e-14, "frame {s}");
        assert_eq!(done.steps, 1 + done.splits as u64, "frame {s}");
        frames_split += (done.splits > 0) as u32;
        assert!(a.bodies[0].is_finite());
    }
    assert!(was_refused > 0 && frames_split > 0, "the cap refused {was_refused} whole steps; {frames_split} frames were split");
    assert_eq!(a.settings.newton_iterations, NEWTON_CAP);
}

/// The modeler's mushroom on the ground, settled for 1 s, then made to cave in: soft springs,
/// no bending, almost no gas and a small restitution (so vertices reaching the ground go to the
/// after-step projection and the top goes through the bottom: the volume falls 2.46 → 0.12 m³
/// in the last 0.3 s before the failure, ~0.7 s after the change). The change is the caller's:
/// `forget_rewind`. Returns the world and the time of the change.
fn caving_mushroom() -> (World, f64) {
    let mut mesh = softsculpt::mesh::builtin::builtin("mushroom").unwrap();
    let lo = mesh.positions.chunks_exact(3).map(|p| p[1]).fold(f64::MAX, f64::min);
    mesh.positions.chunks_exact_mut(3).for_each(|p| p[1] -= lo);
    let mut w = World::single(SoftBody::new(&mesh, 1.0, Material::default()).unwrap(), WorldSettings { ground: Some(Ground::at(0.0)), ..WorldSettings::default() });
    w.apply_preset(0, "modeler").unwrap();
    let budget = Budget { rewind: true, splits: 3, relax: true, ..Budget::converge() };
    for _ in 0..60 {
        w.advance(FRAME, &budget).unwrap();
    }
    use softsculpt::params::Value::Number;
    for (id, v) in [("stiffness", 1.0), ("bending", 0.0), ("rigidity", 0.0), ("gas.amount", 1e-6), ("ground.restitution", 0.01)] {
        w.set_param(0, id, Number(v)).unwrap();
    }
    w.forget_rewind();
    let t = w.time();
    (w, t)
}

/// A frame that fails goes back to the last sound state: a rewind point at least one interval
/// (`REWIND_EVERY`) before the failure, whose volume is at least `HEALTHY` of the volume at the
/// change, never before the change; without `rewind` the world is where the rollback left it
/// (the failing step's start, already caved in).
#[test]
fn a_failed_frame_goes_back_to_the_last_sound_state_never_before_the_last_change() {
    use softsculpt::world::{HEALTHY, REWIND_EVERY};
    for rewind in [true, false] {
        let (mut w, changed) = caving_mushroom();
        let v0 = w.bodies[0].volume();
        let budget = Budget { rewind, splits: 3, relax: true, ..Budget::converge() };
        let e = (0..600).find_map(|_| w.advance(FRAME, &budget).err()).expect("the mushroom caves in and a step fails");
        let back = w.time();
        if !rewind {
            assert_eq!(e.rewound_to, None);
            assert!(w.bodies[0].volume() < HEALTHY * v0, "the rollback leaves it caved in: {} of {v0} m³", w.bodies[0].volume());
            continue;
        }
        assert_eq!(e.rewound_to, Some(back), "{e}");
        assert!(e.to_string().contains("the last sound state"), "{e}");
        // The failing frame starts within one frame of the failure; the point is at least an
        // interval before it (the newest point's successor is the failure, never chosen).
        assert!(e.time - back >= REWIND_EVERY - FRAME, "failed at {} s, back to {back} s", e.time);
        assert!(back >= changed - 1e-12, "back to {back} s, before the change at {changed} s");
        assert!(w.bodies[0].volume() > HEALTHY * v0, "{} of {v0} m³", w.bodies[0].volume());
        assert!(w.bodies[0].positions().iter().all(|x| x.is_finite()));
        // And it goes on from there (the next failure, if any, rewinds again: never a panic).
        for _ in 0..5 {
            let _ = w.advance(FRAME, &budget);
        }
        assert!(w.time() >= back);
    }
}

/// A scene event is a change too. The world steps in 1/240 s (four steps a frame; measured: the
/// frame from 1.725 s fails at its third step, 1.733 s, and rewinds to 1.258 s without events),
/// so a frame's failure can come steps after an event fired in it: then no rewind (the points are from before
/// the event, which the rollback to the failing step's start does not undo: it stands). An event
/// due at the failing step itself is undone with it by the rollback (it fires again when its
/// time comes), so that frame rewinds as without it. The event sets the wind the world already
/// has: the motion is bit for bit the run without it, the failure in the same step.
#[test]
fn a_failed_frame_does_not_rewind_past_a_scene_event_fired_in_it() {
    use softsculpt::params::Value::Number;
    use softsculpt::world::{Action, Event};
    let budget = Budget { rewind: true, splits: 3, relax: true, ..Budget::converge() };
    let dt = 1.0 / 240.0;
    let world = || {
        let (mut w, _) = caving_mushroom();
        w.set_param(0, "dt", Number(dt)).unwrap();
        w.forget_rewind();
        // Half a frame first: the frames then start between the steps of the run's own frames,
        // so the failing step (the same one: the steps do not depend on how they are grouped)
        // is not a frame's first.
        w.advance(2.0 * dt, &budget).unwrap();
        w
    };
    // The run without events: the failing frame's start, the failing step's time, the rewind.
    let mut w = world();
    let mut start = 0.0;
    let e = (0..2400)
        .find_map(|_| {
            start = w.time();
            w.advance(FRAME, &budget).err()
        })
        .expect("the mushroom caves in and a step fails");
    let back = e.rewound_to.expect("without events the failure rewinds");
    assert!(e.time > start + 0.5 * dt, "the failure is not the frame's first step (frame from {start} s, failed at {} s)", e.time);
    // An event at the frame's start (fired by its first step, which succeeded): no rewind.
    // An event at the failing step's time: undone by the rollback, the rewind as without it.
    for (at, expect) in [(start, None), (e.time, Some(back))] {
        let mut w = world();
        let wind = w.settings.wind;
        w.set_events(vec![Event { time: at, body: 0, action: Action::SetWind(wind), line: 1 }]);
        let f = (0..2400).find_map(|_| w.advance(FRAME, &budget).err()).expect("the same failure");
        assert_eq!(f.time, e.time, "the same failing step");
        assert_eq!(f.rewound_to, expect, "event at {at} s: {f}");
        assert!(w.bodies[0].positions().iter().all(|x| x.is_finite()));
    }
}
