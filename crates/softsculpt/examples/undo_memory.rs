//! What 100 brush strokes cost the undo history: inflate dabs (brush radius 0.35 m, the
//! modeler's default) at random places on a 163,842-vertex balloon the modeler's size (2.5 m
//! across), with the body moving in between, each stroke's undo step a `Touched` delta.
//!
//!     cargo run --release -p softsculpt --example undo_memory [LEVEL] [STROKES]

use softsculpt::delta::{Delta, StateScope};
use softsculpt::mesh::builtin::icosphere;
use softsculpt::world::{World, WorldSettings};
use softsculpt::{Material, SoftBody};
use std::time::Instant;

fn main() {
    let mut args = std::env::args().skip(1);
    let level: u32 = args.next().and_then(|a| a.parse().ok()).unwrap_or(7);
    let strokes: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(100);
    let mut m = Material::default();
    m.set_nrt(2.0);
    let body = SoftBody::new(&icosphere(level, 1.25), 1.0, m).unwrap();
    let mut w = World::single(body, WorldSettings { gravity: 0.0, dt: 1e-5, ..WorldSettings::default() });
    let n = w.bodies[0].vertex_count();
    let snapshot = w.snapshot().len();
    let (mut total, mut largest, mut seed) = (0usize, 0usize, 12345u64);
    let t0 = Instant::now();
    for _ in 0..strokes {
        let before = w.clone();
        seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        let c = (seed >> 33) as usize % n;
        let x = w.bodies[0].positions().to_vec();
        let f: Vec<f64> = (0..n)
            .map(|i| {
                let d2: f64 = (0..3).map(|k| (x[3 * i + k] - x[3 * c + k]).powi(2)).sum();
                if d2 < 0.35 * 0.35 { 1.0 + 0.05 * (1.0 - d2 / 0.1225) } else { 1.0 }
            })
            .collect();
        w.bodies[0].scale_rest_lengths_by_vertex(&f).unwrap();
        w.step_n(2).unwrap();
        let d = Delta::between(&before, &w, StateScope::Touched).to_bytes().len();
        total += d;
        largest = largest.max(d);
    }
    let mb = |b: usize| b as f64 / 1e6;
    println!("{n} vertices, snapshot {:.1} MB; {strokes} strokes: undo {:.1} MB in all, {:.2} MB per stroke on average, {:.2} MB the largest ({:.1} s)", mb(snapshot), mb(total), mb(total) / strokes as f64, mb(largest), t0.elapsed().as_secs_f64());
}
