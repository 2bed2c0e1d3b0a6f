//! Where the disc robot may be and go on a map: the cells that block it, the
//! obstacles inflated by its radius, and the shortest paths from its pose
//! through that free space (see the [module documentation](crate::planner)).

use crate::coverage_map::CoverageMap;
use crate::error::Result;
use crate::grid::{Cell, Grid};
use crate::planner::path::{Reachability, shortest_paths};
use crate::planner::viewpoint::Planner;
use crate::pose::{Pose, check_pose};
use crate::stamp::Stamp;

impl Planner {
    /// Where the robot's centre may be on `map`: see the module documentation.
    pub fn free_space(&self, map: &CoverageMap) -> Vec<bool> {
        let blocked = self.blocked(map, !self.config.unknown_is_free);
        self.free_of(map.grid(), &blocked)
    }

    /// The free space on `grid` around the cells `blocked`.
    fn free_of(&self, grid: &Grid, blocked: &[bool]) -> Vec<bool> {
        let offsets = self.disc_offsets(grid);
        // Every blocked cell takes the cells its disc reaches from the free
        // space; those outside the blocked region are also reached by the
        // disc of a blocked cell on the region's edge (one with a neighbour,
        // of the 8, that does not block): the straight line from a cell to
        // the nearest point of a blocked cell leaves the blocked region
        // through such an edge cell, no farther from the cell, and the disc
        // is decided by that distance alone ([`disc_offsets`]). So a blocked
        // cell whose neighbours all block only takes itself; unknown space,
        // most of a map early on, is one large such region.
        let stamp = Stamp::new(&offsets);
        let mut free: Vec<bool> = blocked.iter().map(|&b| !b).collect();
        for (i, _) in blocked.iter().enumerate().filter(|(_, b)| **b) {
            if cells_at(grid, i, &NEIGHBOURS).all(|n| blocked[n]) {
                continue;
            }
            let cell = grid.cell(i);
            stamp.apply(grid, &mut free, cell.row, cell.col, false);
        }
        free
    }

    /// [`disc_offsets`] for this robot's planning radius on `grid`
    /// ([`Self::planning_radius_m`]). A disc wider than the
    /// grid's diagonal overlaps every cell from anywhere on it, as the disc
    /// of that diagonal does, so the radius is cut to it (the offsets never
    /// outnumber the cells of a grid twice the size).
    fn disc_offsets(&self, grid: &Grid) -> Vec<(i64, i64)> {
        let diagonal = (grid.rows() as f64).hypot(grid.cols() as f64);
        disc_offsets((self.planning_radius_m(grid) / grid.resolution_m()).min(diagonal))
    }

    /// Cells that block: covered above the threshold on the ML map, or, with
    /// `unknown_blocks`, still unknown.
    pub(super) fn blocked(&self, map: &CoverageMap, unknown_blocks: bool) -> Vec<bool> {
        self.blocked_of(map.bins(), &map.ml(), &map.entropy(), unknown_blocks)
    }

    /// [`Self::blocked`] of a map of `bins` bins whose ML map is `ml` and
    /// whose entropy map is `entropy`.
    pub(super) fn blocked_of(
        &self,
        bins: usize,
        ml: &[f32],
        entropy: &[f32],
        unknown_blocks: bool,
    ) -> Vec<bool> {
        // The prior's entropy as the map computes every cell's (in `f32`,
        // a little off `ln bins`), so that a fraction of 1 holds it unknown.
        let prior = vec![1.0 / bins as f32; bins];
        let unknown_entropy =
            self.config.unknown_entropy_fraction * f64::from(crate::histogram::entropy(&prior));
        ml.iter()
            .zip(entropy)
            .map(|(&coverage, &cell_entropy)| {
                f64::from(coverage) > self.config.blocked_coverage
                    || (unknown_blocks && f64::from(cell_entropy) >= unknown_entropy)
            })
            .collect()
    }

