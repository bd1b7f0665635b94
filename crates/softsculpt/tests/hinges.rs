//! Hinges (`body/hinges.rs`): bending by the dihedral angles, a thin plate's flexural rigidity D
//! at any mesh resolution.

mod common;
use common::*;
use softsculpt::body::{Material, SoftBody};
use softsculpt::mesh::TriMesh;
use softsculpt::world::{Integrator, World, WorldSettings};

/// A flat plate of near-equilateral triangles in the x–z plane: `nu` triangles' widths along
/// x (edge h = width / nu), rows of height h √3/2 along z up to `depth`.
fn plate(width: f64, depth: f64, nu: usize) -> TriMesh {
    let h = width / nu as f64;
    let rows = (depth / (h * 3f64.sqrt() / 2.0)).round() as usize;
    let cols = nu + 1;
    let mut positions = Vec::new();
    for r in 0..=rows {
        for c in 0..cols {
            let shift = if r % 2 == 1 { 0.5 * h } else { 0.0 };
            // Odd rows are shifted by h/2; their last vertex is pulled back to the edge x = width.
            let x = (c as f64 * h + shift).min(width);
            positions.extend([x, 0.0, r as f64 * h * 3f64.sqrt() / 2.0]);
        }
    }
    let id = |r: usize, c: usize| (r * cols + c) as u32;
    let mut triangles = Vec::new();
    for r in 0..rows {
        for c in 0..nu {
            let (a, b, cc, d) = (id(r, c), id(r, c + 1), id(r + 1, c), id(r + 1, c + 1));
            if r % 2 == 0 {
                triangles.push([a, b, cc]);
                triangles.push([b, d, cc]);
            } else {
                triangles.push([a, d, cc]);
                triangles.push([a, b, d]);
            }
        }
    }
    TriMesh { positions, triangles }
}

/// The plate's vertices rolled around the z axis onto a cylinder of radius `r` (an isometry:
/// x is the arc length).
fn rolled(flat: &[f64], r: f64) -> Vec<f64> {
    flat.chunks_exact(3).flat_map(|p| [r * (p[0] / r).sin(), r * (1.0 - (p[0] / r).cos()), p[2]]).collect()
}

/// Elastic energy of `body` at `x`: with k = 0 and no bending springs, the hinges' alone.
fn bending_energy(body: &mut SoftBody, x: &[f64]) -> f64 {
    let v = vec![0.0; x.len()];
    body.set_state(x, &v).unwrap();
    World::single(body.clone(), still()).stats(0).elastic_energy
}

/// Twice the area of the triangle (a, b, c) of the x–z plane.
fn area_xz(x: &[f64], t: &[u32; 3]) -> f64 {
    let q = |k: usize| [x[3 * t[k] as usize], x[3 * t[k] as usize + 2]];
    let (a, b, c) = (q(0), q(1), q(2));
    0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])).abs()
}

/// The plate's bending energy rolled into a half cylinder of radius `r` (a width of π r along
/// x, 0.6 m along the axis z), against Kirchhoff's ½ D A / R². `along`: the mesh's rows of
/// vertices run along the axis (else across it). `n`: edges along the rows' direction per
/// metre-ish resolution (see `plate`).
fn rolled_ratio(d: f64, r: f64, n: usize, along: bool) -> f64 {
    let (width, depth) = (std::f64::consts::PI * r, 0.6);
    let mut mesh = if along { plate(depth, width, n) } else { plate(width, depth, n) };
    if along {
        // Rows along z: swap x and z (a mirror: every face's winding flips alike).
        for p in mesh.positions.chunks_exact_mut(3) {
            p.swap(0, 2);
        }
    }
    let flat = mesh.positions.clone();
    let area: f64 = mesh.triangles.iter().map(|t| area_xz(&flat, t)).sum();
    let mut body = SoftBody::new(&mesh, 1.0, Material { stiffness: 0.0, rigidity: d, ..bare() }).unwrap();
    bending_energy(&mut body, &rolled(&flat, r)) / (0.5 * d * area / (r * r))
}

