//! Expected information gain: the fast evaluator against the reference, and
//! what the gain must say about known and unknown space.

use covmap::ScanMap;
use covmap::gain::{GainEvaluator, GainMethod, GainOptions, StopCoverage};
use covmap::{CoverageMap, Grid, LaserModel, Pose, SensorModel, SonarModel};
use proptest::prelude::*;

fn grid() -> Grid {
    Grid::new([0.0, 0.0], 0.1, 30, 36).unwrap()
}

/// Random histograms: each cell's bins drawn from `weights` (a flat list the
/// strategy fills), so cells range from nearly uniform to nearly certain; a
/// cell whose sharpness is 0 stays at the uniform prior (which the fast
/// evaluator looks up rather than computes).
fn random_map(bins: usize, weights: &[f32], sharpness: &[u8]) -> CoverageMap {
    let g = grid();
    let mut data = Vec::with_capacity(g.len() * bins);
    for c in 0..g.len() {
        let s = i32::from(sharpness[c % sharpness.len()]);
        if s == 0 {
            data.extend(std::iter::repeat_n(1.0 / bins as f32, bins));
            continue;
        }
        let mut h: Vec<f32> = (0..bins)
            .map(|b| weights[(c * bins + b) % weights.len()].powi(s) + 1e-6)
            .collect();
        let sum: f32 = h.iter().sum();
        h.iter_mut().for_each(|v| *v /= sum);
        data.extend(h);
    }
    CoverageMap::from_histograms(g, bins, data).unwrap()
}

fn model(kind: u8, range_m: f64, opening_rad: f64) -> Box<dyn SensorModel> {
    if kind == 0 {
        let mut m = LaserModel::default();
        m.range.max_range_m = range_m;
        Box::new(m)
    } else {
        let mut m = SonarModel::default();
        m.range.max_range_m = range_m;
        m.opening_angle_rad = opening_rad;
        Box::new(m)
    }
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 512,
        rng_seed: proptest::test_runner::RngSeed::Fixed(0x6a1e),
        ..ProptestConfig::default()
    })]

    /// `fast` equals `exact` within 1e-6 relative on random maps, poses and sensors.
    #[test]
    fn fast_equals_exact(
        bins in prop::sample::select(vec![4usize, 8, 16, 20]),
        weights in prop::collection::vec(0.0f32..1.0, 97..300),
        sharpness in prop::collection::vec(0u8..16, 1..9),
        kind in 0u8..2,
        range_m in 0.5f64..2.5,
        opening_rad in 0.05f64..1.0,
        mean_stop in any::<bool>(),
        poses in prop::collection::vec((0.0f64..3.6, 0.0f64..3.0, -3.2f64..3.2), 1..4),
        bearings in prop::collection::vec(-3.2f64..3.2, 1..5),
    ) {
        let map = random_map(bins, &weights, &sharpness);
        let sensor = model(kind, range_m, opening_rad);
        let stop_coverage = if mean_stop { StopCoverage::Mean } else { StopCoverage::MaximumLikelihood };
        let eval = GainEvaluator::new(&map, sensor.as_ref(), GainOptions { range_step_m: None, stop_coverage }).unwrap();
        let poses: Vec<Pose> = poses.into_iter().map(|(x, y, t)| Pose::new(x, y, t)).collect();
        let fast = eval.evaluate(&poses, &bearings, GainMethod::Fast).unwrap();
        let exact = eval.evaluate(&poses, &bearings, GainMethod::Exact).unwrap();
        for (f, e) in fast.iter().zip(&exact) {
            prop_assert!((f - e).abs() <= 1e-6 * e.abs().max(1e-12), "fast {f} exact {e}");
        }
    }
}

fn ring() -> Vec<f64> {
    (0..24)
        .map(|i| i as f64 * std::f64::consts::TAU / 24.0)
        .collect()
}

