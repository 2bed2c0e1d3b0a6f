//! No-echo readings occluded by the map: a no-echo reading that the map
//! says crossed an obstacle missed it (a specular reflection) and says
//! nothing of what lies behind.

use super::{CONTACT_COVERAGE, CoverageMap};
use crate::error::Result;
use crate::footprint::visit;
use crate::grid::Grid;
use crate::histogram;
use crate::pose::Pose;
use crate::scan_map::{ScanBeams, ScanMap};
use crate::sensor::SensorModel;

/// A coverage map that integrates each scan with its no-echo readings
/// occluded by the map as it stands when the scan comes
/// ([`CoverageMap::occluding`]).
#[derive(Debug)]
pub struct Occluding<'a>(&'a mut CoverageMap);

impl ScanMap for Occluding<'_> {
    fn grid(&self) -> &Grid {
        self.0.grid()
    }

    fn integrate_checked<M: SensorModel + ?Sized>(
        &mut self,
        scan: ScanBeams<'_>,
        model: &M,
    ) -> Result<usize> {
        let mut reaches = self
            .0
            .no_echo_reaches(scan.pose, scan.ranges, scan.bearings, model);
        for (r, &given) in reaches.iter_mut().zip(scan.no_echo_reach_m.unwrap_or(&[])) {
            *r = r.min(given);
        }
        let no_echo_reach_m = Some(&reaches[..]);
        self.0.integrate_checked(
            ScanBeams {
                no_echo_reach_m,
                ..scan
            },
            model,
        )
    }
}

impl CoverageMap {
    /// This map, integrating each scan ([`ScanMap::integrate`],
    /// [`ScanMap::integrate_log`] and the rest) with its no-echo readings
    /// occluded by the map as it stands when the scan comes: a no-echo
    /// reading clears only up to the nearest cell of its footprint the map
    /// holds as covered ([`CoverageMap::no_echo_reaches`]), as the
    /// exploration loop integrates its scans. A no-echo reading through a
    /// wall that earlier echoes found is then taken for a specular miss,
    /// which says nothing of the wall or of what lies behind it.
    pub fn occluding(&mut self) -> Occluding<'_> {
        Occluding(self)
    }

    /// How far each no-echo reading of a scan from `pose` should clear: to
    /// the nearest cell of its footprint that this map holds as covered (ML
    /// coverage above [`CONTACT_COVERAGE`]; a cell the robot ran into is
    /// pinned so: [`CoverageMap::pin_covered`]), at most the maximum range;
    /// echo readings get the maximum range (they ignore it).
    /// The result is the `no_echo_reach_m` of a
    /// [`ScanBeams`](crate::ScanBeams). The scan is not validated: an
    /// invalid one gives reaches the update then refuses.
    pub fn no_echo_reaches<M: SensorModel + ?Sized>(
        &self,
        pose: &Pose,
        ranges: &[f64],
        bearings: &[f64],
        model: &M,
    ) -> Vec<f64> {
        let grid = self.grid();
        let (bins, histograms) = (self.bins(), self.histograms());
        let range = model.range_model();
        let max_range_m = range.max_range_m;
        let footprint = model.footprint();
        let half = 0.5 * grid.resolution_m();
        let is_covered = |i: usize| {
            let ml = histogram::bin_value(
                histogram::argmax(&histograms[i * bins..(i + 1) * bins]),
                bins,
            );
            ml > CONTACT_COVERAGE
        };
        ranges
            .iter()
            .zip(bearings)
            .map(|(&r, &bearing)| {
                let mut reach = max_range_m;
                if r >= max_range_m && r.is_finite() && bearing.is_finite() {
                    visit(
                        grid,
                        [pose.x_m, pose.y_m],
                        pose.theta_rad + bearing,
                        max_range_m,
                        footprint,
                        &mut |i: usize, d_l: f64| {
                            if d_l - half < reach && is_covered(i) {
                                reach = (d_l - half).max(0.0);
                            }
                        },
                    );
                }
                reach
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grid::Cell;
    use crate::grid::Grid;
    use crate::scan_map::ScanMap;
    use crate::sensor::{LaserModel, SonarModel};

    /// On a map holding walls, every no-echo reading stops before the
    /// nearest cell of its footprint the ML map holds covered (more than
    /// half), and echo readings and readings that meet none reach as far
    /// as the model lets them.
    #[test]
    fn no_echo_readings_stop_before_covered_cells() {
        let grid = Grid::new([0.0, 0.0], 0.05, 120, 160).unwrap();
        let mut map = CoverageMap::new(grid);
        let laser = LaserModel::default();
        let bearings: Vec<f64> = (0..90).map(|k| f64::from(k) * 0.0698).collect();
        for pose in [Pose::new(2.0, 3.0, 0.0), Pose::new(6.0, 3.5, 0.0)] {
            let ranges: Vec<f64> = bearings.iter().map(|b| 1.2 + b.sin().abs()).collect();
            map.integrate(&pose, &ranges, &bearings, &laser).unwrap();
        }
        map.pin_covered(&[Cell { row: 60, col: 60 }]).unwrap();
        let ml = map.ml();
        let half = 0.5 * grid.resolution_m();
        let mut next = crate::test_rng::uniform(3);
        let sonar = SonarModel::default();
        let limit = sonar.range.max_range_m;
        let ring: Vec<f64> = (0..24).map(|k| f64::from(k) * 0.2618).collect();
        let mut stopped = 0;
        for trial in 0..40 {
            let pose = Pose::new(1.0 + 6.0 * next(), 1.0 + 4.0 * next(), next());
            let mut ranges = vec![sonar.range.max_range_m; 24];
            ranges[trial % 24] = 1.0;
            let got = map.no_echo_reaches(&pose, &ranges, &ring, &sonar);
            for (k, (&reach, &r)) in got.iter().zip(&ranges).enumerate() {
                if r < sonar.range.max_range_m {
                    assert_eq!(reach, sonar.range.max_range_m, "an echo");
                    continue;
                }
                let mut want = limit;
                visit(
                    &grid,
                    [pose.x_m, pose.y_m],
                    pose.theta_rad + ring[k],
                    limit,
                    sonar.footprint(),
                    &mut |i: usize, d_l: f64| {
                        if f64::from(ml[i]) > CONTACT_COVERAGE {
                            want = want.min((d_l - half).max(0.0));
                        }
                    },
                );
                assert_eq!(reach, want, "trial {trial}, beam {k}");
                stopped += usize::from(reach < limit);
            }
        }
        assert!(stopped > 100, "{stopped} readings stopped");
    }
}
