//! The ground inside the implicit solve (`body/implicit/ground.rs`): a body resting on it is the
//! model's equilibrium, the one the explicit model comes to, and a step at rest has nothing left
//! to solve.

mod common;

use common::rooted_mushroom;
use softsculpt::body::{Material, SoftBody};
use softsculpt::mesh::builtin::icosphere;
use softsculpt::world::{Ground, Integrator, World, WorldSettings};

/// The modeler's world and material (its preset: k = k_b = 100 N/m, cs = 0.1 N·s/m,
/// c = 1.5 1/s, 30 J of gas, gravity, a ground at 0; implicit at 1/60 s, tolerance 1e-3) on a
/// 162-vertex sphere of radius 0.7 m and 1 kg whose lowest point is 5 cm above the ground, with
/// the ground's friction μ and the given integrator, dt and tolerance.
fn world(friction: f64, integrator: Integrator, dt: f64, tolerance: f64) -> World {
    let body = SoftBody::new(&icosphere(2, 0.7), 1.0, Material::default()).unwrap();
    let mut w = World::single(body, WorldSettings::default());
    w.apply_preset(0, "modeler").unwrap();
    w.settings.ground = Some(Ground { friction, ..Ground::at(0.0) });
    (w.settings.integrator, w.settings.dt, w.settings.tolerance) = (integrator, dt, tolerance);
    let x: Vec<f64> = w.bodies[0].positions().chunks_exact(3).flat_map(|p| [p[0], p[1] + 0.75, p[2]]).collect();
    w.bodies[0].set_state(&x, &vec![0.0; x.len()]).unwrap();
    w
}

fn run_for(w: &mut World, seconds: f64) {
    let steps = (seconds / w.settings.dt).round() as u64;
    w.step_n(steps).unwrap();
}

/// Dropped straight onto the ground (μ = 0.5), the implicit model at dt = 1/60 s comes to rest
/// in the explicit one's shape (symplectic Euler at dt = 5e-4 s, 6× below its stability limit
/// 2/ω_max ≈ 3e-3 s here, its contact within g dt² = 2.5e-6 m of exact). Before the ground was
/// part of the solve, the solve let gravity pull the bottom g dt² = 2.7 mm into the plane every
/// step and the body came to rest 2.7 cm too low (measured: centre 0.5913 m against 0.6188 m,
/// 1 % less volume).
///
/// Compared at 8 s: later the resting ball is unstable — in both models, at ~10–12 s, the
/// rounding noise grows (~e^(4 t)) into a roll onto a neighbouring face (explicit and implicit
/// alike: a surge to 0.1–0.2 m/s, then rest at a centre 6 mm higher) — a property of the
/// discrete ball, not of either integrator. At 8 s both still move at ≤ 7e-5 m/s (damped at
/// c = 1.5 1/s); their centres differed by 3.3e-5 m and their volumes by 4e-6 relative. Bounds:
/// 1e-4 m and 1e-4 (an oscillation of 7e-5 m/s at the body's slowest mode, ~1 Hz, is ~1e-5 m
/// in amplitude; ×3 for the two runs' phases and the implicit step's damping of it; the old
/// error was 270× the bound).
#[test]
fn a_body_at_rest_on_the_ground_has_the_explicit_models_equilibrium() {
    let mut imp = world(0.5, Integrator::Implicit, 1.0 / 60.0, 1e-7);
    let mut exp = world(0.5, Integrator::Symplectic, 5e-4, 1e-7);
    run_for(&mut imp, 8.0);
    run_for(&mut exp, 8.0);
    let (si, se) = (imp.stats(0), exp.stats(0));
    println!("implicit: centre {:.6} m, volume {:.6} m³, max speed {:.2e}", si.center_of_mass[1], si.volume, si.max_speed);
    println!("explicit: centre {:.6} m, volume {:.6} m³, max speed {:.2e}", se.center_of_mass[1], se.volume, se.max_speed);
    assert!((si.center_of_mass[1] - se.center_of_mass[1]).abs() < 1e-4, "centre {} vs {}", si.center_of_mass[1], se.center_of_mass[1]);
    assert!((si.volume / se.volume - 1.0).abs() < 1e-4, "volume {} vs {}", si.volume, se.volume);
    let lowest = imp.bodies[0].positions().chunks_exact(3).map(|p| p[1]).fold(f64::INFINITY, f64::min);
    assert!((0.0..1e-9).contains(&lowest), "the implicit body rests on the plane: lowest vertex at {lowest}");
}