    /// Shortest paths from `pose` over the robot's free space and the cells
    /// its disc there overlaps that do not block.
    ///
    /// # Errors
    /// [`CovmapError::InvalidPose`](crate::CovmapError::InvalidPose) if the
    /// pose is not finite,
    /// [`CovmapError::PoseOutsideMap`](crate::CovmapError::PoseOutsideMap) if
    /// it lies in no cell of the map.
    pub fn reachability(&self, map: &CoverageMap, pose: &Pose) -> Result<Reachability> {
        Ok(self.free_and_reachable(map, pose)?.1)
    }

    /// [`Self::free_space`], and shortest paths from `pose` over it and the
    /// unblocked cells the robot's disc at `pose` overlaps.
    pub(super) fn free_and_reachable(
        &self,
        map: &CoverageMap,
        pose: &Pose,
    ) -> Result<(Vec<bool>, Reachability)> {
        self.free_and_reachable_driven(map, pose, None)
    }

    /// [`Self::free_and_reachable`], the cells `driven` (one flag a cell:
    /// where the robot's centre has been) passable whatever the map says
    /// of them (the exploration loop's "way back", see
    /// [`crate::exploration`]).
    pub(crate) fn free_and_reachable_driven(
        &self,
        map: &CoverageMap,
        pose: &Pose,
        driven: Option<&[bool]>,
    ) -> Result<(Vec<bool>, Reachability)> {
        let start = check_pose(map.grid(), pose)?;
        let blocked = self.blocked(map, !self.config.unknown_is_free);
        self.free_and_reachable_of(map.grid(), &blocked, start, driven)
    }

    /// [`Self::free_and_reachable_driven`] on `grid` around the cells
    /// `blocked` (as [`Self::blocked`] finds them for planning), from the
    /// cell `start`.
    pub(super) fn free_and_reachable_of(
        &self,
        grid: &Grid,
        blocked: &[bool],
        start: Cell,
        driven: Option<&[bool]>,
    ) -> Result<(Vec<bool>, Reachability)> {
        let free = self.free_of(grid, blocked);
        let start_index = grid.index(start)?;
        let mut passable = free.clone();
        passable[start_index] = true;
        // The disc overlaps a cell exactly when the cell, inflated, takes in
        // the disc's centre: the same offsets.
        for overlapped in cells_at(grid, start_index, &self.disc_offsets(grid)) {
            passable[overlapped] |= !blocked[overlapped];
        }
        if let Some(driven) = driven {
            pass_where_driven(&mut passable, driven);
        }
        let reach = shortest_paths(grid, &passable, start)?;
        Ok((free, reach))
    }
}

/// Make passable every cell the robot's centre has driven through
/// (`driven`), whatever the map says of it now: the robot fitted there, and
/// the world does not change (see [`crate::exploration`], "The way back").
pub(crate) fn pass_where_driven(passable: &mut [bool], driven: &[bool]) {
    assert_eq!(passable.len(), driven.len(), "one flag a cell");
    for (p, &d) in passable.iter_mut().zip(driven) {
        *p |= d;
    }
}

/// The eight neighbours of a cell, as offsets `(rows, columns)`.
const NEIGHBOURS: [(i64, i64); 8] = [
    (-1, -1),
    (-1, 0),
    (-1, 1),
    (0, -1),
    (0, 1),
    (1, -1),
    (1, 0),
    (1, 1),
];

/// The cell offsets `(rows, columns)` a blocked cell takes from the robot's
/// free space, for a robot of `radius` cells: the cell itself, and every cell
/// whose centre lies less than `radius` from some point of it (the robot's
/// disc there would overlap it). The squared distance is exact (a sum of
/// squared halves of whole numbers), so that a cell nearer than another is
/// in the disc whenever the other is.
fn disc_offsets(radius: f64) -> Vec<(i64, i64)> {
    let reach = (radius + 0.5).ceil() as i64;
    // Distance from a centre `offset` cells away to the nearest point of a cell.
    let gap = |offset: i64| (offset.abs() as f64 - 0.5).max(0.0);
    let mut offsets = Vec::new();
    for dr in -reach..=reach {
        for dc in -reach..=reach {
            if (dr == 0 && dc == 0) || gap(dr) * gap(dr) + gap(dc) * gap(dc) < radius * radius {
                offsets.push((dr, dc));
            }
        }
    }
    offsets
}

