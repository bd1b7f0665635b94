//! The ground plane.

mod common;
use common::*;
use softsculpt::body::Material;
use softsculpt::world::{Ground, Integrator, WorldSettings};

/// A balloon dropped on the ground comes to rest on it: no vertex is ever below the plane at the
/// end of a step (checked after every step, tolerance 0: the projection sets y = h exactly),
/// the body stops, and it is resting on the ground, not hovering.
#[test]
fn a_balloon_dropped_on_the_ground_comes_to_rest_on_it() {
    for integrator in [Integrator::Symplectic, Integrator::Rk4, Integrator::Midpoint] {
        let h = -0.3;
        let mut p = Material { spring_damping: 0.2, damping: 0.5, ..bare() };
        p.set_nrt(20.0);
        let mut body = sphere_body(2, 1.0, p);
        let x = body.positions().iter().enumerate().map(|(k, &c)| if k % 3 == 1 { c + 1.0 } else { c }).collect::<Vec<_>>();
        let v = vec![0.0; x.len()];
        body.set_state(&x, &v).unwrap(); // lowest point at y = 0, 0.3 m above the ground
        let mut w = alone(body, WorldSettings { gravity: 9.81, ground: Some(Ground::at(h)), integrator, dt: 5e-4, ..still() });
        let mut touched = false;
        for _ in 0..30000 {
            w.step().unwrap();
            let lowest = w.bodies[0].positions().chunks_exact(3).map(|p| p[1]).fold(f64::INFINITY, f64::min);
            assert!(lowest >= h, "{integrator:?}: vertex below the ground: {lowest}");
            touched |= lowest == h;
        }
        assert!(touched);
        let s = w.stats(0);
        let body = &w.bodies[0];
        // At rest: damping e^{-0.5 t} over 15 s leaves ~5e-4 of the impact speed (~2.4 m/s).
        assert!(s.max_speed < 5e-3, "{integrator:?}: still moving at {}", s.max_speed);
        let resting = body.positions().chunks_exact(3).filter(|p| p[1] == h).count();
        assert!(resting >= 3, "{integrator:?}: only {resting} vertices on the ground");
        // Squashed by gravity but still a balloon: positive volume, centre above the ground.
        assert!(body.exact_volume() > 1.0 && s.center_of_mass[1] > h + 0.5);
    }
}

/// Friction stops a body sliding along the ground; without friction it keeps sliding.
#[test]
fn friction_stops_sliding() {
    let run_with = |mu: f64| {
        let mut p = Material { spring_damping: 0.2, ..bare() };
        p.set_nrt(20.0);
        let mut body = sphere_body(2, 1.0, p);
        body.set_uniform_velocity([1.0, 0.0, 0.0]).unwrap();
        let mut w = alone(body, WorldSettings { gravity: 9.81, ground: Some(Ground { friction: mu, ..Ground::at(-1.0) }), ..still() });
        run(&mut w, 5e-4, 4000);
        w.stats(0).momentum[0]
    };
    let (sticky, slippery) = (run_with(1.0), run_with(0.0));
    assert!(slippery > 0.9, "frictionless ground keeps the momentum: {slippery}");
    assert!(sticky < 0.5 * slippery, "friction slows it: {sticky} vs {slippery}");
}
