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
    rooted_mushroom_subdivided(0)
}

/// [`rooted_mushroom`] subdivided `subdivisions` times before its foot is pinned.
pub fn rooted_mushroom_subdivided(subdivisions: u32) -> World {
    let mut mesh = builtin("mushroom").unwrap();
    let lo = mesh.positions.chunks_exact(3).map(|p| p[1]).fold(f64::MAX, f64::min);
    for p in mesh.positions.chunks_exact_mut(3) {
        p[1] -= lo;
    }
    let mut body = SoftBody::new(&mesh, 1.0, Material::default()).unwrap();
    for _ in 0..subdivisions {
        body = body.subdivided().unwrap();
    }
    let mut w = World::single(body, WorldSettings::default());
    w.apply_preset(0, "modeler").unwrap();
    for i in 0..w.bodies[0].vertex_count() {
        if w.bodies[0].positions()[3 * i + 1] < 0.01 {
            w.bodies[0].set_pinned(i, true).unwrap();
        }
    }
    w
}

/// A press's dent in positions `x0` (flat xyz): the front-most vertex (largest z) and those
/// within 35 cm of it pushed back along −z by 15 cm × ½ (1 + cos(π d / 0.35)), the modeler's
/// default press (a cosine profile). Returns the dented positions and the front-most vertex.
pub fn dented(x0: &[f64]) -> (Vec<f64>, usize) {
    let n = x0.len() / 3;
    let c = (0..n).max_by(|&a, &b| x0[3 * a + 2].total_cmp(&x0[3 * b + 2])).unwrap();
    let mut x = x0.to_vec();
    for i in 0..n {
        let d = (0..3).map(|k| (x0[3 * i + k] - x0[3 * c + k]).powi(2)).sum::<f64>().sqrt();
        if d < 0.35 {
            x[3 * i + 2] -= 0.15 * 0.5 * (1.0 + (std::f64::consts::PI * d / 0.35).cos());
        }
    }
    (x, c)
}

/// A world as the modeler makes one (its preset: implicit at 1/60 s, gravity, ground at 0)
/// for `mesh` subdivided `subdivisions` times, the body set on the ground, then the material
/// `preset`.
pub fn on_ground(mesh: &softsculpt::TriMesh, subdivisions: u32, preset: &str) -> World {
    let mut body = SoftBody::new(mesh, 1.0, Material::default()).unwrap();
    for _ in 0..subdivisions {
        body = body.subdivided().unwrap();
    }
    let mut w = World::single(body, WorldSettings::default());
    w.apply_preset(0, "modeler").unwrap();
    w.apply_preset(0, preset).unwrap();
    let lowest = w.bodies[0].positions().chunks_exact(3).map(|p| p[1]).fold(f64::INFINITY, f64::min);
    let x: Vec<f64> = w.bodies[0].positions().chunks_exact(3).flat_map(|p| [p[0], p[1] - lowest + 1e-3, p[2]]).collect();
    let v = vec![0.0; x.len()];
    w.bodies[0].set_state(&x, &v).unwrap();
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
