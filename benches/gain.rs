//! Expected information gain: the fast evaluator against the exact reference,
//! on one thread and on two.
//!
//! A 20 m x 20 m map at 5 cm, partly explored by 60 seeded sonar scans from
//! random poses; a ring of 24 sonar cones; 1000 candidate poses on a grid.
//! Throughput of the fast evaluator is in (beam, cell) pairs: the cells of each
//! beam's widest footprint. The exact evaluator costs seconds per candidate, so
//! it is timed on 4 candidates spread over the map (every 250th): compare the
//! two evaluators' times on those. `fast_1_thread_6_scans` evaluates the same
//! candidates early in an exploration, on the map after its first 6 scans,
//! where most cells are still at the prior. `fast_1_thread_office` evaluates
//! them on a map of a building: the built-in `office` world after 60
//! simulated sonar scans, whose walls stop the predicted beams (the random
//! ranges of the other maps trace no walls, so their beams mostly run to the
//! maximum range). `cone_walk_only` walks the same footprints
//! and computes nothing. The `planning_step` cases time what a robot pays per
//! decision on that map: building the evaluator (ML map and the per-bin
//! `h ln h` every candidate shares), and the planner's whole
//! `next_viewpoint` (free space, Dijkstra, candidates, gains, choice), on all
//! the machine's cores.
//!
//! Run: `cargo bench --bench gain`

use covmap::ScanMap;
use covmap::gain::{GainEvaluator, GainMethod, GainOptions};
use covmap::planner::{Planner, PlannerConfig};
use covmap::sim::{Robot, SonarRing, World, simulate};
use covmap::{CoverageMap, Grid, Pose, SonarModel};
use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// The benchmark's 20 m x 20 m map at 5 cm, at the prior.
fn empty_map() -> CoverageMap {
    CoverageMap::new(Grid::new([0.0, 0.0], 0.05, 400, 400).expect("valid grid"))
}

/// The 20 m map after `scans` seeded sonar scans from random poses.
fn explored_map(sonar: &SonarModel, bearings: &[f64], scans: usize) -> CoverageMap {
    let mut map = empty_map();
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    for _ in 0..scans {
        let pose = Pose::new(
            rng.random_range(2.0..18.0),
            rng.random_range(2.0..18.0),
            rng.random_range(-3.1..3.1),
        );
        let ranges: Vec<f64> = bearings
            .iter()
            .map(|_| rng.random_range(0.5..6.0))
            .collect();
        map.integrate(&pose, &ranges, bearings, sonar)
            .expect("valid scan");
    }
    map
}

/// The 20 m map over the western 20 m of the built-in `office` world (30 m x
/// 20 m) after `scans` simulated sonar scans from seeded collision-free poses: walls the
/// ML map holds as covered stop the predicted beams, as in a real building.
fn office_map(sonar: &SonarModel, scans: usize) -> CoverageMap {
    let world = World::builtin("office").expect("built-in world");
    let robot = Robot::new(0.25).expect("valid radius");
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let mut poses = Vec::with_capacity(scans);
    while poses.len() < scans {
        let pose = Pose::new(
            rng.random_range(1.0..19.0),
            rng.random_range(1.0..19.0),
            rng.random_range(-3.1..3.1),
        );
        if !robot.collides(&world, &pose) {
            poses.push(pose);
        }
    }
    let ring = SonarRing::ring(24).with_model(sonar);
    let mut map = empty_map();
    for scan in simulate(&ring, &world, &poses, 11).expect("valid poses") {
        map.integrate(&scan.pose, &scan.ranges_m, &scan.bearings_rad, sonar)
            .expect("valid scan");
    }
    map
}

fn candidates() -> Vec<Pose> {
    (0..1000)
        .map(|k| {
            Pose::new(
                0.5 + 0.6 * (k % 32) as f64,
                0.5 + 0.6 * (k / 32) as f64,
                0.1 * k as f64,
            )
        })
        .collect()
}

