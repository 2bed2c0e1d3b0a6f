//! How the next goal is chosen, and when exploration is done: the paper's
//! decision-theoretic strategy and its two baselines, one file each.
//!
//! Every strategy chooses on the *maps* the robot has built (never on the
//! world), plans its path on them, and says when it is done:
//!
//! - [`Strategy::Coverage`] (`decision_theoretic.rs`): eq. 14 through the
//!   [`Planner`](crate::planner::Planner); done when every cell of the
//!   reachable region is certain or stagnated.
//! - [`Strategy::Counting`] (`scan_counting.rs`): the paper's (extended) scan counting on the
//!   [`ScanCounts`](crate::ScanCounts); done when no reachable candidate
//!   would intercept an unexplored cell.
//! - [`Strategy::Frontier`] (`nearest_frontier.rs`): nearest-frontier exploration (Yamauchi 1997)
//!   on the [`OccupancyGrid`](crate::OccupancyGrid); done when no frontier
//!   is left.
//!
//! # The reachable region
//! Coverage's termination and counting's "known, reachable region" are
//! built alike ([`region`](super::region)): the cells the robot's centre
//! can reach through known free space (the coverage map's for coverage,
//! the occupancy grid's, what the beams have seen, for counting), plus a
//! shell around them: the planning radius and the sensor model's end band
//! (`band_m`) for coverage (the cells the disc and the readings' end bands
//! touch), the planning radius and one cell for counting (the cells the
//! disc touches and the end points' cells: what a count can reach). An
//! unexplored doorway lies in that shell (the robot stops a radius short of
//! unknown cells, and the doorway's cells are within a radius of where it
//! stops), so it keeps the run going; the unknown margin outside a building
//! lies behind walls the robot cannot pass and more than the band behind
//! their faces, so it does not.

mod decision_theoretic;
mod nearest_frontier;
mod scan_counting;

use serde::{Deserialize, Serialize};

use super::config::ExplorationConfig;
use super::result::Termination;
use super::sensor::AnySensorModel;
use crate::coverage_map::CoverageMap;
use crate::error::{Result, check_parameter};
use crate::grid::{Cell, Grid};
use crate::occupancy::OccupancyGrid;
use crate::pose::Pose;

/// The discount range of the paper-style scan-counting runs (Table I's
/// `n = 50`, "longer beams discounted"), metres: a beam reading `d` beyond it
/// counts `2 / d` ([`ScanCounts::weight`](crate::ScanCounts::weight)). The
/// paper gives no value; 2 m is where the default sonar model's uniform
/// weight `xi` has grown to three times its value at the sensor (0.08 + 0.08
/// per metre), that is where a reading has become markedly less reliable.
pub const DEFAULT_DISCOUNT_BEYOND_M: f64 = 2.0;

/// How the robot chooses where to go next.
///
/// Build one with [`Strategy::coverage`], [`Strategy::counting`] or
/// [`Strategy::frontier`], which check the values; a run checks them again
/// ([`Strategy::validate`]). How each chooses its goals and when it is done:
/// the [module documentation](crate::exploration).
///
/// # Example
/// ```
/// use covmap_core::exploration::Strategy;
/// assert_eq!(Strategy::coverage(0.5).unwrap().name(), "coverage");
/// assert!(Strategy::coverage(1.5).is_err());
/// assert!(Strategy::counting(0, None).is_err());
/// assert!(Strategy::counting(50, Some(-1.0)).is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", tag = "strategy")]
pub enum Strategy {
    /// The paper's decision-theoretic choice (eq. 14): the candidate that
    /// maximises `alpha * gain / max gain - (1 - alpha) * cost / max cost`.
    Coverage {
        /// Weight of information against travel, in `[0, 1]`.
        alpha: f64,
    },
    /// Extended scan counting: a cell is explored once counted `n` times;
    /// the robot goes to the nearest candidate from which it would intercept
    /// an unexplored cell.
    Counting {
        /// Interceptions (weighted) that make a cell explored, at least 1.
        n: u32,
        /// Beams reading farther than this count `discount_beyond_m / d`
        /// instead of 1 (`None`: every beam counts 1). See
        /// [`DEFAULT_DISCOUNT_BEYOND_M`].
        discount_beyond_m: Option<f64>,
    },
    /// Nearest-frontier exploration on the occupancy grid.
    Frontier,
    /// A strategy outside the loop: the caller chooses each goal
    /// ([`Exploration::step_to`](super::Exploration::step_to)) and says when
    /// it is done ([`Exploration::finish`](super::Exploration::finish)); the
    /// loop's own [`Exploration::step`](super::Exploration::step) refuses to
    /// choose for it. (A strategy in Rust drives the loop itself, through
    /// [`ExplorationStrategy`] and
    /// [`Exploration::with_strategy`](super::Exploration::with_strategy).)
    Custom,
}