/// A plate rolled into a half cylinder of radius R stores Kirchhoff's ½ D A / R² (K = 0), and
/// the same at every mesh resolution — where bending springs' energy for the same rolling
/// falls 4× per halving of the edge (their rigidity goes as k_b h²).
#[test]
fn a_rolled_plate_stores_half_d_area_over_r_squared_at_any_resolution() {
    let (d, r) = (0.02, 0.4);
    let mut across = Vec::new();
    for n in [16, 32, 64] {
        // Rows along the axis: only the axis-parallel edges bend (`hinges.rs`), E = ½ D A / R²
        // but for the plate's two straight ends, whose axis-parallel edges have one face and no
        // hinge: of the ~2n/√3 + 1 lines of them across the width (n edges of the 0.6 m rows
        // set h = 0.6/n; lines √3 h/2 apart over π R = 1.26 m), 2 are missing, and the angle's
        // expansion adds O(h²/R²) (< 1e-3). So the ratio is 1 − 2/lines ± 1e-3; we allow
        // 1.2 · 2/lines + 1e-3 below 1 and 1e-3 above.
        let lines = std::f64::consts::PI * r / (0.6 / n as f64 * 3f64.sqrt() / 2.0) + 1.0;
        let along = rolled_ratio(d, r, n, true);
        assert!(along < 1.0 + 1e-3 && along > 1.0 - 2.4 / lines - 1e-3, "rows along the axis, n = {n}: ratio {along}");
        across.push(rolled_ratio(d, r, n, false));
    }
    // Rows across the axis: the plate's ends along x are zigzags of slanted edges with one face
    // each; of a row's 2n slanted edges about 2 miss their hinge: 1 − 1/n ± 1e-3 (measured
    // 1 − 0.77/n at n = 16, 32, 64); we allow 1.2/n + 1e-3 below 1 and 1e-3 above.
    for (a, n) in across.iter().zip([16.0, 32.0, 64.0]) {
        assert!(*a < 1.0 + 1e-3 && *a > 1.0 - 1.2 / n - 1e-3, "rows across the axis, n = {n}: ratio {a}");
    }
}

/// Hinges are conservative: RK4 keeps the total energy (their bending energy included) as
/// well as without them (see conservation.rs for the tolerance: 1e-8 of the kinetic energy).
#[test]
fn hinges_conserve_energy() {
    let mut p = Material { rigidity: 0.05, ..bare() };
    p.set_nrt(2.0);
    let mut w = alone(sphere_body(2, 1.0, p), WorldSettings { gravity: 9.81, integrator: Integrator::Rk4, ..still() });
    swirl(&mut w.bodies[0], 1.0);
    let e0 = w.stats(0);
    run(&mut w, 1e-4, 2000);
    let s = w.stats(0);
    let drift = (s.total_energy - e0.total_energy).abs();
    assert!(s.elastic_energy > 1e-3 * e0.kinetic_energy, "the hinges are bent: {} J", s.elastic_energy);
    assert!(drift < 1e-8 * e0.kinetic_energy, "drift {drift}");
}

/// Without external forces, hinges keep the momentum (their forces sum to zero per hinge) on
/// the implicit integrator too: to rounding, 1e-9 of the momentum scale Σ m |v|.
#[test]
fn implicit_steps_with_hinges_keep_the_momentum() {
    let mut p = Material { stiffness: 300.0, spring_damping: 0.5, rigidity: 0.1, ..bare() };
    p.set_nrt(3.0);
    let mut w = alone(sphere_body(3, 1.0, p), WorldSettings { integrator: Integrator::Implicit, tolerance: 1e-8, dt: 1.0 / 60.0, ..still() });
    swirl(&mut w.bodies[0], 1.0);
    let m0 = w.stats(0).momentum;
    let scale = momentum_scale(&w.bodies[0]);
    w.step_n(30).unwrap();
    let m1 = w.stats(0).momentum;
    for d in 0..3 {
        assert!((m1[d] - m0[d]).abs() < 1e-9 * scale, "momentum {m0:?} -> {m1:?}");
    }
}

/// A ball of rigidity D dented and let go springs back to its frozen shape with the implicit
/// integrator at 1/60 s: with no gas and soft edges, only the hinges restore it.
#[test]
fn hinges_alone_restore_a_dented_shell() {
    let p = Material { stiffness: 20.0, spring_damping: 0.2, damping: 2.0, rigidity: 0.05, ..bare() };
    let body = sphere_body(3, 1.0, p);
    let x0 = body.positions().to_vec();
    let mut w = alone(body, WorldSettings { integrator: Integrator::Implicit, dt: 1.0 / 60.0, ..still() });
    // Dent: push the top cap in by 0.3 m (the vertices above y = 0.7 to y = 0.4 and below).
    let dented: Vec<f64> = x0.chunks_exact(3).flat_map(|q| [q[0], if q[1] > 0.7 { q[1] - 0.3 } else { q[1] }, q[2]]).collect();
    let v = vec![0.0; dented.len()];
    w.bodies[0].set_state(&dented, &v).unwrap();
    w.step_n(600).unwrap();
    let top = w.bodies[0].positions().chunks_exact(3).map(|q| q[1]).fold(f64::MIN, f64::max);
    let bottom = w.bodies[0].positions().chunks_exact(3).map(|q| q[1]).fold(f64::MAX, f64::min);
    // Tolerance: back to the unit sphere's height 2 m within 1 cm (the dent was 30 cm; after
    // 10 s at c = 2 1/s the motion has decayed by e^-20). Without hinges a gas-less shell of
    // soft edges keeps a dent as an equilibrium (nothing resists the fold): the test asks that
    // it stays at least 5 cm short of 2 m, a sixth of the dent.
    assert!((top - bottom - 2.0).abs() < 0.01, "height {} m", top - bottom);
    let without = {
        let p = Material { stiffness: 20.0, spring_damping: 0.2, damping: 2.0, ..bare() };
        let mut w = alone(sphere_body(3, 1.0, p), WorldSettings { integrator: Integrator::Implicit, dt: 1.0 / 60.0, ..still() });
        w.bodies[0].set_state(&dented, &v).unwrap();
        w.step_n(600).unwrap();
        let ys: Vec<f64> = w.bodies[0].positions().chunks_exact(3).map(|q| q[1]).collect();
        ys.iter().cloned().fold(f64::MIN, f64::max) - ys.iter().cloned().fold(f64::MAX, f64::min)
    };
    assert!(without < 1.95, "without hinges the dent stays: height {without} m");
}

