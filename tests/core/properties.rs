//! Invariants of the coverage map under arbitrary scans.

use covmap::ScanMap;
use covmap::{CoverageMap, Grid, LaserModel, Pose, SensorModel, SonarModel};
use proptest::prelude::*;

fn grid() -> Grid {
    Grid::new([-1.0, -1.0], 0.05, 40, 48).unwrap()
}

/// A scan: pose inside the grid, up to 12 beams with ranges up to beyond the
/// sonar's maximum (no-echo readings included).
fn scan() -> impl Strategy<Value = (Pose, Vec<(f64, f64)>)> {
    (
        (-1.0f64..1.39, -1.0f64..0.99, -7.0f64..7.0),
        prop::collection::vec((0.0f64..6.0, -3.2f64..3.2), 1..12),
    )
        .prop_map(|((x, y, t), beams)| (Pose::new(x, y, t), beams))
}

fn apply(map: &mut CoverageMap, scans: &[(Pose, Vec<(f64, f64)>)], model: &dyn SensorModel) {
    for (pose, beams) in scans {
        let (r, b): (Vec<f64>, Vec<f64>) = beams.iter().copied().unzip();
        map.integrate(pose, &r, &b, model).unwrap();
    }
}

fn check_invariants(map: &CoverageMap) -> Result<(), TestCaseError> {
    let floor = covmap::histogram::BIN_FLOOR;
    for h in map.histograms().chunks_exact(map.bins()) {
        let sum: f32 = h.iter().sum();
        prop_assert!((sum - 1.0).abs() <= 1e-5, "histogram sums to {sum}");
        for &v in h {
            prop_assert!(v.is_finite() && v >= floor && v > 0.0, "bin {v}");
        }
    }
    let max_h = (map.bins() as f32).ln() + 1e-5;
    for h in map.entropy() {
        prop_assert!((-1e-6..=max_h).contains(&h), "entropy {h}");
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, rng_seed: proptest::test_runner::RngSeed::Fixed(0xc0_7e4a), ..ProptestConfig::default() })]

    #[test]
    fn histograms_stay_valid(scans in prop::collection::vec(scan(), 1..8), bins in prop::sample::select(vec![2usize, 8, 16, 32, 50])) {
        let mut sonar_map = CoverageMap::with_bins(grid(), bins).unwrap();
        apply(&mut sonar_map, &scans, &SonarModel::default());
        check_invariants(&sonar_map)?;
        let mut laser_map = CoverageMap::with_bins(grid(), bins).unwrap();
        apply(&mut laser_map, &scans, &LaserModel::default());
        check_invariants(&laser_map)?;
    }

    /// Bayes' rule is a product: the order of the measurements does not matter.
    #[test]
    fn order_independent(scans in prop::collection::vec(scan(), 2..6)) {
        for model in [&SonarModel::default() as &dyn SensorModel, &LaserModel::default()] {
            let mut forward = CoverageMap::new(grid());
            apply(&mut forward, &scans, model);
            let mut reversed = CoverageMap::new(grid());
            let mut rev: Vec<_> = scans.iter().map(|(p, b)| (*p, b.iter().rev().copied().collect::<Vec<_>>())).collect();
            rev.reverse();
            apply(&mut reversed, &rev, model);
            for (a, b) in forward.histograms().iter().zip(reversed.histograms()) {
                prop_assert!((a - b).abs() <= 1e-5, "{a} vs {b}");
            }
        }
    }
}
