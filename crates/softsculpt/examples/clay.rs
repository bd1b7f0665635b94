//! How much of a press and of a pull a material keeps (issue #37), `common::press_or_pull`:
//! the modeler's model (the rooted mushroom, or the sphere or octopus set on the ground),
//! settled, frozen under load and given the material preset with the gas's push kept (what the
//! page's material switch does); then the modeler's default press or grab, let go. Prints the
//! change of the body's depth at the brush's centre under the tool, and 5 s and 10 s after
//! release (the fraction kept), and the wall time.
//!
//!     [SET=id=value,…] cargo run --release -p softsculpt --example clay -- PRESET MODEL press|pull [SUBDIVISIONS]

#[path = "../tests/common.rs"]
mod common;

fn main() {
    let a: Vec<String> = std::env::args().collect();
    let preset = a.get(1).map(String::as_str).unwrap_or("clay");
    let model = a.get(2).map(String::as_str).unwrap_or("mushroom");
    let pull = a.get(3).map(String::as_str) == Some("pull");
    let sub: u32 = a.get(4).and_then(|s| s.parse().ok()).unwrap_or(0);
    // SET="id=value,id=value": parameters overridden after the preset.
    let set = std::env::var("SET").unwrap_or_default();
    let overrides: Vec<(&str, f64)> = set
        .split(',')
        .filter(|s| !s.is_empty())
        .map(|kv| {
            let (id, v) = kv.split_once('=').expect("SET: id=value");
            (id, v.parse().expect("SET: a number"))
        })
        .collect();
    let t0 = std::time::Instant::now();
    let r = common::press_or_pull(preset, model, pull, sub, &overrides);
    println!(
        "{preset} {model} x{sub} ({} vertices) {}: held {:+.4} m, 5 s after release {:+.4} m ({:.0} %), 10 s {:+.4} m ({:.0} %) ({:.1} s wall)",
        r.vertices,
        if pull { "pull" } else { "press" },
        r.held,
        r.at5,
        100.0 * r.at5 / r.held,
        r.at10,
        100.0 * r.at10 / r.held,
        t0.elapsed().as_secs_f64()
    );
}
