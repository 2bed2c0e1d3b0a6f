//! Where the robot can go on a map, and the region of cells it can reach:
//! the rule behind the coverage strategy's termination and the counting
//! strategy's "known, reachable region".
//!
//! # Planning radius
//! Every strategy plans for a disc one cell wider than the robot, or
//! [`FACE_MARGIN_M`] (5 cm) wider where cells are finer than that: the
//! planner's planning radius ([`Planner::planning_radius_m`], where the
//! reasons are). With one cell, every strategy leaves the start room of
//! the built-in corridor on seeds 0 to 2, and the coverage strategy touches
//! a wall a little more often than with two (33, 21 and 24 contacts
//! against 22, 20 and 18): a contact stops the robot at its last free
//! point and is integrated as evidence, so it costs a step, never a
//! collision (`cargo run --release -p covmap-sim --example table1 --
//! --seeds 3`).
//!
//! # The way back
//! Every strategy may always pass the cells the robot's centre has driven
//! through, whatever its map says of them since: the robot fitted there
//! and the world does not change (a robot's own motion is evidence, as its bumper is; costmaps
//! clear the robot's footprint for the same reason). Without it, a door the
//! robot came through closes behind it on the grid as the end arcs of the
//! readings that catch its jambs pile up, and the baseline ends shut in a
//! room: before this rule, counting to 50 on the corridor, seed 0, stopped
//! after 1330 m with 24.5 % of the evaluation cells uncertain, and on the
//! office, seed 1, after 327 m with 78 %; with it, they end by their rule
//! after 2291.5 m (0.41 %) and 9237.0 m (0.33 %) (`cargo run --release -p
//! covmap-sim --example table1 -- --worlds corridor,office --seeds 2
//! --strategies count50`). The coverage strategy, its termination region
//! and the paths to a goal the caller gives (`Exploration::step_to`) keep
//! the same rule on the coverage map: since no-echo readings clear what
//! their line of sight reaches ([`crate::NoEchoSight`]), the coverage
//! strategy enters gaps that the jambs' end arcs later narrow on the map,
//! and without the rule four of the 26 development runs ended shut in a
//! corner of 144 to 1 220 cells with 3 to 36 % of the evaluation cells
//! uncertain (docs/experiments.md, "The line of sight").
//!
//! # The region
//! The cells the robot's centre can reach through space the coverage map
//! knows to be free (the [`Planner`]'s reachability with unknown cells
//! blocking), plus every cell whose centre lies within the planning radius
//! and the sensor model's end band (`band_m`, the distance behind an end
//! point that a reading still updates) of one of them: the cells the robot's
//! disc and its readings' end bands touch from where it can go.

use crate::coverage_map::CoverageMap;
use crate::error::Result;
use crate::grid::{Cell, Grid};
use crate::occupancy::OccupancyGrid;
use crate::planner::{
    FACE_MARGIN_M, Planner, PlannerConfig, Reachability, pass_where_driven, shortest_paths,
};
use crate::pose::{Pose, check_pose};
use crate::stamp::Stamp;

/// The radius the strategies plan with on `grid` for a robot of
/// `robot_radius_m`: [`Planner::planning_radius_m`].
pub(super) fn planning_radius_m(robot_radius_m: f64, grid: &Grid) -> f64 {
    robot_radius_m + grid.resolution_m().max(FACE_MARGIN_M)
}

/// The planner the strategies navigate the coverage map with (its path
/// costs, its free space), for a robot of `robot_radius_m`.
pub(super) fn navigator(robot_radius_m: f64, alpha: f64) -> Result<Planner> {
    Planner::new(PlannerConfig {
        alpha,
        robot_radius_m,
        ..PlannerConfig::default()
    })
}

/// The region of `map` a robot at `pose` can reach (see the module
/// documentation), one flag a cell, for a planner `navigator` and a sensor
/// whose end band is `band_m` deep.
pub(super) fn reachable_region(
    navigator: &Planner,
    map: &CoverageMap,
    pose: &Pose,
    band_m: f64,
    driven: &[bool],
) -> Result<Vec<bool>> {
    let (_, reach) = navigator.free_and_reachable_driven(map, pose, Some(driven))?;
    Ok(region_of(&reach, map.grid(), navigator, band_m))
}

/// [`reachable_region`] from the paths `reach` of `navigator` on `grid`.
pub(super) fn region_of(
    reach: &Reachability,
    grid: &Grid,
    navigator: &Planner,
    band_m: f64,
) -> Vec<bool> {
    let reachable: Vec<bool> = reach.costs().iter().map(|c| c.is_finite()).collect();
    dilate(grid, &reachable, navigator.planning_radius_m(grid) + band_m)
}

