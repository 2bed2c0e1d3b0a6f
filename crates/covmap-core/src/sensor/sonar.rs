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

impl SonarModel {
    /// The model `covmap learn` fits with its defaults: 13 parameters fitted
    /// by maximum likelihood on the simulated corridor drive (300 scans of
    /// the 24-sonar ring, seed 0) with no-echo readings occluded by the map
    /// ([`crate::CoverageMap::occluding`]), as the exploration
    /// loop builds its maps. Reproduced by `cargo run --release -p covmap-sim
    /// --example learn` (and checked against it by the Python tests).
    ///
    /// Use it for maps built that way. On unseen office drives it beats the
    /// default's likelihood and mean-map error, and keeps the faced walls
    /// above 0.5 coverage (BENCHMARKS.md, "The sensor-model fit with no-echo
    /// readings occluded"). In maps whose no-echo readings clear their whole
    /// footprint, those walls fall below 0.5 under it. So the default stays
    /// the paper's model.
    pub fn learned() -> Self {
        Self {
            range: RangeModel {
                max_range_m: 5.0,
                band_m: 0.102100702538144,
                sigma_min: 0.036288673889530616,
                sigma_per_m: 0.011702332463868363,
                sigma_end: 0.44842817427662646,
                xi_min: 0.6672966439928844,
                xi_per_m: 0.3343058426491916,
                no_echo_reach: 0.935403869318932,
                no_echo_weight: 0.9427802911546003,
                end_weight: 0.8841802275335975,
                posterior_floor: 0.0005375585256818079,
                end_attribution: 0.0699352584749032,
                free_yield: 0.07712778979285619,
            },
            opening_angle_rad: 0.32335088521800354,
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
    fn the_learned_model_is_valid_and_not_the_default() {
        let m = SonarModel::learned();
        m.validate().unwrap();
        assert_ne!(m, SonarModel::default());
        assert_eq!(m.range.max_range_m, SonarModel::default().range.max_range_m);
    }

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
