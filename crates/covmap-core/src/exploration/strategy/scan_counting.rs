//! The paper's extended scan counting (its Table I baseline) on the
//! [`ScanCounts`](crate::ScanCounts).
//!
//! # Counts
//! Every beam intercepts the cells of its footprint up to the end point's
//! cell (`d_l <= d + r/2`; a no-echo reading its whole footprint up to the
//! maximum range) and adds its weight to each: 1, or with a discount range
//! `D`, `min(1, D / d)` for a reading of `d` metres, so that long, less
//! reliable beams count less ([`ScanCounts::weight`](crate::ScanCounts::weight);
//! the paper: "longer beams were discounted", no value given: see
//! [`DEFAULT_DISCOUNT_BEYOND_M`](super::DEFAULT_DISCOUNT_BEYOND_M)). A cell
//! is *explored* once its count reaches `n`; `n = 1` is the classic "visit
//! until everything was seen once".
//!
//! # Choice
//! Scan counting knows a cell once a beam has intercepted it, so the robot
//! navigates as the frontier strategy does, on what the beams have seen:
//! the occupancy grid's known-free cells (and never a cell it ran into),
//! and every cell its centre has driven through (the way back, see the
//! [loop's documentation](crate::exploration)).
//! Its region is the cells it can reach so, and those within the planning
//! radius and one cell of them (the cells its disc touches and the end
//! points' cells: what a count can reach). (On the coverage map a cell one
//! long beam has crossed may still be unknown, and the robot would never
//! pass the doorway of the room it starts in.) Candidates are the cells on
//! the lattice of `candidate_stride_m` where the robot (at the planning
//! radius) fits and which it can reach, at least `min_travel_m` away along
//! the path. The robot goes to the nearest one (by path length; ties to the
//! lower cell index) from which its sensor would intercept at least one
//! unexplored cell of the reachable region (with the robot's heading for a
//! sensor that sees all around, else with the first of eight headings 45
//! degrees apart that would: the robot turns to it at the goal, and a
//! 180-degree laser facing the way it came would intercept nothing new).
//! Interceptions are predicted by
//! tracing every beam in the current ML coverage map (the sensor's forward
//! model, [`reading_distribution`](crate::sensor::reading_distribution)):
//! a beam is taken to read its median predicted reading and to intercept
//! what a reading of that length would.
//!
//! A prediction can be wrong (the ML map is not the world), and a cell only
//! long, discounted beams reach may need far more visits than `n`. When the
//! robot has reached a goal and scanned there, every unexplored cell it went
//! for whose count grew by less than one full interception (and did not
//! reach `n`) has missed once; a cell that has missed three times is given
//! up: no goal is chosen for it again.
//!
//! # Termination
//! [`Termination::NoGoal`]: no candidate would intercept an unexplored cell.

use super::{DecisionInputs, ExplorationStrategy, GoalOutcome, NextGoal, viewpoint_headings};
use crate::error::Result;
use crate::exploration::config::ExplorationConfig;
use crate::exploration::dilation::Dilation;
use crate::exploration::region::{
    blocked_on_occupancy, clearance_offsets, dilation_offsets, open_start, planning_radius_m,
};
use crate::exploration::result::Termination;
use crate::footprint::visit;
use crate::grid::Grid;
use crate::planner::pass_where_driven;
use crate::planner::{Search, SearchMemory, reachable_cells};
use crate::pose::{Pose, check_pose};
use crate::sensor::{SensorModel, trace_readings};

/// Visits that miss a cell after which it is given up.
const GIVE_UP_AFTER: u8 = 3;

/// The scan-counting strategy's state.
pub(crate) struct ScanCounting {
    n: f32,
    /// Visits to each cell that did not count it when the prediction said
    /// they would; at [`GIVE_UP_AFTER`] the cell is given up.
    misses: Vec<u8>,
    /// The cells the last goal was chosen for, and their counts then.
    targets: Vec<(usize, f32)>,
    /// The blocked cells grown by the planning radius: the cells where the
    /// robot is not clear of them, kept from step to step by the cells the
    /// maps changed.
    unclear: Dilation,
    /// The reachable cells grown by the planning radius and a cell: the
    /// region, kept from step to step (a fill of the free space, it can
    /// change far from the cells the maps changed: compared a block at a
    /// time).
    region: Dilation,
    /// The memory of the candidates' searches, kept from step to step.
    search: SearchMemory,
}

impl ScanCounting {
    pub fn new(n: u32, config: &ExplorationConfig, grid: &Grid) -> Self {
        let radius_m = planning_radius_m(config.robot_radius_m, grid);
        Self {
            n: n as f32,
            misses: vec![0; grid.len()],
            targets: Vec::new(),
            unclear: Dilation::new(grid, &clearance_offsets(grid, radius_m)),
            region: Dilation::new(
                grid,
                &dilation_offsets(grid, radius_m + grid.resolution_m()),
            ),
            search: SearchMemory::default(),
        }
    }

