//! How the next goal is chosen, and when exploration is done: the paper's
//! decision-theoretic strategy and its two baselines, one file each.
//!
//! Every strategy chooses on the *maps* the robot has built (never on the
//! world), plans its path on them, and says when it is done:
//!
//! - [`Strategy::Coverage`] ([`coverage`](self) module): eq. 14 through the
//!   [`Planner`](crate::planner::Planner); done when every cell of the
//!   reachable region is certain or stagnated.
//! - [`Strategy::Counting`]: the paper's (extended) scan counting on the
//!   [`ScanCounts`](crate::ScanCounts); done when no reachable candidate
//!   would intercept an unexplored cell.
//! - [`Strategy::Frontier`]: nearest-frontier exploration (Yamauchi 1997)
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

mod counting;
mod coverage;
mod frontier;

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

    /// `"coverage"`, `"counting"` or `"frontier"`.
    pub fn name(&self) -> &'static str {
        match self {
            Self::Coverage { .. } => "coverage",
            Self::Counting { .. } => "counting",
            Self::Frontier => "frontier",
        }
    }

    /// Whether the strategy plans on the coverage map's histograms (with
    /// the contacts pinned), not only on its ML coverage: the loop keeps a
    /// copy of the map for it.
    pub(super) fn plans_on_histograms(&self) -> bool {
        matches!(self, Self::Coverage { .. })
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
            Self::Frontier => Ok(()),
        }
    }
}

/// What a strategy sees when it decides: the maps, the robot, the sensor.
pub(super) struct View<'a> {
    /// The coverage map, as the readings and contacts made it.
    pub map: &'a CoverageMap,
    /// The coverage map to plan on: `map` with every cell the robot has run
    /// into pinned as covered (the robot remembers its contacts, whatever
    /// the readings say since). Kept by the loop for the strategy that
    /// plans on its histograms, coverage's ([`Strategy::plans_on_histograms`]);
    /// `None` for the others, which read `planning_ml`.
    pub planning_map: Option<&'a CoverageMap>,
    /// The ML coverage of the map to plan on ([`CoverageMap::ml`] of
    /// `map` with the contacts pinned), kept by the loop from step to step.
    pub planning_ml: &'a [f32],
    /// The cells the robot has run into.
    pub contact_cells: &'a [Cell],
    /// The cells the robot's centre has driven through (row-major), which
    /// the strategies navigating the occupancy grid may always pass.
    pub driven: &'a [bool],
    pub occupancy: &'a OccupancyGrid,
    /// The coverage map's entropy, nats, computed once after the last scan.
    pub entropy: &'a [f32],
    pub pose: Pose,
    pub bearings: &'a [f64],
    pub model: &'a AnySensorModel,
    pub config: &'a ExplorationConfig,
    /// Goals (row-major cells) the robot could make no headway towards:
    /// none is chosen again (the map may keep showing the way free).
    pub failed_goals: &'a [usize],
}

impl View<'_> {
    pub fn grid(&self) -> &Grid {
        self.map.grid()
    }
}

/// The headings a candidate is considered with when the sensor does not
/// see all around: every 45 degrees.
pub(super) const HEADINGS: usize = 8;

/// The widest gap between neighbouring bearings (radians) of a sensor that
/// sees all around: 45 degrees (the 24-sonar ring's is 15).
const ALL_AROUND_GAP_RAD: f64 = std::f64::consts::FRAC_PI_4;

/// Whether no two neighbouring `bearings` (around the circle) are more than
/// [`ALL_AROUND_GAP_RAD`] apart: a sensor for which the heading of a
/// viewpoint hardly matters.
pub(super) fn sees_all_around(bearings: &[f64]) -> bool {
    widest_gap_rad(bearings) <= ALL_AROUND_GAP_RAD
}

/// The widest gap between neighbouring `bearings` around the circle,
/// radians: `2 pi` for one bearing or none.
pub(super) fn widest_gap_rad(bearings: &[f64]) -> f64 {
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

/// The headings a viewpoint is considered with by a sensor seeing through
/// `bearings`: `robot_heading` alone for one that sees all around, else
/// [`HEADINGS`] fixed headings, `i * 2 pi / HEADINGS` (the robot turns on
/// the spot to the one chosen).
pub(super) fn viewpoint_headings(bearings: &[f64], robot_heading: f64) -> Vec<f64> {
    if sees_all_around(bearings) {
        vec![robot_heading]
    } else {
        crate::planner::fixed_headings(HEADINGS)
    }
}

/// A strategy's answer.
pub(super) enum Decision {
    /// Drive along `path` (cell centres, from the robot's cell) to `pose`.
    Goal { pose: Pose, path: Vec<[f64; 2]> },
    /// Exploration is done.
    Done(Termination),
}

/// How the drive to a goal went, for the strategy to learn from.
pub(super) struct Outcome {
    /// Whether the robot got to the goal.
    pub reached: bool,
}

/// A strategy at work: its settings and what it remembers between steps.
pub(super) enum Chooser {
    // Boxed: the planner's state and the counting strategy's kept
    // dilations outweigh the frontier strategy's.
    Coverage(Box<coverage::Coverage>),
    Counting(Box<counting::Counting>),
    Frontier(frontier::Frontier),
}

impl Chooser {
    /// The strategy's state at the start of a run on `grid` (validated).
    pub fn new(
        strategy: &Strategy,
        config: &ExplorationConfig,
        grid: &Grid,
        bins: usize,
        bearings: &[f64],
    ) -> Result<Self> {
        strategy.validate()?;
        Ok(match *strategy {
            Strategy::Coverage { alpha } => Self::Coverage(Box::new(coverage::Coverage::new(
                alpha, config, grid, bins, bearings,
            )?)),
            Strategy::Counting { n, .. } => {
                Self::Counting(Box::new(counting::Counting::new(n, config, grid)))
            }
            Strategy::Frontier => Self::Frontier(frontier::Frontier::new(grid)),
        })
    }

    /// The next goal, or why there is none.
    pub fn decide(&mut self, view: &View) -> Result<Decision> {
        match self {
            Self::Coverage(s) => s.decide(view),
            Self::Counting(s) => s.decide(view),
            Self::Frontier(s) => s.decide(view),
        }
    }

    /// Learn from how the drive to the last goal went; `view` shows the maps
    /// after it.
    pub fn learn(&mut self, view: &View, outcome: &Outcome) {
        match self {
            Self::Coverage(s) => s.learn(view, outcome),
            Self::Counting(s) => s.learn(view, outcome),
            Self::Frontier(s) => s.learn(view, outcome),
        }
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