/// `mask` (one flag a cell of `grid`, row-major) grown by `radius_m`: every
/// cell whose centre lies within `radius_m` of the centre of a cell of
/// `mask`. The region's shell (see the [module documentation](crate::exploration)), and a
/// simulation's evaluation cells, are grown so.
///
/// # Panics
/// If `mask` does not hold one flag a cell.
///
/// # Example
/// ```
/// use covmap_core::Grid;
/// use covmap_core::exploration::dilate;
/// let grid = Grid::new([0.0, 0.0], 1.0, 5, 5).unwrap();
/// let mut mask = vec![false; 25];
/// mask[12] = true; // the centre
/// let grown = dilate(&grid, &mask, 1.0);
/// assert_eq!(grown.iter().filter(|&&g| g).count(), 5); // and its 4 neighbours
/// ```
pub fn dilate(grid: &Grid, mask: &[bool], radius_m: f64) -> Vec<bool> {
    grow(grid, mask, &dilation_offsets(grid, radius_m))
}

/// The offsets `(rows, columns)` [`dilate`] grows a mask by on `grid`: the
/// cells whose centres lie within `radius_m` of a cell's.
pub(super) fn dilation_offsets(grid: &Grid, radius_m: f64) -> Vec<(i64, i64)> {
    // A radius of whole cells is not lost to the rounding of the division.
    let radius = radius_m / grid.resolution_m() * (1.0 + 1e-12);
    disc(radius, |dr, dc| {
        ((dr * dr + dc * dc) as f64).sqrt() <= radius
    })
}

/// The cells where a disc of `radius_m` may stand clear of every `blocked`
/// cell: no blocked cell's area lies closer than `radius_m` to the cell's
/// centre (the obstacles, whole cells, inflated by the radius).
pub(super) fn clear_of(grid: &Grid, blocked: &[bool], radius_m: f64) -> Vec<bool> {
    grow(grid, blocked, &clearance_offsets(grid, radius_m))
        .iter()
        .map(|b| !b)
        .collect()
}

/// The offsets `(rows, columns)` a blocked cell takes from the free space
/// of a disc of `radius_m` on `grid` ([`clear_of`]): the cell itself, and
/// the cells whose centres lie closer than `radius_m` to some point of it.
pub(super) fn clearance_offsets(grid: &Grid, radius_m: f64) -> Vec<(i64, i64)> {
    let radius = radius_m / grid.resolution_m();
    // Distance from a centre `offset` cells away to the nearest point of a cell.
    let gap = |offset: i64| (offset.abs() as f64 - 0.5).max(0.0);
    disc(radius, |dr, dc| {
        (dr == 0 && dc == 0) || gap(dr).hypot(gap(dc)) < radius
    })
}

/// Shortest paths from `pose` for a disc of `radius_m` over a map whose
/// cells `blocked` holds: through the cells where the disc is clear, and the
/// unblocked cells its disc at `pose` overlaps (so that a robot standing too
/// close to an obstacle can leave). Returns the clear cells too.
pub(super) fn paths_from(
    grid: &Grid,
    blocked: &[bool],
    radius_m: f64,
    pose: &Pose,
    driven: &[bool],
) -> Result<(Vec<bool>, Reachability)> {
    let start = check_pose(grid, pose)?;
    let free = clear_of(grid, blocked, radius_m);
    let mut passable = free.clone();
    open_start(grid, blocked, radius_m, pose, &mut passable)?;
    pass_where_driven(&mut passable, driven);
    let reach = shortest_paths(grid, &passable, start)?;
    Ok((free, reach))
}

