//! Helpers shared by the physics tests.
#![allow(dead_code)]

use softsculpt::body::{Integrator, Params, SoftBody};
use softsculpt::mesh::builtin::{builtin, icosphere};

/// Parameters with no gravity, no damping, no gas: add what a test needs.
pub fn bare() -> Params {
    Params { stiffness: 100.0, spring_damping: 0.0, damping: 0.0, gravity: 0.0, integrator: Integrator::Symplectic, ..Params::default() }
}

pub fn sphere_body(level: u32, mass: f64, params: Params) -> SoftBody {
    SoftBody::new(&icosphere(level, 1.0), mass, params).unwrap()
}

pub fn model_body(name: &str, mass: f64, params: Params) -> SoftBody {
    SoftBody::new(&builtin(name).unwrap(), mass, params).unwrap()
}

/// A smooth, deterministic, non-uniform velocity field (m/s) that excites many modes.
pub fn swirl(body: &mut SoftBody, amplitude: f64) {
    let x = body.positions().to_vec();
    let v: Vec<f64> = x
        .chunks_exact(3)
        .flat_map(|p| {
            [
                amplitude * (2.0 * p[1]).sin(),
                amplitude * (3.0 * p[2] + 0.5).cos() * 0.5,
                amplitude * (1.5 * p[0]).sin() * p[1],
            ]
        })
        .collect();
    body.set_state(&x, &v).unwrap();
}

pub fn run(body: &mut SoftBody, dt: f64, steps: usize) {
    for _ in 0..steps {
        body.step(dt).unwrap();
    }
}

pub fn max_abs_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max)
}
