//! The ultrasound sensor: a cone.

use serde::{Deserialize, Serialize};

use super::parameters::{SONAR_PARAMETERS, check_each};
use super::{Footprint, RangeModel, SensorModel};
use crate::error::Result;

/// The sonar inverse model: a [`RangeModel`] spread over a cone.
///
/// Every cell whose centre lies within half the opening angle of the beam axis
/// and no further than the reach of the reading is updated, with `d_l` its
/// centre's Euclidean distance from the sensor. Cells off the axis are treated
/// like cells on it: a sonar cannot tell where in its cone the echo came from.
///
/// # Example
/// ```
/// use covmap_core::{SensorModel, SonarModel};
/// let sonar = SonarModel::default();
/// assert_eq!(sonar.range.band_m, 0.20);
/// // A cell 1 m out, reading 2 m: the beam passed through, the kernel favours empty.
/// let k = sonar.kernel(1.0, 2.0, 0.05, 16).unwrap().unwrap();
/// assert!(k[0] > k[15]);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SonarModel {
    /// The inverse model along the cone's axis.
    #[serde(flatten)]
    pub range: RangeModel,
    /// Full opening angle of the cone, radians, in `(0, pi)`.
    pub opening_angle_rad: f64,
}

impl Default for SonarModel {
    /// A Polaroid-class ultrasound sensor as on the B21r: 15 degree cone, 5 m.
    ///
    /// `sigma` and `xi` were chosen on the simulated Fig. 3 run
    /// (`cargo run --release -p covmap-sim --example fig3`): sharper settings
    /// (`sigma_min` 0.10, `xi` 0.02 + 0.03/m) made the map so confident that the
    /// ground truth scored worse under it than under the uniform prior
    /// (log-likelihood -92 782 against -74 516); these score -70 985 and lower
    /// both mean absolute errors below the occupancy grid's. Maximum-likelihood
    /// fitting on recorded data is the way to do better.
    fn default() -> Self {
        Self {
            range: RangeModel::SONAR,
            opening_angle_rad: SONAR_PARAMETERS[0].sonar_default,
        }
    }
}

impl SensorModel for SonarModel {
    fn range_model(&self) -> &RangeModel {
        &self.range
    }
    fn footprint(&self) -> Footprint {
        Footprint::Cone {
            half_angle_rad: 0.5 * self.opening_angle_rad,
        }
    }
    fn validate(&self) -> Result<()> {
        self.range.validate()?;
        check_each(&SONAR_PARAMETERS, &[self.opening_angle_rad])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::CovmapError;

    #[test]
    fn default_is_valid_and_serde_round_trips() {
        let m = SonarModel::default();
        m.validate().unwrap();
        let s = serde_json::to_string(&m).unwrap();
        assert!(s.contains("\"band_m\":0.2"), "{s}");
        assert_eq!(serde_json::from_str::<SonarModel>(&s).unwrap(), m);
    }

    #[test]
    fn rejects_bad_parameters() {
        let m = SonarModel {
            opening_angle_rad: std::f64::consts::PI,
            ..SonarModel::default()
        };
        assert!(matches!(
            m.validate(),
            Err(CovmapError::InvalidParameter {
                name: "opening_angle_rad",
                ..
            })
        ));
        let mut m = SonarModel::default();
        m.range.xi_min = 0.0;
        assert!(m.validate().is_err());
        let mut m = SonarModel::default();
        m.range.sigma_end = 0.01;
        assert!(matches!(
            m.validate(),
            Err(CovmapError::InvalidParameter {
                name: "sigma_end",
                ..
            })
        ));
        let mut m = SonarModel::default();
        m.range.max_range_m = f64::NAN;
        assert!(m.validate().is_err());
    }
}
