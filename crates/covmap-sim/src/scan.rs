//! A simulated scan, in the form the core's maps integrate.

use covmap_core::Pose;

/// One simulated scan: reading `ranges_m[i]` along `pose.theta_rad +
/// bearings_rad[i]` from the pose, ready for
/// [`covmap_core::ScanMap::integrate`]. A reading equal to the sensor's
/// maximum range means "no echo".
#[derive(Clone, Debug, PartialEq)]
pub struct Scan {
    /// Where the scan was taken.
    pub pose: Pose,
    /// Ranges, metres.
    pub ranges_m: Vec<f64>,
    /// Bearings relative to the heading, radians.
    pub bearings_rad: Vec<f64>,
}
