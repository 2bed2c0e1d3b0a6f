//! Planning after a scan: the planner's cached step
//! (`Planner::next_viewpoint_cached`, which recomputes only what the scan
//! changed) against the full one (`Planner::next_viewpoint`), on the built-in
//! `corridor` and `office` worlds.
//!
//! Each world is explored to the end by the exploration loop
//! (`covmap::sim::exploration::SimExploration`, `coverage(0.5)`, default
//! options). At the positions of its scans (every 0.25 m of its paths and at
//! its goals) a 24-sonar ring (`SonarModel::default()`) is simulated anew,
//! all with the heading 0: the coverage strategy plans a sensor that sees all
//! around with that one fixed heading and the loop turns the robot to it at
//! every goal, so that the candidates' headings repeat from plan to plan. Those scans are replayed,
//! with a plan (default settings) after every scan:
//! - once, the whole run with the cache (printed: the candidates computed
//!   again, of all, and the time planning took against the time the robot
//!   drove at 0.5 m/s);
//! - `step/.../full` and `step/.../incremental`: the plan after the scan
//!   half way through the run, `next_viewpoint` against
//!   `next_viewpoint_cached` with the cache of the plan before (a copy of it
//!   for every run, made outside the timing);
//! - `step/.../unchanged`: `next_viewpoint_cached` once more on a map it has
//!   already seen: free space, paths, the comparison of every histogram and
//!   no gain; the floor of a cached step;
//! - `window/.../full` and `window/.../incremental`: the 40 scans from half
//!   way, each integrated and followed by a plan, without and with the cache
//!   (the map and the cache of half way copied outside the timing).
//!
//! - `run/corridor/coverage`: the loop's whole run of the corridor, scans,
//!   integration and termination included (printed: its speed against real
//!   time at 0.5 m/s).
//!
//! All on the machine's cores (rayon's default pool), as a robot would plan.
//!
//! Run: `cargo bench --bench planning` (short: `-- --measurement-time 5`).
//! `PLANNING_WORLDS` names the worlds of the step and window cases
//! (default `corridor,office`; empty: none, for the whole run alone). The
//! office's coverage run drives 2.5 km, and replaying its 10 000 scans
//! with a plan after each takes many minutes.

use covmap::ScanMap;
use std::sync::Arc;
use std::time::{Duration, Instant};

use covmap::exploration::Strategy;
use covmap::planner::{Planner, PlannerConfig, PlanningCache};
use covmap::sim::exploration::{ExploreOptions, SimExploration};
use covmap::sim::{RangeSensor, SonarRing, World, simulate};
use covmap::{CoverageMap, Grid, Pose, SonarModel};
use criterion::{BatchSize, Criterion, criterion_group, criterion_main};

/// A recorded run: its grid, its scans (pose and ranges) in order and the
/// bearings.
struct Run {
    grid: Grid,
    scans: Vec<(Pose, Vec<f64>)>,
    bearings: Vec<f64>,
}

impl Run {
    /// The distance between the positions of scans `from .. to`, metres.
    fn driven_m(&self, from: usize, to: usize) -> f64 {
        self.scans[from..to]
            .windows(2)
            .map(|w| (w[1].0.x_m - w[0].0.x_m).hypot(w[1].0.y_m - w[0].0.y_m))
            .sum()
    }
}

/// The exploration loop's `coverage(0.5)` run of `world` to its end (default
/// options: seed 0, its start, the 24-sonar ring), and the scans of a
/// 24-sonar ring re-simulated at its scan positions, all with the heading 0
/// (see the module documentation).
fn explore(world: &World, sonar: &SonarModel) -> Run {
    let options = ExploreOptions::default();
    let strategy = Strategy::coverage(0.5).expect("valid strategy");
    let mut run =
        SimExploration::new(Arc::new(world.clone()), strategy, &options).expect("valid run");
    let termination = run.run().expect("a run");
    let exploration = run.exploration();
    eprintln!(
        "{} steps, {} scans, {:.1} m, ended {termination:?}",
        exploration.steps(),
        exploration.scans(),
        exploration.path_length_m()
    );
    let heading = 0.0;
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
    }
}

/// Scans of the window replayed by the `window` cases.
const WINDOW: usize = 40;

/// A robot's speed, metres a second, for the real-time figures.
const SPEED_M_S: f64 = 0.5;

