//! What the true world says about a run before it starts: where a disc
//! robot fits, where it may start, and which cells it is judged on.
//!
//! # Evaluation cells
//! The cells a robot could observe, from the true world alone and the same
//! for every strategy: the *reachable free space* (the cells whose centre
//! lies at least the robot's radius from every obstacle, connected to the
//! start's cell through such cells, 8-connected without cutting corners, as
//! the planner's paths are) and every cell whose centre lies within the
//! robot's radius and the sensor model's end band (`band_m`) of one of them
//! ([`dilate`]) and holds some obstacle (true coverage above 0): the cells
//! the robot's disc touches, and the obstacle cells behind a face that a
//! reading ending on the face still updates. Free cells behind an obstacle
//! (the outside of a building behind its walls, a room behind a glass
//! front) are not among them, though the end band of a reading on the
//! obstacle reaches them: no sensor sees them, and the model's end band
//! holds them as partly covered whatever they are, so no strategy could
//! make them certain or right.
//!
//! # The start
//! Without a given start, the robot starts in the *start region*: of the
//! connected regions of cells where its disc fits ([`free_regions`]), the
//! one holding the most *enclosed* cells: cells from which, in each of the
//! grid's eight directions (along the rows, the columns and both
//! diagonals), a cell where the disc does not fit lies before the grid's
//! border ([`enclosed_cells`]). The margin around a world, the outside of a
//! building (connected to its inside through an outer door or a gap in a
//! plan's walls), a map's free space beyond its walls are not enclosed; a
//! building's rooms and corridors are (but for the cells that look out
//! straight through an outer door). Where no region holds an enclosed cell
//! (an open world, a single obstacle) the start region is the largest.
//!
//! The robot starts at the centre of a cell drawn uniformly from the
//! enclosed cells of the start region whose centre keeps twice the robot's
//! radius from every obstacle (a clearance well above the radius: room to
//! turn and scan), or where none does from the start region's enclosed
//! cells, or from all its cells; facing a heading drawn uniformly from
//! `[-pi, pi)`; both draws come from stream [`START_STREAM`] of the run's
//! seed.
//!
//! On a world read from an occupancy image whose unknown pixels are
//! obstacles ([`crate::load::image`]) the start region is thus the largest
//! free region that the image's known free pixels enclose.

use covmap_core::exploration::dilate;
use covmap_core::planner::shortest_paths;
use covmap_core::{CovmapError, Grid, Pose};
use rand::RngExt;

use crate::error::Result;
use crate::rng::sim_rng_stream;
use crate::robot::Robot;
use crate::world::World;

/// The stream of the run's seed the start is drawn from (the scans use
/// streams 0, 1, 2, ...).
pub const START_STREAM: u64 = u64::MAX;

/// The gap between the disc at each cell's centre and the nearest obstacle,
/// metres, row-major ([`Robot::clearance_m`]): at least 0 where the robot
/// fits.
pub fn clearances(world: &World, grid: &Grid, robot: &Robot) -> Vec<f64> {
    let rows = covmap_core::parallel::map((0..grid.rows()).collect(), |row| {
        (0..grid.cols())
            .map(|col| robot.clearance_m(world, grid.cell_center(covmap_core::Cell { row, col })))
            .collect::<Vec<f64>>()
    });
    rows.concat()
}

