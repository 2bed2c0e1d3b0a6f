//! No-echo readings occluded by the map: a no-echo reading that the map
//! is certain crossed an obstacle missed it (a specular reflection) and
//! says nothing of what lies behind; an echo the map explains marks only
//! the cells that explain it ([`EchoSources`]). A scan at a time, read
//! against the map as it stands (the exploration loop); a whole log, read
//! against the map of all of its echoes, which does not depend on the order
//! of the scans.
//!
//! Only cells the map is certain of occlude ([`CoverageMap::occludes`]):
//! a cell held covered on the evidence of an echo arc or two may be a
//! cell of the arc that did not return the echo (a doorway between two
//! jambs), and a no-echo reading through it is evidence that it did not.
//! Were such a cell to occlude, it would shadow the very readings that
//! could clear it and stay covered for good.

use super::{CONTACT_COVERAGE, CoverageMap};
use crate::echo_sources::EchoSources;
use crate::error::Result;
use crate::grid::Grid;
use crate::histogram;
use crate::log::Log;
use crate::planner::DEFAULT_EPSILON;
use crate::pose::Pose;
use crate::scan_map::{ScanBeams, ScanMap};
use crate::sensor::SensorModel;
use crate::sight::NoEchoSight;

/// A coverage map that integrates each scan read against the map as it
/// stands when the scan comes (its no-echo readings occluded, its echoes
/// explained by what the map is certain of), and a whole log read against
/// the map of the log's echoes ([`CoverageMap::occluding`]).
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
        let reading = ScanReading::of_scan(map.grid(), &scan, model, |i| {
            map.occludes(i, DEFAULT_EPSILON)
        });
        self.0.integrate_checked(reading.beams(scan), model)
    }

    /// Every scan of `log`, read against the map of all of the log's
    /// echoes ([`integrate_log_occluded`]); `progress` is told of each
    /// scan once it is in.
    fn integrate_log_with_progress<M: SensorModel + ?Sized>(
        &mut self,
        log: &Log,
        model: &M,
        progress: &mut dyn FnMut(usize),
    ) -> Result<usize> {
        integrate_log_occluded(self.0, log, model, DEFAULT_EPSILON, progress, |_| Ok(0))
    }
}

