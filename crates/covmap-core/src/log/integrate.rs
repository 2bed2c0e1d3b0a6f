//! A whole log into a map: every scan checked first, then every scan
//! integrated through the map's own [`ScanMap::integrate_checked`](crate::ScanMap::integrate_checked), so that
//! the three maps share one update each and a log changes nothing unless all
//! of it is good.

use crate::error::Result;
use crate::grid::Grid;
use crate::log::Log;
use crate::pose::{Pose, validate_scan};
use crate::scan_map::ScanBeams;
use crate::sensor::SensorModel;

/// One scan of a log as the maps take it: the sensor's world pose, the
/// beams that gave a reading (dropped beams left out), each no-echo reading
/// at the model's maximum range and reaching no further than the log's.
#[derive(Default)]
struct PreparedScan {
    pose: Pose,
    ranges: Vec<f64>,
    bearings: Vec<f64>,
    reaches: Vec<f64>,
}

impl PreparedScan {
    /// The scan as a map takes it.
    fn beams(&self) -> ScanBeams<'_> {
        ScanBeams {
            pose: &self.pose,
            ranges: &self.ranges,
            bearings: &self.bearings,
            no_echo_reach_m: Some(&self.reaches),
            no_echo_sight: None,
            echo_sources: None,
        }
    }

    fn fill<M: SensorModel + ?Sized>(&mut self, log: &Log, i: usize, model: &M) {
        let model_max_m = model.range_model().max_range_m;
        self.pose = log.sensor_pose(i);
        self.ranges.clear();
        self.bearings.clear();
        for (&r, &b) in log.scan_ranges(i).iter().zip(log.scan_bearings(i)) {
            if r.is_nan() {
                continue;
            }
            // The log's no-echo reading is a no-echo reading for the model
            // too, whatever the two maxima.
            self.ranges.push(if r >= log.max_range_m() {
                model_max_m
            } else {
                r
            });
            self.bearings.push(b);
        }
        self.reaches.clear();
        self.reaches.resize(self.ranges.len(), log.max_range_m());
    }
}

