//! Maps the gain's tests evaluate.

use crate::coverage_map::CoverageMap;
use crate::grid::Grid;
use crate::pose::Pose;
use crate::scan_map::ScanMap;
use crate::sensor::SensorModel;

/// The bearings of a ring of eight sonars, 0.785 rad apart.
pub(super) fn ring_of_eight() -> Vec<f64> {
    (0..8).map(|i| i as f64 * 0.785).collect()
}

/// A map of `grid` after one scan of `model` along `bearings` from each
/// pose, with the ranges beside it.
pub(super) fn scanned(
    grid: Grid,
    scans: &[(Pose, &[f64])],
    bearings: &[f64],
    model: &dyn SensorModel,
) -> CoverageMap {
    let mut map = CoverageMap::new(grid);
    for (pose, ranges) in scans {
        map.integrate(pose, ranges, bearings, model).unwrap();
    }
    map
}