/// Row-major indices of the cells at `offsets` from the cell at `index` that
/// lie on `grid`.
fn cells_at<'o>(
    grid: &Grid,
    index: usize,
    offsets: &'o [(i64, i64)],
) -> impl Iterator<Item = usize> + 'o {
    let (rows, cols) = (grid.rows() as i64, grid.cols() as i64);
    let cell = grid.cell(index);
    let (row, col) = (cell.row as i64, cell.col as i64);
    offsets.iter().filter_map(move |&(dr, dc)| {
        let (nr, nc) = (row + dr, col + dc);
        (nr >= 0 && nc >= 0 && nr < rows && nc < cols).then_some((nr * cols + nc) as usize)
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grid::Cell;
    use crate::planner::test_maps::walled_map;
    use crate::planner::{PlannerConfig, PlanningCache};
    use crate::scan_map::ScanMap;
    use crate::sensor::LaserModel;

    /// A cell is free exactly when the disc of the planning radius at its
    /// centre overlaps no blocked cell, checked against the geometry for
    /// radii that are and are not whole numbers of cells.
    #[test]
    fn free_space_is_the_disc_clear_of_blocked_cells() {
        let map = walled_map(|row, col| (row, col) == (30, 30), false);
        let grid = map.grid();
        let wall = Cell { row: 30, col: 30 };
        let [wx0, wy0] = grid.cell_center(wall);
        let half = 0.5 * grid.resolution_m();
        for radius in [0.0, 0.05, 0.12, 0.25, 0.27, 0.29] {
            let planner = Planner::new(PlannerConfig {
                robot_radius_m: radius,
                ..PlannerConfig::default()
            })
            .unwrap();
            let free = planner.free_space(&map);
            let planning = planner.planning_radius_m(grid);
            assert_eq!(planning, radius + 0.05);
            for (i, &f) in free.iter().enumerate() {
                let [x, y] = grid.cell_center(grid.cell(i));
                // Distance from the centre to the nearest point of the blocked cell.
                let gap = ((x - wx0).abs() - half)
                    .max(0.0)
                    .hypot(((y - wy0).abs() - half).max(0.0));
                let clear = grid.cell(i) != wall && gap >= planning;
                // Away from the rounding of `gap == planning` itself.
                if (gap - planning).abs() > 1e-9 {
                    assert_eq!(
                        f,
                        clear,
                        "radius {radius}, cell {:?}, gap {gap}",
                        grid.cell(i)
                    );
                }
            }
        }
    }

    /// A doorway closed on the map behind the robot: the cells its centre
    /// drove through lead back through it (the way back), for the plan's
    /// paths and its cached paths alike; without them the far side is out
    /// of reach.
    #[test]
    fn the_cells_driven_through_lead_back_through_a_doorway_closed_on_the_map() {
        // A wall along column 30 with no gap, the robot west of it.
        let map = walled_map(|_, col| col == 30, false);
        let grid = *map.grid();
        let planner = Planner::new(PlannerConfig::default()).unwrap();
        let pose = Pose::new(0.5, 1.5, 0.0);
        let east = grid.index(Cell { row: 30, col: 50 }).unwrap();
        let (_, shut) = planner
            .free_and_reachable_driven(&map, &pose, None)
            .unwrap();
        assert!(!shut.reachable(east), "the wall closes the east side");
        // The robot drove along row 30 from the west side to the east.
        let driven: Vec<bool> = (0..grid.len())
            .map(|i| grid.cell(i).row == 30 && (10..=50).contains(&grid.cell(i).col))
            .collect();
        let (free, back) = planner
            .free_and_reachable_driven(&map, &pose, Some(&driven))
            .unwrap();
        assert!(back.reachable(east), "the way back");
        let through = grid.index(Cell { row: 30, col: 30 }).unwrap();
        assert!(
            !free[through],
            "the doorway stays out of the free space (no goal there)"
        );
        let mut cache = PlanningCache::default();
        let (cached_free, cached) = planner
            .free_and_reachable_cached(&mut cache, &map, &pose, Some(&driven))
            .unwrap();
        assert_eq!((cached_free, cached.costs()), (free, back.costs()));
    }

    /// Inflating only the blocked region's edge cells takes the same cells
    /// from the free space as inflating every blocked cell, on random
    /// blocked patterns (blobs, scattered cells, the map's border) and radii.
    #[test]
    fn edge_cells_take_what_every_blocked_cell_takes() {
        let mut next = crate::test_rng::uniform(31);
        for trial in 0..12 {
            let density = [0.02, 0.3, 0.7][trial % 3];
            let (cr, cc, blob) = (60.0 * next(), 60.0 * next(), 25.0 * next());
            let picks: Vec<bool> = (0..3600).map(|_| next() < density).collect();
            let map = walled_map(
                |row, col| {
                    let (dr, dc) = (row as f64 - cr, col as f64 - cc);
                    picks[row * 60 + col] || dr.hypot(dc) < blob || col == 0
                },
                false,
            );
            let grid = map.grid();
            for radius in [0.0, 0.05, 0.12, 0.25, 0.31, 0.6] {
                let planner = Planner::new(PlannerConfig {
                    robot_radius_m: radius,
                    unknown_is_free: true,
                    ..PlannerConfig::default()
                })
                .unwrap();
                let blocked = planner.blocked(&map, false);
                let offsets = planner.disc_offsets(grid);
                let mut every = vec![true; grid.len()];
                for (i, _) in blocked.iter().enumerate().filter(|(_, b)| **b) {
                    for covered in cells_at(grid, i, &offsets) {
                        every[covered] = false;
                    }
                }
                assert_eq!(
                    planner.free_space(&map),
                    every,
                    "trial {trial}, radius {radius}"
                );
            }
        }
    }

    /// With `unknown_entropy_fraction = 1`, a cell at the prior is still
    /// unknown, whatever the bin count (the map's `f32` entropy of the prior
    /// lies a little below `ln bins` for some).
    #[test]
    fn a_fraction_of_one_keeps_the_prior_unknown() {
        for bins in [10, 16, 17, 100, 256] {
            let map =
                CoverageMap::with_bins(Grid::new([0.0, 0.0], 0.05, 20, 20).unwrap(), bins).unwrap();
            let config = PlannerConfig {
                unknown_entropy_fraction: 1.0,
                robot_radius_m: 0.0,
                ..PlannerConfig::default()
            };
            let free = Planner::new(config).unwrap().free_space(&map);
            assert!(
                free.iter().all(|&f| !f),
                "{bins} bins: unexplored cells counted free"
            );
        }
    }

    /// A radius far beyond the map blocks the whole map around one blocked
    /// cell, without building a disc of that radius.
    #[test]
    fn a_robot_wider_than_the_map_fits_nowhere_near_an_obstacle() {
        let mut map = CoverageMap::new(Grid::new([0.0, 0.0], 0.05, 40, 40).unwrap());
        let laser = LaserModel::default();
        for _ in 0..20 {
            map.integrate(&Pose::new(0.3, 1.0, 0.0), &[1.2], &[0.0], &laser)
                .unwrap();
        }
        let config = PlannerConfig {
            robot_radius_m: 1e3,
            unknown_is_free: true,
            ..PlannerConfig::default()
        };
        let free = Planner::new(config).unwrap().free_space(&map);
        assert!(free.iter().all(|&f| !f));
        let unblocked = PlannerConfig {
            robot_radius_m: 0.25,
            ..config
        };
        assert!(
            Planner::new(unblocked)
                .unwrap()
                .free_space(&map)
                .iter()
                .any(|&f| f),
            "a small robot fits"
        );
    }
}
