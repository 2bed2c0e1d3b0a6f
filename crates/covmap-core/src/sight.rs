//! What a no-echo reading saw past the obstacles a map holds: its line of
//! sight, sector by sector (see [`NoEchoSight`]).

use std::f64::consts::{PI, SQRT_2, TAU};

use crate::echo_sources::Attributed;
use crate::footprint::{CellVisitor, visit};
use crate::grid::Grid;
use crate::scan_map::ScanBeams;
use crate::sensor::{Footprint, SensorModel};

/// How far each no-echo reading of one scan clears, sector by sector of its
/// footprint ([`NoEchoSight::of_scan`]); the maps take it with the scan
/// ([`ScanBeams::no_echo_sight`]).
///
/// A no-echo reading that crossed a cell the map holds covered, and is
/// certain of ([`CoverageMap::occludes`](crate::CoverageMap::occludes)),
/// missed it (a specular reflection) and says nothing of what lies behind that cell:
/// behind it as seen from the sensor, not behind it anywhere in the cone. A
/// sonar cone aimed at a doorway passes between the jambs: the cells of the
/// opening and of the room beyond lie in no jamb's shadow and are cleared;
/// the cells in a jamb's shadow are not. The cone is cut into sectors as
/// wide as one cell at the maximum range (the finest angle the grid
/// resolves anywhere in the cone); each sector clears up to the nearest
/// covered cell whose circumscribed circle overlaps it (from half a cell
/// before that cell's centre on). A ray is one sector: it clears up to the
/// first covered cell it crosses.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct NoEchoSight {
    /// Sectors a reading.
    sectors: usize,
    /// Half the cone's opening, radians (0 for a ray).
    half_angle_rad: f64,
    /// Reading `k`'s sector `s` at `k * sectors + s`: the farthest centre
    /// distance of a cell the reading clears there, metres.
    reach_m: Vec<f64>,
    /// Reading `k`'s greatest reach over its sectors, metres.
    max_reach_m: Vec<f64>,
    /// Reading `k`'s least reach over its sectors, metres: every cell
    /// nearer is cleared whatever its sector.
    min_reach_m: Vec<f64>,
}

/// `angle` brought into `(-pi, pi]`.
fn wrapped(angle: f64) -> f64 {
    let a = angle % TAU;
    if a > PI {
        a - TAU
    } else if a <= -PI {
        a + TAU
    } else {
        a
    }
}

impl NoEchoSight {
    /// The sight of every reading of `scan`: an echo reading (which the
    /// sight does not limit) and a reading whose footprint holds no cell
    /// `is_covered` clear as far as the scan lets them (its
    /// `no_echo_reach_m`, at most the maximum range); a no-echo reading
    /// stops, in each sector, before the nearest covered cell that shadows
    /// it (see [`NoEchoSight`]).
    pub fn of_scan<M: SensorModel + ?Sized>(
        grid: &Grid,
        scan: &ScanBeams<'_>,
        model: &M,
        is_covered: impl Fn(usize) -> bool,
    ) -> Self {
        let max_range_m = model.range_model().max_range_m;
        let footprint = model.footprint();
        let resolution = grid.resolution_m();
        let half = 0.5 * resolution;
        let (sectors, half_angle_rad) = match footprint {
            Footprint::Cone { half_angle_rad } => (
                ((2.0 * half_angle_rad * max_range_m / resolution).ceil() as usize).max(1),
                half_angle_rad,
            ),
            Footprint::Ray => (1, 0.0),
        };
        let n = scan.ranges.len();
        let mut sight = Self {
            sectors,
            half_angle_rad,
            reach_m: Vec::with_capacity(n * sectors),
            max_reach_m: Vec::with_capacity(n),
            min_reach_m: Vec::with_capacity(n),
        };
        let pose = scan.pose;
        let origin = [pose.x_m, pose.y_m];
        for (k, (&r, &bearing)) in scan.ranges.iter().zip(scan.bearings).enumerate() {
            let given = scan.no_echo_reach_m.map_or(max_range_m, |g| g[k]);
            let cap = max_range_m.min(given);
            let start = sight.reach_m.len();
            sight.reach_m.resize(start + sectors, cap);
            if r >= max_range_m && r.is_finite() && bearing.is_finite() {
                let axis = pose.theta_rad + bearing;
                let row = &mut sight.reach_m[start..];
                visit(
                    grid,
                    origin,
                    axis,
                    cap,
                    footprint,
                    &mut |i: usize, d_l: f64| {
                        // Most cells of a cone do not occlude: that is asked
                        // first, the sectors a cell shadows (two inverse
                        // trigonometric functions) only of those that do.
                        if !is_covered(i) {
                            return;
                        }
                        let reach = (d_l - half).max(0.0);
                        if sectors == 1 {
                            row[0] = row[0].min(reach);
                            return;
                        }
                        let [lo, hi] =
                            sight_sectors(grid, origin, axis, half_angle_rad, sectors, i, d_l);
                        for s in &mut row[lo..=hi] {
                            *s = s.min(reach);
                        }
                    },
                );
            }
            let row = &sight.reach_m[start..];
            sight
                .max_reach_m
                .push(row.iter().copied().fold(0.0, f64::max));
            sight
                .min_reach_m
                .push(row.iter().copied().fold(f64::INFINITY, f64::min));
        }
        sight
    }

