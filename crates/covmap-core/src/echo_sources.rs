//! Which cells of an echo's arc may have returned it, given the cells a map
//! is certain are covered (see [`EchoSources`]).

use std::f64::consts::FRAC_1_SQRT_2;

use crate::footprint::{CellVisitor, ROW_BLOCK, cells_of_block, visit};
use crate::grid::Grid;
use crate::scan_map::ScanBeams;
use crate::sensor::SensorModel;

/// For each echo reading of one scan, the cells at and past its end point
/// the echo is not attributed to ([`EchoSources::of_scan`]); the maps take
/// it with the scan ([`ScanBeams::echo_sources`]) and leave those cells as
/// they are.
///
/// An echo comes from some cell of the arc at its range, not from every
/// one. Where the arc's end band (the cells whose centres lie within half
/// a cell of the range) holds a cell the map is certain is covered, that
/// cell explains the echo: the echo is attributed to the cells at its
/// bearing (within the angle its circumscribed circle subtends from the
/// sensor) and to every cell the map is certain is covered, and marks no
/// other cell at or past the end band. The cells before the end band are
/// cleared as always: the sound went through them whichever cell returned
/// it. An echo whose end band holds no such cell is not explained and marks
/// its whole arc, as in the paper. So a wall the map has settled keeps
/// answering the echoes off it, and the cells of a doorway beside a
/// settled jamb are not marked by the jamb's echoes.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct EchoSources {
    /// Reading `k`'s withheld cells (row-major indices, sorted) at
    /// `withheld[offsets[k]..offsets[k + 1]]`.
    withheld: Vec<usize>,
    offsets: Vec<usize>,
    /// Reading `k`'s end band starts `from_m[k]` metres from the sensor.
    from_m: Vec<f64>,
}

/// A cell of an echo's arc at or past its end band.
struct Tail {
    index: usize,
    /// The direction of the cell's centre from the sensor, unit length.
    direction: [f64; 2],
    d_l: f64,
    certain: bool,
}

/// A visitor that gathers the cells of an echo's footprint at or past
/// `from` metres, and passes over the blocks of a cone's row that lie
/// wholly before it at once.
struct TailOf<'a, F> {
    grid: &'a Grid,
    origin: [f64; 2],
    from: f64,
    is_certain: &'a F,
    tail: &'a mut Vec<Tail>,
}

impl<F: Fn(usize) -> bool> CellVisitor for TailOf<'_, F> {
    #[inline(always)]
    fn cell(&mut self, index: usize, d_l: f64, _enter_m: f64) {
        if d_l >= self.from {
            let [cx, cy] = self.grid.cell_center(self.grid.cell(index));
            let (dx, dy) = (cx - self.origin[0], cy - self.origin[1]);
            let norm = dx.hypot(dy).max(f64::MIN_POSITIVE);
            self.tail.push(Tail {
                index,
                direction: [dx / norm, dy / norm],
                d_l,
                certain: (self.is_certain)(index),
            });
        }
    }

    #[inline(always)]
    fn row_block(
        &mut self,
        first: usize,
        d: &[f64; ROW_BLOCK],
        n: usize,
        [_, far]: [f64; 2],
        reach_m: f64,
    ) {
        if far >= self.from {
            cells_of_block(self, first, d, n, reach_m);
        }
    }
}