/// The hinge passes split over threads (`implicit/system/`): each hinge's values are computed
/// alone and every vertex sums its hinges in one fixed order, so one and two threads agree —
/// the issue asks for 1e-12 relative (beyond summation order); here the same bits are expected.
#[test]
fn one_and_two_threads_step_hinges_alike() {
    let run_on = |threads: usize| {
        let mut p = Material { stiffness: 500.0, spring_damping: 0.5, damping: 0.5, rigidity: 0.05, ..bare() };
        p.set_nrt(5.0);
        let mut body = sphere_body(5, 1.0, p);
        swirl(&mut body, 0.5);
        let mut w = alone(body, WorldSettings { gravity: 9.81, integrator: Integrator::Implicit, tolerance: 1e-6, dt: 1.0 / 60.0, ..still() });
        w.set_threads(threads).unwrap();
        w.step_n(5).unwrap();
        w.bodies[0].positions().to_vec()
    };
    assert_eq!(run_on(1), run_on(2));
}

/// The hinges' damping (τ = c_s / k) only takes energy out: a swirled shell with hinges, weak
/// edges and nothing else dissipative but the springs' and hinges' damping never gains total
/// energy, checked every 0.01 s over 0.5 s of RK4 steps of 1e-4 s (RK4's own error on this
/// smooth motion is ~1e-12 of the energy: 1e-9 of the starting energy allows it), and loses
/// some of it.
#[test]
fn the_hinges_damping_never_adds_energy() {
    let p = Material { stiffness: 5.0, spring_damping: 0.05, rigidity: 0.05, ..bare() };
    let mut w = alone(sphere_body(2, 1.0, p), WorldSettings { integrator: Integrator::Rk4, ..still() });
    swirl(&mut w.bodies[0], 1.0);
    let e0 = w.stats(0).total_energy;
    let mut last = e0;
    for _ in 0..50 {
        run(&mut w, 1e-4, 100);
        let e = w.stats(0).total_energy;
        assert!(e <= last + 1e-9 * e0, "energy rose {last} -> {e} J");
        last = e;
    }
    assert!(last < 0.99 * e0, "the damping took {} of {e0} J", e0 - last);
}

/// Hinges switched on in the middle of a run (the solver's hinge arrays are allocated at its
/// first evaluation with D > 0, the multigrid's per-hinge nodes at its first assembly with them:
/// `implicit/system/`, `multigrid/`) step exactly as a solver built afresh does: the world
/// restored from a snapshot taken at the switch, given the same D, takes the same bits (a
/// restored world continues bit for bit: `tests/snapshot.rs`). 10,242 vertices, so that the
/// multigrid's coarse levels, which carry the hinges, are in use.
#[test]
fn hinges_switched_on_mid_run_step_as_a_fresh_solver_does() {
    let mut p = Material { stiffness: 500.0, spring_damping: 0.5, damping: 0.5, rigidity: 0.0, ..bare() };
    p.set_nrt(5.0);
    let mut body = sphere_body(5, 1.0, p);
    swirl(&mut body, 0.2);
    let mut w = alone(body, WorldSettings { gravity: 9.81, integrator: Integrator::Implicit, tolerance: 1e-4, dt: 1.0 / 60.0, ..still() });
    w.step_n(2).unwrap();
    let snap = w.snapshot();
    let mut fresh = World::restore(&snap).unwrap();
    for world in [&mut w, &mut fresh] {
        world.set_param(0, "rigidity", softsculpt::params::Value::Number(0.05)).unwrap();
        world.step_n(3).unwrap();
    }
    assert_eq!(w.bodies[0].positions(), fresh.bodies[0].positions());
    assert_eq!(w.bodies[0].velocities(), fresh.bodies[0].velocities());
}
