//! The settings of an exploration run, their defaults and their ranges.

use serde::{Deserialize, Serialize};

use crate::error::{Result, check_parameter};
use crate::planner::PlannerConfig;

/// Settings of an exploration run that do not depend on the strategy.
///
/// Every setting is checked by [`ExplorationConfig::validate`] before the
/// run starts ([`Exploration::new`](super::Exploration::new)).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ExplorationConfig {
    /// Entropy below which a cell counts as certain, nats (the paper's
    /// epsilon; its Fig. 7 uses 0.65).
    pub epsilon: f64,
    /// Radius of the disc robot, metres (the B21r's is about 0.26 m).
    pub robot_radius_m: f64,
    /// Spacing of the lattice of candidate viewpoints, metres.
    pub candidate_stride_m: f64,
    /// Distance driven between two scans, metres: the robot scans every
    /// `scan_spacing_m` of travel, and at every goal.
    pub scan_spacing_m: f64,
    /// A goal closer than this along the path is no goal, metres: without it
    /// the robot's own cell keeps winning (scanning again always teaches a
    /// little) and the robot never moves.
    pub min_travel_m: f64,
    /// The run stops when the robot has driven this far, metres (it stops
    /// driving there, scans and ends with [`Termination::Limit`](super::Termination::Limit)).
    /// A safety net: the default (10 km) lies well beyond where every
    /// strategy's runs in the built-in worlds end by their rule (scan
    /// counting to 50 drives up to 2.3 km on the corridor).
    pub max_path_m: f64,
    /// The run stops after this many steps ([`Termination::Limit`](super::Termination::Limit));
    /// a safety net too (default 20 000).
    pub max_steps: usize,
    /// Whether a reading at the maximum range ("no echo") clears only the
    /// cells its line of sight reaches past the obstacles the coverage map
    /// holds, and is certain of at `epsilon`, in its footprint
    /// ([`CoverageMap::occludes`](crate::CoverageMap::occludes),
    /// [`NoEchoSight`](crate::NoEchoSight), see the
    /// [module documentation](super)), rather than its whole footprint to
    /// the maximum range as the sensor model has it (the default, `true`).
    /// With `false`, the paper's reading, runs leave fewer cells uncertain
    /// but wear walls away: specular misses clear the cells behind the
    /// faces that echoes found, the maps err more and the robot runs into
    /// walls twice as often on the development buildings
    /// (docs/experiments.md, "The paper's no-echo reading in the loop").
    /// With `true` each echo is also explained by what the map is certain
    /// of ([`EchoSources`](crate::EchoSources)): both read a scan against
    /// the cells the map holds covered and is certain of; `false` is the
    /// paper's update throughout.
    pub occlude_no_echo: bool,
}

/// The finest scan spacing, as a fraction of a cell: a tenth
/// ([`ExplorationConfig::check_scan_spacing`]).
pub const MIN_SCANS_PER_CELL: f64 = 10.0;

impl Default for ExplorationConfig {
    /// The settings it shares with the planner (`epsilon`, `robot_radius_m`,
    /// `candidate_stride_m`, `min_travel_m`) are the planner's defaults
    /// ([`PlannerConfig::default`]), so that a planner with its defaults
    /// makes the loop's decision-theoretic choice.
    fn default() -> Self {
        let shared = PlannerConfig::default();
        Self {
            epsilon: shared.epsilon,
            robot_radius_m: shared.robot_radius_m,
            candidate_stride_m: shared.candidate_stride_m,
            scan_spacing_m: 0.25,
            min_travel_m: shared.min_travel_m,
            max_path_m: 10_000.0,
            max_steps: 20_000,
            occlude_no_echo: true,
        }
    }
}

impl ExplorationConfig {
    /// Errors unless `epsilon` is below `ln(bins)`, the entropy of the
    /// uniform prior of a map of `bins` bins: at or above it every cell
    /// would count as certain before the first scan, and the run would end
    /// at once.
    ///
    /// # Errors
    /// [`CovmapError::InvalidSetting`](crate::CovmapError::InvalidSetting)
    /// naming `epsilon`, its value and the bound.
    pub fn check_epsilon(&self, bins: usize) -> Result<()> {
        let prior_nats = (bins as f64).ln();
        if self.epsilon < prior_nats {
            return Ok(());
        }
        Err(crate::CovmapError::InvalidSetting {
            name: "epsilon",
            reason: format!(
                "{}: expected an entropy below ln({bins}) = {prior_nats:.4} nats, the prior's \
                 (at or above it every cell is certain before the first scan)",
                self.epsilon
            ),
        })
    }

