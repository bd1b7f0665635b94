//! The modeler's grab natively, frame by frame, under a real-time budget (`World::advance`) and
//! converged side by side: the built-in mushroom on the ground with the `modeler` preset,
//! subdivided SUB times (frozen under load, as the page does), settled, its cap grabbed (target
//! springs at ω = 600 1/s on the vertices within 0.15 m of the top, as the grab tool ties
//! them) and pulled 0.8 m aside and 0.4 m up over 0.5 s, held 1 s, let go for 2 s. Prints per
//! phase the wall-clock ms per frame (mean, worst), the Newton iterations, the steps stopped
//! early, and at the end of the hold how far the top vertex is from its anchor; at the end, the
//! top's height and the volume against the converged run.
//!
//!   cargo run --release -p softsculpt --example anytime -- [SUB=2] [BUDGET_MS=12] [MIN_ACCURACY=0.1]
//!
//! `ONLY=budget` skips the converged run; `TRACE=1` prints every frame.
use softsculpt::body::{FreezeOptions, Material, SoftBody, Target};
use softsculpt::mesh::builtin::builtin;
use softsculpt::world::{wall_clock, Budget, Ground, World, WorldSettings};

const FRAME: f64 = 1.0 / 60.0;

fn mushroom(sub: u32) -> World {
    let mut mesh = builtin("mushroom").unwrap();
    let lo = mesh.positions.chunks_exact(3).map(|p| p[1]).fold(f64::MAX, f64::min);
    for p in mesh.positions.chunks_exact_mut(3) {
        p[1] -= lo;
    }
    let mut w = World::single(SoftBody::new(&mesh, 1.0, Material::default()).unwrap(), WorldSettings { ground: Some(Ground::at(0.0)), ..WorldSettings::default() });
    w.apply_preset(0, "modeler").unwrap();
    for _ in 0..120 {
        w.advance(FRAME, &Budget::converge()).unwrap();
    }
    for _ in 0..sub {
        w.subdivide(0, FreezeOptions::default()).unwrap();
        w.freeze(0, FreezeOptions { under_load: true, keep_tension: false }).unwrap();
    }
    for _ in 0..60 {
        w.advance(FRAME, &Budget { splits: 3, relax: true, ..Budget::converge() }).unwrap();
    }
    w
}

fn top(w: &World) -> usize {
    let x = w.bodies[0].positions();
    (0..x.len() / 3).max_by(|&a, &b| x[3 * a + 1].total_cmp(&x[3 * b + 1])).unwrap()
}

struct Phase {
    name: &'static str,
    ms: Vec<f64>,
    newton: u32,
    linear: u32,
    early: u32,
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let sub: u32 = args.first().and_then(|s| s.parse().ok()).unwrap_or(2);
    let budget_ms: f64 = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(12.0);
    let accuracy: f64 = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(0.1);
    let start = mushroom(sub);
    let n = start.bodies[0].vertex_count();
    let t = top(&start);
    let x0 = start.bodies[0].positions().to_vec();
    let grabbed: Vec<usize> = (0..n).filter(|&i| (0..3).map(|d| (x0[3 * i + d] - x0[3 * t + d]).powi(2)).sum::<f64>().sqrt() < 0.15).collect();
    let k = start.bodies[0].masses()[t] * 600.0f64.powi(2);
    let pull = |f: usize| -> Vec<Target> {
        let s = (f as f64 / 30.0).min(1.0);
        grabbed.iter().map(|&i| Target { vertex: i, anchor: [x0[3 * i] + 0.8 * s, x0[3 * i + 1] + 0.4 * s, x0[3 * i + 2]], stiffness: k, damping: 0.0 }).collect()
    };
    println!("mushroom subdivided {sub}x: {n} vertices, {} grabbed; budget {budget_ms} ms, min accuracy {accuracy}", grabbed.len());
    let mut budget = Budget::real_time(budget_ms / 1000.0, wall_clock);
    budget.real_time.as_mut().unwrap().min_accuracy = accuracy;
    let conv = Budget { splits: 3, relax: true, ..Budget::converge() };
    let mut results = Vec::new();
    let only_budget = std::env::var("ONLY").is_ok_and(|v| v == "budget");
    for (label, b) in [("budget", budget), ("converge", conv)] {
        if only_budget && label == "converge" {
            break;
        }
        let mut w = start.clone();
        let mut phases: Vec<Phase> = ["pull+hold", "released"].iter().map(|&name| Phase { name, ms: vec![], newton: 0, linear: 0, early: 0 }).collect();
        let mut gap = 0.0;
        for f in 0..180 {
            let p = if f < 90 { 0 } else { 1 };
            if f < 90 {
                w.bodies[0].set_targets(&pull(f)).unwrap();
            } else if f == 90 {
                w.bodies[0].set_targets(&[]).unwrap();
            }
            let t0 = wall_clock();
            let a = w.advance(FRAME, &b).unwrap_or_else(|e| panic!("{label} frame {f}: {e}"));
            phases[p].ms.push(1000.0 * (wall_clock() - t0));
            phases[p].newton += w.bodies[0].solver_iterations().newton;
            phases[p].linear += w.bodies[0].solver_iterations().linear;
            phases[p].early += a.early;
            if std::env::var("TRACE").is_ok() {
                let it = w.bodies[0].solver_iterations();
                println!("frame {f}: {:.1} ms, newton {}, linear {}, accepted at {:.3}", phases[p].ms.last().unwrap(), it.newton, it.linear, it.residual);
            }
            if f == 89 {
                let x = w.bodies[0].positions();
                let anchor = pull(89).into_iter().find(|g| g.vertex == t).unwrap().anchor;
                gap = (0..3).map(|d| (x[3 * t + d] - anchor[d]).powi(2)).sum::<f64>().sqrt();
            }
        }
        let ls = w.bodies[0].line_stats();
        println!("{label:9} line searches {}: G changed below its rounding {}, halved for the Armijo test {}, not passed {}", ls.searches, ls.unresolved, ls.backtracked, ls.rose);
        for ph in &phases {
            let mean = ph.ms.iter().sum::<f64>() / ph.ms.len() as f64;
            let worst = ph.ms.iter().cloned().fold(0.0, f64::max);
            println!("{label:9} {:10} mean {mean:7.1} ms  worst {worst:7.1} ms  newton {:5}  linear {:6}  early {:4}", ph.name, ph.newton, ph.linear, ph.early);
        }
        let x = w.bodies[0].positions();
        let height = (0..n).map(|i| x[3 * i + 1]).fold(f64::MIN, f64::max);
        println!("{label:9} top to anchor at the end of the hold {:.1} mm; after: height {height:.4} m, volume {:.4} m3", 1000.0 * gap, w.stats(0).volume);
        results.push((height, w.stats(0).volume));
    }
    if results.len() < 2 {
        return;
    }
    println!("budget/converge: height {:.4}, volume {:.4}", results[0].0 / results[1].0, results[0].1 / results[1].1);
}