impl Strategy {
    /// The decision-theoretic strategy with weight `alpha`.
    ///
    /// # Errors
    /// [`CovmapError::InvalidParameter`](crate::CovmapError::InvalidParameter)
    /// naming `alpha` unless it lies in `[0, 1]` (NaN does not).
    pub fn coverage(alpha: f64) -> Result<Self> {
        let strategy = Self::Coverage { alpha };
        strategy.validate()?;
        Ok(strategy)
    }

    /// Scan counting to `n`, with beams beyond `discount_beyond_m` discounted.
    ///
    /// # Errors
    /// [`CovmapError::InvalidParameter`](crate::CovmapError::InvalidParameter)
    /// naming `n` if it is 0, or `discount_beyond_m` unless it is positive
    /// and finite.
    pub fn counting(n: u32, discount_beyond_m: Option<f64>) -> Result<Self> {
        let strategy = Self::Counting {
            n,
            discount_beyond_m,
        };
        strategy.validate()?;
        Ok(strategy)
    }

    /// Nearest-frontier exploration.
    pub fn frontier() -> Self {
        Self::Frontier
    }

    /// `"coverage"`, `"counting"`, `"frontier"` or `"custom"`.
    pub fn name(&self) -> &'static str {
        match self {
            Self::Coverage { .. } => "coverage",
            Self::Counting { .. } => "counting",
            Self::Frontier => "frontier",
            Self::Custom => "custom",
        }
    }

    /// Errors as the constructors do.
    pub fn validate(&self) -> Result<()> {
        match *self {
            Self::Coverage { alpha } => check_parameter(
                (0.0..=1.0).contains(&alpha),
                "alpha",
                alpha,
                "a weight in [0, 1]",
            ),
            Self::Counting {
                n,
                discount_beyond_m,
            } => {
                check_parameter(n >= 1, "n", f64::from(n), "a count of at least 1")?;
                match discount_beyond_m {
                    Some(d) => check_parameter(
                        d > 0.0 && d.is_finite(),
                        "discount_beyond_m",
                        d,
                        "a positive, finite distance (metres)",
                    ),
                    None => Ok(()),
                }
            }
            Self::Frontier | Self::Custom => Ok(()),
        }
    }
}

/// What a strategy sees when it chooses its next goal: the maps the robot
/// has built (never the world), where it is, its sensor and the loop's
/// settings. The loop keeps the read-outs up to date from the coverage
/// map's change feed ([`CoverageMap::changes_since`]).
pub struct DecisionInputs<'a> {
    /// The coverage map, as the readings made it, every cell the robot ran
    /// into held certainly covered ([`CoverageMap::pin_covered`]).
    pub map: &'a CoverageMap,
    /// The coverage map's ML coverage ([`CoverageMap::ml`]).
    pub ml: &'a [f32],
    /// The coverage map's entropy, nats ([`CoverageMap::entropy`]).
    pub entropy: &'a [f32],
    /// The cells (row-major, ascending) any map changed since the last
    /// decision (every cell at the first: the feed from where the loop
    /// started reading).
    pub changed: &'a [usize],
    /// The occupancy grid built from the same beams (and its scan counts).
    pub occupancy: &'a OccupancyGrid,
    /// The cells the robot has run into.
    pub contact_cells: &'a [Cell],
    /// The cells the robot's centre has driven through (row-major), which
    /// the strategies navigating the occupancy grid may always pass.
    pub driven: &'a [bool],
    /// Where the robot is.
    pub pose: Pose,
    /// The bearings of its sensor's beams, radians.
    pub bearings: &'a [f64],
    /// The inverse model its scans are integrated with.
    pub model: &'a AnySensorModel,
    /// The loop's settings.
    pub config: &'a ExplorationConfig,
    /// Goals (row-major cells) the robot could make no headway towards:
    /// none may be chosen again (the map may keep showing the way free).
    pub failed_goals: &'a [usize],
}