/// Integrate `log` into `map` read against the map of the log's echoes,
/// which does not depend on the order of the scans: first every scan's
/// echo readings go into a copy of `map` (as much memory again); the cells
/// that copy then holds as covered, with an entropy of at most `epsilon`
/// nats ([`CoverageMap::occludes`]), stop the line of sight of every
/// no-echo reading ([`NoEchoSight`]; no further than the log's maximum
/// range) and explain the echoes off them ([`EchoSources`]); then every
/// scan goes into `map` whole, so read. `also` is handed every set of beams
/// `map` takes, checked, so that another map (the occupancy grid baseline)
/// can take the very same ones; its updates are added to the count
/// returned. `progress` is told of each scan once it is in. A map that
/// keeps its history ([`CoverageMap::track_history`]) counts each scan as
/// one measurement.
///
/// # Errors
/// As [`ScanMap::integrate_log`]: every scan is checked before anything
/// changes.
pub fn integrate_log_occluded<M: SensorModel + ?Sized>(
    map: &mut CoverageMap,
    log: &Log,
    model: &M,
    epsilon: f64,
    progress: &mut dyn FnMut(usize),
    mut also: impl FnMut(ScanBeams<'_>) -> Result<usize>,
) -> Result<usize> {
    let grid = *map.grid();
    let max_range_m = model.range_model().max_range_m;
    let mut kept = KeptBeams::default();
    // The map of every echo, on a copy that keeps no history.
    let history = map.history.take();
    let mut echoes = map.clone();
    map.history = history;
    crate::log::integrate_scans(&grid, log, model, &mut |_| {}, |scan| {
        echoes.integrate_checked(kept.echoes(scan, max_range_m), model)
    })?;
    let covered = echoes.occluding_cells(epsilon);
    drop(echoes);
    crate::log::integrate_scans(&grid, log, model, progress, |scan| {
        let reading = ScanReading::of_scan(&grid, &scan, model, |i| covered[i]);
        let beams = reading.beams(scan);
        Ok(map.integrate_checked(beams, model)? + also(beams)?)
    })
}

/// Integrate `log` into `map` with each no-echo reading occluded by the
/// cells `occludes` names instead of by the map (obstacles known
/// otherwise, such as a world's true ones): each clears, sector by sector,
/// only what its line of sight reaches before the first such cell
/// ([`NoEchoSight`]). The map does not read itself, so it does not depend
/// on the order of the scans.
///
/// # Errors
/// As [`ScanMap::integrate_log`]: every scan is checked before anything
/// changes.
pub fn integrate_log_occluded_by<M: SensorModel + ?Sized>(
    map: &mut CoverageMap,
    log: &Log,
    model: &M,
    occludes: impl Fn(usize) -> bool,
) -> Result<usize> {
    let grid = *map.grid();
    crate::log::integrate_scans(&grid, log, model, &mut |_| {}, |scan| {
        let sight = NoEchoSight::of_scan(&grid, &scan, model, &occludes);
        map.integrate_checked(
            ScanBeams {
                no_echo_sight: Some(&sight),
                ..scan
            },
            model,
        )
    })
}

/// The beams of a scan one pass of [`integrate_log_occluded`] keeps.
#[derive(Default)]
struct KeptBeams {
    ranges: Vec<f64>,
    bearings: Vec<f64>,
    reaches: Vec<f64>,
}

impl KeptBeams {
    /// The echo readings of `scan` (those short of `max_range_m`), with
    /// their reaches.
    fn echoes<'a>(&'a mut self, scan: ScanBeams<'a>, max_range_m: f64) -> ScanBeams<'a> {
        self.ranges.clear();
        self.bearings.clear();
        self.reaches.clear();
        for (k, (&r, &b)) in scan.ranges.iter().zip(scan.bearings).enumerate() {
            if r < max_range_m {
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
            no_echo_sight: None,
            echo_sources: None,
        }
    }
}

/// A scan read against the cells a map is certain are covered: how far
/// each no-echo reading sees past them ([`NoEchoSight`]) and which cells
/// of each echo's arc may have returned it ([`EchoSources`]). The
/// exploration loop, [`Occluding`] and [`integrate_log_occluded`] read
/// every scan so ([`CoverageMap::read_scan`] against a map as it stands).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ScanReading {
    /// The no-echo readings' sight.
    pub sight: NoEchoSight,
    /// The echoes' sources.
    pub sources: EchoSources,
}

impl ScanReading {
    /// `scan` read against the cells `is_certain` names. No-echo readings
    /// and echoes are disjoint, so each cell's certainty is asked of at
    /// most once a reading.
    pub fn of_scan<M: SensorModel + ?Sized>(
        grid: &Grid,
        scan: &ScanBeams<'_>,
        model: &M,
        is_certain: impl Fn(usize) -> bool,
    ) -> Self {
        Self {
            sight: NoEchoSight::of_scan(grid, scan, model, &is_certain),
            sources: EchoSources::of_scan(grid, scan, model, &is_certain),
        }
    }

    /// `scan` with this reading: the beams a map takes.
    pub fn beams<'a>(&'a self, scan: ScanBeams<'a>) -> ScanBeams<'a> {
        ScanBeams {
            no_echo_sight: Some(&self.sight),
            echo_sources: Some(&self.sources),
            ..scan
        }
    }
}

impl CoverageMap {
    /// This map, integrating each scan ([`ScanMap::integrate`],
    /// [`ScanMap::integrate_scan`]) with its no-echo readings occluded by
    /// the map as it stands when the scan comes: a no-echo reading clears
    /// only the cells of its footprint that no cell the map holds as
    /// covered, and is certain of, shadows ([`CoverageMap::read_scan`];
    /// certain: an entropy of at most [`DEFAULT_EPSILON`] nats), as the
    /// exploration loop integrates its scans (at its own epsilon). A no-echo reading through a wall that earlier
    /// echoes found is then taken for a specular miss, which says nothing
    /// of the wall or of what lies behind it. Each echo is explained by
    /// the same cells ([`EchoSources`]). A whole log
    /// ([`ScanMap::integrate_log`]) is read against the map of all of its
    /// echoes ([`integrate_log_occluded`]): that map does not depend on
    /// the order of the scans.
    pub fn occluding(&mut self) -> Occluding<'_> {
        Occluding(self)
    }

    /// A scan from `pose` read against the cells that occlude at
    /// `epsilon` ([`CoverageMap::occludes`]): each no-echo reading's sight
    /// and each echo's sources ([`ScanReading`]), to go with the scan
    /// ([`ScanReading::beams`]). The scan is not validated: an invalid one
    /// gives a reading the update then refuses.
    pub fn read_scan<M: SensorModel + ?Sized>(
        &self,
        pose: &Pose,
        ranges: &[f64],
        bearings: &[f64],
        model: &M,
        epsilon: f64,
    ) -> ScanReading {
        let scan = ScanBeams::new(pose, ranges, bearings);
        ScanReading::of_scan(self.grid(), &scan, model, |i| self.occludes(i, epsilon))
    }

    /// Whether cell `i` (row-major) stops the line of sight of no-echo
    /// readings: this map holds it as covered (ML coverage above
    /// [`CONTACT_COVERAGE`]) and is certain of it (its entropy at most
    /// `epsilon` nats, as a cell counts as explored). A cell the robot ran
    /// into is pinned so ([`CoverageMap::pin_covered`]). A cell held
    /// covered but uncertain does not occlude: the no-echo readings through
    /// it are evidence the map still weighs.
    pub fn occludes(&self, i: usize, epsilon: f64) -> bool {
        let bins = self.bins();
        let h = &self.histograms()[i * bins..(i + 1) * bins];
        histogram::bin_value(histogram::argmax(h), bins) > CONTACT_COVERAGE
            && f64::from(histogram::entropy(h)) <= epsilon
    }

    /// [`CoverageMap::occludes`] of every cell.
    fn occluding_cells(&self, epsilon: f64) -> Vec<bool> {
        (0..self.grid().len())
            .map(|i| self.occludes(i, epsilon))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::footprint::visit;
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

    /// A log occluded by given cells: by none, it is the paper's map of the
    /// log; by a wall across a miss, the miss clears in front of the wall
    /// and not behind it, and the echoes mark as before.
    #[test]
    fn a_log_occluded_by_given_cells() {
        use crate::log::{Bearings, Log};
        let grid = Grid::new([0.0, 0.0], 0.05, 80, 80).unwrap();
        let log = Log::new(
            vec![Pose::new(1.8, 2.0, 0.0); 3],
            vec![0.0, 1.0, 2.0],
            [1.5, 5.0].repeat(3),
            Bearings::Fixed(vec![3.0, 0.0]),
            5.0,
        )
        .unwrap();
        let sonar = SonarModel::default();
        let mut paper = CoverageMap::new(grid);
        paper.integrate_log(&log, &sonar).unwrap();
        let mut none = CoverageMap::new(grid);
        integrate_log_occluded_by(&mut none, &log, &sonar, |_| false).unwrap();
        assert_eq!(none.histograms(), paper.histograms());
        // A wall across the miss (bearing 0) at x = 3.0 m.
        let wall = |i: usize| i % 80 == 60;
        let mut walled = CoverageMap::new(grid);
        integrate_log_occluded_by(&mut walled, &log, &sonar, wall).unwrap();
        let mean = |m: &CoverageMap, x: f64| {
            m.mean()[grid.index(grid.world_to_cell(x, 2.0).unwrap()).unwrap()]
        };
        assert!(mean(&walled, 2.5) < 0.5, "in front of the wall: cleared");
        assert_eq!(mean(&walled, 3.5), 0.5, "behind the wall: untouched");
        assert!(mean(&paper, 3.5) < 0.5, "the paper's miss clears behind it");
        // The echo (bearing 3, away from the wall) marks as before.
        let echo = grid
            .index(
                grid.world_to_cell(1.8 + 1.5 * 3f64.cos(), 2.0 + 1.5 * 3f64.sin())
                    .unwrap(),
            )
            .unwrap();
        assert_eq!(
            walled.histograms()[echo * 16..(echo + 1) * 16],
            paper.histograms()[echo * 16..(echo + 1) * 16]
        );
    }

    /// On a map holding walls, every cell a no-echo reading clears lies in
    /// its line of sight: the segment from the sensor to the cell's centre
    /// crosses no cell of the reading's footprint the ML map holds covered
    /// (more than half) and the map is certain of (entropy at most epsilon)
    /// short of
    /// the last half cell and half diagonal before the centre (a covered
    /// cell shadows the cells more than half a cell farther than its own
    /// centre). Readings that pass beside a covered
    /// cell clear what lies beyond it in their other sectors, and echo
    /// readings are not limited.
    #[test]
    fn no_echo_readings_clear_only_what_their_line_of_sight_reaches() {
        let grid = Grid::new([0.0, 0.0], 0.05, 120, 160).unwrap();
        let mut map = CoverageMap::new(grid);
        let laser = LaserModel::default();
        let bearings: Vec<f64> = (0..90).map(|k| f64::from(k) * 0.0698).collect();
        // Each scan four times: walls the map is certain of.
        for pose in [Pose::new(2.0, 3.0, 0.0), Pose::new(6.0, 3.5, 0.0)] {
            let ranges: Vec<f64> = bearings.iter().map(|b| 1.2 + b.sin().abs()).collect();
            for _ in 0..4 {
                map.integrate(&pose, &ranges, &bearings, &laser).unwrap();
            }
        }
        map.pin_covered(&[Cell { row: 60, col: 60 }]).unwrap();
        // The cells that occlude, read off the ML map and the entropies.
        let (ml, entropy) = (map.ml(), map.entropy());
        let occluding: Vec<bool> = (0..grid.len())
            .map(|i| {
                f64::from(ml[i]) > CONTACT_COVERAGE && f64::from(entropy[i]) <= DEFAULT_EPSILON
            })
            .collect();
        let occluders = occluding.iter().filter(|&&o| o).count();
        assert!(occluders > 100, "{occluders} certain covered cells");
        let covered_at = |covered: &[bool], x: f64, y: f64| {
            grid.world_to_cell(x, y)
                .is_some_and(|c| covered[grid.index(c).unwrap()])
        };
        let mut next = crate::test_rng::uniform(3);
        let sonar = SonarModel::default();
        let limit = sonar.range.max_range_m;
        let ring: Vec<f64> = (0..24).map(|k| f64::from(k) * 0.2618).collect();
        let (mut cleared, mut past_covered) = (0usize, 0usize);
        for trial in 0..40 {
            let pose = Pose::new(1.0 + 6.0 * next(), 1.0 + 4.0 * next(), next());
            let mut ranges = vec![limit; 24];
            ranges[trial % 24] = 1.0;
            let sight = map
                .read_scan(&pose, &ranges, &ring, &sonar, DEFAULT_EPSILON)
                .sight;
            let origin = [pose.x_m, pose.y_m];
            for (k, &r) in ranges.iter().enumerate() {
                let axis = pose.theta_rad + ring[k];
                if r < limit {
                    assert_eq!(sight.max_reach_m(k), limit, "an echo");
                    continue;
                }
                let mut nearest_covered = f64::INFINITY;
                let mut covered = vec![false; grid.len()];
                visit(
                    &grid,
                    origin,
                    axis,
                    limit,
                    sonar.footprint(),
                    &mut |i: usize, d_l: f64| {
                        if occluding[i] {
                            nearest_covered = nearest_covered.min(d_l);
                            covered[i] = true;
                        }
                    },
                );
                let reach = sight.max_reach_m(k);
                visit(
                    &grid,
                    origin,
                    axis,
                    reach,
                    sonar.footprint(),
                    &mut |i: usize, d_l: f64| {
                        if !sight.sees(&grid, origin, axis, k, i, d_l) {
                            return;
                        }
                        cleared += 1;
                        past_covered += usize::from(d_l > nearest_covered);
                        let [cx, cy] = grid.cell_center(grid.cell(i));
                        let steps = (d_l / (0.05 * grid.resolution_m())).ceil() as usize;
                        for s in 0..steps {
                            let t = s as f64 / steps as f64;
                            // A covered cell shadows the cells more than half a
                            // cell farther than its centre, which lies at most
                            // half a diagonal beyond its nearest point.
                            if (1.0 - t) * d_l
                                < (0.5 + 0.5 * std::f64::consts::SQRT_2) * grid.resolution_m()
                            {
                                break;
                            }
                            let (x, y) = (
                                origin[0] + t * (cx - origin[0]),
                                origin[1] + t * (cy - origin[1]),
                            );
                            assert!(
                                !covered_at(&covered, x, y),
                                "trial {trial}, beam {k}: ({x}, {y}) on the way to ({cx}, {cy})"
                            );
                        }
                    },
                );
            }
        }
        assert!(cleared > 10_000, "{cleared} cells cleared");
        assert!(
            past_covered > 100,
            "{past_covered} cells cleared beyond a covered cell beside them"
        );
    }

    /// A cell held covered on one echo's evidence is uncertain and does not
    /// stop the no-echo readings that pass it, which clear it and what lies
    /// behind it; the same cell once certain (pinned) stops them.
    #[test]
    fn only_cells_the_map_is_certain_of_occlude() {
        let grid = Grid::new([0.0, 0.0], 0.05, 80, 120).unwrap();
        let sonar = SonarModel::default();
        let limit = sonar.range.max_range_m;
        let mut map = CoverageMap::new(grid);
        // One echo 1.5 m ahead: an arc of cells held covered, uncertain.
        let from = Pose::new(1.0, 2.0, 0.0);
        map.integrate(&from, &[1.5], &[0.0], &sonar).unwrap();
        let arc = grid.world_to_cell(2.5, 2.0).unwrap();
        let i = grid.index(arc).unwrap();
        assert!(f64::from(map.ml()[i]) > CONTACT_COVERAGE);
        assert!(f64::from(map.entropy()[i]) > DEFAULT_EPSILON);
        assert!(!map.occludes(i, DEFAULT_EPSILON));
        let beyond = grid.index(grid.world_to_cell(3.5, 2.0).unwrap()).unwrap();
        let before = map.histograms()[beyond * 16..(beyond + 1) * 16].to_vec();
        // A no-echo reading from the same place clears the arc and beyond.
        let mut cleared = map.clone();
        cleared
            .occluding()
            .integrate(&from, &[limit], &[0.0], &sonar)
            .unwrap();
        assert!(cleared.mean()[i] < map.mean()[i]);
        assert_ne!(
            cleared.histograms()[beyond * 16..(beyond + 1) * 16],
            before[..]
        );
        // Pinned, the cell is certain: it shadows the reading's axis, and
        // the cell behind it stays as it was.
        map.pin_covered(&[arc]).unwrap();
        assert!(map.occludes(i, DEFAULT_EPSILON));
        map.occluding()
            .integrate(&from, &[limit], &[0.0], &sonar)
            .unwrap();
        assert_eq!(map.histograms()[beyond * 16..(beyond + 1) * 16], before[..]);
    }
}
