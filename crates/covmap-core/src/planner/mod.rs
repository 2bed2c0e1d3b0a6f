//! The decision-theoretic choice of the next viewpoint ([the model](crate::model),
//! section 4, paper eq. 14), reachability and path costs for a disc robot, and
//! termination.
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
//! less than 0.001 over its last five measurements
//! ([`CoverageMap::track_history`](crate::CoverageMap::track_history)).

mod config;
mod path;
mod termination;
#[cfg(test)]
mod test_maps;
mod traversability;
mod viewpoint;

pub use config::PlannerConfig;
pub use path::{Reachability, shortest_paths};
pub use termination::ExplorationStatus;
pub use viewpoint::{Candidates, Plan, Planner};