/// At rest on a ground with friction (the modeler's μ = 0.5, tolerance 1e-3), the plane carries
/// the bottom's weight inside the solve, so the state at a step's start already solves it (to
/// the tolerance, relative to the weight's impulse over the step): after 8 s of settling, the
/// next 60 steps take at most one Newton iteration each on average (before: 3 every step,
/// forever, each solving the bottom's fall into the plane again) and the body stays put
/// (≤ 1 mm/s: the accepted velocity error is ≤ 1e-3 g dt = 0.16 mm/s per step, damped at 1.5 1/s).
#[test]
fn a_body_at_rest_on_the_ground_leaves_its_steps_nothing_to_solve() {
    let mut w = world(0.5, Integrator::Implicit, 1.0 / 60.0, 1e-3);
    run_for(&mut w, 8.0);
    let mut newton = 0;
    for _ in 0..60 {
        w.step().unwrap();
        newton += w.bodies[0].solver_iterations().newton;
    }
    let s = w.stats(0);
    println!("Newton iterations in 60 steps at rest: {newton}; max speed {:.2e} m/s", s.max_speed);
    assert!(newton <= 60, "{newton} Newton iterations in 60 steps at rest");
    assert!(s.max_speed < 1e-3, "max speed {} at rest", s.max_speed);
}

/// A stiffer balloon (the modeler's preset with k = k_b = 500 N/m) of 10,242 vertices landing
/// on the ground (its first 40 steps, 0.67 s) converges at every step without a retry. Its
/// flattened, compressed bottom has vertices whose springs are all compressed; the clamped
/// matrix leaves them almost only their mass (1e-4 kg against dt² k = 0.14 kg) against moving
/// out of the surface, so a Newton step could move them by centimetres, the springs stretched
/// at second order (l/L 1.02 → 1.12 in one trial) and Newton wandered at a relative residual of
/// 1e-2 until the cap; the step was then solved again without the ground's vertices held.
/// Measured here before the switch to the absolute-value projection after an overshoot
/// (`body/implicit/mod.rs`, `OVERSHOOT`), block Jacobi preconditioning: 709 Newton iterations
/// in 40 steps, retried steps of 221; with it: 508, at most 88 per step. With the V-cycle
/// (`multigrid::MULTIGRID_FROM`; the Newton path depends on the linear solves' inexact
/// directions): 667, at most 90, and without the switch 2,654 with retried steps of 157.
/// Since the vertices landing in a step are held in the solve (`body/implicit/ground.rs`):
/// 237, at most 11, 1,686 CG iterations (whether the bounds below still catch those two
/// faults with the landing held was not measured again). Bounds, kept from before: no step
/// above the cap (a retry adds the failed attempt's 100 to the step's count), and 800 in all.
/// And at most 6,000 conjugate-gradient iterations: measured 4,208 then; 8,267 with coarse
/// matrices kept from the first Newton iteration of a solve through the ground's releases and
/// the switch (`stale` in `newton`), which then mis-precondition.
/// Later, once the ball rolls on its flattened bottom, some steps still fail and are retried
/// (BENCHMARKS.md): the switch shortens the landing, it does not make every contact step
/// converge.
#[test]
fn a_stiff_balloon_settling_on_the_ground_converges_at_every_step() {
    let body = SoftBody::new(&icosphere(5, 0.7), 1.0, Material::default()).unwrap();
    let mut w = World::single(body, WorldSettings::default());
    w.apply_preset(0, "modeler").unwrap();
    w.bodies[0].material.stiffness = 500.0;
    w.bodies[0].material.bending_stiffness = 500.0;
    let lo = w.bodies[0].positions().chunks_exact(3).map(|p| p[1]).fold(f64::INFINITY, f64::min);
    let x: Vec<f64> = w.bodies[0].positions().chunks_exact(3).flat_map(|p| [p[0], p[1] - lo, p[2]]).collect();
    w.bodies[0].set_state(&x, &vec![0.0; x.len()]).unwrap();
    let cap = w.settings.newton_iterations;
    let (mut total, mut worst, mut linear) = (0, 0, 0);
    for _ in 0..40 {
        w.step().unwrap();
        let it = w.bodies[0].solver_iterations();
        (total, worst, linear) = (total + it.newton, worst.max(it.newton), linear + it.linear);
    }
    println!("Newton iterations in 40 steps: {total}, at most {worst} per step; {linear} CG iterations");
    assert!(worst <= cap, "a step took {worst} Newton iterations (cap {cap}): it was retried");
    assert!(total <= 800, "{total} Newton iterations in 40 steps");
    assert!(linear <= 6000, "{linear} conjugate-gradient iterations in 40 steps");
}