#[test]
fn certain_map_has_no_gain() {
    // Every cell certain: the first 18 columns empty, the rest fully covered.
    let g = grid();
    let bins = 16;
    let mut data = Vec::new();
    for c in 0..g.len() {
        let mut h = vec![1e-9f32; bins];
        h[if c % g.cols() < 18 { 0 } else { bins - 1 }] = 1.0 - 15e-9;
        data.extend(h);
    }
    let map = CoverageMap::from_histograms(g, bins, data).unwrap();
    let sonar = SonarModel::default();
    let eval = GainEvaluator::new(&map, &sonar, GainOptions::default()).unwrap();
    let poses: Vec<Pose> = (0..12)
        .map(|k| Pose::new(0.15 + 0.15 * k as f64, 0.3 + 0.2 * k as f64, 0.0))
        .collect();
    let gains = eval.evaluate(&poses, &ring(), GainMethod::Fast).unwrap();
    let pairs = eval.pairs(&poses, &ring()).unwrap() as f64;
    let prior = CoverageMap::new(g);
    let prior_gains = GainEvaluator::new(&prior, &sonar, GainOptions::default())
        .unwrap()
        .evaluate(&poses, &ring(), GainMethod::Fast)
        .unwrap();
    for (g, p) in gains.iter().zip(&prior_gains) {
        assert!(g.abs() < 1e-5 * pairs / 12.0, "gain {g} on a certain map");
        assert!(g.abs() < 1e-4 * p, "certain {g} vs prior {p}");
    }
}

#[test]
fn prior_map_gains_everywhere() {
    let map = CoverageMap::new(grid());
    for sensor in [model(0, 2.0, 0.0), model(1, 2.0, 0.3)] {
        for stop_coverage in [StopCoverage::MaximumLikelihood, StopCoverage::Mean] {
            let eval = GainEvaluator::new(
                &map,
                sensor.as_ref(),
                GainOptions {
                    range_step_m: None,
                    stop_coverage,
                },
            )
            .unwrap();
            let poses: Vec<Pose> = (0..30)
                .map(|k| {
                    Pose::new(
                        0.05 + 0.12 * k as f64,
                        0.05 + 0.1 * k as f64,
                        0.7 * k as f64,
                    )
                })
                .collect();
            for (pose, g) in poses.iter().zip(
                eval.evaluate(&poses, &[0.0, 2.0], GainMethod::Fast)
                    .unwrap(),
            ) {
                assert!(g > 0.0, "{pose:?}: gain {g}");
            }
        }
    }
}

#[test]
fn unexplored_space_is_worth_more() {
    // Explore the left half of a map by scanning from inside it.
    let g = Grid::new([0.0, 0.0], 0.05, 120, 240).unwrap();
    let mut map = CoverageMap::new(g);
    let sonar = SonarModel::default();
    for k in 0..20 {
        let pose = Pose::new(
            0.6 + 0.2 * (k % 5) as f64,
            1.0 + 0.25 * (k / 5) as f64,
            0.3 * k as f64,
        );
        // Walls at x = 0, y = 0 and y = 6; open space to the right (no echo).
        let ranges: Vec<f64> = ring()
            .iter()
            .map(|b| {
                let a = pose.theta_rad + b;
                let (c, s) = (a.cos(), a.sin());
                let tx = if c < 0.0 {
                    -pose.x_m / c
                } else {
                    f64::INFINITY
                };
                let ty = if s < 0.0 {
                    -pose.y_m / s
                } else {
                    (6.0 - pose.y_m) / s
                };
                tx.min(ty).min(10.0)
            })
            .collect();
        map.integrate(&pose, &ranges, &ring(), &sonar).unwrap();
    }
    let eval = GainEvaluator::new(&map, &sonar, GainOptions::default()).unwrap();
    let explored = Pose::new(1.0, 1.5, 0.0);
    let facing_unknown = Pose::new(6.0, 3.0, 0.0);
    let gains = eval
        .evaluate(&[explored, facing_unknown], &ring(), GainMethod::Fast)
        .unwrap();
    assert!(
        gains[1] > 2.0 * gains[0],
        "explored {} vs frontier {}",
        gains[0],
        gains[1]
    );
}
