//! The simulated sensor of a run: a sonar ring or a laser, and the inverse
//! model that matches it.

use covmap_core::exploration::AnySensorModel;
use covmap_core::{LaserModel, Pose, SonarModel};
use rand::Rng;

use crate::error::Result;
use crate::laser::Laser;
use crate::simulate::RangeSensor;
use crate::sonar::SonarRing;
use crate::world::World;

/// The simulated sensor a robot explores with.
///
/// # Example
/// ```
/// use covmap_core::exploration::AnySensorModel;
/// use covmap_sim::exploration::SimSensor;
/// let sonar = SimSensor::default();
/// assert_eq!(sonar.bearings_rad().len(), 24);
/// assert!(matches!(sonar.default_model(), AnySensorModel::Sonar(_)));
/// assert_eq!(SimSensor::laser().bearings_rad().len(), 361);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub enum SimSensor {
    /// A ring of sonars.
    Sonar(SonarRing),
    /// A laser scanner.
    Laser(Laser),
}

impl Default for SimSensor {
    /// The paper's 24-sonar ring, [`SonarRing::default`].
    fn default() -> Self {
        Self::Sonar(SonarRing::default())
    }
}

impl SimSensor {
    /// A 180-degree SICK laser of 361 beams, [`Laser::sick_361`].
    pub fn laser() -> Self {
        Self::Laser(Laser::sick_361())
    }

    /// The inverse model that matches the sensor: [`SonarModel::default`]
    /// for a sonar ring, [`LaserModel::default`] for a laser.
    pub fn default_model(&self) -> AnySensorModel {
        match self {
            Self::Sonar(_) => AnySensorModel::Sonar(SonarModel::default()),
            Self::Laser(_) => AnySensorModel::Laser(LaserModel::default()),
        }
    }

    /// The bearing of every beam relative to the heading, radians.
    pub fn bearings_rad(&self) -> &[f64] {
        match self {
            Self::Sonar(s) => s.bearings_rad(),
            Self::Laser(l) => l.bearings_rad(),
        }
    }

    /// Errors unless every parameter of the sensor lies in its range.
    pub fn validate(&self) -> Result<()> {
        match self {
            Self::Sonar(s) => s.validate(),
            Self::Laser(l) => l.validate(),
        }
    }

    /// One scan's ranges from `pose` in `world`, every draw from `rng`.
    pub fn ranges<R: Rng + ?Sized>(
        &self,
        world: &World,
        pose: &Pose,
        rng: &mut R,
    ) -> Result<Vec<f64>> {
        Ok(match self {
            Self::Sonar(s) => s.scan(world, pose, rng)?.ranges_m,
            Self::Laser(l) => l.scan(world, pose, rng)?.ranges_m,
        })
    }
}
