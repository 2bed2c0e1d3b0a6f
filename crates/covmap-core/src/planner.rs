//! The decision-theoretic choice of the next viewpoint (MODEL.md section 4, paper
//! eq. 14), reachability and path costs for a disc robot, and termination.
//!
//! # Traversability
//! A cell is *blocked* when its coverage on the ML map exceeds
//! `blocked_coverage`, and *unknown* while its entropy is at least
//! `unknown_entropy_fraction` of the prior's (a cell at the prior has ML
//! coverage 0, so only this rule keeps unexplored space out of reach). The
//! robot's centre may be at a cell's centre when its disc of
//! `robot_radius_m` there overlaps no blocked cell (and, unless
//! `unknown_is_free`, no unknown cell): the obstacles, whole cells, inflated by
//! the robot's radius. Paths run between cell centres, 8-connected, with
//! Euclidean step lengths (Dijkstra). The robot may also pass through the
//! cells its disc overlaps where it stands that are not blocked themselves,
//! so that a robot too close to an obstacle (as the map now has it) can move
//! away; those cells are goals only if they are free.
//!
//! # Candidates and choice
//! Candidate viewpoints are the reachable free cells on a lattice of
//! `candidate_stride_m`, at least `min_travel_m` away along the path, whose
//! expected information gain exceeds `min_gain_nats` (a negligible gain makes no
//! goal). Of those, the pose maximising
//! `alpha * gain / max gain - (1 - alpha) * cost / max cost` is chosen (ties to
//! the lower cell index). Candidates keep the robot's heading: a full sonar ring
//! sees the same from any heading up to its spacing.
//!
//! # Termination
//! Exploration is done when every cell the robot could reach, passing through
//! unknown space (the cells connected to it through cells not blocked), is
//! either certain (entropy below `epsilon`) or stagnated: its entropy changed by
//! less than 0.001 over its last five measurements ([`CoverageMap::track_history`]).

use std::cmp::Ordering;
use std::collections::BinaryHeap;

use serde::{Deserialize, Serialize};

use crate::coverage_map::CoverageMap;
use crate::error::{CovmapError, Result};
use crate::gain::{GainEvaluator, GainMethod, GainOptions};
use crate::grid::{Cell, Grid};
use crate::scan::{Pose, check_pose};
use crate::sensor::SensorModel;

/// Settings of the planner. See the [module documentation](self).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlannerConfig {
    /// Weight of information against travel, in `[0, 1]`: 0 is greedy
    /// nearest, 1 pure information gain.
    pub alpha: f64,
    /// Radius of the disc robot, metres.
    pub robot_radius_m: f64,
    /// Spacing of the candidate lattice, metres.
    pub candidate_stride_m: f64,
    /// Candidates closer than this along the path are not goals, metres.
    pub min_travel_m: f64,
    /// Candidates whose expected gain is at most this are not goals, nats.
    pub min_gain_nats: f64,
    /// Coverage on the ML map above which a cell blocks the robot.
    pub blocked_coverage: f64,
    /// A cell is unknown while its entropy is at least this fraction of the
    /// prior's (`ln bins`, as the map computes it: in `f32`).
    pub unknown_entropy_fraction: f64,
    /// Whether the robot may plan through unknown cells.
    pub unknown_is_free: bool,
    /// Entropy below which a cell counts as explored, nats (the paper's
    /// epsilon; its Fig. 7 uses 0.65).
    pub epsilon: f64,
    /// Settings of the gain computation.
    pub gain: GainOptions,
}

impl Default for PlannerConfig {
    fn default() -> Self {
        Self {
            alpha: 0.5,
            robot_radius_m: 0.25,
            candidate_stride_m: 0.5,
            min_travel_m: 0.0,
            min_gain_nats: 1.0,
            blocked_coverage: 0.5,
            unknown_entropy_fraction: 0.95,
            unknown_is_free: false,
            epsilon: 0.65,
            gain: GainOptions::default(),
        }
    }
}

