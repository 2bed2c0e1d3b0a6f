//! Scan integration throughput: cell updates per second.
//!
//! A 20 m x 20 m map at 5 cm (160 000 cells; 10 MiB of histograms at 16 bins,
//! larger than L2, so updates stream from memory), 64 seeded random scans from
//! random poses, integrated in turn. Throughput is reported in cell updates.
//!
//! A scan read against the map (`sonar_24_read_against_map`): what reading
//! the scans of a drive along the built-in corridor against the cells its
//! map is certain of costs (no-echo sight and echo sources,
//! `CoverageMap::read_scan`), beside integrating the same scans so read and
//! as the paper has them (unread).
//!
//! Run: `cargo bench --bench integrate`

use covmap::exploration::AnySensorModel;
use covmap::sim::experiments::Drive;
use covmap::{
    CoverageMap, Grid, LaserModel, OccupancyGrid, Pose, ScanBeams, ScanMap, ScanReading,
    SensorModel, SonarModel,
};
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

/// The 300 scans of a corridor drive, read against the map of the whole
/// drive (the cells it is certain are covered occlude and explain echoes)
/// and integrated so read.
fn read_against_map(c: &mut Criterion) {
    let model = AnySensorModel::default();
    let drive = Drive::simulate("corridor", &model, (300, 0.15, 0.05), 0, false)
        .expect("the corridor drive");
    let log = &drive.log;
    let scans: Vec<Scan> = (0..log.len())
        .map(|i| Scan {
            pose: log.sensor_pose(i),
            ranges: log.scan_ranges(i).to_vec(),
            bearings: log.scan_bearings(i).to_vec(),
        })
        .collect();
    let mut map = CoverageMap::new(drive.grid);
    map.occluding()
        .integrate_log(log, &model)
        .expect("valid log");
    let epsilon = covmap::planner::DEFAULT_EPSILON;
    let read = |map: &CoverageMap| -> Vec<ScanReading> {
        scans
            .iter()
            .map(|s| map.read_scan(&s.pose, &s.ranges, &s.bearings, &model, epsilon))
            .collect()
    };
    let readings = read(&map);
    let mut group = c.benchmark_group("sonar_24_read_against_map");
    group.throughput(Throughput::Elements(scans.len() as u64));
    group.bench_function("reading_300_scans", |bench| bench.iter(|| read(&map)));
    let mut into = map.clone();
    group.bench_function("integrating_300_scans_unread", |bench| {
        bench.iter(|| {
            for s in &scans {
                into.integrate(&s.pose, &s.ranges, &s.bearings, &model)
                    .expect("valid scan");
            }
        })
    });
    let mut into = map.clone();
    group.bench_function("integrating_300_scans_so_read", |bench| {
        bench.iter(|| {
            for (s, reading) in scans.iter().zip(&readings) {
                let scan = ScanBeams::new(&s.pose, &s.ranges, &s.bearings);
                into.integrate_scan(reading.beams(scan), &model)
                    .expect("valid scan");
            }
        })
    });
    group.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20).measurement_time(std::time::Duration::from_secs(4));
    targets = integrate, integrate_small, read_against_map
}
criterion_main!(benches);