    /// Errors unless `scan_spacing_m` is at least a cell of `resolution_m`
    /// metres divided by `MIN_SCANS_PER_CELL` (a tenth of a cell): the
    /// robot would scan more often than a map of that grid can tell apart,
    /// and a leg of a few metres could take millions of scans.
    ///
    /// # Errors
    /// [`CovmapError::InvalidParameter`](crate::CovmapError::InvalidParameter)
    /// naming `scan_spacing_m`.
    pub fn check_scan_spacing(&self, resolution_m: f64) -> Result<()> {
        check_parameter(
            self.scan_spacing_m >= resolution_m / MIN_SCANS_PER_CELL,
            "scan_spacing_m",
            self.scan_spacing_m,
            "a distance of at least a tenth of the map's cell (metres)",
        )
    }

    /// Errors ([`CovmapError::InvalidParameter`](crate::CovmapError::InvalidParameter),
    /// naming the setting and its value) unless `epsilon`, `robot_radius_m`,
    /// `candidate_stride_m`, `scan_spacing_m` and `max_path_m` are positive
    /// and finite, `min_travel_m` is non-negative and finite, and `max_steps`
    /// is at least 1.
    pub fn validate(&self) -> Result<()> {
        let positive = [
            ("epsilon", self.epsilon, "a positive, finite entropy (nats)"),
            (
                "robot_radius_m",
                self.robot_radius_m,
                "a positive, finite radius (metres)",
            ),
            (
                "candidate_stride_m",
                self.candidate_stride_m,
                "a positive, finite spacing (metres)",
            ),
            (
                "scan_spacing_m",
                self.scan_spacing_m,
                "a positive, finite distance (metres)",
            ),
            (
                "max_path_m",
                self.max_path_m,
                "a positive, finite distance (metres)",
            ),
        ];
        for (name, value, expected) in positive {
            check_parameter(value > 0.0 && value.is_finite(), name, value, expected)?;
        }
        check_parameter(
            self.min_travel_m >= 0.0 && self.min_travel_m.is_finite(),
            "min_travel_m",
            self.min_travel_m,
            "a non-negative, finite distance (metres)",
        )?;
        check_parameter(
            self.max_steps >= 1,
            "max_steps",
            self.max_steps as f64,
            "at least one step",
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::CovmapError;

    #[test]
    fn every_bad_setting_is_named() {
        ExplorationConfig::default().validate().unwrap();
        type Edit = fn(&mut ExplorationConfig);
        let cases: [(Edit, &str); 9] = [
            (|c| c.epsilon = 0.0, "epsilon"),
            (|c| c.epsilon = f64::NAN, "epsilon"),
            (|c| c.robot_radius_m = -0.1, "robot_radius_m"),
            (
                |c| c.candidate_stride_m = f64::INFINITY,
                "candidate_stride_m",
            ),
            (|c| c.scan_spacing_m = 0.0, "scan_spacing_m"),
            (|c| c.min_travel_m = -1.0, "min_travel_m"),
            (|c| c.max_path_m = -5.0, "max_path_m"),
            (|c| c.max_path_m = f64::NAN, "max_path_m"),
            (|c| c.max_steps = 0, "max_steps"),
        ];
        for (edit, name) in cases {
            let mut config = ExplorationConfig::default();
            edit(&mut config);
            let err = config.validate().unwrap_err();
            assert!(
                matches!(err, CovmapError::InvalidParameter { name: n, .. } if n == name),
                "{err}"
            );
        }
    }

    /// An epsilon at or above the prior's entropy would end every run at
    /// once: refused, naming the bound; just below it is taken.
    #[test]
    fn an_epsilon_every_cell_starts_below_is_refused() {
        let config = |epsilon| ExplorationConfig {
            epsilon,
            ..ExplorationConfig::default()
        };
        let ln16 = 16f64.ln();
        for epsilon in [ln16, 3.0, 100.0] {
            let err = config(epsilon).check_epsilon(16).unwrap_err().to_string();
            assert!(
                err.contains("`epsilon`") && err.contains("ln(16) = 2.7726"),
                "{err}"
            );
        }
        config(ln16 - 1e-9).check_epsilon(16).unwrap();
        assert!(config(0.65).check_epsilon(2).is_ok() && config(0.7).check_epsilon(2).is_err());
    }
}