impl PlannerConfig {
    /// Errors unless every setting lies in its valid range.
    pub fn validate(&self) -> Result<()> {
        let bad = |name, value, expected| {
            Err(CovmapError::InvalidParameter {
                name,
                value,
                expected,
            })
        };
        if !(0.0..=1.0).contains(&self.alpha) {
            return bad("alpha", self.alpha, "a weight in [0, 1]");
        }
        if !(self.robot_radius_m >= 0.0 && self.robot_radius_m.is_finite()) {
            return bad(
                "robot_radius_m",
                self.robot_radius_m,
                "a non-negative, finite radius",
            );
        }
        if !(self.candidate_stride_m > 0.0 && self.candidate_stride_m.is_finite()) {
            return bad(
                "candidate_stride_m",
                self.candidate_stride_m,
                "a positive, finite spacing",
            );
        }
        if !(self.min_travel_m >= 0.0 && self.min_travel_m.is_finite()) {
            return bad(
                "min_travel_m",
                self.min_travel_m,
                "a non-negative, finite distance",
            );
        }
        if !(self.min_gain_nats >= 0.0 && self.min_gain_nats.is_finite()) {
            return bad(
                "min_gain_nats",
                self.min_gain_nats,
                "a non-negative, finite gain",
            );
        }
        if !(0.0..1.0).contains(&self.blocked_coverage) {
            return bad(
                "blocked_coverage",
                self.blocked_coverage,
                "a coverage in [0, 1)",
            );
        }
        if !(self.unknown_entropy_fraction > 0.0 && self.unknown_entropy_fraction <= 1.0) {
            return bad(
                "unknown_entropy_fraction",
                self.unknown_entropy_fraction,
                "a fraction in (0, 1]",
            );
        }
        if !(self.epsilon > 0.0 && self.epsilon.is_finite()) {
            return bad("epsilon", self.epsilon, "a positive, finite entropy");
        }
        if let Some(step) = self.gain.range_step_m
            && !(step > 0.0 && step.is_finite())
        {
            return bad(
                "gain.range_step_m",
                step,
                "a positive, finite step (at most the grid resolution)",
            );
        }
        Ok(())
    }
}

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

/// Shortest path lengths over the free cells from one start cell.
#[derive(Clone, Debug)]
pub struct Reachability {
    grid: Grid,
    /// Path length to each cell, metres (`inf` where unreachable).
    cost: Vec<f64>,
    /// The previous cell on a shortest path (`usize::MAX` at the start and
    /// unreachable cells).
    previous: Vec<usize>,
}

/// Cells are named by their row-major index on the map's grid
/// ([`Grid::index`]); like a slice, the methods taking an index panic if it is
/// not below [`Grid::len`].
impl Reachability {
    /// Path length to a cell, metres (`inf` where unreachable).
    ///
    /// # Panics
    /// If `index` is not a cell of the grid.
    pub fn cost(&self, index: usize) -> f64 {
        self.cost[index]
    }
    /// All path lengths, row-major.
    pub fn costs(&self) -> &[f64] {
        &self.cost
    }
    /// Whether the cell can be reached.
    ///
    /// # Panics
    /// If `index` is not a cell of the grid.
    pub fn reachable(&self, index: usize) -> bool {
        self.cost[index].is_finite()
    }
    /// The cell centres of a shortest path from the start to `index`.
    ///
    /// # Panics
    /// If `index` is not a cell of the grid.
    pub fn path_to(&self, index: usize) -> Vec<[f64; 2]> {
        if !self.reachable(index) {
            return Vec::new();
        }
        let mut cells = vec![index];
        let mut at = index;
        while self.previous[at] != usize::MAX {
            at = self.previous[at];
            cells.push(at);
        }
        cells
            .iter()
            .rev()
            .map(|&i| self.grid.cell_center(self.grid.cell(i)))
            .collect()
    }
}

