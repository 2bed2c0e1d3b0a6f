//! Scans as ROS hands them (`sensor_msgs/LaserScan`), with REP 117's
//! conventions for readings that are not distances converted at this edge:
//!
//! | reading | meaning (REP 117) | in the [`Log`] |
//! | --- | --- | --- |
//! | `+inf` | no return within range | no echo (the maximum range) |
//! | finite, above `range_max` | beyond range (drivers before REP 117) | no echo |
//! | finite, from `range_min` to `range_max` | a return | the range |
//! | finite, below `range_min` | not a valid reading | dropped |
//! | `-inf` | too close to measure | dropped |
//! | NaN | an erroneous reading | dropped |
//!
//! A dropped beam is a NaN in the log and integrating skips it; the maps'
//! `integrate` stays strict, refusing any range that is not a distance.

use crate::error::{CovmapError, Result, check_parameter};
use crate::log::{Bearings, Log};
use crate::pose::Pose;

/// The fan of a `sensor_msgs/LaserScan`: beam `k` points `angle_min_rad +
/// k angle_increment_rad` from the sensor's heading, readings from
/// `range_min_m` to `range_max_m` are returns.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LaserScanFan {
    /// The first beam's bearing, radians (`angle_min`).
    pub angle_min_rad: f64,
    /// The step between beams, radians (`angle_increment`; negative for a
    /// clockwise scanner).
    pub angle_increment_rad: f64,
    /// The shortest valid reading, metres (`range_min`).
    pub range_min_m: f64,
    /// The longest valid reading, metres (`range_max`): the log's maximum
    /// range.
    pub range_max_m: f64,
}

impl LaserScanFan {
    /// Errors ([`CovmapError::InvalidParameter`]) unless the angles are
    /// finite and `0 <= range_min_m < range_max_m`, both finite.
    pub fn validate(&self) -> Result<()> {
        check_parameter(
            self.angle_min_rad.is_finite(),
            "angle_min",
            self.angle_min_rad,
            "a finite angle (radians)",
        )?;
        check_parameter(
            self.angle_increment_rad.is_finite(),
            "angle_increment",
            self.angle_increment_rad,
            "a finite angle (radians)",
        )?;
        check_parameter(
            self.range_min_m.is_finite() && self.range_min_m >= 0.0,
            "range_min",
            self.range_min_m,
            "a finite, non-negative distance (metres)",
        )?;
        check_parameter(
            self.range_max_m.is_finite() && self.range_max_m > self.range_min_m,
            "range_max",
            self.range_max_m,
            "a finite distance above range_min (metres)",
        )
    }

    /// One reading as the log holds it (see the module documentation).
    pub fn convert(&self, r: f64) -> f64 {
        if r == f64::INFINITY || r > self.range_max_m {
            self.range_max_m
        } else if r >= self.range_min_m {
            r
        } else {
            // NaN, -inf and readings below range_min.
            f64::NAN
        }
    }
}

impl Log {
    /// A log of `poses.len()` LaserScan scans: `ranges` holds them one after
    /// the other (`scans x beams`, row-major, `beams = ranges.len() /
    /// scans`), converted as the module documentation says; `timestamps_s`,
    /// if given, one a scan (else each scan's index).
    ///
    /// # Errors
    /// [`CovmapError::InvalidParameter`] for an invalid fan;
    /// [`CovmapError::LengthMismatch`] unless the ranges fill whole scans
    /// and there is one timestamp a scan; [`CovmapError::InScan`] for a
    /// non-finite pose or timestamp.
    ///
    /// # Example
    /// ```
    /// use covmap_core::{Log, Pose, log::laser_scan::LaserScanFan};
    /// let fan = LaserScanFan { angle_min_rad: -0.1, angle_increment_rad: 0.1,
    ///                          range_min_m: 0.1, range_max_m: 10.0 };
    /// let log = Log::from_laser_scans(vec![Pose::default()],
    ///     &[f64::INFINITY, 2.0, f64::NAN], &fan, None).unwrap();
    /// assert_eq!(log.scan_ranges(0)[..2], [10.0, 2.0]);
    /// assert!(log.scan_ranges(0)[2].is_nan()); // dropped
    /// ```
    pub fn from_laser_scans(
        poses: Vec<Pose>,
        ranges: &[f64],
        fan: &LaserScanFan,
        timestamps_s: Option<Vec<f64>>,
    ) -> Result<Log> {
        fan.validate()?;
        let scans = poses.len();
        let beams = ranges.len().checked_div(scans).unwrap_or(0);
        if beams * scans != ranges.len() {
            return Err(CovmapError::LengthMismatch {
                what: "ranges and whole scans",
                left: ranges.len(),
                right: beams * scans,
            });
        }
        let bearings = (0..beams)
            .map(|k| fan.angle_min_rad + k as f64 * fan.angle_increment_rad)
            .collect();
        let timestamps = timestamps_s.unwrap_or_else(|| (0..scans).map(|i| i as f64).collect());
        let ranges = ranges.iter().map(|&r| fan.convert(r)).collect();
        Log::with_dropped(
            poses,
            timestamps,
            ranges,
            Bearings::Fixed(bearings),
            fan.range_max_m,
        )
    }
}
