//! Scan integration throughput: cell updates per second.
//!
//! A 20 m x 20 m map at 5 cm (160 000 cells; 10 MiB of histograms at 16 bins,
//! larger than L2, so updates stream from memory), 64 seeded random scans from
//! random poses, integrated in turn. Throughput is reported in cell updates.
//!
//! Run: `cargo bench --bench integrate`

use covmap::ScanMap;
use covmap::{CoverageMap, Grid, LaserModel, OccupancyGrid, Pose, SensorModel, SonarModel};
use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

struct Scan {
    pose: Pose,
    ranges: Vec<f64>,
    bearings: Vec<f64>,
}

fn scans(beams: usize, fov_rad: f64, max_range_m: f64, seed: u64) -> Vec<Scan> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let bearings: Vec<f64> = (0..beams)
        .map(|i| -0.5 * fov_rad + fov_rad * i as f64 / beams as f64)
        .collect();
    (0..64)
        .map(|_| Scan {
            pose: Pose::new(
                rng.random_range(1.0..19.0),
                rng.random_range(1.0..19.0),
                rng.random_range(-std::f64::consts::PI..std::f64::consts::PI),
            ),
            ranges: (0..beams)
                .map(|_| rng.random_range(0.3..max_range_m))
                .collect(),
            bearings: bearings.clone(),
        })
        .collect()
}

fn grid() -> Grid {
    Grid::new([0.0, 0.0], 0.05, 400, 400).expect("valid grid")
}

fn bench_model(
    c: &mut Criterion,
    name: &str,
    model: &dyn SensorModel,
    scans: &[Scan],
    bins: &[usize],
) {
    let mut group = c.benchmark_group(name);
    for &b in bins {
        let mut map = CoverageMap::with_bins(grid(), b).expect("valid bins");
        let updates: usize = scans
            .iter()
            .map(|s| {
                map.integrate(&s.pose, &s.ranges, &s.bearings, model)
                    .expect("valid scan")
            })
            .sum();
        group.throughput(Throughput::Elements(updates as u64));
        group.bench_function(format!("coverage_{b}_bins"), |bench| {
            bench.iter(|| {
                for s in scans {
                    map.integrate(&s.pose, &s.ranges, &s.bearings, model)
                        .expect("valid scan");
                }
            })
        });
    }
    let mut occ = OccupancyGrid::new(grid());
    group.bench_function("occupancy_baseline", |bench| {
        bench.iter(|| {
            for s in scans {
                occ.integrate(&s.pose, &s.ranges, &s.bearings, model)
                    .expect("valid scan");
            }
        })
    });
    group.finish();
}

/// The same sonar scans on a 5 m x 5 m map (640 KiB at 16 bins, L2-resident):
/// the cost of the update itself, without the memory traffic.
fn integrate_small(c: &mut Criterion) {
    let sonar = SonarModel::default();
    let small = Grid::new([7.5, 7.5], 0.05, 100, 100).expect("valid grid");
    let scans: Vec<Scan> = scans(24, std::f64::consts::TAU, 5.5, 3)
        .into_iter()
        .map(|mut s| {
            s.pose = Pose::new(
                8.0 + (s.pose.x_m - 1.0) / 18.0 * 4.0,
                8.0 + (s.pose.y_m - 1.0) / 18.0 * 4.0,
                s.pose.theta_rad,
            );
            s
        })
        .collect();
    let mut group = c.benchmark_group("sonar_24_small_map");
    let mut map = CoverageMap::new(small);
    let updates: usize = scans
        .iter()
        .map(|s| {
            map.integrate(&s.pose, &s.ranges, &s.bearings, &sonar)
                .expect("valid scan")
        })
        .sum();
    group.throughput(Throughput::Elements(updates as u64));
    group.bench_function("coverage_16_bins", |bench| {
        bench.iter(|| {
            for s in &scans {
                map.integrate(&s.pose, &s.ranges, &s.bearings, &sonar)
                    .expect("valid scan");
            }
        })
    });
    group.finish();
}

fn integrate(c: &mut Criterion) {
    let sonar = SonarModel::default();
    let sonar_scans = scans(24, std::f64::consts::TAU, 5.5, 1);
    bench_model(c, "sonar_24", &sonar, &sonar_scans, &[8, 16, 32]);
    let laser = LaserModel::default();
    let laser_scans = scans(360, std::f64::consts::TAU, 10.0, 2);
    bench_model(c, "laser_360", &laser, &laser_scans, &[16]);
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20).measurement_time(std::time::Duration::from_secs(4));
    targets = integrate, integrate_small
}
criterion_main!(benches);