impl EchoSources {
    /// The sources of every echo reading of `scan`, with `is_certain`
    /// naming the cells the map is certain are covered (see
    /// [`EchoSources`]); a no-echo reading, and an echo no certain cell of
    /// its end band explains, withholds nothing. A scan that is not valid
    /// gives sources the maps then refuse or ignore; nothing panics.
    pub fn of_scan<M: SensorModel + ?Sized>(
        grid: &Grid,
        scan: &ScanBeams<'_>,
        model: &M,
        is_certain: impl Fn(usize) -> bool,
    ) -> Self {
        let range = model.range_model();
        let footprint = model.footprint();
        let half = 0.5 * grid.resolution_m();
        let radius = FRAC_1_SQRT_2 * grid.resolution_m();
        let pose = scan.pose;
        let origin = [pose.x_m, pose.y_m];
        let n = scan.ranges.len();
        let mut sources = Self {
            withheld: Vec::new(),
            offsets: Vec::with_capacity(n + 1),
            from_m: Vec::with_capacity(n),
        };
        sources.offsets.push(0);
        let mut tail: Vec<Tail> = Vec::new();
        let mut explainers: Vec<([f64; 2], f64)> = Vec::new();
        for (k, &r) in scan.ranges.iter().enumerate() {
            let bearing = scan.bearings.get(k).copied().unwrap_or(f64::NAN);
            let (reach, echo) = range.reach(r);
            let from = r - half;
            sources.from_m.push(from);
            if echo && r >= 0.0 && bearing.is_finite() && reach.is_finite() {
                tail.clear();
                let mut tail_of = TailOf {
                    grid,
                    origin,
                    from,
                    is_certain: &is_certain,
                    tail: &mut tail,
                };
                visit(
                    grid,
                    origin,
                    pose.theta_rad + bearing,
                    reach,
                    footprint,
                    &mut tail_of,
                );
                // The certain cells of the end band, each with the cosine
                // of the angle its circumscribed circle subtends.
                explainers.clear();
                explainers.extend(tail.iter().filter(|t| t.certain && t.d_l <= r + half).map(
                    |t| {
                        let sin = (radius / t.d_l.max(f64::MIN_POSITIVE)).min(1.0);
                        (t.direction, (1.0 - sin * sin).sqrt())
                    },
                ));
                if !explainers.is_empty() {
                    let start = sources.withheld.len();
                    sources.withheld.extend(
                        tail.iter()
                            .filter(|t| {
                                !t.certain
                                    && !explainers.iter().any(|&(u, cos)| {
                                        u[0] * t.direction[0] + u[1] * t.direction[1] >= cos
                                    })
                            })
                            .map(|t| t.index),
                    );
                    sources.withheld[start..].sort_unstable();
                }
            }
            sources.offsets.push(sources.withheld.len());
        }
        sources
    }

    /// How many readings the sources are for.
    pub fn len(&self) -> usize {
        self.from_m.len()
    }

    /// Whether the sources are for no reading.
    pub fn is_empty(&self) -> bool {
        self.from_m.is_empty()
    }

    /// The cells echo reading `k` is not attributed to (row-major, sorted).
    pub fn withheld(&self, k: usize) -> &[usize] {
        &self.withheld[self.offsets[k]..self.offsets[k + 1]]
    }
}

/// A visitor that passes on every cell of echo reading `k` but those its
/// sources withhold.
pub(crate) struct Attributed<'a, V> {
    withheld: &'a [usize],
    from_m: f64,
    inner: &'a mut V,
}

impl<'a, V> Attributed<'a, V> {
    /// `inner`, told only of the cells echo reading `k` is attributed to.
    #[inline]
    pub(crate) fn new(sources: &'a EchoSources, k: usize, inner: &'a mut V) -> Self {
        Self {
            withheld: sources.withheld(k),
            from_m: sources.from_m[k],
            inner,
        }
    }
}

