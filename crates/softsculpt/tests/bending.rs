//! Bending springs: a surface that resists folding.

mod common;
use common::*;
use softsculpt::body::Material;
use softsculpt::world::{Ground, Integrator, WorldSettings};

/// Bending springs are ordinary conservative springs: RK4 keeps the total energy (their elastic
/// energy included) as well as without them (see conservation.rs for the tolerance).
#[test]
fn bending_springs_conserve_energy() {
    let mut p = Material { bending_stiffness: 40.0, ..bare() };
    p.set_nrt(2.0);
    let mut w = alone(sphere_body(2, 1.0, p), WorldSettings { gravity: 9.81, integrator: Integrator::Rk4, ..still() });
    swirl(&mut w.bodies[0], 1.0);
    let e0 = w.stats(0);
    run(&mut w, 1e-4, 2000);
    let drift = (w.stats(0).total_energy - e0.total_energy).abs();
    assert!(drift < 1e-8 * e0.kinetic_energy, "drift {drift}");
}

/// A rooted mushroom nudged sideways: without bending springs its soft stem buckles and the cap
/// falls to the ground; with them it stands back up.
#[test]
fn bending_springs_keep_a_mushroom_standing() {
    let stand = |kb: f64| {
        let mut p = Material { spring_damping: 0.1, damping: 1.5, bending_stiffness: kb, ..bare() };
        p.set_nrt(30.0);
        let mut body = model_body("mushroom", 1.0, p);
        for i in 0..body.vertex_count() {
            if body.positions()[3 * i + 1] < 0.01 {
                body.set_pinned(i, true).unwrap();
            }
        }
        let mut w = alone(body, WorldSettings { gravity: 9.81, ground: Some(Ground::at(0.0)), ..still() });
        run(&mut w, 5e-4, 6000);
        let y0 = w.stats(0).center_of_mass[1];
        let push: Vec<f64> = w.bodies[0].positions().chunks_exact(3).flat_map(|x| [if x[1] > 1.2 { 0.1 } else { 0.0 }, 0.0, 0.0]).collect();
        w.bodies[0].set_user_forces(&push).unwrap();
        run(&mut w, 5e-4, 600);
        w.bodies[0].set_user_forces(&vec![0.0; push.len()]).unwrap();
        run(&mut w, 5e-4, 20000);
        (y0, w.stats(0).center_of_mass[1])
    };
    let (y0, limp) = stand(0.0);
    // k_b = k: measured 0.951 -> 0.951 (k_b = 50 is not enough: 0.958 -> 0.628).
    let (y1, stiff) = stand(100.0);
    assert!(limp < y0 - 0.2, "without bending the cap falls: {y0} -> {limp}");
    // Tolerance: standing back up returns the centre of mass to within a few millimetres
    // (measured 0.3 mm); falling over drops it by ~0.3 m. We allow 2 cm.
    assert!((stiff - y1).abs() < 0.02, "with bending it stands: {y1} -> {stiff}");
}
