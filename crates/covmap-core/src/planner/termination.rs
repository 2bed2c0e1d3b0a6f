//! When exploration is done: every cell the robot could reach through cells
//! not blocked is certain or has stagnated (see the
//! [module documentation](crate::planner)).

use serde::{Deserialize, Serialize};

use crate::coverage_map::CoverageMap;
use crate::error::Result;
use crate::planner::path::shortest_paths;
use crate::planner::viewpoint::Planner;
use crate::pose::{Pose, check_pose};

/// How far exploration has come.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct ExplorationStatus {
    /// Cells connected to the robot through cells not blocked.
    pub reachable_cells: usize,
    /// Of those, cells with entropy below epsilon.
    pub certain_cells: usize,
    /// Of the rest, cells whose entropy stagnated.
    pub stagnated_cells: usize,
    /// Whether every reachable cell is certain or stagnated.
    pub done: bool,
}

impl Planner {
    /// The exploration status of `map` for a robot at `pose`.
    ///
    /// # Errors
    /// As [`Self::reachability`].
    pub fn status(&self, map: &CoverageMap, pose: &Pose) -> Result<ExplorationStatus> {
        let start = check_pose(map.grid(), pose)?;
        let mut passable: Vec<bool> = self.blocked(map, false).iter().map(|b| !b).collect();
        passable[map.grid().index(start)?] = true;
        let reach = shortest_paths(map.grid(), &passable, start)?;
        let entropy = map.entropy();
        let mut status = ExplorationStatus::default();
        for (i, &cell_entropy) in entropy.iter().enumerate() {
            if !reach.reachable(i) {
                continue;
            }
            status.reachable_cells += 1;
            if f64::from(cell_entropy) < self.config.epsilon {
                status.certain_cells += 1;
            } else if map.stagnated_at(i) {
                status.stagnated_cells += 1;
            }
        }
        status.done = status.reachable_cells > 0
            && status.certain_cells + status.stagnated_cells == status.reachable_cells;
        Ok(status)
    }
}
