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
            range: RangeModel {
                max_range_m: 30.0,
                band_m: 0.10,
                sigma_min: 0.08,
                sigma_per_m: 0.004,
                sigma_end: 0.25,
                xi_min: 0.02,
                xi_per_m: 0.005,
                no_echo_reach: 1.0,
                no_echo_weight: 1.0,
                end_weight: 1.0,
                posterior_floor: 0.0,
                end_attribution: 0.0,
                free_yield: 0.0,
            },
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
