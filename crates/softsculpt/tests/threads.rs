//! The explicit force stages on several threads (`body/parforces.rs`): the same motion as on
//! one thread, and the same bits on any number of threads above one.

mod common;
use common::*;
use softsculpt::body::Material;
use softsculpt::world::{Integrator, World, WorldSettings};

/// 10,242 vertices of 1/256 kg (5 chunks of 2048 and a partial one), gas, spring and bending springs,
/// viscous damping, gravity, a swirl: every explicit stage and both kinds of crossing terms.
fn world(integrator: Integrator, threads: usize) -> World {
    let mut p = Material { stiffness: 1000.0, spring_damping: 1.0, damping: 0.2, bending_stiffness: 300.0, ..bare() };
    p.set_nrt(2.0);
    let mut body = sphere_body(5, 40.0, p);
    swirl(&mut body, 0.5);
    let mut w = alone(body, WorldSettings { gravity: 9.81, integrator, dt: 1e-4, ..still() });
    w.set_threads(threads).unwrap();
    w
}

#[test]
fn two_threads_step_the_explicit_integrators_like_one() {
    for integrator in [Integrator::Symplectic, Integrator::Rk4] {
        let (mut one, mut two) = (world(integrator, 1), world(integrator, 2));
        one.step_n(20).unwrap();
        two.step_n(20).unwrap();
        let scale = one.bodies[0].positions().iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let vscale = one.bodies[0].velocities().iter().fold(0.0f64, |m, v| m.max(v.abs()));
        // Tolerance: the terms are the same numbers, summed per vertex in another order (the
        // chunk-border terms last), so each force differs by a few ulps of the largest term.
        // The largest terms are the spring damping forces, cs |Δv| ≈ 1 · 1 N per spring (the
        // swirl), so dt Σ|f| / m ≈ 1e-4 · 10 N / 3.9e-3 kg ≈ 0.3 m/s per step: ulps of that,
        // ~1e-16 m/s per step. The run is stable (ω dt = sqrt(12 k / m) dt ≈ 0.18 and
        // 12 cs dt / m ≈ 0.3), so over 20 steps they add up to ~1e-14 of the 0.5 m/s velocities:
        // far inside the 1e-12 relative, which is what is asserted.
        let dx = max_abs_diff(one.bodies[0].positions(), two.bodies[0].positions());
        let dv = max_abs_diff(one.bodies[0].velocities(), two.bodies[0].velocities());
        assert!(dx <= 1e-12 * scale && dv <= 1e-12 * vscale, "{integrator:?}: |Δx| {dx:e}, |Δv| {dv:e}");
    }
}

#[test]
fn two_and_three_threads_give_the_same_bits() {
    let (mut two, mut three) = (world(Integrator::Symplectic, 2), world(Integrator::Symplectic, 3));
    two.step_n(20).unwrap();
    three.step_n(20).unwrap();
    // The chunks do not depend on the thread count: the same sums in the same order.
    assert_eq!(two.bodies[0].positions(), three.bodies[0].positions());
    assert_eq!(two.bodies[0].velocities(), three.bodies[0].velocities());
}

