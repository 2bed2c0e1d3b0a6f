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
