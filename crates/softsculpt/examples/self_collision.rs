//! What self-collision costs and how calm it leaves a body: the modeler's mushroom (362 vertices,
//! `modeler` preset: implicit steps of 1/60 s, foot pinned to the ground), idle (30 J of gas) and
//! crushed (gas amount 0.0002 mol: it collapses into a dome that folds onto itself), each with
//! self-collision off and on. Per run: wall-clock time per step, simulated seconds per
//! wall-clock second, the largest vertex speed after the run, the solver's iterations in the
//! last step.
//!
//!     cargo run --release -p softsculpt --example self_collision [STEPS]

use std::time::Instant;

#[path = "../tests/support/mushroom.rs"]
mod support;
use support::modeler_mushroom as mushroom;

fn main() {
    let steps: usize = std::env::args().nth(1).and_then(|a| a.parse().ok()).unwrap_or(600);
    println!("{:<8} {:<5} {:>10} {:>12} {:>12} {:>8} {:>8}", "mushroom", "self", "ms/step", "real-time x", "max speed", "newton", "linear");
    for crushed in [false, true] {
        for self_collision in [false, true] {
            let mut w = mushroom(self_collision, crushed);
            let t0 = Instant::now();
            for _ in 0..steps {
                w.step().unwrap();
            }
            let wall = t0.elapsed().as_secs_f64();
            let it = w.bodies[0].solver_iterations();
            let ms = 1e3 * wall / steps as f64;
            let rt = steps as f64 * w.settings.dt / wall;
            println!("{:<8} {:<5} {:>10.3} {:>12.1} {:>12.3e} {:>8} {:>8}", if crushed { "crushed" } else { "idle" }, self_collision, ms, rt, w.bodies[0].max_speed(), it.newton, it.linear);
        }
    }
}
