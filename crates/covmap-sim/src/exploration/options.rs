//! The options of a simulated exploration run, their defaults and checks.

use covmap_core::exploration::{AnySensorModel, ExplorationConfig};
use covmap_core::histogram::{DEFAULT_BINS, check_bins};
use covmap_core::{Pose, SensorModel};

use super::sensor::SimSensor;
use crate::error::{Result, check_param};

/// How a simulated run is set up ([`explore`](super::explore)).
#[derive(Clone, Debug, PartialEq)]
pub struct ExploreOptions {
    /// Where the robot starts; `None`: a free pose drawn from the seed (see
    /// [`choose_start`](super::choose_start)).
    pub start: Option<Pose>,
    /// The seed of every random draw: the start, and every scan's noise.
    pub seed: u64,
    /// The simulated sensor (default: the 24-sonar ring).
    pub sensor: SimSensor,
    /// The inverse model the maps integrate with; `None`: the one that
    /// matches the sensor ([`SimSensor::default_model`]).
    pub model: Option<AnySensorModel>,
    /// Grid resolution, metres (the paper's 5 cm).
    pub resolution_m: f64,
    /// Histogram bins of the coverage map (default 16).
    pub bins: usize,
    /// How far the grid reaches beyond the world's bounds, metres (default
    /// 0.5 m: more than the robot's radius and the sonar's end band, so that
    /// every cell a reading at the outer walls updates is on the map).
    pub margin_m: f64,
    /// The settings of the loop.
    pub config: ExplorationConfig,
}

impl Default for ExploreOptions {
    fn default() -> Self {
        Self {
            start: None,
            seed: 0,
            sensor: SimSensor::default(),
            model: None,
            resolution_m: 0.05,
            bins: DEFAULT_BINS,
            margin_m: 0.5,
            config: ExplorationConfig::default(),
        }
    }
}

impl ExploreOptions {
    /// The inverse model of the run.
    pub fn model(&self) -> AnySensorModel {
        self.model.unwrap_or_else(|| self.sensor.default_model())
    }

    /// Errors, naming the value, unless the resolution and the margin are
    /// finite (the resolution positive, the margin non-negative), the bin
    /// count is supported, and the settings, the sensor and the model are
    /// valid. (The start is checked against the world by the run.)
    pub fn validate(&self) -> Result<()> {
        check_param(
            "resolution_m",
            self.resolution_m,
            self.resolution_m > 0.0,
            "a positive, finite resolution (metres)",
        )?;
        check_param(
            "margin_m",
            self.margin_m,
            self.margin_m >= 0.0,
            "a non-negative, finite margin (metres)",
        )?;
        check_bins(self.bins)?;
        self.config.validate()?;
        self.config.check_scan_spacing(self.resolution_m)?;
        self.config.check_epsilon(self.bins)?;
        self.sensor.validate()?;
        self.model().validate()?;
        Ok(())
    }
}
