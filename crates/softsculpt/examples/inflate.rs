//! The inflate brush's bulge (issue #37, item 2): the modeler's model (`common::on_ground` or the
//! rooted mushroom), settled, the material preset applied (as `examples/clay.rs`), then the
//! modeler's inflate brush held at the front-most vertex (radius 0.35 m, weight (1 − (d/r)²)²,
//! rest lengths × (1 + rate w dt) per frame, rate 0.3 1/s, its default) for SECONDS, then 2 s to
//! settle. Prints the bulge's height, the largest angle between neighbouring faces' normals
//! within twice the brush radius before and after, and the smooth bound `common::bulge_bound`.
//!
//!     cargo run --release -p softsculpt --example inflate -- PRESET MODEL [SECONDS] [SUBDIVISIONS]

#[path = "../tests/common.rs"]
mod common;

fn main() {
    let a: Vec<String> = std::env::args().collect();
    let preset = a.get(1).map(String::as_str).unwrap_or("clay");
    let model = a.get(2).map(String::as_str).unwrap_or("sphere");
    let seconds: f64 = a.get(3).and_then(|s| s.parse().ok()).unwrap_or(2.0);
    let sub: u32 = a.get(4).and_then(|s| s.parse().ok()).unwrap_or(0);
    let b = common::inflated(preset, model, seconds, sub);
    println!(
        "{preset} {model} x{sub} ({} vertices), inflated {seconds} s: bulge {:.4} m; largest neighbouring normals' angle {:.3} rad before, {:.3} after; smooth bound {:.3} rad",
        b.vertices, b.height, b.before, b.after, b.bound
    );
}
