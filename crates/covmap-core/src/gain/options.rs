//! What the expected gain is computed with: the evaluator, and the options of
//! the predicted readings.

use serde::{Deserialize, Serialize};

use crate::sensor::StopCoverage;

/// Which evaluator computes the expected gain.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum GainMethod {
    /// The equation as written: the reference.
    Exact,
    /// The production evaluator: equal to `Exact` up to rounding.
    #[default]
    Fast,
}

/// Settings of the expected-gain computation.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GainOptions {
    /// Spacing of the hypothetical readings, metres; `None`: the grid
    /// resolution. Between [`MIN_STEP_FRACTION`](super::MIN_STEP_FRACTION)
    /// (1/1024) of the grid resolution and the resolution.
    pub range_step_m: Option<f64>,
    /// Which coverage value of a cell stops a predicted beam.
    pub stop_coverage: StopCoverage,
}
