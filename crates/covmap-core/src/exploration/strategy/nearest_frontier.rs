//! Nearest-frontier exploration (Yamauchi 1997, what ROS's explore_lite
//! does) on the [`OccupancyGrid`](crate::OccupancyGrid).
//!
//! # Frontiers
//! A cell is *known* once observed ([`OccupancyGrid::observed`](crate::OccupancyGrid::observed):
//! a beam intercepted it or a contact marked it), *known free* when known
//! with a log-odds below 0. A *frontier cell* is a known-free cell with an
//! unknown 4-neighbour. Frontier cells are grouped by 8-connectivity;
//! groups of fewer cells than the robot's diameter spans
//! (`2 robot_radius_m / resolution`, 10 cells for the defaults) are dropped
//! as too small to matter (explore_lite's `min_frontier_size`: specks the
//! sonar cones leave along walls, not openings a robot could explore).
//!
//! # Choice
//! The robot navigates the occupancy grid: cells not known free block, and
//! the robot's centre keeps the planning radius (the robot's and a cell,
//! at least 5 cm) from every blocked cell, but may always pass the cells it
//! has driven through (the way back, see the
//! [loop's documentation](crate::exploration)). A frontier group is reached
//! from any reachable cell within the planning radius and two cells of one
//! of its cells (the robot cannot stand on the frontier itself: the unknown
//! cells next to it block). The goal is the nearest such cell of the
//! nearest group (by path length, at least `min_travel_m`; ties to the
//! lower cell index). A robot whose sensor does not see all around (a
//! 180-degree laser) faces the frontier cell the goal was chosen for when
//! it scans there.
//!
//! When the robot has reached the goal and scanned there and not one cell
//! of the group stopped being a frontier, the group cannot be explored from
//! where the robot can go: its cells are given up.
//!
//! # Termination
//! [`Termination::NoGoal`]: no reachable frontier group is left.

use super::{DecisionInputs, ExplorationStrategy, GoalOutcome, NextGoal, sees_all_around};
use crate::error::Result;
use crate::exploration::region::{
    blocked_on_occupancy, known_cells, paths_from, planning_radius_m,
};
use crate::exploration::result::Termination;
use crate::grid::Grid;
use crate::pose::Pose;

/// The frontier strategy's state.
pub(crate) struct NearestFrontier {
    given_up: Vec<bool>,
    /// The frontier cells of the last goal's group.
    group: Vec<usize>,
}

impl NearestFrontier {
    pub fn new(grid: &Grid) -> Self {
        Self {
            given_up: vec![false; grid.len()],
            group: Vec::new(),
        }
    }

    fn choose(&mut self, view: &DecisionInputs<'_>) -> Result<NextGoal> {
        let grid = view.grid();
        let radius_m = planning_radius_m(view.config.robot_radius_m, grid);
        let (known, known_free) = known_cells(view.occupancy);
        let blocked = blocked_on_occupancy(view.occupancy, view.contact_cells)?;
        let (free, reach) = paths_from(grid, &blocked, radius_m, &view.pose, view.driven)?;
        let frontier: Vec<bool> = frontier_cells(grid, &known, &known_free)
            .into_iter()
            .zip(&self.given_up)
            .map(|(f, g)| f && !g)
            .collect();
        let min_cells = (2.0 * view.config.robot_radius_m / grid.resolution_m()).ceil() as usize;
        let approach = radius_m + 2.0 * grid.resolution_m();
        let span = (approach / grid.resolution_m()).ceil() as i64;
        let mut best: Option<(f64, usize, [f64; 2], Vec<usize>)> = None;
        for group in groups(grid, &frontier) {
            if group.len() < min_cells {
                continue;
            }
            // The nearest cell the robot may stand on to look at the group.
            let mut nearest: Option<(f64, usize, [f64; 2])> = None;
            for &cell in &group {
                let [fx, fy] = grid.cell_center(grid.cell(cell));
                for goal in cells_near(grid, cell, span) {
                    let [x, y] = grid.cell_center(grid.cell(goal));
                    let cost = reach.cost(goal);
                    let usable = free[goal]
                        && cost.is_finite()
                        && cost >= view.config.min_travel_m
                        && !view.failed_goals.contains(&goal)
                        && (x - fx).hypot(y - fy) <= approach;
                    if usable && nearest.is_none_or(|(c, g, _)| (cost, goal) < (c, g)) {
                        nearest = Some((cost, goal, [fx, fy]));
                    }
                }
            }
            if let Some((cost, goal, seen_from)) = nearest
                && best
                    .as_ref()
                    .is_none_or(|(c, g, _, _)| (cost, goal) < (*c, *g))
            {
                best = Some((cost, goal, seen_from, group));
            }
        }
        let Some((_, goal, [fx, fy], group)) = best else {
            return Ok(NextGoal::Done(Termination::NoGoal));
        };
        self.group = group;
        let [x, y] = grid.cell_center(grid.cell(goal));
        // Facing the frontier cell the goal was chosen for, for a sensor
        // that does not see all around; a ring keeps the robot's heading.
        let heading = if sees_all_around(view.bearings) || (fx == x && fy == y) {
            view.pose.theta_rad
        } else {
            (fy - y).atan2(fx - x)
        };
        Ok(NextGoal::Goal {
            pose: Pose::new(x, y, heading),
            path: reach.path_to(goal),
        })
    }
}

