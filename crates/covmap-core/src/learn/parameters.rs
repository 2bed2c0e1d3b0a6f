//! The parameters a fit may change, by name: the sensor models' own
//! declaration ([`crate::sensor::parameters`]), those with fit bounds.

use crate::exploration::AnySensorModel;
pub use crate::sensor::Parameter;
use crate::sensor::{
    FITTABLE_RANGE_PARAMETERS, FITTABLE_SONAR_PARAMETERS, LaserModel, SensorModel, SonarModel,
};

/// A sensor model whose parameters [`super::fit_sensor_model`] can fit.
///
/// The maximum range is not among them: it is a property of the sensor
/// (which readings mean "no echo"), not of the inverse model.
pub trait Fittable: SensorModel + Clone + Send + Sync {
    /// Every parameter a fit may change, in the order of the model's
    /// fields (each with its [`Parameter::fit_bounds`]).
    fn parameters(&self) -> &'static [Parameter];
    /// The value of parameter `name`, if the model has it.
    fn get(&self, name: &str) -> Option<f64>;
    /// Set parameter `name` to `value`; false if the model has no such
    /// parameter. The model is not validated.
    fn set(&mut self, name: &str, value: f64) -> bool;
}

impl Fittable for LaserModel {
    fn parameters(&self) -> &'static [Parameter] {
        &FITTABLE_RANGE_PARAMETERS
    }
    fn get(&self, name: &str) -> Option<f64> {
        self.range.get(name)
    }
    fn set(&mut self, name: &str, value: f64) -> bool {
        self.range.set(name, value)
    }
}

impl Fittable for SonarModel {
    fn parameters(&self) -> &'static [Parameter] {
        &FITTABLE_SONAR_PARAMETERS
    }
    fn get(&self, name: &str) -> Option<f64> {
        match name {
            "opening_angle_rad" => Some(self.opening_angle_rad),
            _ => self.range.get(name),
        }
    }
    fn set(&mut self, name: &str, value: f64) -> bool {
        match name {
            "opening_angle_rad" => {
                self.opening_angle_rad = value;
                true
            }
            _ => self.range.set(name, value),
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
                let [low, high] = p.fit_bounds.unwrap();
                assert!(
                    low <= v && v <= high,
                    "{} = {v} outside {low} to {high}",
                    p.name
                );
                let mut m = model;
                assert!(m.set(p.name, v * 0.5 + 0.013));
                assert_eq!(m.get(p.name), Some(v * 0.5 + 0.013));
                assert_ne!(m, model);
            }
            assert!(model.parameters().iter().all(|p| p.name != "max_range_m"));
            let mut m = model;
            assert!(!m.set("nonsense", 1.0));
            assert_eq!(m, model);
        }
    }
}
