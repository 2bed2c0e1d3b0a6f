//! The laser range finder: a thin beam.

use serde::{Deserialize, Serialize};

use super::{Footprint, RangeModel, SensorModel};
use crate::error::Result;

/// The laser inverse model: a [`RangeModel`] along a ray.
///
/// Every cell the ray crosses up to the reach of the reading is updated once,
/// with `d_l` the distance of the cell's centre projected on the ray.
///
/// # Example
/// ```
/// use covmap_core::{LaserModel, SensorModel};
/// let laser = LaserModel::default();
/// // The cell where the beam ends 0.3 cells past its centre is 20 % covered.
/// let k = laser.kernel(2.0, 2.0 + 0.3 * 0.05, 0.05, 16).unwrap().unwrap();
/// let best = (0..16).max_by(|&a, &b| k[a].total_cmp(&k[b])).unwrap();
/// assert_eq!(best, 3); // bin value 3/15 = 0.2
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LaserModel {
    /// The inverse model along the beam.
    #[serde(flatten)]
    pub range: RangeModel,
}

impl Default for LaserModel {
    /// A SICK-class laser: 30 m, sharp readings.
    fn default() -> Self {
        Self {
            range: RangeModel::LASER,
        }
    }
}

impl SensorModel for LaserModel {
    fn range_model(&self) -> &RangeModel {
        &self.range
    }
    fn footprint(&self) -> Footprint {
        Footprint::Ray
    }
    fn validate(&self) -> Result<()> {
        self.range.validate()
    }
}
