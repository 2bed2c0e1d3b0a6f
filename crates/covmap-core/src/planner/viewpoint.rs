//! The planner and its choice of the next viewpoint (paper eq. 14): the
//! candidate lattice over the reachable free space, each candidate's expected
//! information gain and path cost, and the utility that weighs them.

use serde::{Deserialize, Serialize};

use crate::coverage_map::CoverageMap;
use crate::error::{CovmapError, Result};
use crate::gain::{GainEvaluator, GainMethod};
use crate::grid::Grid;
use crate::planner::config::{DEFAULT_HEADINGS, MIN_GAIN_FLOOR_NATS, PlannerConfig};
use crate::planner::path::Reachability;
use crate::pose::Pose;

/// The least margin beyond the robot's radius that paths keep from blocked
/// cells, metres ([`Planner::planning_radius_m`]).
pub const FACE_MARGIN_M: f64 = 0.05;
use crate::sensor::SensorModel;

/// Every candidate considered, with its figures.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Candidates {
    /// Candidate poses.
    pub poses: Vec<Pose>,
    /// Expected information gain of each, nats.
    pub gains: Vec<f64>,
    /// Path length from the robot to each, metres.
    pub costs: Vec<f64>,
    /// Eq. 14's utility of each (`-inf` for those that are no goal).
    pub utilities: Vec<f64>,
}

/// The planner's answer.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Plan {
    /// The chosen viewpoint, or `None` when no candidate is worth visiting.
    pub pose: Option<Pose>,
    /// The path to it: cell centres from the robot's cell to the goal's.
    pub path: Vec<[f64; 2]>,
    /// Index of the chosen candidate in `candidates`.
    pub chosen: Option<usize>,
    /// All candidates.
    pub candidates: Candidates,
}

/// The decision-theoretic exploration planner.
///
/// # Example
/// ```
/// use covmap_core::planner::{Planner, PlannerConfig};
/// use covmap_core::{CoverageMap, Grid, Pose, ScanMap, SonarModel};
/// let sonar = SonarModel::default();
/// let bearings: Vec<f64> = (0..24).map(|i| i as f64 * std::f64::consts::TAU / 24.0).collect();
/// let mut map = CoverageMap::new(Grid::new([0.0, 0.0], 0.05, 200, 200).unwrap());
/// let pose = Pose::new(5.0, 5.0, 0.0);
/// map.integrate(&pose, &vec![3.0; 24], &bearings, &sonar).unwrap(); // a round room
/// let planner = Planner::new(PlannerConfig::default()).unwrap();
/// let plan = planner.next_viewpoint(&map, &pose, &bearings, &sonar).unwrap();
/// let goal = plan.pose.unwrap();
/// assert!(((goal.x_m - 5.0).powi(2) + (goal.y_m - 5.0).powi(2)).sqrt() < 3.0); // inside the room
/// assert_eq!(plan.path.first().map(|p| map.grid().world_to_cell(p[0], p[1])), Some(map.grid().world_to_cell(5.0, 5.0)));
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Planner {
    pub(super) config: PlannerConfig,
}

impl Planner {
    /// A planner with `config`.
    ///
    /// # Errors
    /// [`CovmapError::InvalidParameter`] naming the first setting outside its
    /// valid range (see [`PlannerConfig::validate`]).
    pub fn new(config: PlannerConfig) -> Result<Self> {
        config.validate()?;
        Ok(Self { config })
    }

    /// The settings.
    pub fn config(&self) -> &PlannerConfig {
        &self.config
    }