/// The evaluation cells of a run from `start` (see the module
/// documentation), given the [`clearances`] of the robot on `grid`.
///
/// # Errors
/// As [`shortest_paths`], for a start off the grid.
pub fn evaluation_cells(
    grid: &Grid,
    clearance_m: &[f64],
    truth: &[f64],
    start: &Pose,
    robot_radius_m: f64,
    band_m: f64,
) -> Result<Vec<bool>> {
    if truth.len() != grid.len() {
        return Err(CovmapError::LengthMismatch {
            what: "true coverage and grid cells",
            left: truth.len(),
            right: grid.len(),
        }
        .into());
    }
    let start_cell = cell_of(grid, start)?;
    let mut free: Vec<bool> = clearance_m.iter().map(|&c| c >= 0.0).collect();
    free[grid.index(start_cell)?] = true;
    let reach = shortest_paths(grid, &free, start_cell)?;
    let reachable: Vec<bool> = reach.costs().iter().map(|c| c.is_finite()).collect();
    let touched = dilate(grid, &reachable, robot_radius_m);
    let banded = dilate(grid, &reachable, robot_radius_m + band_m);
    Ok(touched
        .iter()
        .zip(&banded)
        .zip(truth)
        .map(|((&touched, &banded), &coverage)| touched || (banded && coverage > 0.0))
        .collect())
}

/// The cells of the start region (see the module documentation), in
/// increasing index order, given the [`clearances`] of the robot on `grid`,
/// and which of all cells are enclosed ([`enclosed_cells`]): empty where
/// the robot fits nowhere.
pub fn start_region(grid: &Grid, clearance_m: &[f64]) -> (Vec<usize>, Vec<bool>) {
    let free: Vec<bool> = clearance_m.iter().map(|&c| c >= 0.0).collect();
    let enclosed = enclosed_cells(grid, &free);
    let regions = free_regions(grid, &free);
    let score = |r: &Vec<usize>| {
        let inside = r.iter().filter(|&&i| enclosed[i]).count();
        (inside, if inside == 0 { r.len() } else { 0 })
    };
    // The most enclosed cells; without any, the most cells; ties to the
    // region of the lowest first cell.
    let best = regions
        .iter()
        .fold(None::<(&Vec<usize>, (usize, usize))>, |best, r| {
            let s = score(r);
            match best {
                Some((_, b)) if b >= s => best,
                _ => Some((r, s)),
            }
        });
    (best.map(|(r, _)| r.clone()).unwrap_or_default(), enclosed)
}

/// Which cells are enclosed: from each, in each of the grid's eight
/// directions, a cell that is not `free` lies before the grid's border.
pub fn enclosed_cells(grid: &Grid, free: &[bool]) -> Vec<bool> {
    let (rows, cols) = (grid.rows() as i64, grid.cols() as i64);
    let mut enclosed = vec![true; free.len()];
    let mut blocked = vec![false; free.len()];
    for (dr, dc) in [
        (0i64, 1i64),
        (0, -1),
        (1, 0),
        (-1, 0),
        (1, 1),
        (1, -1),
        (-1, 1),
        (-1, -1),
    ] {
        // Walk each cell after the one it looks at (`blocked` of the cell
        // one step in the direction is known first): rows and columns in
        // the order opposite to the direction.
        let row_order: Vec<i64> = if dr > 0 {
            (0..rows).rev().collect()
        } else {
            (0..rows).collect()
        };
        let col_order: Vec<i64> = if dc > 0 {
            (0..cols).rev().collect()
        } else {
            (0..cols).collect()
        };
        for &r in &row_order {
            for &c in &col_order {
                let (nr, nc) = (r + dr, c + dc);
                let i = (r * cols + c) as usize;
                blocked[i] = if nr < 0 || nc < 0 || nr >= rows || nc >= cols {
                    false
                } else {
                    let n = (nr * cols + nc) as usize;
                    !free[n] || blocked[n]
                };
                enclosed[i] &= blocked[i];
            }
        }
    }
    enclosed
}

