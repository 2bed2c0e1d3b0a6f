//! Maps and a sonar ring the planner's tests share.

use crate::coverage_map::CoverageMap;
use crate::grid::Grid;
use crate::pose::Pose;
use crate::scan_map::ScanMap;
use crate::sensor::SonarModel;

/// The bearings of a ring of 24 beams, 15° apart.
pub(super) fn ring() -> Vec<f64> {
    (0..24)
        .map(|i| i as f64 * std::f64::consts::TAU / 24.0)
        .collect()
}

/// A square room 4 m wide seen from its centre a few times.
pub(super) fn room() -> (CoverageMap, Pose) {
    let mut map = CoverageMap::new(Grid::new([0.0, 0.0], 0.05, 160, 160).unwrap());
    let pose = Pose::new(4.0, 4.0, 0.0);
    let sonar = SonarModel::default();
    let bearings = ring();
    let ranges: Vec<f64> = bearings
        .iter()
        .map(|b| 2.0 / b.cos().abs().max(b.sin().abs()))
        .collect();
    for _ in 0..3 {
        map.integrate(&pose, &ranges, &bearings, &sonar).unwrap();
    }
    (map, pose)
}

/// A 3 m square map at 5 cm whose cells in `walls` are certainly covered
/// (all mass in the last bin) and the others certainly free (all mass in
/// bin 0) or, with `rest_at_prior`, still at the prior.
pub(super) fn walled_map(walls: impl Fn(usize, usize) -> bool, rest_at_prior: bool) -> CoverageMap {
    let grid = Grid::new([0.0, 0.0], 0.05, 60, 60).unwrap();
    let bins = 16;
    let mut data = vec![0.0f32; grid.len() * bins];
    for (i, h) in data.chunks_exact_mut(bins).enumerate() {
        if walls(i / 60, i % 60) {
            h[bins - 1] = 1.0;
        } else if rest_at_prior {
            h.fill(1.0 / bins as f32);
        } else {
            h[0] = 1.0;
        }
    }
    CoverageMap::from_histograms(grid, bins, data).unwrap()
}
