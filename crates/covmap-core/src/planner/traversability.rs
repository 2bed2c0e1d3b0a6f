//! Where the disc robot may be and go on a map: the cells that block it, the
//! obstacles inflated by its radius, and the shortest paths from its pose
//! through that free space (see the [module documentation](crate::planner)).

use crate::coverage_map::CoverageMap;
use crate::error::Result;
use crate::grid::Grid;
use crate::planner::path::{Reachability, shortest_paths};
use crate::planner::viewpoint::Planner;
use crate::pose::{Pose, check_pose};

impl Planner {
    /// Where the robot's centre may be on `map`: see the module documentation.
    pub fn free_space(&self, map: &CoverageMap) -> Vec<bool> {
        self.free_and_blocked(map).0
    }

    /// [`Self::free_space`], and the cells that block.
    fn free_and_blocked(&self, map: &CoverageMap) -> (Vec<bool>, Vec<bool>) {
        let grid = map.grid();
        let blocked = self.blocked(map, !self.config.unknown_is_free);
        let offsets = self.disc_offsets(grid);
        let mut free = vec![true; grid.len()];
        for (i, _) in blocked.iter().enumerate().filter(|(_, b)| **b) {
            for covered in cells_at(grid, i, &offsets) {
                free[covered] = false;
            }
        }
        (free, blocked)
    }

    /// [`disc_offsets`] for this robot on `grid`. A disc wider than the
    /// grid's diagonal overlaps every cell from anywhere on it, as the disc
    /// of that diagonal does, so the radius is cut to it (the offsets never
    /// outnumber the cells of a grid twice the size).
    fn disc_offsets(&self, grid: &Grid) -> Vec<(i64, i64)> {
        let diagonal = (grid.rows() as f64).hypot(grid.cols() as f64);
        disc_offsets((self.config.robot_radius_m / grid.resolution_m()).min(diagonal))
    }

    /// Cells that block: covered above the threshold on the ML map, or, with
    /// `unknown_blocks`, still unknown.
    pub(super) fn blocked(&self, map: &CoverageMap, unknown_blocks: bool) -> Vec<bool> {
        // The prior's entropy as the map computes every cell's (in `f32`,
        // a little off `ln bins`), so that a fraction of 1 holds it unknown.
        let prior = vec![1.0 / map.bins() as f32; map.bins()];
        let unknown_entropy =
            self.config.unknown_entropy_fraction * f64::from(crate::histogram::entropy(&prior));
        let ml = map.ml();
        let entropy = map.entropy();
        ml.iter()
            .zip(&entropy)
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
        let start = check_pose(map.grid(), pose)?;
        let grid = map.grid();
        let (free, blocked) = self.free_and_blocked(map);
        let start_index = grid.index(start)?;
        let mut passable = free.clone();
        passable[start_index] = true;
        // The disc overlaps a cell exactly when the cell, inflated, takes in
        // the disc's centre: the same offsets.
        for overlapped in cells_at(grid, start_index, &self.disc_offsets(grid)) {
            passable[overlapped] |= !blocked[overlapped];
        }
        let reach = shortest_paths(grid, &passable, start)?;
        Ok((free, reach))
    }
}

/// The cell offsets `(rows, columns)` a blocked cell takes from the robot's
/// free space, for a robot of `radius` cells: the cell itself, and every cell
/// whose centre lies less than `radius` from some point of it (the robot's
/// disc there would overlap it).
fn disc_offsets(radius: f64) -> Vec<(i64, i64)> {
    let reach = (radius + 0.5).ceil() as i64;
    // Distance from a centre `offset` cells away to the nearest point of a cell.
    let gap = |offset: i64| (offset.abs() as f64 - 0.5).max(0.0);
    let mut offsets = Vec::new();
    for dr in -reach..=reach {
        for dc in -reach..=reach {
            if (dr == 0 && dc == 0) || gap(dr).hypot(gap(dc)) < radius {
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
    use crate::planner::PlannerConfig;
    use crate::planner::test_maps::walled_map;
    use crate::sensor::LaserModel;

    /// A cell is free exactly when the robot's disc at its centre overlaps no
    /// blocked cell, checked against the geometry for radii that are and are
    /// not whole numbers of cells.
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
            for (i, &f) in free.iter().enumerate() {
                let [x, y] = grid.cell_center(grid.cell(i));
                // Distance from the centre to the nearest point of the blocked cell.
                let gap = ((x - wx0).abs() - half)
                    .max(0.0)
                    .hypot(((y - wy0).abs() - half).max(0.0));
                let clear = grid.cell(i) != wall && gap >= radius;
                // Away from the rounding of `gap == radius` itself.
                if (gap - radius).abs() > 1e-9 {
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