    /// How many readings the sight is for.
    pub fn len(&self) -> usize {
        self.max_reach_m.len()
    }

    /// Whether the sight is for no reading.
    pub fn is_empty(&self) -> bool {
        self.max_reach_m.is_empty()
    }

    /// How far reading `k` clears in its farthest sector, metres.
    pub fn max_reach_m(&self, k: usize) -> f64 {
        self.max_reach_m[k]
    }

    /// Whether no-echo reading `k`, from `origin` along `axis`, clears the
    /// cell at row-major `index`, `d_l` metres from the sensor, of a cell its
    /// walk to [`NoEchoSight::max_reach_m`] visits.
    #[inline]
    pub(crate) fn sees(
        &self,
        grid: &Grid,
        origin: [f64; 2],
        axis: f64,
        k: usize,
        index: usize,
        d_l: f64,
    ) -> bool {
        if self.sectors == 1 || d_l <= self.min_reach_m[k] {
            return true;
        }
        let [cx, cy] = grid.cell_center(grid.cell(index));
        let phi = wrapped((cy - origin[1]).atan2(cx - origin[0]) - axis);
        let s = self.sector(phi);
        d_l <= self.reach_m[k * self.sectors + s]
    }

    /// The sector of a direction `phi` radians off the axis.
    fn sector(&self, phi: f64) -> usize {
        sector_of(phi, self.half_angle_rad, self.sectors)
    }
}

/// Visit the cells reading `k` of `scan` (from `scan.pose` along
/// `axis`) updates, out to `reach_m`: its footprint, and for a no-echo
/// reading (`echo` false) of a scan with a sight only the cells that sight
/// clears ([`ScanBeams::no_echo_sight`]), and for an echo reading of a scan
/// with sources only the cells the echo is attributed to
/// ([`ScanBeams::echo_sources`]). What the three maps share.
#[inline(always)]
pub(crate) fn visit_reading(
    grid: &Grid,
    scan: &ScanBeams<'_>,
    k: usize,
    echo: bool,
    reach_m: f64,
    footprint: Footprint,
    f: &mut impl CellVisitor,
) {
    let origin = [scan.pose.x_m, scan.pose.y_m];
    let axis = scan.pose.theta_rad + scan.bearings[k];
    match scan.no_echo_sight {
        Some(sight) if !echo => {
            let reach_m = reach_m.min(sight.max_reach_m(k));
            let mut sighted = Sighted {
                sight,
                grid,
                origin,
                axis,
                k,
                inner: f,
            };
            visit(grid, origin, axis, reach_m, footprint, &mut sighted);
        }
        _ => match scan.echo_sources {
            Some(sources) if echo && !sources.withheld(k).is_empty() => {
                let mut attributed = Attributed::new(sources, k, f);
                visit(grid, origin, axis, reach_m, footprint, &mut attributed);
            }
            _ => visit(grid, origin, axis, reach_m, footprint, f),
        },
    }
}

/// A visitor that passes on only the cells a no-echo reading's sight clears.
struct Sighted<'a, V> {
    sight: &'a NoEchoSight,
    grid: &'a Grid,
    origin: [f64; 2],
    axis: f64,
    k: usize,
    inner: &'a mut V,
}

impl<V: CellVisitor> CellVisitor for Sighted<'_, V> {
    #[inline(always)]
    fn cell(&mut self, index: usize, d_l: f64, enter_m: f64) {
        if self
            .sight
            .sees(self.grid, self.origin, self.axis, self.k, index, d_l)
        {
            self.inner.cell(index, d_l, enter_m);
        }
    }

    #[inline(always)]
    fn done(&self) -> bool {
        self.inner.done()
    }
}