impl ExplorationStrategy for NearestFrontier {
    fn decide(&mut self, inputs: &DecisionInputs<'_>) -> Result<NextGoal> {
        self.choose(inputs)
    }

    fn learn(&mut self, view: &DecisionInputs<'_>, outcome: &GoalOutcome) {
        if !outcome.reached {
            return;
        }
        let (known, known_free) = known_cells(view.occupancy);
        let still = frontier_cells(view.grid(), &known, &known_free);
        if self.group.iter().all(|&i| still[i]) {
            for &i in &self.group {
                self.given_up[i] = true;
            }
        }
        self.group.clear();
    }
}

/// Known-free cells with an unknown 4-neighbour.
fn frontier_cells(grid: &Grid, known: &[bool], known_free: &[bool]) -> Vec<bool> {
    let (rows, cols) = (grid.rows(), grid.cols());
    (0..grid.len())
        .map(|i| {
            let (r, c) = (i / cols, i % cols);
            known_free[i]
                && ((r > 0 && !known[i - cols])
                    || (r + 1 < rows && !known[i + cols])
                    || (c > 0 && !known[i - 1])
                    || (c + 1 < cols && !known[i + 1]))
        })
        .collect()
}

/// The 8-connected groups of flagged cells, each in increasing index order,
/// the groups in the order of their first cells.
fn groups(grid: &Grid, flagged: &[bool]) -> Vec<Vec<usize>> {
    let mut seen = vec![false; flagged.len()];
    let mut out = Vec::new();
    for start in 0..flagged.len() {
        if !flagged[start] || seen[start] {
            continue;
        }
        seen[start] = true;
        let mut group = vec![start];
        let mut next = 0;
        while next < group.len() {
            let at = group[next];
            next += 1;
            for n in cells_near(grid, at, 1) {
                if flagged[n] && !seen[n] {
                    seen[n] = true;
                    group.push(n);
                }
            }
        }
        group.sort_unstable();
        out.push(group);
    }
    out
}

/// The cells within `span` rows and columns of `index` (itself included).
fn cells_near(grid: &Grid, index: usize, span: i64) -> impl Iterator<Item = usize> {
    let (rows, cols) = (grid.rows() as i64, grid.cols() as i64);
    let (row, col) = ((index as i64) / cols, (index as i64) % cols);
    (-span..=span).flat_map(move |dr| {
        (-span..=span).filter_map(move |dc| {
            let (r, c) = (row + dr, col + dc);
            (r >= 0 && c >= 0 && r < rows && c < cols).then_some((r * cols + c) as usize)
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn groups_are_the_connected_components() {
        let grid = Grid::new([0.0, 0.0], 1.0, 5, 6).unwrap();
        let mut flagged = vec![false; grid.len()];
        for i in [0, 7, 14, 4, 5, 29] {
            flagged[i] = true;
        }
        assert_eq!(
            groups(&grid, &flagged),
            vec![vec![0, 7, 14], vec![4, 5], vec![29]]
        );
    }
}
