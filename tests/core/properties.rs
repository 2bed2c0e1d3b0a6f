//! Invariants of the coverage map under arbitrary scans.

use covmap::ScanMap;
use covmap::exploration::AnySensorModel;
use covmap::{
    Bearings, CoverageMap, Grid, LaserModel, Log, OccupancyGrid, OccupancyModel, Pose, ScanCounts,
    SensorModel, SonarModel,
};
use proptest::prelude::*;

fn grid() -> Grid {
    Grid::new([-1.0, -1.0], 0.05, 40, 48).unwrap()
}

/// A scan: pose inside the grid, up to 12 beams with ranges up to beyond the
/// sonar's maximum (no-echo readings included).
fn scan() -> impl Strategy<Value = (Pose, Vec<(f64, f64)>)> {
    scan_with(0.0f64..6.0)
}

/// A scan whose ranges `range` draws.
fn scan_with(range: impl Strategy<Value = f64>) -> impl Strategy<Value = (Pose, Vec<(f64, f64)>)> {
    (
        (-1.0f64..1.39, -1.0f64..0.99, -7.0f64..7.0),
        prop::collection::vec((range, -3.2f64..3.2), 1..12),
    )
        .prop_map(|((x, y, t), beams)| (Pose::new(x, y, t), beams))
}

/// Every sensor model covmap ships: its defaults (and any preset it adds).
fn shipped_models() -> [AnySensorModel; 2] {
    [AnySensorModel::default(), AnySensorModel::laser()]
}

/// A scan whose readings include no-echo ones: at either shipped model's
/// maximum range exactly, and beyond both.
fn scan_with_no_echoes() -> impl Strategy<Value = (Pose, Vec<(f64, f64)>)> {
    scan_with(prop_oneof![6 => 0.0f64..6.0, 1 => Just(5.0), 1 => Just(30.0), 1 => Just(31.0)])
}

/// Scans and the same scans in two other orders: reversed (with each
/// scan's beams reversed too) and shuffled.
type Orders = [Vec<(Pose, Vec<(f64, f64)>)>; 3];

fn three_orders() -> impl Strategy<Value = Orders> {
    three_orders_of(scan_with_no_echoes())
}

/// [`three_orders`] of scans `scan` draws.
fn three_orders_of(
    scan: impl Strategy<Value = (Pose, Vec<(f64, f64)>)>,
) -> impl Strategy<Value = Orders> {
    prop::collection::vec(scan, 2..=6).prop_flat_map(|scans| {
        let reversed: Vec<_> = scans
            .iter()
            .rev()
            .map(|(p, beams)| (*p, beams.iter().rev().copied().collect()))
            .collect();
        (
            Just(scans.clone()),
            Just(reversed),
            Just(scans).prop_shuffle(),
        )
            .prop_map(|(a, b, c)| [a, b, c])
    })
}

/// [`three_orders`] of long runs of evidence: two to four scans, each
/// repeated 10 to 60 times, so that the cells they share gather far more
/// evidence (hundreds of nats) than an `f32` probability holds: where a map
/// that floored its bins would clamp the evidence, and its result would
/// depend on the order.
fn three_long_orders() -> impl Strategy<Value = Orders> {
    (
        prop::collection::vec(scan_with_no_echoes(), 2..=4),
        prop::collection::vec(10usize..=60, 4),
    )
        .prop_flat_map(|(scans, repeats)| {
            let long: Vec<_> = scans
                .iter()
                .zip(&repeats)
                .flat_map(|(scan, &n)| std::iter::repeat_n(scan.clone(), n))
                .collect();
            let reversed: Vec<_> = long.iter().rev().cloned().collect();
            (
                Just(long.clone()),
                Just(reversed),
                Just(long).prop_shuffle(),
            )
                .prop_map(|(a, b, c)| [a, b, c])
        })
}

/// A scan of 12 readings as [`scan_with_no_echoes`] draws them (a log's
/// scans all have as many).
fn log_scan() -> impl Strategy<Value = (Pose, Vec<(f64, f64)>)> {
    (
        (-1.0f64..1.39, -1.0f64..0.99, -7.0f64..7.0),
        prop::collection::vec(
            (
                prop_oneof![6 => 0.0f64..6.0, 1 => Just(5.0), 1 => Just(30.0), 1 => Just(31.0)],
                -3.2f64..3.2,
            ),
            12,
        ),
    )
        .prop_map(|((x, y, t), beams)| (Pose::new(x, y, t), beams))
}

