//! The planner's settings, their defaults and the ranges they must lie in.

use serde::{Deserialize, Serialize};

use crate::error::{CovmapError, Result};
use crate::gain::GainOptions;
use crate::sensor::check_range_step;

/// Settings of the planner. See the [module documentation](crate::planner).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlannerConfig {
    /// Weight of information against travel, in `[0, 1]`: 0 is greedy
    /// nearest, 1 pure information gain.
    pub alpha: f64,
    /// Radius of the disc robot, metres (the B21r's is about 0.26 m). Paths
    /// keep the planning radius, this and a margin, from blocked cells
    /// ([`Planner::planning_radius_m`](crate::planner::Planner::planning_radius_m)).
    pub robot_radius_m: f64,
    /// Spacing of the candidate lattice, metres.
    pub candidate_stride_m: f64,
    /// Candidates closer than this along the path are not goals, metres:
    /// without it the robot's own cell keeps winning (scanning again always
    /// teaches a little) and the robot never moves.
    pub min_travel_m: f64,
    /// Candidates whose expected gain is at most this are not goals, nats;
    /// `None` (the default): what making one cell at the prior certain is
    /// worth, `ln bins - epsilon`, at least [`MIN_GAIN_FLOOR_NATS`]
    /// ([`Planner::min_gain_nats`](crate::planner::Planner::min_gain_nats)).
    #[serde(default)]
    pub min_gain_nats: Option<f64>,
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
    /// Headings a candidate position is considered with, 1 to
    /// [`MAX_CANDIDATE_HEADINGS`]: 1 keeps the robot's heading (a full ring
    /// of sonars sees much the same from any); `k > 1` tries the `k`
    /// headings `i * 2 pi / k`, each a candidate of its own. `None` (the
    /// default): the fixed heading 0 alone for a sensor that sees all
    /// around (no two neighbouring bearings more than 45 degrees apart, as
    /// the 24-sonar ring), else [`DEFAULT_HEADINGS`] (a 180° laser); fixed
    /// headings let a cache keep the candidates' gains whichever way the
    /// robot faces ([`Planner::headings`](crate::planner::Planner::headings)).
    #[serde(default)]
    pub candidate_headings: Option<usize>,
}

/// The most headings a candidate position may be considered with.
pub const MAX_CANDIDATE_HEADINGS: usize = 64;

/// The default epsilon, nats: the entropy at or below which a cell counts
/// as explored (certain), the value of the paper's Fig. 7. Maps built
/// without an exploration's settings (a whole log with its no-echo
/// readings occluded, [`CoverageMap::occluding`](crate::CoverageMap::occluding))
/// use it for the cells they are certain of.
pub const DEFAULT_EPSILON: f64 = 0.65;

/// The headings a candidate position is considered with by default when
/// the sensor does not see all around: every 45 degrees.
pub const DEFAULT_HEADINGS: usize = 8;

/// The least gain a goal must promise by default, nats, however few the
/// bins: a negligible gain makes no goal.
pub const MIN_GAIN_FLOOR_NATS: f64 = 1.0;

impl Default for PlannerConfig {
    /// The settings the exploration loop's decision-theoretic strategy plans
    /// with (its [`ExplorationConfig`](crate::exploration::ExplorationConfig)'s
    /// defaults are these): a planner with these makes the loop's choice.
    fn default() -> Self {
        Self {
            alpha: 0.5,
            robot_radius_m: 0.25,
            candidate_stride_m: 0.5,
            min_travel_m: 0.25,
            min_gain_nats: None,
            blocked_coverage: 0.5,
            unknown_entropy_fraction: 0.95,
            unknown_is_free: false,
            epsilon: DEFAULT_EPSILON,
            gain: GainOptions::default(),
            candidate_headings: None,
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
        if let Some(gain) = self.min_gain_nats
            && !(gain >= 0.0 && gain.is_finite())
        {
            return bad("min_gain_nats", gain, "a non-negative, finite gain");
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
        if let Some(headings) = self.candidate_headings
            && !(1..=MAX_CANDIDATE_HEADINGS).contains(&headings)
        {
            return bad(
                "candidate_headings",
                headings as f64,
                "a count of headings from 1 to 64",
            );
        }
        // The grid is not known yet: the step's bound by the resolution is
        // checked when the gain is evaluated on a map.
        match self.gain.range_step_m {
            Some(step) => check_range_step(step, None),
            None => Ok(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::planner::Planner;

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
        for headings in [0, 65, usize::MAX] {
            let err = Planner::new(PlannerConfig {
                candidate_headings: Some(headings),
                ..PlannerConfig::default()
            })
            .unwrap_err();
            assert!(
                matches!(
                    err,
                    CovmapError::InvalidParameter { name: "candidate_headings", value, .. }
                        if value == headings as f64
                ),
                "{err}"
            );
        }
        for headings in [1, 2, 64] {
            assert!(
                Planner::new(PlannerConfig {
                    candidate_headings: Some(headings),
                    ..PlannerConfig::default()
                })
                .is_ok()
            );
        }
        let planner = Planner::new(PlannerConfig::default()).unwrap();
        assert!(matches!(
            planner.utilities(&[2.0, 3.0], &[1.0], 16),
            Err(CovmapError::LengthMismatch { .. })
        ));
    }
}