/// Make passable, among the cells `passable` (the clear cells of a map
/// whose cells `blocked` holds, for a disc of `radius_m`), the robot's own
/// cell and the unblocked cells its disc at `pose` overlaps: what
/// [`paths_from`] passes through besides the clear cells.
///
/// # Errors
/// As [`paths_from`] for the pose.
pub(super) fn open_start(
    grid: &Grid,
    blocked: &[bool],
    radius_m: f64,
    pose: &Pose,
    passable: &mut [bool],
) -> Result<()> {
    let start = check_pose(grid, pose)?;
    let start_index = grid.index(start)?;
    passable[start_index] = true;
    // The cells the disc at `pose` overlaps: some point of theirs lies
    // within the radius of the pose.
    let r = grid.resolution_m();
    let span = (radius_m / r).ceil() as i64 + 1;
    let (rows, cols) = (grid.rows() as i64, grid.cols() as i64);
    for dr in -span..=span {
        for dc in -span..=span {
            let (row, col) = (start.row as i64 + dr, start.col as i64 + dc);
            if row < 0 || col < 0 || row >= rows || col >= cols {
                continue;
            }
            let i = (row * cols + col) as usize;
            let [x, y] = grid.cell_center(grid.cell(i));
            let gap = ((pose.x_m - x).abs() - 0.5 * r)
                .max(0.0)
                .hypot(((pose.y_m - y).abs() - 0.5 * r).max(0.0));
            if gap < radius_m {
                passable[i] |= !blocked[i];
            }
        }
    }
    Ok(())
}

/// Which cells of `occupancy` are known (some evidence reached them), and
/// which known free (log-odds below 0).
pub(super) fn known_cells(occupancy: &OccupancyGrid) -> (Vec<bool>, Vec<bool>) {
    let known = occupancy.observed();
    let known_free = known
        .iter()
        .zip(occupancy.log_odds())
        .map(|(&k, &l)| k && l < 0.0)
        .collect();
    (known, known_free)
}

/// The cells that block a robot navigating `occupancy`: every cell not
/// known free, and every cell it ran into (`contact_cells`), whatever the
/// readings say since.
pub(super) fn blocked_on_occupancy(
    occupancy: &OccupancyGrid,
    contact_cells: &[Cell],
) -> Result<Vec<bool>> {
    // Known free is a log-odds below 0, which no unknown cell has (its
    // log-odds is 0): one pass over the log-odds.
    let mut blocked: Vec<bool> = occupancy.log_odds().iter().map(|&l| !(l < 0.0)).collect();
    for &cell in contact_cells {
        blocked[occupancy.grid().index(cell)?] = true;
    }
    Ok(blocked)
}

/// The offsets `(rows, columns)` within `radius` cells for which `keep` holds.
fn disc(radius: f64, keep: impl Fn(i64, i64) -> bool) -> Vec<(i64, i64)> {
    let reach = (radius + 1.0).ceil() as i64;
    let mut offsets = Vec::new();
    for dr in -reach..=reach {
        for dc in -reach..=reach {
            if keep(dr, dc) {
                offsets.push((dr, dc));
            }
        }
    }
    offsets
}