/// Check every scan of `log` against `grid` and `model`, then hand each to
/// `apply` (a map's [`ScanMap::integrate_checked`](crate::ScanMap::integrate_checked)), reporting the scans
/// done to `progress`. An error names its scan ([`crate::CovmapError::InScan`]).
pub(crate) fn integrate_scans<M: SensorModel + ?Sized>(
    grid: &Grid,
    log: &Log,
    model: &M,
    progress: &mut dyn FnMut(usize),
    mut apply: impl FnMut(ScanBeams<'_>) -> Result<usize>,
) -> Result<usize> {
    model.validate()?;
    let mut scan = PreparedScan::default();
    for i in 0..log.len() {
        scan.fill(log, i, model);
        validate_scan(grid, &scan.pose, &scan.ranges, &scan.bearings, model)
            .map_err(|e| e.in_scan(i))?;
    }
    let mut updates = 0;
    for i in 0..log.len() {
        scan.fill(log, i, model);
        // Checked above: only a model whose kernels cannot be computed fails
        // here, and it fails on the first scan, before any change.
        updates += apply(scan.beams()).map_err(|e| e.in_scan(i))?;
        progress(i + 1);
    }
    Ok(updates)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::counting::ScanCounts;
    use crate::coverage_map::CoverageMap;
    use crate::error::CovmapError;
    use crate::log::Bearings;
    use crate::occupancy::OccupancyGrid;
    use crate::scan_map::ScanMap;
    use crate::sensor::{LaserModel, SonarModel};

    fn grid() -> Grid {
        Grid::new([0.0, 0.0], 0.1, 60, 80).unwrap()
    }

    fn log(poses: Vec<Pose>) -> Log {
        let n = poses.len();
        let ranges: Vec<f64> = (0..n * 3).map(|i| 0.5 + (i % 7) as f64 * 0.3).collect();
        Log::new(
            poses,
            (0..n).map(|i| i as f64).collect(),
            ranges,
            Bearings::Fixed(vec![-0.4, 0.0, 0.4]),
            2.0,
        )
        .unwrap()
    }

    fn poses(n: usize) -> Vec<Pose> {
        (0..n)
            .map(|i| Pose::new(2.0 + 0.2 * i as f64, 3.0, 0.1 * i as f64))
            .collect()
    }

    #[test]
    fn a_log_is_its_scans_integrated_one_by_one() {
        let log = log(poses(6))
            .with_sensor_offset(Pose::new(0.3, 0.1, 0.2))
            .unwrap();
        let model = LaserModel::default();
        let mut whole = CoverageMap::new(grid());
        let mut done = Vec::new();
        let updates = whole
            .integrate_log_with_progress(&log, &model, &mut |n| done.push(n))
            .unwrap();
        assert_eq!(done, (1..=6).collect::<Vec<_>>());
        let mut by_scan = CoverageMap::new(grid());
        let mut occupancy = OccupancyGrid::new(grid());
        let (mut sum, mut occupancy_sum) = (0, 0);
        for i in 0..log.len() {
            // The log's no-echo readings (2.0 and above) as the model's.
            let ranges: Vec<f64> = log
                .scan_ranges(i)
                .iter()
                .map(|&r| if r >= 2.0 { model.range.max_range_m } else { r })
                .collect();
            let pose = log.poses()[i].compose(&Pose::new(0.3, 0.1, 0.2));
            let reach = vec![2.0; 3];
            let scan = ScanBeams {
                pose: &pose,
                ranges: &ranges,
                bearings: log.scan_bearings(i),
                no_echo_reach_m: Some(&reach),
                no_echo_sight: None,
                echo_sources: None,
            };
            sum += by_scan.integrate_scan(scan, &model).unwrap();
            occupancy_sum += occupancy.integrate_scan(scan, &model).unwrap();
        }
        assert_eq!(updates, sum);
        assert_eq!(whole.histograms(), by_scan.histograms());
        let mut occupancy_log = OccupancyGrid::new(grid());
        assert_eq!(
            occupancy_log.integrate_log(&log, &model).unwrap(),
            occupancy_sum
        );
        assert_eq!(occupancy_log, occupancy);
        let mut counts = ScanCounts::new(grid());
        counts.integrate_log(&log, &model).unwrap();
        assert_eq!(counts.counts(), occupancy.counts().counts());
    }

    #[test]
    fn a_bad_scan_in_the_middle_changes_nothing_and_is_named() {
        let mut p = poses(5);
        p[3] = Pose::new(50.0, 3.0, 0.0); // outside the 8 x 6 m map
        let bad = log(p);
        let model = SonarModel::default();
        let mut map = CoverageMap::new(grid());
        map.integrate_log(&log(poses(2)), &model).unwrap();
        let before = map.histograms().to_vec();
        let err = map.integrate_log(&bad, &model).unwrap_err();
        assert!(
            matches!(&err, CovmapError::InScan { scan: 3, source } if matches!(**source, CovmapError::PoseOutsideMap { .. })),
            "{err}"
        );
        assert!(err.to_string().starts_with("scan 3 of the log"), "{err}");
        assert_eq!(map.histograms(), &before[..]);
        let mut occupancy = OccupancyGrid::new(grid());
        let empty = occupancy.clone();
        assert!(occupancy.integrate_log(&bad, &model).is_err());
        assert_eq!(occupancy, empty);
        let mut counts = ScanCounts::new(grid());
        assert!(counts.integrate_log(&bad, &model).is_err());
        assert!(counts.counts().iter().all(|&c| c == 0.0));
        // A model whose kernels cannot be computed fails on the first scan,
        // before anything changes.
        let mut broken = model;
        (broken.range.sigma_min, broken.range.sigma_per_m) = (1e-310, 0.0);
        assert!(map.integrate_log(&log(poses(3)), &broken).is_err());
        assert_eq!(map.histograms(), &before[..]);
    }

    #[test]
    fn dropped_beams_are_skipped() {
        let fan = crate::log::laser_scan::LaserScanFan {
            angle_min_rad: -0.4,
            angle_increment_rad: 0.4,
            range_min_m: 0.1,
            range_max_m: 2.0,
        };
        let p = vec![Pose::new(2.0, 3.0, 0.0)];
        let with_dropped =
            Log::from_laser_scans(p.clone(), &[1.0, f64::NAN, f64::NEG_INFINITY], &fan, None)
                .unwrap();
        let model = LaserModel::default();
        let mut a = CoverageMap::new(grid());
        a.integrate_log(&with_dropped, &model).unwrap();
        let one = Log::new(p, vec![0.0], vec![1.0], Bearings::Fixed(vec![-0.4]), 2.0).unwrap();
        let mut b = CoverageMap::new(grid());
        b.integrate_log(&one, &model).unwrap();
        assert_eq!(a.histograms(), b.histograms());
        assert_ne!(a.histograms(), CoverageMap::new(grid()).histograms());
    }
}
