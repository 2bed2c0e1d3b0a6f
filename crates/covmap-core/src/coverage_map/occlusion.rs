//! No-echo readings occluded by the map: a no-echo reading that the map
//! says crossed an obstacle missed it (a specular reflection) and says
//! nothing of what lies behind. A scan at a time, occluded by the map as it
//! stands (the exploration loop); a whole log, occluded by the map of all
//! of its echoes, which does not depend on the order of the scans.

use super::{CONTACT_COVERAGE, CoverageMap};
use crate::error::Result;
use crate::footprint::visit;
use crate::grid::Grid;
use crate::histogram;
use crate::log::Log;
use crate::pose::Pose;
use crate::scan_map::{ScanBeams, ScanMap};
use crate::sensor::SensorModel;

/// A coverage map that integrates each scan with its no-echo readings
/// occluded by the map as it stands when the scan comes, and a whole log
/// with them occluded by the map of the log's echoes
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
        let map = &*self.0;
        let reaches = reaches_before(map.grid(), &scan, model, |i| map.is_covered(i));
        let no_echo_reach_m = Some(&reaches[..]);
        self.0.integrate_checked(
            ScanBeams {
                no_echo_reach_m,
                ..scan
            },
            model,
        )
    }

    /// Every scan of `log`, the echoes first and then the no-echo readings,
    /// each occluded by the map as all the echoes left it
    /// ([`integrate_log_occluded`]); `progress` is told of a scan once its
    /// no-echo readings are in too.
    fn integrate_log_with_progress<M: SensorModel + ?Sized>(
        &mut self,
        log: &Log,
        model: &M,
        progress: &mut dyn FnMut(usize),
    ) -> Result<usize> {
        integrate_log_occluded(self.0, log, model, progress, |_| Ok(0))
    }
}