fn planning(c: &mut Criterion) {
    let sonar = SonarModel::default();
    let planner = Planner::new(PlannerConfig::default()).expect("valid config");
    let worlds = std::env::var("PLANNING_WORLDS").unwrap_or_else(|_| "corridor,office".into());
    for name in worlds.split(',').map(str::trim).filter(|w| !w.is_empty()) {
        let world = World::builtin(name).expect("built-in world");
        eprint!("{name}: the loop's run: ");
        let run = explore(&world, &sonar);
        let (bearings, n) = (&run.bearings, run.scans.len());

        // The whole run replayed once, planning after every scan with the
        // cache: how much of the planning it kept, and how long it took.
        let (mut map, mut cache) = (CoverageMap::new(run.grid), PlanningCache::new());
        let (mut candidates, mut recomputed, mut beams, mut recomputed_beams) = (0, 0, 0, 0);
        let mut planning = Duration::ZERO;
        let mut warm = None;
        for (k, (pose, ranges)) in run.scans.iter().enumerate() {
            map.integrate(pose, ranges, bearings, &sonar)
                .expect("valid scan");
            let started = Instant::now();
            planner
                .next_viewpoint_cached(&mut cache, &map, pose, bearings, &sonar)
                .expect("valid plan");
            planning += started.elapsed();
            let stats = cache.stats();
            candidates += stats.candidates;
            recomputed += stats.recomputed;
            beams += stats.beams;
            recomputed_beams += stats.recomputed_beams;
            if k + 1 == n / 2 {
                // Half way: the map and the cache the cases start from.
                warm = Some((map.clone(), cache.clone()));
            }
        }
        let driven_m = run.driven_m(0, n);
        eprintln!(
            "{name}: {} cells; the whole run replayed, a plan after each of {n} scans: \
             {candidates} candidates, {recomputed} computed again ({:.0} %), of their \
             {beams} beams {recomputed_beams} ({:.0} %); planning {:.1} s for \
             {driven_m:.1} m ({:.0} s at {SPEED_M_S} m/s)",
            run.grid.len(),
            100.0 * recomputed as f64 / candidates as f64,
            100.0 * recomputed_beams as f64 / beams as f64,
            planning.as_secs_f64(),
            driven_m / SPEED_M_S
        );

        // Half way: one scan, and the step after it.
        let (before, warm) = warm.expect("a run of two scans or more");
        let mid = n / 2;
        let (pose, ranges) = &run.scans[mid];
        let mut after = before.clone();
        after
            .integrate(pose, ranges, bearings, &sonar)
            .expect("valid scan");
        let mut cache = warm.clone();
        let cached = planner
            .next_viewpoint_cached(&mut cache, &after, pose, bearings, &sonar)
            .expect("valid plan");
        let full = planner
            .next_viewpoint(&after, pose, bearings, &sonar)
            .expect("valid plan");
        assert_eq!(cached, full, "the cached plan is the full one");
        let stats = cache.stats();
        eprintln!(
            "{name}: the step after scan {mid}: {} candidates, {} computed again ({:.0} %), \
             {} of {} beams ({:.0} %), {} cells changed by the scan",
            stats.candidates,
            stats.recomputed,
            100.0 * stats.recomputed as f64 / stats.candidates as f64,
            stats.recomputed_beams,
            stats.beams,
            100.0 * stats.recomputed_beams as f64 / stats.beams as f64,
            stats.changed_cells
        );
        let mut group = c.benchmark_group(format!("step/{name}"));
        group
            .sample_size(10)
            .measurement_time(Duration::from_secs(10));
        group.bench_function("full", |b| {
            b.iter(|| {
                planner
                    .next_viewpoint(&after, pose, bearings, &sonar)
                    .expect("valid plan")
            })
        });
        group.bench_function("incremental", |b| {
            b.iter_batched(
                || warm.clone(),
                |mut cache| {
                    planner
                        .next_viewpoint_cached(&mut cache, &after, pose, bearings, &sonar)
                        .expect("valid plan")
                },
                BatchSize::LargeInput,
            )
        });
        group.bench_function("unchanged", |b| {
            b.iter(|| {
                planner
                    .next_viewpoint_cached(&mut cache, &after, pose, bearings, &sonar)
                    .expect("valid plan")
            })
        });
        group.finish();

        // Half way: the next scans, a plan after each.
        let window = &run.scans[mid..(mid + WINDOW).min(n)];
        eprintln!(
            "{name}: the window: {} scans over {:.1} m ({:.1} s at {SPEED_M_S} m/s)",
            window.len(),
            run.driven_m(mid, mid + window.len()),
            run.driven_m(mid, mid + window.len()) / SPEED_M_S
        );
        let mut group = c.benchmark_group(format!("window/{name}"));
        group
            .sample_size(10)
            .measurement_time(Duration::from_secs(10));
        for cached in [false, true] {
            group.bench_function(if cached { "incremental" } else { "full" }, |b| {
                b.iter_batched(
                    || (before.clone(), warm.clone()),
                    |(mut map, mut cache)| {
                        for (pose, ranges) in window {
                            map.integrate(pose, ranges, bearings, &sonar)
                                .expect("valid scan");
                            let plan = if cached {
                                planner
                                    .next_viewpoint_cached(&mut cache, &map, pose, bearings, &sonar)
                            } else {
                                planner.next_viewpoint(&map, pose, bearings, &sonar)
                            };
                            std::hint::black_box(plan.expect("valid plan"));
                        }
                    },
                    BatchSize::LargeInput,
                )
            });
        }
        group.finish();
    }
}

/// `run/corridor/coverage`: the exploration loop's whole `coverage(0.5)` run
/// of the built-in corridor (default options, seed 0), from its start to its
/// end, with everything the loop does: scans, integration into the three
/// maps, planning with the cache, the termination rule. Printed: the time
/// the robot would have driven at 0.5 m/s against the run's wall time.
fn whole_run(c: &mut Criterion) {
    let world = Arc::new(World::builtin("corridor").expect("built-in world"));
    let options = ExploreOptions::default();
    let strategy = Strategy::coverage(0.5).expect("valid strategy");
    let run = || {
        let mut run =
            SimExploration::new(Arc::clone(&world), strategy, &options).expect("valid run");
        run.run().expect("a run");
        run
    };
    let started = Instant::now();
    let once = run();
    let seconds = started.elapsed().as_secs_f64();
    let path_m = once.exploration().path_length_m();
    eprintln!(
        "corridor, coverage(0.5): {path_m:.1} m in {seconds:.2} s of wall time, {:.0} s at \
         {SPEED_M_S} m/s: {:.0}x real time",
        path_m / SPEED_M_S,
        path_m / SPEED_M_S / seconds
    );
    let mut group = c.benchmark_group("run/corridor");
    group.sample_size(10);
    group.bench_function("coverage", |b| b.iter(|| std::hint::black_box(run())));
    group.finish();
}

criterion_group!(benches, planning, whole_run);
criterion_main!(benches);