    /// Choose the next viewpoint for a robot at `pose` scanning with beams at
    /// `bearings` through `model` (eq. 14).
    ///
    /// # Errors
    /// As [`Self::reachability`] for the pose; [`CovmapError::InvalidBearing`]
    /// for a bearing that is not finite (or not when added to the heading);
    /// [`CovmapError::InvalidParameter`] for an invalid model or a
    /// `gain.range_step_m` the map's resolution does not allow (see
    /// [`GainEvaluator::new`]).
    pub fn next_viewpoint<M: SensorModel + ?Sized>(
        &self,
        map: &CoverageMap,
        pose: &Pose,
        bearings: &[f64],
        model: &M,
    ) -> Result<Plan> {
        let (free, reach) = self.free_and_reachable(map, pose)?;
        let (cells, poses) = self.candidates(map.grid(), pose, bearings, &free, &reach);
        let evaluator = GainEvaluator::new(map, model, self.config.gain)?;
        let gains = evaluator.evaluate(&poses, bearings, GainMethod::Fast)?;
        self.choose(&reach, &cells, poses, gains, map.bins())
    }

    /// The radius paths keep from blocked cells, metres, on `grid`: the
    /// robot's and a cell, or [`FACE_MARGIN_M`] (5 cm) if that is more
    /// (`robot_radius_m + max(resolution, 0.05)`). A cell less than half
    /// covered reads free on the maps, so an obstacle may reach up to a cell
    /// past the cells that block; a sonar map also holds the first few
    /// centimetres of a wall's face as free or unknown. A wider margin keeps
    /// the robot off walls more often, but sonar arcs narrow every doorway
    /// on the map too: a robot planning 10 cm wider than itself (0.7 m for a
    /// 0.25 m robot) found the 0.9 m doorways of the built-in corridor
    /// closed, and frontier exploration ended in the room it started in.
    pub fn planning_radius_m(&self, grid: &Grid) -> f64 {
        self.config.robot_radius_m + grid.resolution_m().max(FACE_MARGIN_M)
    }

    /// The least gain a candidate must promise to be a goal, nats, on a map
    /// of `bins` bins: `min_gain_nats`, or by default what making one cell
    /// at the prior (entropy `ln bins`) certain (entropy `epsilon`) is
    /// worth, at least [`MIN_GAIN_FLOOR_NATS`] (2.12 nats for 16 bins and
    /// epsilon 0.65).
    pub fn min_gain_nats(&self, bins: usize) -> f64 {
        self.config
            .min_gain_nats
            .unwrap_or_else(|| ((bins as f64).ln() - self.config.epsilon).max(MIN_GAIN_FLOOR_NATS))
    }

    /// The candidate poses for a robot at `pose` with a sensor of
    /// `bearings`, with the cell of each: the reachable free cells of the
    /// lattice at least `min_travel_m` away, each with every heading of
    /// [`Self::headings`], in that order.
    pub(super) fn candidates(
        &self,
        grid: &Grid,
        pose: &Pose,
        bearings: &[f64],
        free: &[bool],
        reach: &Reachability,
    ) -> (Vec<usize>, Vec<Pose>) {
        let stride =
            ((self.config.candidate_stride_m / grid.resolution_m()).round() as usize).max(1);
        let headings = self.headings(pose, bearings);
        let mut cells = Vec::new();
        let mut poses = Vec::new();
        for row in (stride / 2..grid.rows()).step_by(stride) {
            for col in (stride / 2..grid.cols()).step_by(stride) {
                let i = row * grid.cols() + col;
                if free[i] && reach.reachable(i) && reach.cost(i) >= self.config.min_travel_m {
                    let [x, y] = grid.cell_center(grid.cell(i));
                    for &heading in &headings {
                        cells.push(i);
                        poses.push(Pose::new(x, y, heading));
                    }
                }
            }
        }
        (cells, poses)
    }

    /// The headings every candidate position is considered with, for a
    /// robot at `pose` with a sensor of `bearings`: the robot's for
    /// `candidate_headings = 1`, `i * 2 pi / k` for `k > 1`; by default
    /// (`None`) the fixed heading 0 for a sensor that
    /// [sees all around](sees_all_around), else [`DEFAULT_HEADINGS`] fixed
    /// headings.
    pub fn headings(&self, pose: &Pose, bearings: &[f64]) -> Vec<f64> {
        match self.config.candidate_headings {
            Some(1) => vec![pose.theta_rad],
            Some(k) => fixed_headings(k),
            None if sees_all_around(bearings) => fixed_headings(1),
            None => fixed_headings(DEFAULT_HEADINGS),
        }
    }

