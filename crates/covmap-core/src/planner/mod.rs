//! The decision-theoretic choice of the next viewpoint ([the model](crate::model),
//! section 4, paper eq. 14), reachability and path costs for a disc robot, and
//! termination.
//!
//! # Traversability
//! A cell is *blocked* when its coverage on the ML map exceeds
//! `blocked_coverage`, and *unknown* while its entropy is at least
//! `unknown_entropy_fraction` of the prior's (a cell at the prior has ML
//! coverage 0, so only this rule keeps unexplored space out of reach). The
//! robot's centre may be at a cell's centre when its disc of the planning
//! radius there overlaps no blocked cell (and, unless `unknown_is_free`, no
//! unknown cell): the obstacles, whole cells, inflated by the planning
//! radius, the robot's and a cell (at least 5 cm:
//! [`Planner::planning_radius_m`]). Paths run between cell centres, 8-connected, with
//! Euclidean step lengths (Dijkstra). The robot may also pass through the
//! cells its disc overlaps where it stands that are not blocked themselves,
//! so that a robot too close to an obstacle (as the map now has it) can move
//! away; those cells are goals only if they are free.
//!
//! # Candidates and choice
//! Candidate viewpoints are the reachable free cells on a lattice of
//! `candidate_stride_m`, at least `min_travel_m` away along the path, whose
//! expected information gain exceeds [`Planner::min_gain_nats`] (by
//! default what making one unknown cell certain is worth: a negligible gain
//! makes no goal). Of those, the pose maximising
//! `alpha * gain / max gain - (1 - alpha) * cost / max cost` is chosen (ties to
//! the lower index). By default a sensor that sees all around (a full sonar
//! ring, which sees the same from any heading up to its spacing) plans every
//! candidate with the fixed heading 0, and one that does not (a 180° laser)
//! with 8 fixed headings `i * 2 pi / 8`, each a candidate of its own, the
//! pose of best utility winning, heading included ([`Planner::headings`]):
//! fixed, not turned with the robot, so that a position's gains can be kept
//! from step to step. The defaults are the exploration loop's: a planner
//! with them makes the loop's decision-theoretic choice.
//!
//! # Planning again after a scan
//! [`Planner::next_viewpoint`] computes everything from the map.
//! [`Planner::next_viewpoint_cached`] returns the same plan, bit for bit, but
//! keeps the gain evaluator's per-map work and every candidate's expected
//! gain in a [`PlanningCache`], and recomputes only what the map's changes can
//! have changed: the terms of the changed cells and the gains of candidates
//! whose beams can reach one. It finds the changed cells itself (from the
//! map's change feed), so a loop passes it the map as it is, however it was
//! changed. A scan changes the cells within the sensor's reach, and a gain
//! reads the cells within its beams' reach (up to walls the map holds as
//! covered with certainty), so after a scan the candidates farther than about
//! twice the reach, or behind such walls, keep their gains. Free space, paths
//! and eq. 14's normalisation are computed anew on every call. See
//! [`cache`] for what is kept.
//!
//! # Termination
//! Exploration is done when every cell the robot could reach, passing through
//! unknown space (the cells connected to it through cells not blocked), is
//! either certain (entropy below `epsilon`) or stagnated: its entropy changed by
//! less than 0.001 over its last five measurements
//! ([`CoverageMap::track_history`](crate::CoverageMap::track_history)).

pub mod cache;
mod config;
mod path;
mod termination;
#[cfg(test)]
mod test_maps;
mod traversability;
mod viewpoint;

pub use cache::{CacheStats, PlanningCache};
pub use config::{
    DEFAULT_EPSILON, DEFAULT_HEADINGS, MAX_CANDIDATE_HEADINGS, MIN_GAIN_FLOOR_NATS, PlannerConfig,
};
pub use path::{Reachability, shortest_paths};
pub(crate) use path::{Search, SearchMemory, reachable_cells};
pub use termination::ExplorationStatus;
pub(crate) use traversability::pass_where_driven;
pub use viewpoint::{
    Candidates, FACE_MARGIN_M, Plan, Planner, fixed_headings, sees_all_around, widest_gap_rad,
};
