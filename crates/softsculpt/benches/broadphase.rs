//! The broad phase's cost per vertex must stay about flat from 10k to 640k vertices: build the
//! spatial hash over k side-by-side icospheres (10,242 vertices each) and query every vertex's
//! neighbourhood within 5 cm (cells of 10 cm, so each query visits at most 8 cells).
//!
//! `world_step`: the whole contact world — k balloons of 2,562 vertices in a grid, each touching
//! its neighbours, stepped together (every body's step, then the contact stage over all of them)
//! — from 10k to 640k vertices; `bodies_only` steps the same bodies without the contact stage, so
//! the difference is what contacts cost.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use softsculpt::hash::SpatialHash;
use softsculpt::mesh::{builtin::icosphere, reorder};

fn world(copies: usize) -> Vec<f64> {
    let (ball, _) = reorder::by_locality(&icosphere(5, 1.0));
    let mut x = Vec::with_capacity(copies * ball.positions.len());
    for c in 0..copies {
        let (ox, oz) = ((c % 8) as f64 * 2.2, (c / 8) as f64 * 2.2);
        x.extend(ball.positions.chunks_exact(3).flat_map(|p| [p[0] + ox, p[1], p[2] + oz]));
    }
    x
}

fn broadphase(c: &mut Criterion) {
    let mut g = c.benchmark_group("broadphase_build_and_query_all");
    g.sample_size(10);
    for copies in [1usize, 4, 16, 64] {
        let x = world(copies);
        let n = x.len() / 3;
        g.throughput(Throughput::Elements(n as u64));
        let mut hash = SpatialHash::new(0.1);
        let mut out = Vec::new();
        g.bench_with_input(BenchmarkId::from_parameter(n), &n, |b, _| {
            b.iter(|| {
                hash.build(&x);
                let mut total = 0usize;
                for p in x.chunks_exact(3) {
                    hash.query([p[0], p[1], p[2]], 0.05, &mut out);
                    total += out.len();
                }
                total
            })
        });
    }
    g.finish();
}

/// k gas-filled balloons (icospheres of radius 1, 2,562 vertices) in a grid, 1.99 m apart so
/// that neighbours touch within the contact thickness.
fn balloons(k: usize) -> softsculpt::world::World {
    use softsculpt::body::{Material, SoftBody};
    use softsculpt::world::{ContactSettings, World, WorldSettings};
    let side = (k as f64).sqrt().ceil() as usize;
    let (ball, _) = reorder::by_locality(&icosphere(4, 1.0));
    let bodies = (0..k)
        .map(|c| {
            let mut mesh = ball.clone();
            let (ox, oz) = ((c % side) as f64 * 1.99, (c / side) as f64 * 1.99);
            for p in mesh.positions.chunks_exact_mut(3) {
                p[0] += ox;
                p[2] += oz;
            }
            let mut p = Material { stiffness: 100.0, spring_damping: 0.05, ..Material::default() };
            p.set_nrt(20.0);
            SoftBody::new(&mesh, 1.0, p).expect("a valid balloon")
        })
        .collect();
    let contact = ContactSettings { thickness: 0.02, ..ContactSettings::default() };
    World::new(bodies, WorldSettings { gravity: 0.0, dt: 2e-4, contact, ..WorldSettings::default() })
}

fn world_step(c: &mut Criterion) {
    let mut g = c.benchmark_group("world_step");
    g.sample_size(10);
    for k in [4usize, 16, 64, 250] {
        let mut w = balloons(k);
        let n: usize = w.bodies.iter().map(|b| b.vertex_count()).sum();
        g.throughput(Throughput::Elements(n as u64));
        g.bench_with_input(BenchmarkId::new("with_contacts", n), &n, |b, _| b.iter(|| w.step().expect("steps")));
        // The same bodies each alone in its own one-body world: no contacts.
        let w = balloons(k);
        let settings = w.settings.clone();
        let mut alone: Vec<softsculpt::World> = w.bodies.into_iter().map(|b| softsculpt::World::single(b, settings.clone())).collect();
        g.bench_with_input(BenchmarkId::new("bodies_only", n), &n, |b, _| {
            b.iter(|| {
                for w in &mut alone {
                    w.step().expect("steps");
                }
            })
        });
    }
    g.finish();
}

criterion_group!(benches, broadphase, world_step);
criterion_main!(benches);