/// The log of `scans` in their order (a maximum range of 30 m).
fn log_of(scans: &[(Pose, Vec<(f64, f64)>)]) -> Log {
    let poses = scans.iter().map(|(pose, _)| *pose).collect();
    let times = (0..scans.len()).map(|i| i as f64).collect();
    let (ranges, bearings): (Vec<f64>, Vec<f64>) = scans
        .iter()
        .flat_map(|(_, beams)| beams.iter().copied())
        .unzip();
    Log::new(poses, times, ranges, Bearings::PerScan(bearings), 30.0).unwrap()
}

fn apply<S: ScanMap>(map: &mut S, scans: &[(Pose, Vec<(f64, f64)>)], model: &dyn SensorModel) {
    for (pose, beams) in scans {
        let (r, b): (Vec<f64>, Vec<f64>) = beams.iter().copied().unzip();
        map.integrate(pose, &r, &b, model).unwrap();
    }
}

/// Every shipped model maps the three `orders` of the same scans to
/// histograms that agree within `tolerance`.
fn orders_agree(orders: &Orders, tolerance: f32) -> Result<(), TestCaseError> {
    for model in shipped_models() {
        let maps = orders.each_ref().map(|scans| {
            let mut map = CoverageMap::new(grid());
            apply(&mut map, scans, &model);
            map
        });
        for other in &maps[1..] {
            for (a, b) in maps[0].histograms().iter().zip(other.histograms()) {
                prop_assert!((a - b).abs() <= tolerance, "{a} vs {b} ({model:?})");
            }
        }
    }
    Ok(())
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

    /// Bayes' rule is a product: the order of the measurements does not
    /// matter, for every model covmap ships (the update multiplies kernels
    /// in and reads nothing of the map), but for float rounding.
    #[test]
    fn no_shipped_model_makes_a_map_depend_on_the_order_of_its_scans(orders in three_orders()) {
        orders_agree(&orders, 1e-5)?;
    }

    /// A log whose no-echo readings are occluded by the map takes them
    /// after all of its echoes, each occluded by the map of every echo,
    /// so the order of its scans does not matter either.
    #[test]
    fn occluded_logs_do_not_depend_on_the_order_of_their_scans(orders in three_orders_of(log_scan())) {
        for model in shipped_models() {
            let maps = orders.each_ref().map(|scans| {
                let mut map = CoverageMap::new(grid());
                map.occluding().integrate_log(&log_of(scans), &model).unwrap();
                map
            });
            for other in &maps[1..] {
                for (a, b) in maps[0].histograms().iter().zip(other.histograms()) {
                    prop_assert!((a - b).abs() <= 1e-5, "{a} vs {b} ({model:?})");
                }
            }
        }
    }

    /// The occupancy grid's log-odds are sums, in any order, where they
    /// stay within the limit: its default limit (5) clamps each sum as it
    /// goes, which does depend on the order, so the limit here is one no
    /// sum of these scans reaches.
    #[test]
    fn the_unclamped_occupancy_grid_does_not_depend_on_the_order_of_its_scans(orders in three_orders()) {
        let unclamped = OccupancyModel { log_odds_limit: 1e6, ..OccupancyModel::default() };
        for model in shipped_models() {
            let grids = orders.each_ref().map(|scans| {
                let mut occupancy = OccupancyGrid::with_model(unclamped, ScanCounts::new(grid())).unwrap();
                apply(&mut occupancy, scans, &model);
                occupancy
            });
            for other in &grids[1..] {
                for (a, b) in grids[0].log_odds().iter().zip(other.log_odds()) {
                    prop_assert!((a - b).abs() <= 1e-4, "{a} vs {b} ({model:?})");
                }
                // Whole beams (no discount) count 1 each: exact sums.
                prop_assert_eq!(grids[0].counts().counts(), other.counts().counts());
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 16, rng_seed: proptest::test_runner::RngSeed::Fixed(0x10_4e4a), ..ProptestConfig::default() })]

    /// The same over long runs of evidence (the map keeps each cell's
    /// evidence as a sum of log-likelihoods, which no floor clamps): the
    /// histograms agree to within the rounding of those sums in `f32`.
    #[test]
    fn long_runs_of_evidence_do_not_make_a_map_depend_on_the_order_of_its_scans(orders in three_long_orders()) {
        orders_agree(&orders, 1e-4)?;
    }
}
