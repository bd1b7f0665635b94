//! Convergence order of every integrator, measured by refining dt.

mod common;
use common::*;
use softsculpt::body::Material;
use softsculpt::world::{Integrator, World, WorldSettings};

const T: f64 = 0.04;

fn world(integrator: Integrator) -> World {
    let mut p = Material { stiffness: 50.0, spring_damping: 0.5, ..bare() };
    p.set_nrt(1.0);
    let mut b = sphere_body(1, 1.0, p);
    swirl(&mut b, 1.0);
    alone(b, WorldSettings { gravity: 9.81, integrator, ..still() })
}

fn solve(integrator: Integrator, steps: usize) -> Vec<f64> {
    let mut w = world(integrator);
    run(&mut w, T / steps as f64, steps);
    let b = &w.bodies[0];
    b.positions().iter().chain(b.velocities()).copied().collect()
}

/// Observed order p = log2(e(dt) / e(dt/2)), from errors against an RK4 reference with a step
/// 16 times finer than the finest tested (its own error is then ~16^-4 of RK4's smallest).
fn observed_order(integrator: Integrator, coarse: usize) -> (f64, f64) {
    let reference = solve(Integrator::Rk4, coarse * 4 * 16);
    let e: Vec<f64> = [coarse, 2 * coarse, 4 * coarse].iter().map(|&n| max_abs_diff(&solve(integrator, n), &reference)).collect();
    ((e[0] / e[1]).log2(), (e[1] / e[2]).log2())
}

#[test]
fn each_integrator_converges_at_its_order() {
    // (integrator, coarsest step count over T, expected order). ω_max ≈ sqrt(12·50·42) ≈ 159
    // rad/s, so the coarse steps keep ω dt ≤ 0.16 (first-order methods, midpoint) or ≤ 0.4 (RK4),
    // inside the asymptotic range, while RK4's errors stay far above rounding.
    let cases = [
        (Integrator::Euler, 40, 1.0),
        (Integrator::Symplectic, 40, 1.0),
        (Integrator::Midpoint, 40, 2.0),
        (Integrator::Rk4, 16, 4.0),
    ];
    for (integrator, coarse, expected) in cases {
        let (p1, p2) = observed_order(integrator, coarse);
        // Tolerance: the observed order approaches the true one as O(dt); at these steps the
        // next error term shifts it by well under 0.25.
        assert!((p2 - expected).abs() < 0.25, "{integrator:?}: observed orders {p1:.3}, {p2:.3}, expected {expected}");
        assert!((p1 - expected).abs() < 0.4, "{integrator:?}: observed orders {p1:.3}, {p2:.3}, expected {expected}");
    }
}