/// `mask` with every cell at `offsets` from an edge cell of it added.
fn grow(grid: &Grid, mask: &[bool], offsets: &[(i64, i64)]) -> Vec<bool> {
    assert_eq!(mask.len(), grid.len(), "one flag a cell");
    // Only the cells on the edge of `mask` are grown: an inner cell's disc
    // lies inside its neighbours'.
    let (rows, cols) = (grid.rows() as i64, grid.cols() as i64);
    let inside = |r: i64, c: i64| r >= 0 && c >= 0 && r < rows && c < cols;
    let stamp = Stamp::new(offsets);
    let mut grown = mask.to_vec();
    for (i, _) in mask.iter().enumerate().filter(|(_, m)| **m) {
        let (row, col) = ((i / grid.cols()) as i64, (i % grid.cols()) as i64);
        let edge = [(0, 1), (1, 0), (0, -1), (-1, 0)].iter().any(|&(dr, dc)| {
            !inside(row + dr, col + dc) || !mask[((row + dr) * cols + col + dc) as usize]
        });
        if edge {
            stamp.apply(grid, &mut grown, row as usize, col as usize, true);
        }
    }
    grown
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::exploration::test_maps::{ROOM, scanned_room};

    /// The region takes in an unexplored doorway (unknown cells within the
    /// shell of where the robot can go) but not the unknown space outside
    /// the walls, nor the far side of a wall beyond its end band.
    #[test]
    fn an_open_doorway_is_in_the_region_the_outside_is_not() {
        let (map, _, pose) = scanned_room(true, 12);
        let grid = *map.grid();
        let navigator = navigator(0.25, 0.5).unwrap();
        let region =
            reachable_region(&navigator, &map, &pose, 0.2, &vec![false; grid.len()]).unwrap();
        let at = |x: f64, y: f64| region[grid.index(grid.world_to_cell(x, y).unwrap()).unwrap()];
        let [x0, y0, x1, y1] = ROOM;
        assert!(at(3.0, 2.5), "the room");
        assert!(at(x1 + 0.12, 2.7), "the doorway");
        assert!(at(x1 + 0.1, 1.5), "the band behind the east wall");
        for (x, y) in [
            (x0 - 0.5, 2.5),
            (3.0, y1 + 0.6),
            (3.0, y0 - 0.8),
            (x1 + 0.8, 1.5),
        ] {
            assert!(!at(x, y), "({x}, {y}) outside the walls");
        }
        let entropy = map.entropy();
        let doorway = grid
            .index(grid.world_to_cell(x1 + 0.12, 2.7).unwrap())
            .unwrap();
        assert!(entropy[doorway] > 2.7, "the doorway is unknown");
    }

    /// A wall whose doorway the map has closed shuts the robot in, unless
    /// it drove through the doorway: then the cells it drove through lead
    /// it back, and only them (a cell beside them stays blocked).
    #[test]
    fn the_cells_driven_through_lead_back_through_a_closed_doorway() {
        let grid = Grid::new([0.0, 0.0], 0.05, 40, 60).unwrap();
        // A wall across column 30, the doorway (rows 15 to 24) closed on the map.
        let blocked: Vec<bool> = (0..grid.len()).map(|i| i % 60 == 30).collect();
        let pose = Pose::new(0.5, 1.0, 0.0);
        let beyond = grid.index(grid.world_to_cell(2.5, 0.5).unwrap()).unwrap();
        let none = vec![false; grid.len()];
        let (_, shut) = paths_from(&grid, &blocked, 0.3, &pose, &none).unwrap();
        assert!(
            shut.cost(beyond).is_infinite(),
            "the wall shuts the robot in"
        );
        // The robot came along row 20 from the far side.
        let driven: Vec<bool> = (0..grid.len())
            .map(|i| i / 60 == 20 && i % 60 >= 10)
            .collect();
        let (free, back) = paths_from(&grid, &blocked, 0.3, &pose, &driven).unwrap();
        assert!(back.cost(beyond).is_finite(), "the way it came leads back");
        let through = grid
            .index(grid.world_to_cell(1.525, 1.025).unwrap())
            .unwrap();
        assert!(
            driven[through] && !free[through],
            "through a cell the map blocks"
        );
        let beside = grid
            .index(grid.world_to_cell(1.525, 0.925).unwrap())
            .unwrap();
        assert!(
            back.cost(beside).is_infinite(),
            "a cell beside it stays blocked"
        );
    }

    /// Growing only the edge cells gives the same set as growing every cell.
    #[test]
    fn dilation_from_the_edge_equals_dilation_from_every_cell() {
        let grid = Grid::new([0.0, 0.0], 0.05, 30, 40).unwrap();
        let mask: Vec<bool> = (0..grid.len())
            .map(|i| {
                let (r, c) = (i / 40, i % 40);
                (5..20).contains(&r) && (8..30).contains(&c) && !(r == 12 && c > 20)
            })
            .collect();
        for radius_m in [0.0, 0.05, 0.12, 0.3] {
            let grown = dilate(&grid, &mask, radius_m);
            for (i, &g) in grown.iter().enumerate() {
                let [x, y] = grid.cell_center(grid.cell(i));
                let near = mask.iter().enumerate().any(|(j, &m)| {
                    let [u, v] = grid.cell_center(grid.cell(j));
                    m && (x - u).hypot(y - v) <= radius_m + 1e-9
                });
                assert_eq!(g, near, "radius {radius_m}, cell {i}");
            }
        }
    }

    /// A cell is clear exactly when no blocked cell's area lies within the
    /// radius of its centre.
    #[test]
    fn clear_cells_keep_the_radius_from_every_blocked_cell() {
        let grid = Grid::new([0.0, 0.0], 0.05, 20, 20).unwrap();
        let mut blocked = vec![false; grid.len()];
        blocked[10 * 20 + 10] = true;
        blocked[3 * 20 + 15] = true;
        let radius_m = 0.17;
        let free = clear_of(&grid, &blocked, radius_m);
        for (i, &f) in free.iter().enumerate() {
            let [x, y] = grid.cell_center(grid.cell(i));
            let clear = blocked.iter().enumerate().all(|(j, &b)| {
                let [u, v] = grid.cell_center(grid.cell(j));
                let gap = ((x - u).abs() - 0.025)
                    .max(0.0)
                    .hypot(((y - v).abs() - 0.025).max(0.0));
                !b || (j != i && gap >= radius_m)
            });
            assert_eq!(f, clear, "cell {i}");
        }
    }
}