impl<V: CellVisitor> CellVisitor for Attributed<'_, V> {
    #[inline(always)]
    fn cell(&mut self, index: usize, d_l: f64, enter_m: f64) {
        if d_l < self.from_m || self.withheld.binary_search(&index).is_err() {
            self.inner.cell(index, d_l, enter_m);
        }
    }

    #[inline(always)]
    fn done(&self) -> bool {
        self.inner.done()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::coverage_map::CoverageMap;
    use crate::grid::Cell;
    use crate::log::{Bearings, Log};
    use crate::occupancy::OccupancyGrid;
    use crate::planner::DEFAULT_EPSILON;
    use crate::pose::Pose;
    use crate::scan_map::ScanMap;
    use crate::sensor::SonarModel;

    fn grid() -> Grid {
        Grid::new([0.0, 0.0], 0.05, 80, 80).unwrap()
    }

    fn index(row: usize, col: usize) -> usize {
        grid().index(Cell { row, col }).unwrap()
    }

    /// The sensor of the tests: an echo of 1.2 m straight ahead has its
    /// end band at x = 3.0 m.
    const POSE: Pose = Pose {
        x_m: 1.8,
        y_m: 2.0,
        theta_rad: 0.0,
    };

    /// A jamb the map is certain of in the end band explains the echo:
    /// the cells of the band off its bearing are withheld, the cells at its
    /// bearing and before the band are not; the coverage map and the
    /// occupancy grid leave the withheld cells as they were.
    #[test]
    fn a_certain_jamb_takes_the_echo_from_the_doorway() {
        let sonar = SonarModel::default();
        let mut map = CoverageMap::new(grid());
        map.pin_covered(&[Cell { row: 42, col: 59 }]).unwrap();
        let sources = map
            .read_scan(&POSE, &[1.2], &[0.0], &sonar, DEFAULT_EPSILON)
            .sources;
        assert_eq!(sources.len(), 1);
        let withheld = sources.withheld(0);
        assert!(
            withheld.contains(&index(40, 59)),
            "the doorway's cell on the axis"
        );
        assert!(!withheld.contains(&index(42, 59)), "the jamb itself");
        assert!(
            !withheld.contains(&index(42, 61)),
            "behind the jamb, at its bearing"
        );
        assert!(!withheld.contains(&index(40, 50)), "before the band");
        assert!(withheld.windows(2).all(|w| w[0] < w[1]));

        let beams = ScanBeams {
            echo_sources: Some(&sources),
            ..ScanBeams::new(&POSE, &[1.2], &[0.0])
        };
        let (mut attributed, mut paper) = (map.clone(), map.clone());
        attributed.integrate_scan(beams, &sonar).unwrap();
        paper
            .integrate_scan(ScanBeams::new(&POSE, &[1.2], &[0.0]), &sonar)
            .unwrap();
        let cell = |m: &CoverageMap, i: usize| m.histograms()[i * 16..(i + 1) * 16].to_vec();
        let door = index(40, 59);
        assert_eq!(
            cell(&attributed, door),
            cell(&map, door),
            "withheld: untouched"
        );
        assert_ne!(
            cell(&paper, door),
            cell(&map, door),
            "the paper's echo marks it"
        );
        for i in [index(42, 61), index(40, 50)] {
            assert_eq!(cell(&attributed, i), cell(&paper, i));
        }

        let (mut grid_attributed, mut grid_paper) =
            (OccupancyGrid::new(grid()), OccupancyGrid::new(grid()));
        grid_attributed.integrate_scan(beams, &sonar).unwrap();
        grid_paper
            .integrate_scan(ScanBeams::new(&POSE, &[1.2], &[0.0]), &sonar)
            .unwrap();
        let (a, p) = (grid_attributed.probabilities(), grid_paper.probabilities());
        assert_eq!(a[door], 0.5, "the grid leaves the doorway too");
        assert!(p[door] > 0.5);
        assert_eq!(a[index(40, 50)], p[index(40, 50)]);
    }

    /// A wall the map is certain of across the whole arc explains every
    /// cell of it: nothing is withheld, and the echo marks as the paper's.
    #[test]
    fn a_certain_wall_withholds_nothing() {
        let sonar = SonarModel::default();
        let mut map = CoverageMap::new(grid());
        let wall: Vec<Cell> = (30..51).map(|row| Cell { row, col: 59 }).collect();
        map.pin_covered(&wall).unwrap();
        let sources = map
            .read_scan(&POSE, &[1.2], &[0.0], &sonar, DEFAULT_EPSILON)
            .sources;
        assert!(sources.withheld(0).is_empty());
    }

    /// Nothing certain, or no echo: nothing withheld.
    #[test]
    fn without_a_certain_cell_or_an_echo_nothing_is_withheld() {
        let sonar = SonarModel::default();
        let map = CoverageMap::new(grid());
        let sources = map
            .read_scan(&POSE, &[1.2, 9.0], &[0.0, 1.0], &sonar, DEFAULT_EPSILON)
            .sources;
        assert!(sources.withheld(0).is_empty() && sources.withheld(1).is_empty());
        let mut pinned = map.clone();
        pinned.pin_covered(&[Cell { row: 50, col: 40 }]).unwrap();
        let max = sonar.range_model().max_range_m;
        let sources = pinned
            .read_scan(&POSE, &[max], &[0.0], &sonar, DEFAULT_EPSILON)
            .sources;
        assert!(sources.withheld(0).is_empty());
        // A scan that is not valid gives sources; nothing panics.
        let sources = pinned
            .read_scan(&POSE, &[f64::NAN, -1.0], &[0.0], &sonar, 0.65)
            .sources;
        assert_eq!(sources.len(), 2);
    }

    /// Sources for another number of readings are refused; the map is as
    /// it was.
    #[test]
    fn sources_of_another_scan_are_refused() {
        let sonar = SonarModel::default();
        let mut map = CoverageMap::new(grid());
        let sources = map
            .read_scan(&POSE, &[1.2, 1.0], &[0.0, 1.0], &sonar, 0.65)
            .sources;
        let before = map.histograms().to_vec();
        let beams = ScanBeams {
            echo_sources: Some(&sources),
            ..ScanBeams::new(&POSE, &[1.2], &[0.0])
        };
        assert!(matches!(
            map.integrate_scan(beams, &sonar),
            Err(crate::CovmapError::LengthMismatch { .. })
        ));
        assert_eq!(map.histograms(), &before[..]);
    }

    /// Readings of a 3 x 3 m box with a doorway, from `poses`: an 8-sonar
    /// ring, each reading the distance to the nearest wall along its
    /// bearing (no echo past the maximum range).
    fn box_log(poses: &[Pose], max_range_m: f64) -> Log {
        let bearings: Vec<f64> = (0..8)
            .map(|k| f64::from(k) * std::f64::consts::FRAC_PI_4)
            .collect();
        let mut ranges = Vec::new();
        for p in poses {
            for b in &bearings {
                let (c, s) = ((p.theta_rad + b).cos(), (p.theta_rad + b).sin());
                let mut t = f64::INFINITY;
                // The walls x = 0.5 and x = 3.5 m (a doorway in the latter
                // at y in [1.6, 2.4] m), y = 0.5 and y = 3.5 m.
                for wall in [0.5, 3.5] {
                    let hit = (wall - p.x_m) / c;
                    let y = p.y_m + hit * s;
                    if hit > 0.0 && !(wall == 3.5 && (1.6..=2.4).contains(&y)) {
                        t = t.min(hit);
                    }
                    let hit = (wall - p.y_m) / s;
                    if hit > 0.0 {
                        t = t.min(hit);
                    }
                }
                ranges.push(if t < max_range_m { t } else { max_range_m });
            }
        }
        let times = (0..poses.len()).map(|i| i as f64).collect();
        Log::new(
            poses.to_vec(),
            times,
            ranges,
            Bearings::Fixed(bearings),
            max_range_m,
        )
        .unwrap()
    }

    /// A log read against the map of its echoes gives one map whatever the
    /// order of its scans, but for float rounding.
    #[test]
    fn a_read_log_does_not_depend_on_the_order_of_its_scans() {
        let sonar = SonarModel::default();
        let max = sonar.range_model().max_range_m;
        let poses: Vec<Pose> = (0..80)
            .map(|i| {
                let i = f64::from(i);
                Pose::new(1.0 + 0.02 * i, 1.2 + 0.3 * (i % 5.0), 0.3 * i)
            })
            .collect();
        let reversed: Vec<Pose> = poses.iter().rev().copied().collect();
        let maps = [&poses, &reversed].map(|p| {
            let log = box_log(p, max);
            let mut map = CoverageMap::new(grid());
            map.occluding().integrate_log(&log, &sonar).unwrap();
            map.mean()
        });
        let largest = |a: &[f32], b: &[f32]| {
            a.iter()
                .zip(b)
                .map(|(x, y)| (x - y).abs())
                .fold(0.0f32, f32::max)
        };
        assert!(largest(&maps[0], &maps[1]) < 1e-4);
        let mut paper = CoverageMap::new(grid());
        paper.integrate_log(&box_log(&poses, max), &sonar).unwrap();
        assert!(
            largest(&paper.mean(), &maps[0]) > 0.01,
            "the reading changes the map"
        );
    }
}