    /// The nearest candidate that would intercept an unexplored cell of the
    /// region (see the module documentation). The free space and the region
    /// are kept from the last step and brought up to date with the cells
    /// that changed; the region needs only which cells the robot reaches (a
    /// fill), and the candidates come in the order of their path lengths
    /// (ties to the lower index) from a search that stops at the first one
    /// that would intercept something: the goal and path that sorting every
    /// reachable candidate by the lengths of a whole search gives.
    fn choose(&mut self, view: &DecisionInputs<'_>) -> Result<NextGoal> {
        let grid = view.grid();
        let model = view.model.as_dyn();
        let radius_m = planning_radius_m(view.config.robot_radius_m, grid);
        let blocked = blocked_on_occupancy(view.occupancy, view.contact_cells)?;
        let start = check_pose(grid, &view.pose)?;
        // The blocked cells change only where the maps did (the loop feeds
        // the occupancy grid the coverage map's beams and contacts).
        self.unclear.take_in_cells(view.changed, |i| blocked[i]);
        let unclear = &self.unclear;
        let free = |i: usize| !unclear.covers(i);
        let mut passable: Vec<bool> = (0..grid.len()).map(free).collect();
        open_start(grid, &blocked, radius_m, &view.pose, &mut passable)?;
        pass_where_driven(&mut passable, view.driven);
        self.region
            .take_in(&reachable_cells(grid, &passable, start)?);
        let counts = view.occupancy.counts().counts();
        let (region, misses, n) = (&self.region, &self.misses, self.n);
        let unexplored = |i: usize| region.covers(i) && counts[i] < n && misses[i] < GIVE_UP_AFTER;
        if !(0..grid.len()).any(unexplored) {
            return Ok(NextGoal::Done(Termination::NoGoal));
        }
        let stride =
            ((view.config.candidate_stride_m / grid.resolution_m()).round() as usize).max(1);
        let on_lattice = |i: usize| {
            let (row, col) = (i / grid.cols(), i % grid.cols());
            row >= stride / 2
                && (row - stride / 2).is_multiple_of(stride)
                && col >= stride / 2
                && (col - stride / 2).is_multiple_of(stride)
        };
        let headings = viewpoint_headings(view.bearings, view.pose.theta_rad);
        let memory = std::mem::take(&mut self.search);
        let mut search = Search::with_memory(grid, &passable, start, memory)?;
        let mut goal = None;
        'candidates: while let Some((i, cost_m)) = search.settle_next() {
            if !(on_lattice(i)
                && free(i)
                && cost_m >= view.config.min_travel_m
                && !view.failed_goals.contains(&i))
            {
                continue;
            }
            let [x, y] = grid.cell_center(grid.cell(i));
            for &heading in &headings {
                let pose = Pose::new(x, y, heading);
                let targets = intercepted(grid, view.ml, &pose, view.bearings, model, unexplored);
                if !targets.is_empty() {
                    goal = Some((pose, search.path_to(i), targets));
                    break 'candidates;
                }
            }
        }
        self.search = search.into_memory();
        Ok(match goal {
            Some((pose, path, targets)) => {
                self.targets = targets.into_iter().map(|t| (t, counts[t])).collect();
                NextGoal::Goal { pose, path }
            }
            None => NextGoal::Done(Termination::NoGoal),
        })
    }
}

impl ExplorationStrategy for ScanCounting {
    fn decide(&mut self, inputs: &DecisionInputs<'_>) -> Result<NextGoal> {
        self.choose(inputs)
    }

    fn learn(&mut self, view: &DecisionInputs<'_>, outcome: &GoalOutcome) {
        if !outcome.reached {
            return;
        }
        let counts = view.occupancy.counts().counts();
        for &(cell, before) in &self.targets {
            if counts[cell] < (before + 1.0).min(self.n) {
                self.misses[cell] = self.misses[cell].saturating_add(1);
            }
        }
        self.targets.clear();
    }
}

/// The cells `wanted` holds for that a scan from `pose` would intercept
/// (in increasing index order, each once), predicting each beam's
/// reading as its median reading on the ML map `ml`.
fn intercepted(
    grid: &Grid,
    ml: &[f32],
    pose: &Pose,
    bearings: &[f64],
    model: &dyn SensorModel,
    wanted: impl Fn(usize) -> bool,
) -> Vec<usize> {
    let range = model.range_model();
    let half = 0.5 * grid.resolution_m();
    let mut found = Vec::new();
    for &bearing in bearings {
        let angle = pose.theta_rad + bearing;
        let predicted = trace_readings(
            grid,
            ml,
            [pose.x_m, pose.y_m],
            angle,
            range,
            grid.resolution_m(),
        );
        let mut below = 0.0;
        let median = predicted.probabilities.iter().position(|&p| {
            below += p;
            below >= 0.5
        });
        // As the counts have it: up to the end point's cell, or the whole
        // footprint up to the maximum range for no echo.
        let reach = median.map_or(range.max_range_m, |j| {
            (j as f64 * predicted.step_m + half).min(range.max_range_m)
        });
        visit(
            grid,
            [pose.x_m, pose.y_m],
            angle,
            reach,
            model.footprint(),
            &mut |i: usize, _| {
                if wanted(i) {
                    found.push(i);
                }
            },
        );
    }
    found.sort_unstable();
    found.dedup();
    found
}
