//! The inverse model a run integrates with: either of the crate's sensor
//! models, as one type.

use serde::{Deserialize, Serialize};

use crate::error::Result;
use crate::sensor::{Footprint, LaserModel, RangeModel, SensorModel, SonarModel};

/// The inverse sensor model of an exploration run: a sonar cone or a laser
/// ray. Every map of the run (coverage map, occupancy grid, scan counts)
/// integrates the same beams with it, and the strategies predict with it.
///
/// # Example
/// ```
/// use covmap_core::exploration::AnySensorModel;
/// use covmap_core::{SensorModel, SonarModel};
/// let model = AnySensorModel::default();
/// assert_eq!(model, AnySensorModel::Sonar(SonarModel::default()));
/// assert_eq!(model.range_model().max_range_m, 5.0);
/// assert_eq!(AnySensorModel::laser().range_model().max_range_m, 30.0);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum AnySensorModel {
    /// An ultrasound cone.
    Sonar(SonarModel),
    /// A laser ray.
    Laser(LaserModel),
}

impl Default for AnySensorModel {
    /// The sonar of the paper's runs, [`SonarModel::default`].
    fn default() -> Self {
        Self::Sonar(SonarModel::default())
    }
}

impl AnySensorModel {
    /// [`LaserModel::default`].
    pub fn laser() -> Self {
        Self::Laser(LaserModel::default())
    }

    /// The model as a trait object, for code that takes any sensor model.
    pub fn as_dyn(&self) -> &dyn SensorModel {
        match self {
            Self::Sonar(m) => m,
            Self::Laser(m) => m,
        }
    }
}

impl SensorModel for AnySensorModel {
    fn range_model(&self) -> &RangeModel {
        self.as_dyn().range_model()
    }
    fn footprint(&self) -> Footprint {
        self.as_dyn().footprint()
    }
    fn validate(&self) -> Result<()> {
        self.as_dyn().validate()
    }
}
