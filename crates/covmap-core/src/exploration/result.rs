//! What a run reports: how it ended, where the robot went, what each step
//! did, where the time went, and the maps it built.

use serde::{Deserialize, Serialize};

use super::Strategy;
use crate::coverage_map::CoverageMap;
use crate::occupancy::OccupancyGrid;
use crate::pose::Pose;

/// Why a run ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Termination {
    /// Every cell of the region the robot can reach is certain (entropy
    /// below epsilon): the paper's rule, met in full.
    Certain,
    /// Every cell of that region is certain or has stagnated (its entropy
    /// changed by less than 0.001 nats over its last five measurements), and
    /// some have stagnated: the paper's rule, with cells that cannot improve.
    Stagnated,
    /// The strategy has no goal left: no candidate worth visiting (coverage),
    /// no candidate that would intercept an unexplored cell (counting), no
    /// reachable frontier (frontier).
    NoGoal,
    /// The run reached `max_path_m` or `max_steps` first.
    Limit,
}

impl Termination {
    /// `"certain"`, `"stagnated"`, `"no_goal"` or `"limit"`.
    pub fn as_str(&self) -> &'static str {
        match self {
            Self::Certain => "certain",
            Self::Stagnated => "stagnated",
            Self::NoGoal => "no_goal",
            Self::Limit => "limit",
        }
    }

    /// Whether the run ended by its strategy's rule rather than at a limit.
    pub fn by_rule(&self) -> bool {
        !matches!(self, Self::Limit)
    }
}

impl std::fmt::Display for Termination {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// Every pose the robot took, in order, and which of them it scanned from.
///
/// Consecutive poses are joined by straight drives (or, at the same
/// position, a turn on the spot), so the path length is the sum of the
/// distances between consecutive positions ([`Trajectory::length_m`]).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Trajectory {
    /// The poses.
    pub poses: Vec<Pose>,
    /// Whether a scan was taken at each pose.
    pub scanned: Vec<bool>,
}

impl Trajectory {
    /// The distance driven along the trajectory, metres.
    pub fn length_m(&self) -> f64 {
        self.poses
            .windows(2)
            .map(|w| (w[1].x_m - w[0].x_m).hypot(w[1].y_m - w[0].y_m))
            .sum()
    }

    /// The poses a scan was taken from.
    pub fn scan_poses(&self) -> Vec<Pose> {
        self.poses
            .iter()
            .zip(&self.scanned)
            .filter(|(_, s)| **s)
            .map(|(p, _)| *p)
            .collect()
    }

    pub(super) fn push(&mut self, pose: Pose, scanned: bool) {
        self.poses.push(pose);
        self.scanned.push(scanned);
    }
}

/// Per-step figures, one entry a step, taken when the step has ended.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Trace {
    /// Path length so far, metres.
    pub path_length_m: Vec<f64>,
    /// Scans so far.
    pub scans: Vec<usize>,
    /// Fraction of the report cells whose entropy is above epsilon (see
    /// [`ExplorationSetup::report_cells`](super::ExplorationSetup::report_cells)).
    pub uncertain_fraction: Vec<f64>,
    /// Whether the step ended in a contact.
    pub contact: Vec<bool>,
    /// Wall time of the step's decision, seconds.
    pub planning_s: Vec<f64>,
}

/// Wall time of a run, split by what it was spent on, seconds. Not part of
/// the run's outcome: the same seed gives the same run with other timings.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Timing {
    /// Choosing goals and checking termination.
    pub planning_s: f64,
    /// Scanning and driving (the scan source and the motion).
    pub sensing_s: f64,
    /// Integrating scans and contacts into the maps, and the entropy map.
    pub integration_s: f64,
}

impl Timing {
    /// The three together.
    pub fn total_s(&self) -> f64 {
        self.planning_s + self.sensing_s + self.integration_s
    }
}

/// What one step did ([`Exploration::step`](super::Exploration::step)).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct StepReport {
    /// The step's number, from 0.
    pub index: usize,
    /// The goal the strategy chose.
    pub goal: Pose,
    /// The planned path to it on the map: cell centres.
    pub path: Vec<[f64; 2]>,
    /// Whether the robot got to the goal (false after a contact or at the
    /// path limit).
    pub reached: bool,
    /// Where the robot touched an obstacle, if it did.
    pub contact_m: Option<[f64; 2]>,
    /// Distance driven in this step, metres.
    pub travelled_m: f64,
    /// Scans taken in this step.
    pub scans: usize,
    /// The robot's pose after the step.
    pub pose: Pose,
}

/// Everything a run reports ([`Exploration::result`](super::Exploration::result)).
#[derive(Clone, Debug)]
pub struct ExplorationResult {
    /// The strategy that chose the goals.
    pub strategy: Strategy,
    /// How the run ended; `None` while it is still running.
    pub termination: Option<Termination>,
    /// Distance driven, metres.
    pub path_length_m: f64,
    /// Scans taken.
    pub scans: usize,
    /// Steps taken (goals driven to).
    pub steps: usize,
    /// Contacts with obstacles the map did not show.
    pub contacts: usize,
    /// Every pose, scans marked.
    pub trajectory: Trajectory,
    /// Per-step figures.
    pub trace: Trace,
    /// Where the time went.
    pub timing: Timing,
    /// The coverage map built (its entropy history tracked).
    pub map: CoverageMap,
    /// The occupancy grid built from the same beams; its
    /// [`counts`](OccupancyGrid::counts) are the scan counts of the same
    /// beams (discounted as the counting strategy asks; undiscounted for the
    /// other strategies).
    pub occupancy: OccupancyGrid,
}