impl DecisionInputs<'_> {
    /// The grid of the maps.
    pub fn grid(&self) -> &Grid {
        self.map.grid()
    }
}

/// A strategy's answer: where to go next, or why exploration is done.
#[derive(Clone, Debug, PartialEq)]
pub enum NextGoal {
    /// Drive along `path` (cell centres, from the robot's cell) to `pose`.
    Goal {
        /// The goal.
        pose: Pose,
        /// The path to it.
        path: Vec<[f64; 2]>,
    },
    /// Exploration is done.
    Done(Termination),
}

/// How the drive to the last goal went.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct GoalOutcome {
    /// Whether the robot got to the goal (not stopped by a contact or a
    /// limit).
    pub reached: bool,
}

/// A strategy at work: chooses the next goal on the maps, and learns from
/// how the drive to it went. The built-in strategies ([`Strategy`])
/// implement it; another can drive the loop through
/// [`Exploration::with_strategy`](super::Exploration::with_strategy).
pub trait ExplorationStrategy: Send + Sync {
    /// The next goal, or why there is none.
    ///
    /// # Errors
    /// An error of the strategy's own; the loop passes it on, and the run
    /// can go on after it.
    fn decide(&mut self, inputs: &DecisionInputs<'_>) -> Result<NextGoal>;

    /// Learn from how the drive to the goal last decided went; `inputs`
    /// show the maps after it. Nothing by default.
    fn learn(&mut self, inputs: &DecisionInputs<'_>, outcome: &GoalOutcome) {
        let _ = (inputs, outcome);
    }
}

pub(crate) use crate::planner::{sees_all_around, widest_gap_rad};

/// The headings a viewpoint is considered with by a sensor seeing through
/// `bearings`: `robot_heading` alone for one that sees all around, else
/// the planner's default fixed headings (the robot turns on the spot to the
/// one chosen).
pub(super) fn viewpoint_headings(bearings: &[f64], robot_heading: f64) -> Vec<f64> {
    if sees_all_around(bearings) {
        vec![robot_heading]
    } else {
        crate::planner::fixed_headings(crate::planner::DEFAULT_HEADINGS)
    }
}

impl Strategy {
    /// The strategy at the start of a run on `grid` with a coverage map of
    /// `bins` bins (validated).
    ///
    /// # Errors
    /// As [`Strategy::validate`].
    pub fn start(
        &self,
        config: &ExplorationConfig,
        grid: &Grid,
        bins: usize,
    ) -> Result<Box<dyn ExplorationStrategy>> {
        self.validate()?;
        Ok(match *self {
            Strategy::Coverage { alpha } => Box::new(decision_theoretic::DecisionTheoretic::new(
                alpha, config, bins,
            )?),
            Strategy::Counting { n, .. } => {
                Box::new(scan_counting::ScanCounting::new(n, config, grid))
            }
            Strategy::Frontier => Box::new(nearest_frontier::NearestFrontier::new(grid)),
            Strategy::Custom => Box::new(Outside),
        })
    }
}

/// The chooser of [`Strategy::Custom`]: the goals come from outside the
/// loop, so it has none of its own.
struct Outside;

impl ExplorationStrategy for Outside {
    fn decide(&mut self, _: &DecisionInputs<'_>) -> Result<NextGoal> {
        Err(crate::error::CovmapError::InvalidSetting {
            name: "strategy",
            reason:
                "a custom strategy chooses its goals outside the loop: give each step its goal \
                     (Exploration::step_to), or end the run (Exploration::finish)"
                    .into(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_ring_sees_all_around_and_a_half_circle_does_not() {
        use std::f64::consts::{PI, TAU};
        let ring: Vec<f64> = (0..24).map(|i| i as f64 * TAU / 24.0 - PI).collect();
        assert!(sees_all_around(&ring));
        // The same ring, one sonar lost: a 30 degree gap is still all around.
        assert!(sees_all_around(&ring[1..]));
        let laser: Vec<f64> = (0..181).map(|i| (i as f64 - 90.0).to_radians()).collect();
        assert!(!sees_all_around(&laser));
        let eight = [-90.0f64, -37.5, -22.5, -7.5, 7.5, 22.5, 37.5, 90.0].map(f64::to_radians);
        assert!(!sees_all_around(&eight));
        assert!(!sees_all_around(&[]));
        assert!(!sees_all_around(&[0.0]));
    }
}