/// A sphere that lands a whole edge deep in one step: the modeler's preset on a 2,562-vertex
/// sphere of radius 1 m (edges ~6.5 cm) dropped from 1 m (4.4 m/s at the plane: |v_y| dt =
/// 7.4 cm at 1/60 s), its first second. The vertices landing in a step are held in the solve
/// and end the step on the plane (`body/implicit/ground.rs`, "Landing in the step"). Before,
/// that ring fell through the plane inside the solve, folded about the held bottom by more
/// than an edge, and was only pushed back by the after-step projection: measured, 350 Newton
/// iterations in the 60 steps and up to 34 in one; with the landing held 211, at most 8 (on
/// the modeler's 40,962-vertex sphere, whose ring is one edge deep at 1.3 m/s: 85–180 → 4–17
/// per step). Bounds: at most 16 in any step (2× the measured worst; half the old one) and 280
/// in all (1.33×).
#[test]
fn a_sphere_landing_an_edge_deep_in_one_step_converges_in_a_few_newton_iterations() {
    let body = SoftBody::new(&icosphere(4, 1.0), 1.0, Material::default()).unwrap();
    let mut w = World::single(body, WorldSettings::default());
    w.apply_preset(0, "modeler").unwrap();
    let lo = w.bodies[0].positions().chunks_exact(3).map(|p| p[1]).fold(f64::INFINITY, f64::min);
    let lift = |p: &[f64]| [p[0], p[1] - lo + 1.0, p[2]];
    let x: Vec<f64> = w.bodies[0].positions().chunks_exact(3).flat_map(lift).collect();
    w.bodies[0].set_state(&x, &vec![0.0; x.len()]).unwrap();
    let (mut total, mut worst) = (0, 0);
    for _ in 0..60 {
        w.step().unwrap();
        let n = w.bodies[0].solver_iterations().newton;
        (total, worst) = (total + n, worst.max(n));
    }
    println!("Newton iterations in 60 steps: {total}, at most {worst} per step");
    assert!(worst <= 16, "a step took {worst} Newton iterations");
    assert!(total <= 280, "{total} Newton iterations in 60 steps");
}

/// The icosphere (`mesh::builtin::icosphere`, the construction of `web/e2e/icosphere.mjs`) as the
/// modeler imports it, 2.5 m across its bounding box's diagonal, resting on y = 0, written with 9
/// significant digits as that script writes it: the same OBJ text, so the same bits, as the
/// benchmarks' `g5.obj` at level 5 (BENCHMARKS.md).
fn imported_icosphere_obj(level: u32) -> String {
    let r = 2.5 / (2.0 * 3f64.sqrt());
    let ball = icosphere(level, 1.0);
    let mut text = String::new();
    for p in ball.positions.chunks_exact(3) {
        text += &format!("v {:.8e} {:.8e} {:.8e}\n", p[0] * r, p[1] * r + r, p[2] * r);
    }
    for t in &ball.triangles {
        text += &format!("f {} {} {}\n", t[0] + 1, t[1] + 1, t[2] + 1);
    }
    text
}

/// A stiff rubber ball (the `stiff_rubber` preset: k = 2000 N/m, 30 J of gas) in the
/// modeler's world, the imported 10,242-vertex icosphere resting on the ground, its first 12
/// steps: its bottom flattens and the ground's releases peel the contact patch. Every linear
/// solve must stay short: measured at most 7.6 conjugate-gradient iterations per Newton
/// iteration in a step (20–34 Newton iterations per step from step 7); with the preset's hinges
/// (D = 0.1 J) at most 12.4 (2–7 Newton iterations per step) — 178 while the coarse levels
/// left the hinges out (`multigrid/`). Bound: 40 (3.2×).
/// Written for the coarse nodes' nearly unfelt tilts (`multigrid::BLOCK_PIVOT`): with the
/// ground's releases at 2, 4, 8, … (an earlier schedule) and those tilts kept down to pivots of
/// 1e-10, the assembly after a release in step 12 made the V-cycle indefinite and every Newton
/// iteration after it ran its conjugate gradient to the cap of 2,000 — 64,598 iterations in
/// that step, 760 per Newton iteration, this test 105 s against 6. With the releases at 1–4,
/// 8, … (`ground::release_due`) this path no longer meets such an assembly (checked: 60 steps
/// with the old threshold stay short), so the test now guards the patch's linear solves in
/// general; the path is chaotic (BENCHMARKS.md), hence the benchmarks' exact input bits.
#[test]
fn a_stiff_rubber_ball_flattening_on_the_ground_keeps_its_linear_solves_short() {
    let mesh = softsculpt::mesh::load_obj(imported_icosphere_obj(5).as_bytes()).unwrap().mesh;
    let body = SoftBody::new(&mesh, 1.0, Material::default()).unwrap();
    let mut w = World::single(body, WorldSettings::default());
    w.apply_preset(0, "modeler").unwrap();
    w.apply_preset(0, "stiff_rubber").unwrap();
    let mut worst = 0.0f64;
    for step in 1..=12 {
        w.step().unwrap();
        let it = w.bodies[0].solver_iterations();
        let per = it.linear as f64 / it.newton.max(1) as f64;
        println!("step {step}: {} Newton, {} conjugate-gradient iterations", it.newton, it.linear);
        worst = worst.max(per);
    }
    assert!(worst <= 40.0, "{worst:.0} CG iterations per Newton iteration in a step");
}

