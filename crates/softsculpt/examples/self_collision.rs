//! What self-collision costs and how calm it leaves a body: the modeler's mushroom (362 vertices,
//! `modeler` preset: implicit steps of 1/60 s, foot pinned to the ground), idle (30 J of gas) and
//! crushed (gas amount 0.0002 mol: it collapses into a dome that folds onto itself), each with
//! self-collision off and on. Per run: wall-clock time per step, simulated seconds per
//! wall-clock second, the largest vertex speed after the run, the solver's iterations in the
//! last step.
//!
//!     cargo run --release -p softsculpt --example self_collision [STEPS]

use softsculpt::mesh::builtin::builtin;
use softsculpt::params::Value;
use softsculpt::world::{World, WorldSettings};
use softsculpt::{Material, SoftBody};
use std::time::Instant;

/// The modeler's mushroom on the ground at y = 0, foot pinned, `modeler` preset.
fn mushroom(self_collision: bool, crushed: bool) -> World {
    let mut mesh = builtin("mushroom").unwrap();
    let lo = mesh.positions.iter().skip(1).step_by(3).fold(f64::INFINITY, |a, &y| a.min(y));
    for y in mesh.positions.iter_mut().skip(1).step_by(3) {
        *y -= lo;
    }
    let mut body = SoftBody::new(&mesh, 1.0, Material::default()).unwrap();
    for i in 0..body.vertex_count() {
        if body.positions()[3 * i + 1] < 0.01 {
            body.set_pinned(i, true).unwrap();
        }
    }
    let mut w = World::single(body, WorldSettings::default());
    w.apply_preset(0, "modeler").unwrap();
    w.set_param(0, "self_collision", Value::Flag(self_collision)).unwrap();
    if crushed {
        w.set_param(0, "gas.amount", Value::Number(0.0002)).unwrap();
    }
    w
}

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