fn gain(c: &mut Criterion) {
    let sonar = SonarModel::default();
    let bearings: Vec<f64> = (0..24)
        .map(|i| i as f64 * std::f64::consts::TAU / 24.0)
        .collect();
    let map = explored_map(&sonar, &bearings, 60);
    let eval = GainEvaluator::new(&map, &sonar, GainOptions::default()).expect("valid options");
    let poses = candidates();
    let pairs = eval.pairs(&poses, &bearings).expect("valid poses");
    // Early in an exploration: the same candidates (so the same pairs) after 6 scans.
    let early = explored_map(&sonar, &bearings, 6);
    let early_eval =
        GainEvaluator::new(&early, &sonar, GainOptions::default()).expect("valid options");
    // A building: the same candidates on the office world after 60 scans.
    let office = office_map(&sonar, 60);
    let office_eval =
        GainEvaluator::new(&office, &sonar, GainOptions::default()).expect("valid options");
    for (name, m) in [
        ("60 scans", &map),
        ("6 scans", &early),
        ("60 scans of the office", &office),
    ] {
        let prior = m
            .histograms()
            .chunks_exact(m.bins())
            .filter(|h| h.iter().all(|&v| v == 1.0 / m.bins() as f32))
            .count();
        eprintln!(
            "map after {name}: {:.1} % of its cells at the prior",
            100.0 * prior as f64 / m.grid().len() as f64
        );
    }

    let mut group = c.benchmark_group("gain_1000_candidates_24_sonars");
    group
        .sample_size(10)
        .measurement_time(std::time::Duration::from_secs(10));
    group.throughput(Throughput::Elements(pairs));
    let pool = |threads| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("thread pool")
    };
    let (one, two) = (pool(1), pool(2));
    for (name, pool, eval) in [
        ("fast_1_threads", &one, &eval),
        ("fast_2_threads", &two, &eval),
        ("fast_1_thread_6_scans", &one, &early_eval),
        ("fast_1_thread_office", &one, &office_eval),
    ] {
        group.bench_function(name, |b| {
            b.iter(|| {
                pool.install(|| {
                    eval.evaluate(&poses, &bearings, GainMethod::Fast)
                        .expect("valid")
                })
            })
        });
    }
    // The cones alone, each cell visited and nothing computed: the part of
    // the per-pair cost that walking the footprints takes.
    group.bench_function("cone_walk_only", |b| {
        b.iter(|| eval.pairs(&poses, &bearings).expect("valid"))
    });
    group.finish();

    let few: Vec<Pose> = poses.iter().step_by(250).copied().collect();
    let few = &few[..];
    let mut group = c.benchmark_group("gain_4_candidates_24_sonars");
    group
        .sample_size(10)
        .measurement_time(std::time::Duration::from_secs(20));
    for (name, method) in [
        ("exact_1_thread", GainMethod::Exact),
        ("fast_1_thread", GainMethod::Fast),
    ] {
        group.bench_function(name, |b| {
            b.iter(|| one.install(|| eval.evaluate(few, &bearings, method).expect("valid")))
        });
    }
    group.finish();

    let mut group = c.benchmark_group("planning_step");
    group
        .sample_size(10)
        .measurement_time(std::time::Duration::from_secs(10));
    // Evaluating no candidate still builds everything they would share.
    group.bench_function("evaluator_build", |b| {
        b.iter(|| {
            let eval =
                GainEvaluator::new(&map, &sonar, GainOptions::default()).expect("valid options");
            eval.evaluate(&[], &bearings, GainMethod::Fast)
                .expect("valid")
        })
    });
    let planner = Planner::new(PlannerConfig::default()).expect("valid config");
    let robot = Pose::new(10.0, 10.0, 0.0);
    let plan = planner
        .next_viewpoint(&map, &robot, &bearings, &sonar)
        .expect("valid plan");
    eprintln!(
        "planning_step/next_viewpoint: {} candidates",
        plan.candidates.gains.len()
    );
    group.bench_function("next_viewpoint", |b| {
        b.iter(|| {
            planner
                .next_viewpoint(&map, &robot, &bearings, &sonar)
                .expect("valid plan")
        })
    });
    group.finish();
}

criterion_group!(benches, gain);
criterion_main!(benches);
