//! An imported mesh as the modeler first runs it, natively, frame by frame: the OBJ at PATH
//! standing on the ground (centred, its lowest point at y = 0), the `modeler` preset scaled to
//! its size (the page's import: diagonal / 2.5 m), dropped under gravity for FRAMES frames of
//! 1/60 s, each frame under a real-time budget of BUDGET_MS (0: every step converged). Prints
//! per frame the wall-clock ms, Newton and CG iterations, whether the deadline stopped it and
//! the residual it was accepted at, the top's height, the volume and the largest speed; then the
//! mean and worst frame.
//!
//!   cargo run --release -p softsculpt --example drop -- PATH [BUDGET_MS=12] [FRAMES=30]
use softsculpt::body::{Material, SoftBody};
use softsculpt::mesh::load_obj;
use softsculpt::world::{wall_clock, Budget, Ground, World, WorldSettings};

const FRAME: f64 = 1.0 / 60.0;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let path = args.first().expect("usage: drop PATH [BUDGET_MS] [FRAMES]");
    let budget_ms: f64 = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(12.0);
    let frames: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(30);
    let mut mesh = load_obj(&std::fs::read(path).expect("read")).expect("an OBJ").mesh;
    let (lo, hi) = mesh.bounds();
    let size = (0..3).map(|d| (hi[d] - lo[d]).powi(2)).sum::<f64>().sqrt() / 2.5;
    for p in mesh.positions.chunks_exact_mut(3) {
        (p[0], p[1], p[2]) = (p[0] - 0.5 * (lo[0] + hi[0]), p[1] - lo[1], p[2] - 0.5 * (lo[2] + hi[2]));
    }
    let mut w = World::single(SoftBody::new(&mesh, 1.0, Material::default()).unwrap(), WorldSettings { ground: Some(Ground::at(0.0)), ..WorldSettings::default() });
    w.apply_preset_scaled(0, "modeler", size).unwrap();
    let budget = if budget_ms > 0.0 { Budget::real_time(budget_ms / 1000.0, wall_clock) } else { Budget::converge() };
    let budget = Budget { splits: 3, relax: true, ..budget };
    println!("{path}: {} vertices, dt {} s, budget {budget_ms} ms", mesh.vertex_count(), w.settings.dt);
    let mut ms = Vec::new();
    for f in 0..frames {
        let t0 = wall_clock();
        let a = w.advance(FRAME, &budget).unwrap_or_else(|e| panic!("frame {f}: {e}"));
        ms.push(1000.0 * (wall_clock() - t0));
        let it = w.bodies[0].solver_iterations();
        let b = &w.bodies[0];
        let top = b.positions().chunks_exact(3).map(|p| p[1]).fold(f64::MIN, f64::max);
        println!("frame {f:3}: {:8.1} ms  steps {} splits {}  newton {:3} linear {:6}  early {}  residual {:.2e}  top {top:.3} m  V {:.3} m³  max speed {:.3} m/s", ms[f], a.steps, a.splits, it.newton, it.linear, a.early, a.residual, b.volume(), b.max_speed());
    }
    let mean = ms.iter().sum::<f64>() / ms.len() as f64;
    println!("mean {mean:.1} ms, worst {:.1} ms", ms.iter().copied().fold(0.0, f64::max));
}
