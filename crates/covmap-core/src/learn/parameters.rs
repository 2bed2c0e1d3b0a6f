//! The parameters a fit may change, by name, with their default bounds.

use std::f64::consts::PI;

use crate::exploration::AnySensorModel;
use crate::sensor::{LaserModel, RangeModel, SensorModel, SonarModel};

/// One parameter a fit may change: its name (the model's field) and the
/// bounds a fit searches within unless told otherwise.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Parameter {
    /// The field's name, as in the model's serde form and Python keywords.
    pub name: &'static str,
    /// The default search bounds, `[low, high]`.
    pub bounds: [f64; 2],
}

/// A sensor model whose parameters [`super::fit_sensor_model`] can fit.
///
/// The maximum range is not among them: it is a property of the sensor
/// (which readings mean "no echo"), not of the inverse model.
pub trait Fittable: SensorModel + Clone + Send + Sync {
    /// Every parameter a fit may change, in the order of the model's fields.
    fn parameters(&self) -> &'static [Parameter];
    /// The value of parameter `name`, if the model has it.
    fn get(&self, name: &str) -> Option<f64>;
    /// Set parameter `name` to `value`; false if the model has no such
    /// parameter. The model is not validated.
    fn set(&mut self, name: &str, value: f64) -> bool;
}

/// The range model's fittable parameters and their default bounds: wide
/// enough to hold every sensible sonar and laser (a standard deviation of
/// coverage up to 1, a uniform weight up to 4 times the peak of a unit
/// Gaussian, an end band up to 1 m deep).
const RANGE: [Parameter; 12] = [
    Parameter {
        name: "band_m",
        bounds: [0.0, 1.0],
    },
    Parameter {
        name: "sigma_min",
        bounds: [0.01, 0.6],
    },
    Parameter {
        name: "sigma_per_m",
        bounds: [0.0, 0.2],
    },
    Parameter {
        name: "sigma_end",
        bounds: [0.05, 1.0],
    },
    Parameter {
        name: "xi_min",
        bounds: [0.001, 4.0],
    },
    Parameter {
        name: "xi_per_m",
        bounds: [0.0, 1.0],
    },
    Parameter {
        name: "no_echo_reach",
        bounds: [0.02, 1.0],
    },
    Parameter {
        name: "no_echo_weight",
        bounds: [0.0, 1.0],
    },
    Parameter {
        name: "end_weight",
        bounds: [0.0, 1.0],
    },
    Parameter {
        name: "posterior_floor",
        bounds: [0.0, 1.0 / 256.0],
    },
    Parameter {
        name: "end_attribution",
        bounds: [0.0, 1.0],
    },
    Parameter {
        name: "free_yield",
        bounds: [0.0, 1.0],
    },
];

/// The sonar's: the range model's and the cone's opening angle (2 to 60
/// degrees).
const SONAR: [Parameter; 13] = [
    RANGE[0],
    RANGE[1],
    RANGE[2],
    RANGE[3],
    RANGE[4],
    RANGE[5],
    RANGE[6],
    RANGE[7],
    RANGE[8],
    RANGE[9],
    RANGE[10],
    RANGE[11],
    Parameter {
        name: "opening_angle_rad",
        bounds: [PI / 90.0, PI / 3.0],
    },
];

/// The range model's field called `name`.
fn range_field<'a>(range: &'a mut RangeModel, name: &str) -> Option<&'a mut f64> {
    Some(match name {
        "band_m" => &mut range.band_m,
        "sigma_min" => &mut range.sigma_min,
        "sigma_per_m" => &mut range.sigma_per_m,
        "sigma_end" => &mut range.sigma_end,
        "xi_min" => &mut range.xi_min,
        "xi_per_m" => &mut range.xi_per_m,
        "no_echo_reach" => &mut range.no_echo_reach,
        "no_echo_weight" => &mut range.no_echo_weight,
        "end_weight" => &mut range.end_weight,
        "posterior_floor" => &mut range.posterior_floor,
        "end_attribution" => &mut range.end_attribution,
        "free_yield" => &mut range.free_yield,
        _ => return None,
    })
}

impl Fittable for LaserModel {
    fn parameters(&self) -> &'static [Parameter] {
        &RANGE
    }
    fn get(&self, name: &str) -> Option<f64> {
        range_field(&mut self.range.clone(), name).map(|v| *v)
    }
    fn set(&mut self, name: &str, value: f64) -> bool {
        range_field(&mut self.range, name)
            .map(|v| *v = value)
            .is_some()
    }
}

impl Fittable for SonarModel {
    fn parameters(&self) -> &'static [Parameter] {
        &SONAR
    }
    fn get(&self, name: &str) -> Option<f64> {
        match name {
            "opening_angle_rad" => Some(self.opening_angle_rad),
            _ => range_field(&mut self.range.clone(), name).map(|v| *v),
        }
    }
    fn set(&mut self, name: &str, value: f64) -> bool {
        match name {
            "opening_angle_rad" => {
                self.opening_angle_rad = value;
                true
            }
            _ => range_field(&mut self.range, name)
                .map(|v| *v = value)
                .is_some(),
        }
    }
}

impl Fittable for AnySensorModel {
    fn parameters(&self) -> &'static [Parameter] {
        match self {
            Self::Sonar(m) => m.parameters(),
            Self::Laser(m) => m.parameters(),
        }
    }
    fn get(&self, name: &str) -> Option<f64> {
        match self {
            Self::Sonar(m) => m.get(name),
            Self::Laser(m) => m.get(name),
        }
    }
    fn set(&mut self, name: &str, value: f64) -> bool {
        match self {
            Self::Sonar(m) => m.set(name, value),
            Self::Laser(m) => m.set(name, value),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_parameter_reads_and_writes_its_field_and_the_defaults_lie_within_bounds() {
        for model in [AnySensorModel::default(), AnySensorModel::laser()] {
            for p in model.parameters() {
                let v = model.get(p.name).unwrap();
                assert!(
                    p.bounds[0] <= v && v <= p.bounds[1],
                    "{} = {v} outside {:?}",
                    p.name,
                    p.bounds
                );
                let mut m = model;
                assert!(m.set(p.name, v * 0.5 + 0.013));
                assert_eq!(m.get(p.name), Some(v * 0.5 + 0.013));
                assert_ne!(m, model);
            }
            assert_eq!(model.get("max_range_m"), None);
            let mut m = model;
            assert!(!m.set("nonsense", 1.0));
            assert_eq!(m, model);
        }
    }
}
