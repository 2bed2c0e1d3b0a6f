//! Planning after a scan: the planner's cached step
//! (`Planner::next_viewpoint_cached`, which recomputes only what the scan
//! changed) against the full one (`Planner::next_viewpoint`), on the built-in
//! `corridor` and `office` worlds.
//!
//! Each world is explored by the exploration loop (`covmap::sim::explore`'s
//! `SimExploration`, `coverage(0.5)`, default options) for a number of
//! steps; at the positions of its scans (every 0.25 m of its paths and at
//! its goals) a 24-sonar ring (`SonarModel::default()`) is simulated anew,
//! all with the start's heading (the loop turns the robot to the planned
//! heading at every goal, which with one candidate heading is the heading it
//! planned with; a synchro-drive base keeps it throughout). The cases replay
//! those scans:
//! - `step/.../full` and `step/.../incremental`: one planning step after the
//!   run's last scan, `next_viewpoint` against `next_viewpoint_cached` with
//!   a cache warmed on the map before that scan (a copy of it for every run,
//!   made outside the timing);
//! - `step/.../unchanged`: `next_viewpoint_cached` once more on a map it has
//!   already seen: free space, paths, the comparison of every histogram and
//!   no gain; the floor of a cached step;
//! - `run/.../full` and `run/.../incremental`: the whole run replayed, each
//!   scan integrated and followed by a plan, without and with the cache.
//!
//! All on the machine's cores (rayon's default pool), as a robot would plan.
//!
//! Run: `cargo bench --bench planning` (short: `-- --measurement-time 5`)

use covmap::planner::{Planner, PlannerConfig, PlanningCache};
use std::sync::Arc;
use std::time::Duration;

use covmap::exploration::Strategy;
use covmap::sim::exploration::{ExploreOptions, SimExploration};
use covmap::sim::{RangeSensor, SonarRing, World, simulate};
use covmap::{CoverageMap, Grid, Pose, SonarModel};
use criterion::{BatchSize, Criterion, criterion_group, criterion_main};

/// A recorded run: its scans (pose and ranges) in order, the bearings, and
/// the path length driven.
struct Run {
    grid: Grid,
    scans: Vec<(Pose, Vec<f64>)>,
    bearings: Vec<f64>,
    path_m: f64,
}

impl Run {
    /// The map after the first `n` scans.
    fn map_after(&self, n: usize, sonar: &SonarModel) -> CoverageMap {
        let mut map = CoverageMap::new(self.grid);
        for (pose, ranges) in &self.scans[..n] {
            map.integrate(pose, ranges, &self.bearings, sonar)
                .expect("valid scan");
        }
        map
    }
}

/// The first `steps` steps of the exploration loop's `coverage(0.5)` run of
/// `world` (default options: seed 0, its start, the 24-sonar ring), and the
/// scans of a 24-sonar ring re-simulated at its scan positions, all with
/// one heading (see the module documentation).
fn explore(world: &World, steps: usize, sonar: &SonarModel) -> Run {
    let options = ExploreOptions::default();
    let strategy = Strategy::coverage(0.5).expect("valid strategy");
    let mut run =
        SimExploration::new(Arc::new(world.clone()), strategy, &options).expect("valid run");
    for _ in 0..steps {
        if run.step().expect("a step").is_none() {
            break;
        }
    }
    let exploration = run.exploration();
    let heading = exploration.trajectory().poses[0].theta_rad;
    let poses: Vec<Pose> = exploration
        .trajectory()
        .scan_poses()
        .iter()
        .map(|p| Pose::new(p.x_m, p.y_m, heading))
        .collect();
    let ring = SonarRing::ring(24).with_model(sonar);
    let scans = simulate(&ring, world, &poses, 1).expect("valid poses");
    Run {
        grid: *exploration.map().grid(),
        scans: scans.into_iter().map(|s| (s.pose, s.ranges_m)).collect(),
        bearings: ring.bearings_rad().to_vec(),
        path_m: exploration.trajectory().length_m(),
    }
}

fn planning(c: &mut Criterion) {
    let sonar = SonarModel::default();
    let planner = Planner::new(PlannerConfig::default()).expect("valid config");
    for (name, steps) in [("corridor", 12), ("office", 16)] {
        let world = World::builtin(name).expect("built-in world");
        let run = explore(&world, steps, &sonar);
        let (bearings, n) = (&run.bearings, run.scans.len());
        let before = run.map_after(n - 1, &sonar);
        let after = run.map_after(n, &sonar);
        let pose = run.scans[n - 1].0;
        let mut warm = PlanningCache::new();
        planner
            .next_viewpoint_cached(&mut warm, &before, &run.scans[n - 2].0, bearings, &sonar)
            .expect("valid plan");
        // What the cache does in the timed step, and that it is the full plan.
        let mut cache = warm.clone();
        let cached = planner
            .next_viewpoint_cached(&mut cache, &after, &pose, bearings, &sonar)
            .expect("valid plan");
        let full = planner
            .next_viewpoint(&after, &pose, bearings, &sonar)
            .expect("valid plan");
        assert_eq!(cached, full, "the cached plan is the full one");
        let stats = cache.stats();
        eprintln!(
            "{name}: {} cells, {steps} steps, {n} scans, {:.1} m driven; the last step: \
             {} candidates, {} recomputed ({:.0} %), {} cells changed by the scan",
            after.grid().len(),
            run.path_m,
            stats.candidates,
            stats.recomputed,
            100.0 * stats.recomputed as f64 / stats.candidates as f64,
            stats.changed_cells
        );

        let mut group = c.benchmark_group(format!("step/{name}"));
        group
            .sample_size(10)
            .measurement_time(Duration::from_secs(10));
        group.bench_function("full", |b| {
            b.iter(|| {
                planner
                    .next_viewpoint(&after, &pose, bearings, &sonar)
                    .expect("valid plan")
            })
        });
        group.bench_function("incremental", |b| {
            b.iter_batched(
                || warm.clone(),
                |mut cache| {
                    planner
                        .next_viewpoint_cached(&mut cache, &after, &pose, bearings, &sonar)
                        .expect("valid plan")
                },
                BatchSize::LargeInput,
            )
        });
        group.bench_function("unchanged", |b| {
            b.iter(|| {
                planner
                    .next_viewpoint_cached(&mut cache, &after, &pose, bearings, &sonar)
                    .expect("valid plan")
            })
        });
        group.finish();

        let mut group = c.benchmark_group(format!("run/{name}"));
        group
            .sample_size(10)
            .measurement_time(Duration::from_secs(10));
        for cached in [false, true] {
            group.bench_function(if cached { "incremental" } else { "full" }, |b| {
                b.iter(|| {
                    let mut map = CoverageMap::new(run.grid);
                    let mut cache = PlanningCache::new();
                    for (pose, ranges) in &run.scans {
                        map.integrate(pose, ranges, bearings, &sonar)
                            .expect("valid scan");
                        let plan = if cached {
                            planner.next_viewpoint_cached(&mut cache, &map, pose, bearings, &sonar)
                        } else {
                            planner.next_viewpoint(&map, pose, bearings, &sonar)
                        };
                        std::hint::black_box(plan.expect("valid plan"));
                    }
                })
            });
        }
        group.finish();
    }
}

criterion_group!(benches, planning);
criterion_main!(benches);