/// A start for a run seeded `seed` (see the module documentation).
///
/// # Errors
/// [`CovmapError::InvalidStart`] if the robot fits nowhere on the grid.
pub fn choose_start(
    grid: &Grid,
    clearance_m: &[f64],
    robot_radius_m: f64,
    seed: u64,
) -> Result<Pose> {
    let (region, enclosed) = start_region(grid, clearance_m);
    let inside: Vec<usize> = region.iter().copied().filter(|&i| enclosed[i]).collect();
    let roomy: Vec<usize> = inside
        .iter()
        .copied()
        .filter(|&i| clearance_m[i] >= robot_radius_m)
        .collect();
    let cells = [roomy, inside, region]
        .into_iter()
        .find(|c| !c.is_empty())
        .unwrap_or_default();
    if cells.is_empty() {
        let [x, y, ..] = grid.bounds_m();
        return Err(CovmapError::InvalidStart {
            x,
            y,
            reason: "the robot fits nowhere on the grid".into(),
        }
        .into());
    }
    let mut rng = sim_rng_stream(seed, START_STREAM);
    let cell = cells[rng.random_range(0..cells.len())];
    let heading = rng.random_range(-std::f64::consts::PI..std::f64::consts::PI);
    let [x, y] = grid.cell_center(grid.cell(cell));
    Ok(Pose::new(x, y, heading))
}

/// Errors unless the robot can start at `start`: inside the grid, its disc
/// clear of every obstacle of `world`.
///
/// # Errors
/// [`CovmapError::InvalidPose`] or [`CovmapError::PoseOutsideMap`] off the
/// grid; [`CovmapError::InvalidStart`] in (or touching) an obstacle.
pub fn check_start(world: &World, grid: &Grid, robot: &Robot, start: &Pose) -> Result<()> {
    start.check_finite()?;
    cell_of(grid, start)?;
    let clearance = robot.clearance_m(world, [start.x_m, start.y_m]);
    if clearance <= 0.0 {
        return Err(CovmapError::InvalidStart {
            x: start.x_m,
            y: start.y_m,
            reason: format!(
                "the robot's disc of radius {} m overlaps an obstacle (clearance {clearance} m)",
                robot.radius_m()
            ),
        }
        .into());
    }
    Ok(())
}

/// The cell of `pose` on `grid`, or [`CovmapError::PoseOutsideMap`].
fn cell_of(grid: &Grid, pose: &Pose) -> Result<covmap_core::Cell> {
    grid.world_to_cell(pose.x_m, pose.y_m).ok_or_else(|| {
        let [x_min, y_min, x_max, y_max] = grid.bounds_m();
        CovmapError::PoseOutsideMap {
            x: pose.x_m,
            y: pose.y_m,
            x_min,
            x_max,
            y_min,
            y_max,
        }
        .into()
    })
}