/// The sector of `sectors` across `[-half, half]` that holds `phi`, clamped.
fn sector_of(phi: f64, half: f64, sectors: usize) -> usize {
    let s = ((phi + half) / (2.0 * half) * sectors as f64).floor();
    if s <= 0.0 {
        0
    } else {
        (s as usize).min(sectors - 1)
    }
}

/// The first and last sector a covered cell at row-major `index`, `d_l`
/// metres from `origin`, shadows: every sector its circumscribed circle
/// overlaps.
fn sight_sectors(
    grid: &Grid,
    origin: [f64; 2],
    axis: f64,
    half: f64,
    sectors: usize,
    index: usize,
    d_l: f64,
) -> [usize; 2] {
    let [cx, cy] = grid.cell_center(grid.cell(index));
    let phi = wrapped((cy - origin[1]).atan2(cx - origin[0]) - axis);
    let radius = 0.5 * SQRT_2 * grid.resolution_m();
    if d_l <= radius {
        return [0, sectors - 1];
    }
    let spread = (radius / d_l).asin();
    [
        sector_of(phi - spread, half, sectors),
        sector_of(phi + spread, half, sectors),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pose::Pose;
    use crate::sensor::{LaserModel, SonarModel};

    fn grid() -> Grid {
        Grid::new([0.0, 0.0], 0.05, 160, 160).unwrap()
    }

    /// A scan of the readings `ranges` at `bearings`, with no reach or
    /// sight of its own.
    fn one_reading<'a>(pose: &'a Pose, ranges: &'a [f64], bearings: &'a [f64]) -> ScanBeams<'a> {
        ScanBeams::new(pose, ranges, bearings)
    }

    /// A covered column across part of a cone shadows only the sectors it
    /// blocks: the cone clears beyond it through the rest (a doorway
    /// between two jambs).
    #[test]
    fn a_cone_clears_between_two_covered_jambs() {
        let grid = grid();
        let sonar = SonarModel::default();
        let max = sonar.range.max_range_m;
        let pose = Pose::new(1.0, 4.0, 0.0);
        // Two jambs 2 m ahead, leaving a 0.3 m opening on the axis.
        let jamb = |i: usize| {
            let [x, y] = grid.cell_center(grid.cell(i));
            (2.95..3.05).contains(&x) && (y - 4.0).abs() > 0.15
        };
        let (ranges, bearings) = ([max], [0.0]);
        let scan = one_reading(&pose, &ranges, &bearings);
        let sight = NoEchoSight::of_scan(&grid, &scan, &sonar, jamb);
        let origin = [pose.x_m, pose.y_m];
        let at = |x: f64, y: f64| {
            let c = grid.world_to_cell(x, y).unwrap();
            let i = grid.index(c).unwrap();
            let [cx, cy] = grid.cell_center(c);
            sight.sees(&grid, origin, 0.0, 0, i, (cx - 1.0).hypot(cy - 4.0))
        };
        assert!(at(2.5, 4.0) && at(2.5, 4.2), "in front of the jambs");
        assert!(at(3.5, 4.0) && at(4.5, 4.02), "through the opening");
        assert!(!at(3.5, 4.3) && !at(4.5, 4.5), "behind a jamb");
        assert!(sight.max_reach_m(0) >= max - 1e-9);
        // The same cone with nothing covered clears everything to the
        // maximum range; an echo reading is never limited.
        let open = NoEchoSight::of_scan(&grid, &scan, &sonar, |_| false);
        assert!(open.reach_m.iter().all(|&r| r == max));
        let echo = ScanBeams {
            ranges: &[1.0],
            ..scan
        };
        let echo_sight = NoEchoSight::of_scan(&grid, &echo, &sonar, jamb);
        assert!(echo_sight.reach_m.iter().all(|&r| r == max));
    }

    /// A ray is one sector: it stops before the first covered cell it
    /// crosses, as the reach of its walk.
    #[test]
    fn a_ray_stops_before_its_first_covered_cell() {
        let grid = grid();
        let laser = LaserModel::default();
        let max = laser.range.max_range_m;
        let pose = Pose::new(1.0, 4.0, 0.0);
        let wall = |i: usize| grid.cell(i).col == 60;
        let (ranges, bearings) = ([max], [0.0]);
        let scan = one_reading(&pose, &ranges, &bearings);
        let sight = NoEchoSight::of_scan(&grid, &scan, &laser, wall);
        assert!(
            (sight.max_reach_m(0) - (3.025 - 1.0 - 0.025)).abs() < 1e-9,
            "{}",
            sight.max_reach_m(0)
        );
    }
}
