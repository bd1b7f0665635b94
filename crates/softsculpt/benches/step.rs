//! Criterion bench of one step of the standard workload (`softsculpt::workload`), per integrator
//! at a small level and for symplectic Euler across levels.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use softsculpt::workload;
use softsculpt::world::Integrator;

fn step(c: &mut Criterion) {
    let mut g = c.benchmark_group("step_symplectic");
    for level in [4u32, 5, 6] {
        let mut world = workload::world(level);
        let (springs, vertices) = (world.bodies[0].spring_count(), world.bodies[0].vertex_count());
        g.throughput(Throughput::Elements(springs as u64));
        g.bench_with_input(BenchmarkId::from_parameter(vertices), &level, |b, _| b.iter(|| world.step().unwrap()));
    }
    g.finish();

    let mut g = c.benchmark_group("step_level4");
    for integrator in [Integrator::Euler, Integrator::Midpoint, Integrator::Rk4, Integrator::Symplectic] {
        let mut world = workload::world(4);
        world.settings.integrator = integrator;
        g.bench_function(integrator.name(), |b| b.iter(|| world.step().unwrap()));
    }
    g.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20).measurement_time(std::time::Duration::from_secs(3));
    targets = step
}
criterion_main!(benches);
