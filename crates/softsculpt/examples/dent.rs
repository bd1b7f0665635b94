//! A material preset's spring-back from a press on the modeler's rooted mushroom (issue #37):
//! settled, frozen under load, the preset applied, settled again; a dent of 15 cm (cosine
//! profile, 35 cm radius) at the cap's front-most point, let go; the dent left after 1, 5 and
//! 10 s. Optionally the rigidity D (J) overridden, and the mushroom subdivided.
//!
//!     cargo run --release -p softsculpt --example dent -- PRESET [RIGIDITY] [SUBDIVISIONS]

use softsculpt::mesh::builtin::builtin;
use softsculpt::params::Value;
use softsculpt::world::Budget;
use softsculpt::{Material, SoftBody, World, WorldSettings};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let preset = args.get(1).map(String::as_str).unwrap_or("jelly");
    let rigidity: Option<f64> = args.get(2).and_then(|s| s.parse().ok());
    let subdivisions: u32 = args.get(3).and_then(|s| s.parse().ok()).unwrap_or(0);
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
    let budget = Budget { splits: 3, relax: true, ..Budget::converge() };
    let t0 = std::time::Instant::now();
    w.advance(2.0, &budget).unwrap();
    w.freeze(0, softsculpt::body::FreezeOptions { under_load: true, keep_tension: false }).unwrap();
    w.apply_preset(0, preset).unwrap();
    if let Some(d) = rigidity {
        w.set_param(0, "rigidity", Value::Number(d)).unwrap();
    }
    let settle: f64 = std::env::var("SETTLE").ok().and_then(|s| s.parse().ok()).unwrap_or(2.0);
    w.advance(settle, &budget).unwrap();
    println!("settled {settle} s: largest speed {:.2e} m/s", w.bodies[0].max_speed());
    let x0 = w.bodies[0].positions().to_vec();
    let n = x0.len() / 3;
    let c = (0..n).max_by(|&a, &b| x0[3 * a + 2].total_cmp(&x0[3 * b + 2])).unwrap();
    let mut x = x0.clone();
    for i in 0..n {
        let d = (0..3).map(|k| (x0[3 * i + k] - x0[3 * c + k]).powi(2)).sum::<f64>().sqrt();
        if d < 0.35 {
            x[3 * i + 2] -= 0.15 * 0.5 * (1.0 + (std::f64::consts::PI * d / 0.35).cos());
        }
    }
    w.bodies[0].set_state(&x, &vec![0.0; x.len()]).unwrap();
    let mut done = 0.0;
    for t in [1.0, 5.0, 10.0] {
        let a = w.advance(t - done, &budget).unwrap();
        done = t;
        let left = x0[3 * c + 2] - w.bodies[0].positions()[3 * c + 2];
        let worst = (0..n).map(|i| (0..3).map(|k| (x0[3 * i + k] - w.bodies[0].positions()[3 * i + k]).powi(2)).sum::<f64>().sqrt()).fold(0.0, f64::max);
        println!("{preset} D={:?} x{subdivisions} ({n} vertices): t = {t:>4} s after release: dent {:.4} m, largest displacement {:.4} m, splits {} ({:.1} s wall)", rigidity, left, worst, a.splits, t0.elapsed().as_secs_f64());
    }
}