/// Integrate `log` into `map` with its no-echo readings occluded by the map
/// of the log's echoes, which does not depend on the order of the scans:
/// first every scan's echo readings, then every scan's no-echo readings,
/// each clearing only up to the nearest cell of its footprint that the map
/// held as covered once all the echoes were in (and no further than the
/// log's maximum range). `also` is handed every set of beams `map` takes,
/// checked, so that another map (the occupancy grid baseline) can take the
/// very same ones; its updates are added to the count returned. `progress`
/// is told of each scan once its no-echo readings are in. A map that keeps
/// its history ([`CoverageMap::track_history`]) counts each scan as one
/// measurement still: the echoes' map is then built on a copy (as much
/// memory again), and each scan goes in whole.
///
/// # Errors
/// As [`ScanMap::integrate_log`]: every scan is checked before anything
/// changes.
pub fn integrate_log_occluded<M: SensorModel + ?Sized>(
    map: &mut CoverageMap,
    log: &Log,
    model: &M,
    progress: &mut dyn FnMut(usize),
    mut also: impl FnMut(ScanBeams<'_>) -> Result<usize>,
) -> Result<usize> {
    let grid = *map.grid();
    let max_range_m = model.range_model().max_range_m;
    let echo = |r: f64| r < max_range_m;
    let mut kept = KeptBeams::default();
    // The map of every echo: this map itself, or, where a scan must stay
    // one measurement of the history, a copy of it (the scans then go into
    // this map whole below).
    let whole = map.tracks_history();
    let mut updates = 0;
    let covered = if whole {
        let history = map.history.take();
        let mut echoes = map.clone();
        map.history = history;
        crate::log::integrate_scans(&grid, log, model, &mut |_| {}, |scan| {
            echoes.integrate_checked(kept.keep(scan, echo), model)
        })?;
        echoes.covered_cells()
    } else {
        updates += crate::log::integrate_scans(&grid, log, model, &mut |_| {}, |scan| {
            let echoes = kept.keep(scan, echo);
            Ok(map.integrate_checked(echoes, model)? + also(echoes)?)
        })?;
        map.covered_cells()
    };
    updates += crate::log::integrate_scans(&grid, log, model, progress, |scan| {
        let mut beams = if whole {
            scan
        } else {
            kept.keep(scan, |r| !echo(r))
        };
        let reaches = reaches_before(&grid, &beams, model, |i| covered[i]);
        beams.no_echo_reach_m = Some(&reaches);
        Ok(map.integrate_checked(beams, model)? + also(beams)?)
    })?;
    Ok(updates)
}

/// The beams of a scan one pass of [`integrate_log_occluded`] keeps.
#[derive(Default)]
struct KeptBeams {
    ranges: Vec<f64>,
    bearings: Vec<f64>,
    reaches: Vec<f64>,
}

impl KeptBeams {
    /// The beams of `scan` whose range `keep` accepts, with their reaches.
    fn keep<'a>(&'a mut self, scan: ScanBeams<'a>, keep: impl Fn(f64) -> bool) -> ScanBeams<'a> {
        self.ranges.clear();
        self.bearings.clear();
        self.reaches.clear();
        for (k, (&r, &b)) in scan.ranges.iter().zip(scan.bearings).enumerate() {
            if keep(r) {
                self.ranges.push(r);
                self.bearings.push(b);
                if let Some(reaches) = scan.no_echo_reach_m {
                    self.reaches.push(reaches[k]);
                }
            }
        }
        ScanBeams {
            pose: scan.pose,
            ranges: &self.ranges,
            bearings: &self.bearings,
            no_echo_reach_m: scan.no_echo_reach_m.map(|_| &self.reaches[..]),
        }
    }
}

/// How far each reading of `scan` should clear: a no-echo reading to the
/// nearest cell of its footprint that `is_covered`, at most the lesser of
/// the maximum range and the scan's own reach; an echo reading the maximum
/// range (it ignores it).
fn reaches_before<M: SensorModel + ?Sized>(
    grid: &Grid,
    scan: &ScanBeams<'_>,
    model: &M,
    is_covered: impl Fn(usize) -> bool,
) -> Vec<f64> {
    let max_range_m = model.range_model().max_range_m;
    let footprint = model.footprint();
    let half = 0.5 * grid.resolution_m();
    let pose = scan.pose;
    scan.ranges
        .iter()
        .zip(scan.bearings)
        .enumerate()
        .map(|(k, (&r, &bearing))| {
            let given = scan.no_echo_reach_m.map_or(max_range_m, |g| g[k]);
            let mut reach = max_range_m.min(given);
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

impl CoverageMap {
    /// This map, integrating each scan ([`ScanMap::integrate`],
    /// [`ScanMap::integrate_scan`]) with its no-echo readings occluded by
    /// the map as it stands when the scan comes: a no-echo reading clears
    /// only up to the nearest cell of its footprint the map holds as
    /// covered ([`CoverageMap::no_echo_reaches`]), as the exploration loop
    /// integrates its scans. A no-echo reading through a wall that earlier
    /// echoes found is then taken for a specular miss, which says nothing
    /// of the wall or of what lies behind it. A whole log
    /// ([`ScanMap::integrate_log`]) goes in echoes first, its no-echo
    /// readings occluded by the map of all of them
    /// ([`integrate_log_occluded`]): that map does not depend on the order
    /// of the scans.
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
        let scan = ScanBeams {
            pose,
            ranges,
            bearings,
            no_echo_reach_m: None,
        };
        reaches_before(self.grid(), &scan, model, |i| self.is_covered(i))
    }

    /// Whether this map holds cell `i` as covered: its ML coverage above
    /// [`CONTACT_COVERAGE`] (a cell the robot ran into is pinned so:
    /// [`CoverageMap::pin_covered`]).
    fn is_covered(&self, i: usize) -> bool {
        let bins = self.bins();
        let ml = histogram::bin_value(
            histogram::argmax(&self.histograms()[i * bins..(i + 1) * bins]),
            bins,
        );
        ml > CONTACT_COVERAGE
    }

    /// [`CoverageMap::is_covered`] of every cell.
    fn covered_cells(&self) -> Vec<bool> {
        (0..self.grid().len()).map(|i| self.is_covered(i)).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grid::Cell;
    use crate::grid::Grid;
    use crate::scan_map::ScanMap;
    use crate::sensor::{LaserModel, SonarModel};

    /// A map that keeps its history takes an occluded log as one that
    /// does not (but for float rounding), counting each scan as one
    /// measurement of every cell it updates, echoes and no-echo readings
    /// alike.
    #[test]
    fn an_occluded_log_counts_a_scan_as_one_measurement() {
        use crate::log::{Bearings, Log};
        let grid = Grid::new([0.0, 0.0], 0.05, 80, 80).unwrap();
        let scans = 7;
        let poses = vec![Pose::new(2.0, 2.0, 0.0); scans];
        // An echo and a miss whose cones overlap near the robot, and a
        // miss the other way (at the log's maximum range).
        let ranges: Vec<f64> = (0..scans).flat_map(|_| [1.0, 5.0, 5.0]).collect();
        let log = Log::new(
            poses,
            (0..scans).map(|i| i as f64).collect(),
            ranges,
            Bearings::Fixed(vec![0.0, 0.1, 3.0]),
            5.0,
        )
        .unwrap();
        let sonar = SonarModel::default();
        let mut kept = CoverageMap::new(grid);
        kept.track_history(true);
        let mut plain = CoverageMap::new(grid);
        let n = kept.occluding().integrate_log(&log, &sonar).unwrap();
        assert_eq!(n, plain.occluding().integrate_log(&log, &sonar).unwrap());
        for (a, b) in kept.histograms().iter().zip(plain.histograms()) {
            assert!((a - b).abs() <= 1e-5, "{a} vs {b}");
        }
        let near = Cell { row: 40, col: 44 };
        assert_eq!(kept.measurements(near).unwrap(), scans as u32);
        let counts = kept.measurement_counts();
        assert_eq!(counts.iter().copied().max(), Some(scans as u32));
    }

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
