//! The fast evaluator against the exact one, with every arithmetic the
//! processor can run.

use super::Arith;
use crate::coverage_map::CoverageMap;
use crate::gain::test_maps::{ring_of_eight, scanned};
use crate::gain::{GainEvaluator, GainMethod, GainOptions, StopCoverage};
use crate::grid::Grid;
use crate::pose::Pose;
use crate::sensor::{LaserModel, SensorModel, SonarModel};
use crate::test_rng::uniform;

#[test]
fn fast_equals_exact_on_a_partly_known_map() {
    let grid = Grid::new([0.0, 0.0], 0.1, 50, 70).unwrap();
    let sonar = SonarModel::default();
    let bearings = ring_of_eight();
    let scans: [(Pose, &[f64]); 2] = [
        (
            Pose::new(3.0, 2.5, 0.1),
            &[1.2, 2.0, 6.0, 0.7, 1.5, 2.2, 3.0, 0.4],
        ),
        (
            Pose::new(5.0, 2.0, -0.3),
            &[2.5, 1.0, 1.7, 0.9, 5.5, 2.2, 1.0, 0.8],
        ),
    ];
    let map = scanned(grid, &scans, &bearings, &sonar);
    // No band behind the end point: an echo's reach then ends where its
    // free space does, give or take the end band.
    let mut laser_no_band = LaserModel::default();
    laser_no_band.range.band_m = 0.0;
    let mut sonar_no_band = sonar;
    sonar_no_band.range.band_m = 0.0;
    // Echoes that mark the end band and behind it weakly.
    let mut sonar_weak_end = sonar;
    sonar_weak_end.range.end_weight = 0.2;
    let mut laser_no_end = LaserModel::default();
    laser_no_end.range.end_weight = 0.0;
    let models: [&dyn SensorModel; 6] = [
        &sonar,
        &LaserModel::default(),
        &laser_no_band,
        &sonar_no_band,
        &sonar_weak_end,
        &laser_no_end,
    ];
    for model in models {
        for stop_coverage in [StopCoverage::MaximumLikelihood, StopCoverage::Mean] {
            let options = GainOptions {
                range_step_m: None,
                stop_coverage,
            };
            let mut eval = GainEvaluator::new(&map, model, options).unwrap();
            let poses: Vec<Pose> = (0..6)
                .map(|k| Pose::new(0.4 + 1.1 * k as f64, 1.0 + 0.6 * k as f64, k as f64))
                .collect();
            let exact = eval.evaluate(&poses, &bearings, GainMethod::Exact).unwrap();
            // Every arithmetic the processor can run.
            for arith in Arith::available() {
                eval.arith = arith;
                let fast = eval.evaluate(&poses, &bearings, GainMethod::Fast).unwrap();
                for (f, e) in fast.iter().zip(&exact) {
                    assert!(*e > 0.0);
                    assert!(
                        (f - e).abs() <= 1e-6 * e.abs(),
                        "{stop_coverage:?}, {arith:?}: fast {f} exact {e}"
                    );
                }
            }
        }
    }
}

/// Every arithmetic the processor can run, for every bin count with a
/// path of its own (8, 16, 32) and one without (12), equals the exact
/// evaluator on seeded random maps: cells from nearly uniform to nearly
/// certain, some at the prior, some with bins far below the rest (which
/// the map raises to its floor, 1e-30).
#[test]
fn every_arithmetic_equals_exact_on_random_maps() {
    let mut next = uniform(0x243f_6a88_85a3_08d3);
    let grid = Grid::new([0.0, 0.0], 0.1, 24, 28).unwrap();
    for case in 0..24 {
        let bins = [8, 16, 32, 12][case % 4];
        let mut data = Vec::with_capacity(grid.len() * bins);
        for _ in 0..grid.len() {
            let kind = next();
            if kind < 0.2 {
                data.extend(std::iter::repeat_n(1.0 / bins as f32, bins));
                continue;
            }
            let sharpness = (1.0 + 40.0 * next()) as i32;
            let mut h: Vec<f32> = (0..bins).map(|_| next().powi(sharpness) as f32).collect();
            if kind > 0.9 {
                // Bins far below the rest (raised to the map's floor).
                h.iter_mut().step_by(3).for_each(|v| *v *= 1e-40);
            }
            h[case % bins] += 1e-3;
            let sum: f32 = h.iter().sum();
            data.extend(h.iter().map(|v| v / sum));
        }
        let map = CoverageMap::from_histograms(grid, bins, data).unwrap();
        let mut sonar = SonarModel::default();
        sonar.range.max_range_m = 1.0 + 1.5 * next();
        sonar.opening_angle_rad = 0.1 + 0.8 * next();
        if case % 2 == 1 {
            sonar.range.end_weight = next();
        }
        let mut laser = LaserModel::default();
        laser.range.max_range_m = 1.0 + 1.5 * next();
        let models: [&dyn SensorModel; 2] = [&sonar, &laser];
        let poses: Vec<Pose> = (0..3)
            .map(|_| Pose::new(0.05 + 2.7 * next(), 0.05 + 2.3 * next(), 6.0 * next() - 3.0))
            .collect();
        let bearings: Vec<f64> = (0..4).map(|_| 6.4 * next() - 3.2).collect();
        let stop_coverage = if case % 3 == 0 {
            StopCoverage::Mean
        } else {
            StopCoverage::MaximumLikelihood
        };
        for model in models {
            let options = GainOptions {
                range_step_m: None,
                stop_coverage,
            };
            let mut eval = GainEvaluator::new(&map, model, options).unwrap();
            let exact = eval.evaluate(&poses, &bearings, GainMethod::Exact).unwrap();
            for arith in Arith::available() {
                eval.arith = arith;
                let fast = eval.evaluate(&poses, &bearings, GainMethod::Fast).unwrap();
                for (f, e) in fast.iter().zip(&exact) {
                    assert!(
                        (f - e).abs() <= 1e-6 * e.abs().max(1e-12),
                        "case {case}, {arith:?}: {f} vs {e}"
                    );
                }
            }
        }
    }
}