/// A heap entry ordered by increasing cost, then index (deterministic ties).
#[derive(PartialEq)]
struct Entry(f64, usize);
impl Eq for Entry {}
impl Ord for Entry {
    fn cmp(&self, other: &Self) -> Ordering {
        other
            .0
            .total_cmp(&self.0)
            .then_with(|| other.1.cmp(&self.1))
    }
}
impl PartialOrd for Entry {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

/// Dijkstra over the 8-connected cells where `passable` holds, from `start`.
pub fn shortest_paths(grid: &Grid, passable: &[bool], start: Cell) -> Result<Reachability> {
    if passable.len() != grid.len() {
        return Err(CovmapError::LengthMismatch {
            what: "passable mask and grid cells",
            left: passable.len(),
            right: grid.len(),
        });
    }
    let start = grid.index(start)?;
    let (rows, cols) = (grid.rows() as i64, grid.cols() as i64);
    let r = grid.resolution_m();
    let mut cost = vec![f64::INFINITY; grid.len()];
    let mut previous = vec![usize::MAX; grid.len()];
    let mut heap = BinaryHeap::new();
    cost[start] = 0.0;
    heap.push(Entry(0.0, start));
    const STEPS: [(i64, i64, f64); 8] = [
        (0, 1, 1.0),
        (1, 0, 1.0),
        (0, -1, 1.0),
        (-1, 0, 1.0),
        (1, 1, std::f64::consts::SQRT_2),
        (1, -1, std::f64::consts::SQRT_2),
        (-1, 1, std::f64::consts::SQRT_2),
        (-1, -1, std::f64::consts::SQRT_2),
    ];
    while let Some(Entry(c, i)) = heap.pop() {
        if c > cost[i] {
            continue;
        }
        let (row, col) = ((i / grid.cols()) as i64, (i % grid.cols()) as i64);
        for &(dr, dc, len) in &STEPS {
            let (nr, nc) = (row + dr, col + dc);
            if nr < 0 || nc < 0 || nr >= rows || nc >= cols {
                continue;
            }
            let n = (nr * cols + nc) as usize;
            // No corner cutting: a diagonal step needs both side cells free.
            if !passable[n]
                || (dr != 0
                    && dc != 0
                    && !(passable[(row * cols + nc) as usize]
                        && passable[(nr * cols + col) as usize]))
            {
                continue;
            }
            let next = c + len * r;
            if next < cost[n] {
                cost[n] = next;
                previous[n] = i;
                heap.push(Entry(next, n));
            }
        }
    }
    Ok(Reachability {
        grid: *grid,
        cost,
        previous,
    })
}

/// The decision-theoretic exploration planner.
///
/// # Example
/// ```
/// use covmap_core::planner::{Planner, PlannerConfig};
/// use covmap_core::{CoverageMap, Grid, Pose, SonarModel};
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
    config: PlannerConfig,
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
            for n in cells_at(grid, i, &offsets) {
                free[n] = false;
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
    fn blocked(&self, map: &CoverageMap, unknown_blocks: bool) -> Vec<bool> {
        // The prior's entropy as the map computes every cell's (in `f32`,
        // a little off `ln bins`), so that a fraction of 1 holds it unknown.
        let prior = vec![1.0 / map.bins() as f32; map.bins()];
        let unknown_entropy =
            self.config.unknown_entropy_fraction * f64::from(crate::histogram::entropy(&prior));
        let ml = map.ml();
        let entropy = map.entropy();
        ml.iter()
            .zip(&entropy)
            .map(|(&c, &h)| {
                f64::from(c) > self.config.blocked_coverage
                    || (unknown_blocks && f64::from(h) >= unknown_entropy)
            })
            .collect()
    }

    /// Shortest paths from `pose` over the robot's free space and the cells
    /// its disc there overlaps that do not block.
    ///
    /// # Errors
    /// [`CovmapError::InvalidPose`] if the pose is not finite,
    /// [`CovmapError::PoseOutsideMap`] if it lies in no cell of the map.
    pub fn reachability(&self, map: &CoverageMap, pose: &Pose) -> Result<Reachability> {
        Ok(self.free_and_reachable(map, pose)?.1)
    }

    /// [`Self::free_space`], and shortest paths from `pose` over it and the
    /// unblocked cells the robot's disc at `pose` overlaps.
    fn free_and_reachable(
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
        for n in cells_at(grid, start_index, &self.disc_offsets(grid)) {
            passable[n] |= !blocked[n];
        }
        let reach = shortest_paths(grid, &passable, start)?;
        Ok((free, reach))
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
        let grid = map.grid();
        let stride =
            ((self.config.candidate_stride_m / grid.resolution_m()).round() as usize).max(1);
        let mut indices = Vec::new();
        for row in (stride / 2..grid.rows()).step_by(stride) {
            for col in (stride / 2..grid.cols()).step_by(stride) {
                let i = row * grid.cols() + col;
                if free[i] && reach.reachable(i) && reach.cost(i) >= self.config.min_travel_m {
                    indices.push(i);
                }
            }
        }
        let poses: Vec<Pose> = indices
            .iter()
            .map(|&i| {
                let [x, y] = grid.cell_center(grid.cell(i));
                Pose::new(x, y, pose.theta_rad)
            })
            .collect();
        let evaluator = GainEvaluator::new(map, model, self.config.gain)?;
        let gains = evaluator.evaluate(&poses, bearings, GainMethod::Fast)?;
        let costs: Vec<f64> = indices.iter().map(|&i| reach.cost(i)).collect();
        let utilities = self.utilities(&gains, &costs)?;
        let chosen = (0..utilities.len())
            .filter(|&k| utilities[k] > f64::NEG_INFINITY)
            .max_by(|&a, &b| {
                utilities[a]
                    .total_cmp(&utilities[b])
                    .then_with(|| b.cmp(&a))
            });
        Ok(Plan {
            pose: chosen.map(|k| poses[k]),
            path: chosen.map_or_else(Vec::new, |k| reach.path_to(indices[k])),
            chosen,
            candidates: Candidates {
                poses,
                gains,
                costs,
                utilities,
            },
        })
    }

    /// Eq. 14 over the candidates worth visiting; `-inf` for the others.
    ///
    /// Errors if `gains` and `costs` differ in length.
    pub fn utilities(&self, gains: &[f64], costs: &[f64]) -> Result<Vec<f64>> {
        if gains.len() != costs.len() {
            return Err(CovmapError::LengthMismatch {
                what: "gains and costs",
                left: gains.len(),
                right: costs.len(),
            });
        }
        let worth = |k: usize| gains[k] > self.config.min_gain_nats;
        let max_gain = (0..gains.len())
            .filter(|&k| worth(k))
            .map(|k| gains[k])
            .fold(0.0, f64::max);
        let max_cost = (0..gains.len())
            .filter(|&k| worth(k))
            .map(|k| costs[k])
            .fold(0.0, f64::max);
        let a = self.config.alpha;
        Ok((0..gains.len())
            .map(|k| {
                if !worth(k) {
                    return f64::NEG_INFINITY;
                }
                let g = if max_gain > 0.0 {
                    gains[k] / max_gain
                } else {
                    0.0
                };
                let c = if max_cost > 0.0 {
                    costs[k] / max_cost
                } else {
                    0.0
                };
                a * g - (1.0 - a) * c
            })
            .collect())
    }

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
        for (i, &h) in entropy.iter().enumerate() {
            if !reach.reachable(i) {
                continue;
            }
            status.reachable_cells += 1;
            if f64::from(h) < self.config.epsilon {
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

/// The cell offsets `(rows, columns)` a blocked cell takes from the robot's
/// free space, for a robot of `radius` cells: the cell itself, and every cell
/// whose centre lies less than `radius` from some point of it (the robot's
/// disc there would overlap it).
fn disc_offsets(radius: f64) -> Vec<(i64, i64)> {
    let reach = (radius + 0.5).ceil() as i64;
    // Distance from a centre `d` cells away to the nearest point of a cell.
    let gap = |d: i64| (d.abs() as f64 - 0.5).max(0.0);
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

/// Row-major indices of the cells at `offsets` from cell `i` that lie on `grid`.
fn cells_at<'o>(
    grid: &Grid,
    i: usize,
    offsets: &'o [(i64, i64)],
) -> impl Iterator<Item = usize> + 'o {
    let (rows, cols) = (grid.rows() as i64, grid.cols() as i64);
    let (row, col) = ((i / grid.cols()) as i64, (i % grid.cols()) as i64);
    offsets.iter().filter_map(move |&(dr, dc)| {
        let (nr, nc) = (row + dr, col + dc);
        (nr >= 0 && nc >= 0 && nr < rows && nc < cols).then_some((nr * cols + nc) as usize)
    })
}

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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sensor::{LaserModel, SonarModel};

    fn ring() -> Vec<f64> {
        (0..24)
            .map(|i| i as f64 * std::f64::consts::TAU / 24.0)
            .collect()
    }

    /// A square room 4 m wide seen from its centre a few times.
    fn room() -> (CoverageMap, Pose) {
        let mut map = CoverageMap::new(Grid::new([0.0, 0.0], 0.05, 160, 160).unwrap());
        let pose = Pose::new(4.0, 4.0, 0.0);
        let sonar = SonarModel::default();
        let bearings = ring();
        let ranges: Vec<f64> = bearings
            .iter()
            .map(|b| 2.0 / b.cos().abs().max(b.sin().abs()))
            .collect();
        for _ in 0..3 {
            map.integrate(&pose, &ranges, &bearings, &sonar).unwrap();
        }
        (map, pose)
    }

    #[test]
    fn dijkstra_lengths() {
        let grid = Grid::new([0.0, 0.0], 1.0, 5, 5).unwrap();
        let mut passable = vec![true; 25];
        passable[2 * 5 + 2] = false;
        let r = shortest_paths(&grid, &passable, Cell { row: 0, col: 0 }).unwrap();
        assert_eq!(r.cost(4), 4.0);
        assert!(
            (r.cost(24) - 4.0 * std::f64::consts::SQRT_2 - 0.0).abs() > 1e-9,
            "the centre is blocked"
        );
        assert!(!r.reachable(12));
        assert_eq!(r.path_to(4).len(), 5);
    }

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
            .filter(|&k| c.gains[k] > config.min_gain_nats)
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

    /// A 3 m square map at 5 cm whose cells in `walls` are certainly covered
    /// (all mass in the last bin) and the others certainly free (all mass in
    /// bin 0) or, with `rest_at_prior`, still at the prior.
    fn walled_map(walls: impl Fn(usize, usize) -> bool, rest_at_prior: bool) -> CoverageMap {
        let grid = Grid::new([0.0, 0.0], 0.05, 60, 60).unwrap();
        let bins = 16;
        let mut data = vec![0.0f32; grid.len() * bins];
        for (i, h) in data.chunks_exact_mut(bins).enumerate() {
            if walls(i / 60, i % 60) {
                h[bins - 1] = 1.0;
            } else if rest_at_prior {
                h.fill(1.0 / bins as f32);
            } else {
                h[0] = 1.0;
            }
        }
        CoverageMap::from_histograms(grid, bins, data).unwrap()
    }

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
            min_gain_nats: 0.0,
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

    #[test]
    fn rejects_bad_config() {
        assert!(
            Planner::new(PlannerConfig {
                alpha: 1.5,
                ..PlannerConfig::default()
            })
            .is_err()
        );
        assert!(
            Planner::new(PlannerConfig {
                candidate_stride_m: 0.0,
                ..PlannerConfig::default()
            })
            .is_err()
        );
        assert!(
            Planner::new(PlannerConfig {
                robot_radius_m: f64::NAN,
                ..PlannerConfig::default()
            })
            .is_err()
        );
        let planner = Planner::new(PlannerConfig::default()).unwrap();
        assert!(matches!(
            planner.utilities(&[2.0, 3.0], &[1.0]),
            Err(CovmapError::LengthMismatch { .. })
        ));
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
