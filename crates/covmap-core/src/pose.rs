//! Poses and the validation of a scan before anything is mutated.

use serde::{Deserialize, Serialize};

use crate::error::{CovmapError, Result};
use crate::grid::{Cell, Grid};
use crate::sensor::SensorModel;

/// A robot pose in the plane: position in metres, heading in radians.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Pose {
    /// x, metres.
    pub x_m: f64,
    /// y, metres.
    pub y_m: f64,
    /// Heading, radians, counter-clockwise from the x axis.
    pub theta_rad: f64,
}

impl Pose {
    /// A pose from its components.
    pub const fn new(x_m: f64, y_m: f64, theta_rad: f64) -> Self {
        Self {
            x_m,
            y_m,
            theta_rad,
        }
    }
}

impl Pose {
    /// Errors ([`CovmapError::InvalidBearing`]) on the first of `bearings`
    /// (radians, relative to the heading) that is not finite or whose beam
    /// direction, heading plus bearing, is not: the rule every scan is held
    /// to, integrated or simulated. The heading must be finite
    /// ([`Pose::check_finite`]).
    pub fn check_bearings(&self, bearings: &[f64]) -> Result<()> {
        check_bearings(self.theta_rad, bearings)
    }

    /// Errors ([`CovmapError::InvalidPose`]) unless every component is finite.
    pub fn check_finite(&self) -> Result<()> {
        if self.x_m.is_finite() && self.y_m.is_finite() && self.theta_rad.is_finite() {
            Ok(())
        } else {
            Err(CovmapError::InvalidPose {
                x: self.x_m,
                y: self.y_m,
                theta: self.theta_rad,
            })
        }
    }
}

impl From<[f64; 3]> for Pose {
    fn from([x_m, y_m, theta_rad]: [f64; 3]) -> Self {
        Self {
            x_m,
            y_m,
            theta_rad,
        }
    }
}

/// Check a scan against a grid before any map changes: a valid sensor model,
/// a finite pose inside the map, equal lengths, finite non-negative ranges,
/// finite bearings whose beam directions (heading plus bearing) are finite
/// too.
pub(crate) fn validate_scan<M: SensorModel + ?Sized>(
    grid: &Grid,
    pose: &Pose,
    ranges: &[f64],
    bearings: &[f64],
    model: &M,
) -> Result<()> {
    model.validate()?;
    check_pose(grid, pose)?;
    if ranges.len() != bearings.len() {
        return Err(CovmapError::LengthMismatch {
            what: "ranges and bearings",
            left: ranges.len(),
            right: bearings.len(),
        });
    }
    if let Some((index, &value)) = ranges
        .iter()
        .enumerate()
        .find(|(_, r)| !(r.is_finite() && **r >= 0.0))
    {
        return Err(CovmapError::InvalidRange { index, value });
    }
    check_bearings(pose.theta_rad, bearings)
}

/// The cell of `pose` on `grid`: an error if a component is not finite
/// ([`CovmapError::InvalidPose`]) or the position lies in no cell
/// ([`CovmapError::PoseOutsideMap`]).
pub(crate) fn check_pose(grid: &Grid, pose: &Pose) -> Result<Cell> {
    pose.check_finite()?;
    grid.check_inside(pose.x_m, pose.y_m)
}

/// Errors on the first bearing that is not finite or whose beam direction,
/// `theta_rad + bearing`, is not (`theta_rad` is finite).
pub(crate) fn check_bearings(theta_rad: f64, bearings: &[f64]) -> Result<()> {
    match bearings
        .iter()
        .enumerate()
        .find(|(_, b)| !(b.is_finite() && (theta_rad + **b).is_finite()))
    {
        Some((index, &value)) => Err(CovmapError::InvalidBearing { index, value }),
        None => Ok(()),
    }
}

impl Pose {
    /// This pose followed by `offset`, given in this pose's frame: the world
    /// pose of a sensor mounted at `offset` on a robot at `self`.
    ///
    /// ```
    /// use covmap_core::Pose;
    /// let robot = Pose::new(1.0, 2.0, std::f64::consts::FRAC_PI_2);
    /// let sensor = robot.compose(&Pose::new(0.5, 0.0, 0.0));
    /// assert!((sensor.x_m - 1.0).abs() < 1e-12 && (sensor.y_m - 2.5).abs() < 1e-12);
    /// ```
    pub fn compose(&self, offset: &Pose) -> Pose {
        let (sin, cos) = self.theta_rad.sin_cos();
        Pose {
            x_m: self.x_m + cos * offset.x_m - sin * offset.y_m,
            y_m: self.y_m + sin * offset.x_m + cos * offset.y_m,
            theta_rad: self.theta_rad + offset.theta_rad,
        }
    }
}

/// The pose as nalgebra's rigid motion (`world_from_robot`): translation
/// `(x_m, y_m)`, rotation by `theta_rad`.
impl From<Pose> for nalgebra::Isometry2<f64> {
    fn from(p: Pose) -> Self {
        nalgebra::Isometry2::new(nalgebra::Vector2::new(p.x_m, p.y_m), p.theta_rad)
    }
}

/// The pose of nalgebra's rigid motion; the heading in `(-pi, pi]`.
impl From<nalgebra::Isometry2<f64>> for Pose {
    fn from(iso: nalgebra::Isometry2<f64>) -> Self {
        Pose {
            x_m: iso.translation.x,
            y_m: iso.translation.y,
            theta_rad: iso.rotation.angle(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn isometry_round_trip_and_composition_agree() {
        let a = Pose::new(1.5, -2.0, 0.7);
        let b = Pose::new(0.3, 0.1, -2.9);
        let iso: nalgebra::Isometry2<f64> = a.into();
        let back = Pose::from(iso);
        assert!((back.x_m - a.x_m).abs() < 1e-15 && (back.y_m - a.y_m).abs() < 1e-15);
        assert!((back.theta_rad - a.theta_rad).abs() < 1e-15);
        let product = Pose::from(iso * nalgebra::Isometry2::from(b));
        let composed = a.compose(&b);
        assert!((product.x_m - composed.x_m).abs() < 1e-12);
        assert!((product.y_m - composed.y_m).abs() < 1e-12);
        // The composed heading is not wrapped; nalgebra's is.
        let wrapped = (composed.theta_rad + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU)
            - std::f64::consts::PI;
        assert!((product.theta_rad - wrapped).abs() < 1e-12);
    }
}