    /// The plan that eq. 14 chooses among the candidates at `poses` (in
    /// cells `cells`) with expected gains `gains`, for paths `reach`, on a
    /// map of `bins` bins.
    pub(super) fn choose(
        &self,
        reach: &Reachability,
        cells: &[usize],
        poses: Vec<Pose>,
        gains: Vec<f64>,
        bins: usize,
    ) -> Result<Plan> {
        let costs: Vec<f64> = cells.iter().map(|&i| reach.cost(i)).collect();
        let utilities = self.utilities(&gains, &costs, bins)?;
        let chosen = (0..utilities.len())
            .filter(|&k| utilities[k] > f64::NEG_INFINITY)
            .max_by(|&a, &b| {
                utilities[a]
                    .total_cmp(&utilities[b])
                    .then_with(|| b.cmp(&a))
            });
        Ok(Plan {
            pose: chosen.map(|k| poses[k]),
            path: chosen.map_or_else(Vec::new, |k| reach.path_to(cells[k])),
            chosen,
            candidates: Candidates {
                poses,
                gains,
                costs,
                utilities,
            },
        })
    }

    /// Eq. 14 over the candidates worth visiting (a gain above
    /// [`Self::min_gain_nats`] on a map of `bins` bins); `-inf` for the
    /// others.
    ///
    /// Errors if `gains` and `costs` differ in length.
    pub fn utilities(&self, gains: &[f64], costs: &[f64], bins: usize) -> Result<Vec<f64>> {
        if gains.len() != costs.len() {
            return Err(CovmapError::LengthMismatch {
                what: "gains and costs",
                left: gains.len(),
                right: costs.len(),
            });
        }
        let min_gain_nats = self.min_gain_nats(bins);
        let worth = |k: usize| gains[k] > min_gain_nats;
        let max_gain = (0..gains.len())
            .filter(|&k| worth(k))
            .map(|k| gains[k])
            .fold(0.0, f64::max);
        let max_cost = (0..gains.len())
            .filter(|&k| worth(k))
            .map(|k| costs[k])
            .fold(0.0, f64::max);
        let alpha = self.config.alpha;
        Ok((0..gains.len())
            .map(|k| {
                if !worth(k) {
                    return f64::NEG_INFINITY;
                }
                let gain = if max_gain > 0.0 {
                    gains[k] / max_gain
                } else {
                    0.0
                };
                let cost = if max_cost > 0.0 {
                    costs[k] / max_cost
                } else {
                    0.0
                };
                alpha * gain - (1.0 - alpha) * cost
            })
            .collect())
    }
}

/// The widest gap between neighbouring bearings (radians) of a sensor that
/// sees all around: 45 degrees (the 24-sonar ring's is 15).
const ALL_AROUND_GAP_RAD: f64 = std::f64::consts::FRAC_PI_4;

/// Whether no two neighbouring `bearings` (around the circle) are more than
/// 45 degrees apart: a sensor for which the heading of a viewpoint hardly
/// matters.
pub fn sees_all_around(bearings: &[f64]) -> bool {
    widest_gap_rad(bearings) <= ALL_AROUND_GAP_RAD
}

/// The widest gap between neighbouring `bearings` around the circle,
/// radians: `2 pi` for one bearing or none.
pub fn widest_gap_rad(bearings: &[f64]) -> f64 {
    use std::f64::consts::TAU;
    let mut angles: Vec<f64> = bearings.iter().map(|b| b.rem_euclid(TAU)).collect();
    angles.sort_by(f64::total_cmp);
    let (Some(first), Some(last)) = (angles.first(), angles.last()) else {
        return TAU;
    };
    let wrap = first + TAU - last;
    angles
        .windows(2)
        .map(|w| w[1] - w[0])
        .chain([wrap])
        .fold(0.0, f64::max)
}

