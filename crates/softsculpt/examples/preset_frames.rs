//! A material preset on a built-in model (optionally subdivided), set on the ground as the
//! modeler makes it, stepped frame by frame as the modeler steps (`World::advance`, converge,
//! refused steps split): per frame the wall time, split steps, Newton iterations, volume and
//! largest speed. For finding which frames of `tests/presets.rs` are slow (its world:
//! `common::on_ground`).
//!
//!     [RIGIDITY=D] cargo run --release -p softsculpt --example preset_frames -- PRESET MODEL [SUBDIVISIONS] [FRAMES]

#[path = "../tests/common.rs"]
mod common;

use softsculpt::mesh::builtin::builtin;
use softsculpt::world::Budget;

fn main() {
    let a: Vec<String> = std::env::args().collect();
    let (preset, model) = (a.get(1).map_or("jelly", String::as_str), a.get(2).map_or("octopus", String::as_str));
    let subdivisions: u32 = a.get(3).and_then(|s| s.parse().ok()).unwrap_or(2);
    let frames: u32 = a.get(4).and_then(|s| s.parse().ok()).unwrap_or(60);
    let mut w = common::on_ground(&builtin(model).unwrap(), subdivisions, preset);
    if let Some(d) = std::env::var("RIGIDITY").ok().and_then(|s| s.parse().ok()) {
        w.set_param(0, "rigidity", softsculpt::params::Value::Number(d)).unwrap();
    }
    let budget = Budget { splits: 3, relax: true, ..Budget::converge() };
    for f in 0..frames {
        let t0 = std::time::Instant::now();
        let r = w.advance(1.0 / 60.0, &budget);
        let it = w.bodies[0].solver_iterations();
        match r {
            Ok(a) => println!("frame {f:>3}: {:>8.1} ms, splits {}, steps {}, newton {}, linear {}, V {:.3}, max speed {:.3}", t0.elapsed().as_secs_f64() * 1e3, a.splits, a.steps, it.newton, it.linear, w.bodies[0].exact_volume(), w.bodies[0].max_speed()),
            Err(e) => {
                println!("frame {f:>3}: {:>8.1} ms, failed: {e}", t0.elapsed().as_secs_f64() * 1e3);
                break;
            }
        }
    }
}
