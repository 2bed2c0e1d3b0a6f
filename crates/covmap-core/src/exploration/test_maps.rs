//! Maps for the exploration tests: a box room seen by a laser ring.

use crate::coverage_map::CoverageMap;
use crate::grid::Grid;
use crate::occupancy::OccupancyGrid;
use crate::pose::Pose;
use crate::scan_map::{ScanBeams, ScanMap};
use crate::sensor::LaserModel;

/// The room's inside: `[1, 5] x [1, 4]` metres, on a 6.5 m x 5.5 m grid.
pub(super) const ROOM: [f64; 4] = [1.0, 1.0, 5.0, 4.0];

/// The room scanned `scans` times with 720 exact laser beams from a few
/// poses near its middle, into a coverage map (entropy history tracked)
/// and an occupancy grid. With `door`, the east wall has a doorway from
/// `y = 2.2` to `3.2`: beams through it read no echo and clear only up to
/// the doorway, so that the doorway and what lies behind it stay unknown.
pub(super) fn scanned_room(door: bool, scans: usize) -> (CoverageMap, OccupancyGrid, Pose) {
    let grid = Grid::new([0.0, 0.0], 0.05, 110, 130).unwrap();
    let mut map = CoverageMap::new(grid);
    map.track_history(true);
    let mut occupancy = OccupancyGrid::new(grid);
    for k in 0..scans {
        let pose = Pose::new(2.0 + 0.3 * (k % 4) as f64, 2.3 + 0.2 * (k % 3) as f64, 0.0);
        scan_room(door, &pose, &mut map);
        scan_room(door, &pose, &mut occupancy);
    }
    (map, occupancy, Pose::new(2.5, 2.5, 0.0))
}

/// One scan of the room (as [`scanned_room`] takes them) from `pose`
/// inside it, integrated into `map`.
pub(super) fn scan_room(door: bool, pose: &Pose, map: &mut impl ScanMap) {
    let laser = LaserModel::default();
    let [x0, y0, x1, y1] = ROOM;
    let (mut ranges, mut bearings, mut reaches) = (Vec::new(), Vec::new(), Vec::new());
    for i in 0..720 {
        let angle = i as f64 * std::f64::consts::TAU / 720.0;
        let (s, c) = angle.sin_cos();
        let to = |v: f64, low: f64, high: f64, p: f64| match v {
            v if v > 1e-12 => (high - p) / v,
            v if v < -1e-12 => (low - p) / v,
            _ => f64::INFINITY,
        };
        let (tx, ty) = (to(c, x0, x1, pose.x_m), to(s, y0, y1, pose.y_m));
        let y_at_east = pose.y_m + tx * s;
        if door && tx < ty && c > 0.0 && (2.2..3.2).contains(&y_at_east) {
            ranges.push(laser.range.max_range_m);
            reaches.push(tx);
        } else {
            ranges.push(tx.min(ty));
            reaches.push(laser.range.max_range_m);
        }
        bearings.push(angle);
    }
    let scan = ScanBeams {
        pose,
        ranges: &ranges,
        bearings: &bearings,
        no_echo_reach_m: Some(&reaches),
        no_echo_sight: None,
        echo_sources: None,
    };
    map.integrate_scan(scan, &laser).unwrap();
}
