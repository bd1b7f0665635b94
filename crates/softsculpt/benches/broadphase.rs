//! The broad phase's cost per vertex must stay about flat from 10k to 640k vertices: build the
//! spatial hash over k side-by-side icospheres (10,242 vertices each) and query every vertex's
//! neighbourhood within 5 cm (cells of 10 cm, so each query visits at most 8 cells).

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

criterion_group!(benches, broadphase);
criterion_main!(benches);
