//! Ray-casting throughput on the built-in `office` world (and the cost of
//! exact ground-truth coverage), with seeded rays from free space.
//!
//! `cargo bench --bench raycast`; the figure of merit is elements (rays) per
//! second of the `sequential` runs (one core).

use std::hint::black_box;

use covmap::Grid;
use covmap::sim::{World, sim_rng};
use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use rand::RngExt;

/// `n` rays from random free points of the world's box, in random directions.
fn rays(world: &World, n: usize, seed: u64) -> (Vec<[f64; 2]>, Vec<f64>) {
    let mut rng = sim_rng(seed);
    let [x0, y0, x1, y1] = world.bounds_m();
    let mut origins = Vec::with_capacity(n);
    while origins.len() < n {
        let p = [
            x0 + (x1 - x0) * rng.random::<f64>(),
            y0 + (y1 - y0) * rng.random::<f64>(),
        ];
        if world.distance_to_obstacle_m(p) > 0.05 {
            origins.push(p);
        }
    }
    let angles = (0..n)
        .map(|_| rng.random::<f64>() * std::f64::consts::TAU)
        .collect();
    (origins, angles)
}

fn raycast(c: &mut Criterion) {
    let world = World::builtin("office").expect("built-in world");
    let n = 100_000;
    let (origins, angles) = rays(&world, n, 7);
    let mut group = c.benchmark_group("raycast_office");
    group.throughput(Throughput::Elements(n as u64));
    group.sample_size(20);
    for max_range_m in [5.0, 30.0] {
        group.bench_with_input(
            BenchmarkId::new("sequential", max_range_m),
            &max_range_m,
            |b, &m| b.iter(|| black_box(world.cast_batch_sequential(&origins, &angles, m))),
        );
        group.bench_with_input(
            BenchmarkId::new("parallel", max_range_m),
            &max_range_m,
            |b, &m| b.iter(|| black_box(world.cast_batch(&origins, &angles, m))),
        );
    }
    group.finish();
}

fn ground_truth(c: &mut Criterion) {
    let world = World::builtin("office").expect("built-in world");
    let [x0, y0, x1, y1] = world.bounds_m();
    let grid = Grid::covering(x0, y0, x1, y1, 0.05).expect("grid");
    let mut group = c.benchmark_group("coverage_office_5cm");
    group.throughput(Throughput::Elements(grid.len() as u64));
    group.sample_size(10);
    group.bench_function("sequential", |b| {
        b.iter(|| black_box(world.coverage_sequential(&grid)))
    });
    group.bench_function("parallel", |b| b.iter(|| black_box(world.coverage(&grid))));
    group.finish();
}

criterion_group!(benches, raycast, ground_truth);
criterion_main!(benches);