/// The modeler's mushroom as it opens (`common::rooted_mushroom`), settled for 2 s.
fn settled_mushroom() -> World {
    let mut w = rooted_mushroom();
    w.step_n(120).unwrap();
    w
}

/// Raising the ground carries what stands on it (`World::move_ground`): before, the rooted
/// mushroom's pinned foot stayed at y = 0 under a ground at 0.1 m, its lower stem crushed against
/// the plane (elastic energy 1.8 → 7.0 J), and at 0.5 m the implicit step failed. Now the whole
/// body moves with the plane: a translation, so every internal force and energy is the same —
/// to rounding, 1e-12 of the energy — and it goes on resting (it moves no faster than before
/// the move, within the settling's own wobble: 1 cm/s).
#[test]
fn raising_the_ground_lifts_a_rooted_body_with_it() {
    let mut w = settled_mushroom();
    let (x0, e0) = (w.bodies[0].positions().to_vec(), w.stats(0).elastic_energy);
    assert_eq!(w.move_ground(0.5).unwrap(), 1);
    let x1 = w.bodies[0].positions();
    for (k, (a, b)) in x0.iter().zip(x1).enumerate() {
        assert_eq!(*b, if k % 3 == 1 { a + 0.5 } else { *a });
    }
    assert!((w.stats(0).elastic_energy - e0).abs() <= 1e-12 * e0, "elastic energy {e0} → {}", w.stats(0).elastic_energy);
    let speed = w.bodies[0].max_speed();
    w.step_n(60).unwrap();
    assert!(w.bodies[0].max_speed() < speed + 0.01, "max speed {speed} → {} m/s", w.bodies[0].max_speed());
    let lowest = w.bodies[0].positions().chunks_exact(3).map(|p| p[1]).fold(f64::MAX, f64::min);
    assert!((lowest - 0.5).abs() < 1e-9, "lowest vertex at {lowest} m");
    // Reset (back to the frozen shape) puts it on the raised plane too, not 0.5 m under it.
    w.bodies[0].reset();
    let lowest = w.bodies[0].positions().chunks_exact(3).map(|p| p[1]).fold(f64::MAX, f64::min);
    assert!((lowest - 0.5).abs() < 1e-9, "reset to a lowest vertex at {lowest} m");
    w.step_n(30).unwrap();
    // And down again, below where it started.
    assert_eq!(w.move_ground(-0.25).unwrap(), 1);
    w.step_n(60).unwrap();
    let lowest = w.bodies[0].positions().chunks_exact(3).map(|p| p[1]).fold(f64::MAX, f64::min);
    assert!((lowest + 0.25).abs() < 1e-9, "lowest vertex at {lowest} m");
}

/// A body in the air stays where it is when the ground moves (it is not standing on it); with
/// no ground the move is refused, nothing changed.
#[test]
fn the_ground_moves_alone_under_a_body_in_the_air_and_not_at_all_without_a_ground() {
    let mut w = settled_mushroom();
    let mut air = softsculpt::mesh::builtin::builtin("sphere").unwrap();
    for p in air.positions.chunks_exact_mut(3) {
        p[1] += 5.0;
    }
    w.add_body(SoftBody::new(&air, 1.0, Material::default()).unwrap());
    let up = w.bodies[1].positions().to_vec();
    assert_eq!(w.move_ground(0.3).unwrap(), 1, "the mushroom, not the ball");
    assert_eq!(w.bodies[1].positions(), &up[..]);
    w.settings.ground = None;
    let x = w.bodies[0].positions().to_vec();
    let e = w.move_ground(1.0).unwrap_err();
    assert!(e.to_string().contains("ground"), "{e}");
    assert_eq!(w.bodies[0].positions(), &x[..]);
    // A move out of the finite numbers (a rise of 3.4e308 m) is refused before anything changes.
    w.settings.ground = Some(Ground::at(0.3));
    assert_eq!(w.move_ground(-1.7e308).unwrap(), 1);
    let x = w.bodies[0].positions().to_vec();
    let e = w.move_ground(1.7e308).unwrap_err();
    assert!(e.to_string().contains("out of range"), "{e}");
    assert_eq!(w.settings.ground.unwrap().height, -1.7e308);
    assert_eq!(w.bodies[0].positions(), &x[..]);
}
