//! How far the wind sways the modeler's rooted mushroom (issue #37): settled, then a wind of
//! S m/s along +x (the modeler's drag coefficient) for T s; the cap rim's largest displacement
//! along x and the centre of mass's.
//!
//!     cargo run --release -p softsculpt --example wind -- SPEED [SECONDS] [PINNED=1]

use softsculpt::mesh::builtin::builtin;
use softsculpt::params::Value;
use softsculpt::world::Budget;
use softsculpt::{Material, SoftBody, World, WorldSettings};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let speed: f64 = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(1.39);
    let seconds: f64 = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(3.0);
    let pinned = args.get(3).is_none_or(|s| s != "0");
    let model = std::env::var("MODEL").unwrap_or_else(|_| "mushroom".into());
    let mut mesh = builtin(&model).unwrap();
    let lo = mesh.positions.chunks_exact(3).map(|p| p[1]).fold(f64::MAX, f64::min);
    for p in mesh.positions.chunks_exact_mut(3) {
        p[1] -= lo;
    }
    let mut w = World::single(SoftBody::new(&mesh, 1.0, Material::default()).unwrap(), WorldSettings::default());
    w.apply_preset(0, "modeler").unwrap();
    if pinned {
        for i in 0..w.bodies[0].vertex_count() {
            if w.bodies[0].positions()[3 * i + 1] < 0.01 {
                w.bodies[0].set_pinned(i, true).unwrap();
            }
        }
    }
    let budget = Budget { splits: 3, relax: true, ..Budget::converge() };
    w.advance(2.0, &budget).unwrap();
    w.freeze(0, softsculpt::body::FreezeOptions { under_load: true, keep_tension: false }).unwrap();
    w.advance(1.0, &budget).unwrap();
    let x0 = w.bodies[0].positions().to_vec();
    let c0 = w.stats(0).center_of_mass;
    let top = x0.chunks_exact(3).map(|p| p[1]).fold(f64::MIN, f64::max);
    w.set_param(0, "wind", Value::Vector([speed, 0.0, 0.0])).unwrap();
    let steps = (seconds * 60.0).round() as u64;
    let mut most: f64 = 0.0;
    for _ in 0..steps {
        w.advance(1.0 / 60.0, &budget).unwrap();
        let x = w.bodies[0].positions();
        // The cap's upper half: vertices above 60 % of the height.
        let d = (0..x.len() / 3).filter(|&i| x0[3 * i + 1] > 0.6 * top).map(|i| x[3 * i] - x0[3 * i]).fold(f64::MIN, f64::max);
        most = most.max(d);
    }
    let c = w.stats(0).center_of_mass;
    println!("{model} wind {speed} m/s for {seconds} s (pinned {pinned}, drag {:?}): cap moved up to {most:.4} m along x; centre of mass {:.4} m", w.param(0, "wind_drag").unwrap(), c[0] - c0[0]);
}
