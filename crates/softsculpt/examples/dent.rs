//! A material preset's spring-back from a press on the modeler's rooted mushroom (issue #37):
//! settled, frozen under load, the preset applied, settled again (SETTLE s, default 2); the
//! press's dent (`common::dented`, as `tests/presets.rs`), let go; the dent left after 1, 5 and
//! 10 s. Optionally the rigidity D (J) overridden, and the mushroom subdivided.
//!
//!     [SETTLE=S] cargo run --release -p softsculpt --example dent -- PRESET [RIGIDITY] [SUBDIVISIONS]

#[path = "../tests/common.rs"]
mod common;

use softsculpt::params::Value;
use softsculpt::world::Budget;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let preset = args.get(1).map(String::as_str).unwrap_or("jelly");
    let rigidity: Option<f64> = args.get(2).and_then(|s| s.parse().ok());
    let subdivisions: u32 = args.get(3).and_then(|s| s.parse().ok()).unwrap_or(0);
    let mut w = common::rooted_mushroom_subdivided(subdivisions);
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
    let (x, c) = common::dented(&x0);
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
