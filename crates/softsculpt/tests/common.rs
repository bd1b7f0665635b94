//! Helpers shared by the physics tests.
#![allow(dead_code)]

use softsculpt::body::{Material, SoftBody, Target};
use softsculpt::mesh::builtin::{builtin, icosphere};
use softsculpt::world::{Integrator, World, WorldSettings};

/// A material with no damping and no gas: add what a test needs.
pub fn bare() -> Material {
    Material { stiffness: 100.0, spring_damping: 0.0, damping: 0.0, ..Material::default() }
}

/// A world with no gravity, symplectic Euler, nothing else: add what a test needs.
pub fn still() -> WorldSettings {
    WorldSettings { gravity: 0.0, integrator: Integrator::Symplectic, ..WorldSettings::default() }
}

pub fn sphere_body(level: u32, mass: f64, material: Material) -> SoftBody {
    SoftBody::new(&icosphere(level, 1.0), mass, material).unwrap()
}

pub fn model_body(name: &str, mass: f64, material: Material) -> SoftBody {
    SoftBody::new(&builtin(name).unwrap(), mass, material).unwrap()
}

/// A lone body in a world with `settings`.
pub fn alone(body: SoftBody, settings: WorldSettings) -> World {
    World::single(body, settings)
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

/// `steps` steps of `dt` seconds.
pub fn run(world: &mut World, dt: f64, steps: usize) {
    world.settings.dt = dt;
    for _ in 0..steps {
        world.step().unwrap();
    }
}

pub fn max_abs_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max)
}

/// The modeler's mushroom as it opens, not yet settled: standing on the ground (y = 0), its foot
/// pinned (the vertices within 1 cm of the ground), the `modeler` preset.
pub fn rooted_mushroom() -> World {
    let mut mesh = builtin("mushroom").unwrap();
    let lo = mesh.positions.chunks_exact(3).map(|p| p[1]).fold(f64::MAX, f64::min);
    for p in mesh.positions.chunks_exact_mut(3) {
        p[1] -= lo;
    }
    let mut w = World::single(SoftBody::new(&mesh, 1.0, Material::default()).unwrap(), WorldSettings::default());
    w.apply_preset(0, "modeler").unwrap();
    for i in 0..w.bodies[0].vertex_count() {
        if w.bodies[0].positions()[3 * i + 1] < 0.01 {
            w.bodies[0].set_pinned(i, true).unwrap();
        }
    }
    w
}

/// Σ m_i |v_i| (kg·m/s): the scale a momentum error is measured against.
pub fn momentum_scale(b: &SoftBody) -> f64 {
    b.velocities().chunks_exact(3).zip(b.masses()).map(|(v, m)| m * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()).sum()
}

/// The modeler's 642-vertex sphere (`modeler` preset, implicit steps at tolerance 1e-3, no
/// gravity) and its hard pull: the targets at step s, the top pulled 2 m aside and 1 m up over
/// 24 steps (0.4 s) and a band round the equator 2 m the other way, at ω = 600 1/s (k_t = m ω²).
pub fn pulled_sphere() -> (World, impl Fn(usize) -> Vec<Target>) {
    let body = sphere_body(2, 1.0, Material::default());
    let mut a = alone(body, WorldSettings { integrator: Integrator::Implicit, tolerance: 1e-3, ..still() });
    a.apply_preset(0, "modeler").unwrap();
    let n = a.bodies[0].vertex_count();
    let k = (1.0 / n as f64) * 600.0f64.powi(2);
    let x0 = a.bodies[0].positions().to_vec();
    let top: Vec<usize> = (0..n).filter(|&i| x0[3 * i + 1] > 0.8).collect();
    let band: Vec<usize> = (0..n).filter(|&i| x0[3 * i + 1].abs() < 0.3 && x0[3 * i] > 0.8).collect();
    let pull = move |s: usize| {
        let t = (s as f64 / 24.0).min(1.0);
        let at = |i: usize, d: [f64; 3]| Target { vertex: i, anchor: [x0[3 * i] + t * d[0], x0[3 * i + 1] + t * d[1], x0[3 * i + 2]], stiffness: k, damping: 0.0 };
        top.iter().map(|&i| at(i, [2.0, 1.0, 0.0])).chain(band.iter().map(|&i| at(i, [-2.0, 0.0, 0.0]))).collect()
    };
    (a, pull)
}