/// The 8-connected regions of `free` cells (a diagonal step needs both
/// side cells free, as the planner's paths do), each in increasing index
/// order, the regions in the order of their first cell.
pub fn free_regions(grid: &Grid, free: &[bool]) -> Vec<Vec<usize>> {
    let (rows, cols) = (grid.rows() as i64, grid.cols() as i64);
    let mut seen = vec![false; free.len()];
    let mut regions = Vec::new();
    for first in 0..free.len() {
        if !free[first] || seen[first] {
            continue;
        }
        seen[first] = true;
        let mut region = vec![first];
        let mut next = 0;
        while next < region.len() {
            let at = region[next] as i64;
            next += 1;
            let (row, col) = (at / cols, at % cols);
            for (dr, dc) in [
                (0, 1),
                (1, 0),
                (0, -1),
                (-1, 0),
                (1, 1),
                (1, -1),
                (-1, 1),
                (-1, -1),
            ] {
                let (r, c) = (row + dr, col + dc);
                if r < 0 || c < 0 || r >= rows || c >= cols {
                    continue;
                }
                let n = (r * cols + c) as usize;
                let corner_free = dr == 0
                    || dc == 0
                    || (free[(row * cols + c) as usize] && free[(r * cols + col) as usize]);
                if free[n] && !seen[n] && corner_free {
                    seen[n] = true;
                    region.push(n);
                }
            }
        }
        region.sort_unstable();
        regions.push(region);
    }
    regions
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small closed room beside a large open yard: the start lies in
    /// the room (the region the world encloses), not in the larger region
    /// around it that reaches the grid's border; a world that encloses
    /// nothing starts in its largest region.
    #[test]
    fn the_start_lies_in_the_region_the_world_encloses() {
        let mut walls = vec![
            vec![[0.0, 0.0], [3.0, 0.0], [3.0, 0.1], [0.0, 0.1]],
            vec![[0.0, 2.9], [3.0, 2.9], [3.0, 3.0], [0.0, 3.0]],
            vec![[0.0, 0.0], [0.1, 0.0], [0.1, 3.0], [0.0, 3.0]],
            vec![[2.9, 0.0], [3.0, 0.0], [3.0, 3.0], [2.9, 3.0]],
        ];
        // A post far away stretches the grid: the yard around the room is
        // far larger than the room.
        walls.push(vec![[20.0, 20.0], [20.1, 20.0], [20.1, 20.1], [20.0, 20.1]]);
        let world = World::from_vertex_lists(walls.clone(), crate::Material::Wall).unwrap();
        let grid = Grid::covering(-0.5, -0.5, 20.6, 20.6, 0.1).unwrap();
        let robot = Robot::new(0.25).unwrap();
        let clearance = clearances(&world, &grid, &robot);
        for seed in 0..5 {
            let start = choose_start(&grid, &clearance, 0.25, seed).unwrap();
            assert!(start.x_m > 0.1 && start.x_m < 2.9 && start.y_m > 0.1 && start.y_m < 2.9);
        }
        let open = World::from_vertex_lists(walls[..3].to_vec(), crate::Material::Wall).unwrap();
        let clearance = clearances(&open, &grid, &robot);
        let (region, _) = start_region(&grid, &clearance);
        assert!(region.len() > 40_000, "{}", region.len());
    }

    #[test]
    fn the_start_lies_in_the_largest_region_with_room() {
        let world = World::builtin("corridor").unwrap();
        let [x0, y0, x1, y1] = world.bounds_m();
        let grid = Grid::covering(x0 - 0.5, y0 - 0.5, x1 + 0.5, y1 + 0.5, 0.05).unwrap();
        let robot = Robot::new(0.25).unwrap();
        let clearance = clearances(&world, &grid, &robot);
        let mut starts = Vec::new();
        for seed in 0..5 {
            let start = choose_start(&grid, &clearance, 0.25, seed).unwrap();
            assert!(robot.clearance_m(&world, [start.x_m, start.y_m]) >= 0.25 - 1e-9);
            // Inside the building, not in the margin outside it.
            assert!(start.x_m > 0.0 && start.x_m < 17.0 && start.y_m > 0.0 && start.y_m < 6.2);
            check_start(&world, &grid, &robot, &start).unwrap();
            starts.push(start);
        }
        assert_eq!(starts[0], choose_start(&grid, &clearance, 0.25, 0).unwrap());
        assert_ne!(starts[0], starts[1]);
        let truth = world.coverage(&grid);
        let cells = evaluation_cells(&grid, &clearance, &truth, &starts[0], 0.25, 0.2).unwrap();
        let at = |x: f64, y: f64| grid.index(grid.world_to_cell(x, y).unwrap()).unwrap();
        let (inside, outside) = (at(8.0, 1.3), at(-0.45, 1.3));
        assert!(cells[inside] && !cells[outside]);
        // The west wall (x in [-0.12, 0]) is judged; the free cell just
        // behind it, within the end band of the free space, is not.
        let (wall, behind) = (at(-0.06, 1.3), at(-0.17, 1.3));
        assert!(truth[wall] > 0.9 && truth[behind] == 0.0);
        assert!(cells[wall] && !cells[behind]);
        assert!(evaluation_cells(&grid, &clearance, &truth[1..], &starts[0], 0.25, 0.2).is_err());
        assert!(check_start(&world, &grid, &robot, &Pose::new(2.0, 0.1, 0.0)).is_err());
        assert!(check_start(&world, &grid, &robot, &Pose::new(-5.0, 1.3, 0.0)).is_err());
    }
}