/// `k` headings evenly around the circle, `i * 2 pi / k` for `i` in
/// `0..k`: the fixed headings a candidate viewpoint (or a strategy's goal)
/// may face.
pub fn fixed_headings(k: usize) -> Vec<f64> {
    (0..k)
        .map(|i| i as f64 * std::f64::consts::TAU / k as f64)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::planner::test_maps::{ring, room, walled_map};
    use crate::sensor::SonarModel;

    #[test]
    fn never_picks_unreachable_or_colliding_poses() {
        let (map, pose) = room();
        let planner = Planner::new(PlannerConfig::default()).unwrap();
        let plan = planner
            .next_viewpoint(&map, &pose, &ring(), &SonarModel::default())
            .unwrap();
        let free = planner.free_space(&map);
        let reach = planner.reachability(&map, &pose).unwrap();
        for p in &plan.candidates.poses {
            let i = map
                .grid()
                .index(map.grid().world_to_cell(p.x_m, p.y_m).unwrap())
                .unwrap();
            assert!(free[i] && reach.reachable(i));
            // Inside the room's walls, minus the robot's radius.
            assert!(
                (p.x_m - 4.0).abs() < 2.0 - 0.2 && (p.y_m - 4.0).abs() < 2.0 - 0.2,
                "{p:?}"
            );
        }
        assert!(plan.pose.is_some());
    }

    #[test]
    fn alpha_extremes() {
        let (map, pose) = room();
        let sonar = SonarModel::default();
        let mut config = PlannerConfig {
            alpha: 0.0,
            min_travel_m: 0.3,
            ..PlannerConfig::default()
        };
        let near = Planner::new(config)
            .unwrap()
            .next_viewpoint(&map, &pose, &ring(), &sonar)
            .unwrap();
        config.alpha = 1.0;
        let far = Planner::new(config)
            .unwrap()
            .next_viewpoint(&map, &pose, &ring(), &sonar)
            .unwrap();
        let c = &near.candidates;
        let worth: Vec<usize> = (0..c.gains.len())
            .filter(|&k| c.gains[k] > Planner::new(config).unwrap().min_gain_nats(16))
            .collect();
        let min_cost = worth
            .iter()
            .map(|&k| c.costs[k])
            .fold(f64::INFINITY, f64::min);
        let max_gain = worth.iter().map(|&k| c.gains[k]).fold(0.0, f64::max);
        assert_eq!(c.costs[near.chosen.unwrap()], min_cost);
        assert_eq!(far.candidates.gains[far.chosen.unwrap()], max_gain);
        assert!(max_gain > c.gains[near.chosen.unwrap()]);
    }

    /// A robot standing too close to a wall may leave, but its own cell is no
    /// goal, and no candidate is.
    #[test]
    fn a_robot_too_close_to_a_wall_never_picks_a_colliding_pose() {
        // A wall along column 40 in unexplored space.
        let map = walled_map(|_, col| col == 40, true);
        // 0.15 m from the wall's face: inside the inflated wall, on the lattice.
        let pose = Pose::new(1.875, 1.875, 0.0);
        let start = map.grid().world_to_cell(pose.x_m, pose.y_m).unwrap();
        let config = PlannerConfig {
            alpha: 0.0,
            candidate_stride_m: 0.25,
            min_gain_nats: Some(0.0),
            unknown_is_free: true,
            ..PlannerConfig::default()
        };
        let planner = Planner::new(config).unwrap();
        let free = planner.free_space(&map);
        assert!(
            !free[map.grid().index(start).unwrap()],
            "the start must lie in the inflated wall"
        );
        let plan = planner
            .next_viewpoint(&map, &pose, &ring(), &SonarModel::default())
            .unwrap();
        for p in &plan.candidates.poses {
            let i = map
                .grid()
                .index(map.grid().world_to_cell(p.x_m, p.y_m).unwrap())
                .unwrap();
            assert!(free[i], "candidate {p:?} collides");
        }
        let goal = plan.pose.expect("free space around");
        assert_ne!(map.grid().world_to_cell(goal.x_m, goal.y_m).unwrap(), start);
        assert_eq!(
            plan.path
                .first()
                .map(|c| map.grid().world_to_cell(c[0], c[1]).unwrap()),
            Some(start)
        );
    }
}
