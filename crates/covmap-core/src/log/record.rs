//! The record of a drive: per scan a pose, a timestamp and ranges, the
//! sensor's bearings and maximum range, and where the sensor sits on the
//! robot.

use std::ops::Range;

use serde::{Deserialize, Serialize};

use crate::error::{CovmapError, Result, check_parameter};
use crate::pose::Pose;

/// The bearings of a log's beams, radians relative to the sensor's heading.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum Bearings {
    /// The same bearings in every scan, one a beam.
    Fixed(Vec<f64>),
    /// Bearings of their own in every scan, scan by scan, one a beam
    /// (`scans x beams`, row-major).
    PerScan(Vec<f64>),
}

/// A recorded drive: scan `i` was taken at `timestamps_s()[i]` from robot
/// pose `poses()[i]`, reading `scan_ranges(i)[k]` metres along bearing
/// `scan_bearings(i)[k]` of a sensor mounted at `sensor_offset()` on the
/// robot.
///
/// A range at or above [`Log::max_range_m`] is a reading without echo. A NaN
/// range is a beam that gave no reading (a dropped beam, as
/// [`Log::from_laser_scans`] makes of REP 117's NaN and `-inf`): integrating
/// the log skips it. [`Log::new`] accepts neither NaN nor infinite ranges,
/// so that a mistake in the caller's numbers is an error rather than a
/// silently dropped beam.
///
/// # Example
/// ```
/// use covmap_core::{Bearings, Log, Pose};
/// let poses = vec![Pose::new(0.0, 0.0, 0.0), Pose::new(1.0, 0.0, 0.0)];
/// let bearings = Bearings::Fixed(vec![-0.5, 0.0, 0.5]);
/// let ranges = vec![2.0, 3.0, 8.0, 2.0, 1.0, 2.0];
/// let log = Log::new(poses, vec![0.0, 0.1], ranges, bearings, 8.0).unwrap();
/// assert_eq!((log.len(), log.beams()), (2, 3));
/// assert_eq!(log.scan_ranges(1), &[2.0, 1.0, 2.0]);
/// assert!(Log::new(vec![Pose::default()], vec![0.0], vec![-1.0], Bearings::Fixed(vec![0.0]), 8.0).is_err());
/// ```
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "LogData", into = "LogData")]
pub struct Log {
    poses: Vec<Pose>,
    timestamps_s: Vec<f64>,
    ranges_m: Vec<f64>,
    beams: usize,
    bearings_rad: Bearings,
    max_range_m: f64,
    sensor_offset: Pose,
}

/// The serialised form of a [`Log`], validated on the way in.
#[derive(Serialize, Deserialize)]
struct LogData {
    poses: Vec<Pose>,
    timestamps_s: Vec<f64>,
    #[serde(with = "dropped_as_null")]
    ranges_m: Vec<f64>,
    bearings_rad: Bearings,
    max_range_m: f64,
    sensor_offset: Pose,
}

/// A log's ranges with its dropped beams (NaN) as `null`, as JSON has no
/// NaN (`serde_json` writes one as `null` and reads `null` as no number),
/// and `null` back as a dropped beam.
mod dropped_as_null {
    use serde::{Deserialize, Deserializer, Serialize, Serializer};

    pub fn serialize<S: Serializer>(ranges: &[f64], s: S) -> Result<S::Ok, S::Error> {
        let kept: Vec<Option<f64>> = ranges.iter().map(|&r| (!r.is_nan()).then_some(r)).collect();
        kept.serialize(s)
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<f64>, D::Error> {
        let kept = Vec::<Option<f64>>::deserialize(d)?;
        Ok(kept.into_iter().map(|r| r.unwrap_or(f64::NAN)).collect())
    }
}

impl TryFrom<LogData> for Log {
    type Error = CovmapError;
    fn try_from(d: LogData) -> Result<Self> {
        Log::with_dropped(
            d.poses,
            d.timestamps_s,
            d.ranges_m,
            d.bearings_rad,
            d.max_range_m,
        )?
        .with_sensor_offset(d.sensor_offset)
    }
}

impl From<Log> for LogData {
    fn from(l: Log) -> Self {
        LogData {
            poses: l.poses,
            timestamps_s: l.timestamps_s,
            ranges_m: l.ranges_m,
            bearings_rad: l.bearings_rad,
            max_range_m: l.max_range_m,
            sensor_offset: l.sensor_offset,
        }
    }
}

impl Log {
    /// A log of `poses.len()` scans: `ranges_m` holds them one after the
    /// other (`scans x beams`, row-major, metres), `bearings` their beams'
    /// directions; the sensor sits at the robot's pose until
    /// [`Log::with_sensor_offset`] says otherwise.
    ///
    /// # Errors
    /// [`CovmapError::LengthMismatch`] unless there is one timestamp a pose
    /// and the ranges (and per-scan bearings) fill whole scans;
    /// [`CovmapError::InvalidParameter`] for a maximum range that is not
    /// positive and finite; [`CovmapError::InScan`] naming the first scan
    /// with a non-finite pose, timestamp or bearing, or a range that is NaN,
    /// infinite or negative.
    pub fn new(
        poses: Vec<Pose>,
        timestamps_s: Vec<f64>,
        ranges_m: Vec<f64>,
        bearings: Bearings,
        max_range_m: f64,
    ) -> Result<Self> {
        let log = Self::with_dropped(poses, timestamps_s, ranges_m, bearings, max_range_m)?;
        if let Some(at) = log.ranges_m.iter().position(|r| r.is_nan()) {
            let (scan, index) = (at / log.beams.max(1), at % log.beams.max(1));
            return Err(CovmapError::InvalidRange {
                index,
                value: f64::NAN,
            }
            .in_scan(scan));
        }
        Ok(log)
    }

    /// [`Log::new`], with NaN ranges accepted as dropped beams.
    pub(crate) fn with_dropped(
        poses: Vec<Pose>,
        timestamps_s: Vec<f64>,
        ranges_m: Vec<f64>,
        bearings: Bearings,
        max_range_m: f64,
    ) -> Result<Self> {
        check_parameter(
            max_range_m.is_finite() && max_range_m > 0.0,
            "max_range_m",
            max_range_m,
            "a positive, finite distance (metres)",
        )?;
        let scans = poses.len();
        if timestamps_s.len() != scans {
            return Err(CovmapError::LengthMismatch {
                what: "poses and timestamps",
                left: scans,
                right: timestamps_s.len(),
            });
        }
        let beams = match &bearings {
            Bearings::Fixed(b) => b.len(),
            Bearings::PerScan(b) if scans == 0 => b.len(),
            Bearings::PerScan(b) => b.len() / scans,
        };
        if ranges_m.len() != scans * beams {
            return Err(CovmapError::LengthMismatch {
                what: "ranges and scans x beams",
                left: ranges_m.len(),
                right: scans * beams,
            });
        }
        if let Bearings::PerScan(b) = &bearings
            && b.len() != ranges_m.len()
        {
            return Err(CovmapError::LengthMismatch {
                what: "per-scan bearings and ranges",
                left: b.len(),
                right: ranges_m.len(),
            });
        }
        let log = Self {
            poses,
            timestamps_s,
            ranges_m,
            beams,
            bearings_rad: bearings,
            max_range_m,
            sensor_offset: Pose::default(),
        };
        for i in 0..scans {
            log.check_scan(i).map_err(|e| e.in_scan(i))?;
        }
        Ok(log)
    }

    fn check_scan(&self, i: usize) -> Result<()> {
        self.poses[i].check_finite()?;
        let t = self.timestamps_s[i];
        check_parameter(t.is_finite(), "timestamp_s", t, "a finite time (seconds)")?;
        if let Some((index, &value)) = self
            .scan_ranges(i)
            .iter()
            .enumerate()
            .find(|(_, r)| !(r.is_nan() || (r.is_finite() && **r >= 0.0)))
        {
            return Err(CovmapError::InvalidRange { index, value });
        }
        match self
            .scan_bearings(i)
            .iter()
            .enumerate()
            .find(|(_, b)| !b.is_finite())
        {
            Some((index, &value)) => Err(CovmapError::InvalidBearing { index, value }),
            None => Ok(()),
        }
    }

    /// This log with its sensor mounted at `offset` in the robot's frame
    /// (CARMEN's `robot_frontlaser_offset`, a `tf` transform): the scans
    /// are taken from `pose.compose(offset)`.
    ///
    /// # Errors
    /// [`CovmapError::InvalidPose`] unless every component is finite.
    pub fn with_sensor_offset(mut self, offset: Pose) -> Result<Self> {
        offset.check_finite()?;
        self.sensor_offset = offset;
        Ok(self)
    }

    /// The number of scans.
    pub fn len(&self) -> usize {
        self.poses.len()
    }

    /// Whether the log holds no scan.
    pub fn is_empty(&self) -> bool {
        self.poses.is_empty()
    }

    /// The number of beams a scan.
    pub fn beams(&self) -> usize {
        self.beams
    }

    /// The robot's pose of every scan.
    pub fn poses(&self) -> &[Pose] {
        &self.poses
    }

    /// The time of every scan, seconds.
    pub fn timestamps_s(&self) -> &[f64] {
        &self.timestamps_s
    }

    /// Every range, metres, `scans x beams` row-major (NaN: a dropped beam).
    pub fn ranges_m(&self) -> &[f64] {
        &self.ranges_m
    }

    /// The ranges of scan `i`, metres.
    ///
    /// # Panics
    /// If `i >= self.len()`.
    pub fn scan_ranges(&self, i: usize) -> &[f64] {
        &self.ranges_m[i * self.beams..(i + 1) * self.beams]
    }

    /// The bearings, radians relative to the sensor's heading.
    pub fn bearings(&self) -> &Bearings {
        &self.bearings_rad
    }

    /// The bearings of scan `i`, radians.
    ///
    /// # Panics
    /// If `i >= self.len()`.
    pub fn scan_bearings(&self, i: usize) -> &[f64] {
        match &self.bearings_rad {
            Bearings::Fixed(b) => b,
            Bearings::PerScan(b) => &b[i * self.beams..(i + 1) * self.beams],
        }
    }

    /// The sensor's maximum range, metres: a reading at or above it has no
    /// echo.
    pub fn max_range_m(&self) -> f64 {
        self.max_range_m
    }

    /// Where the sensor sits in the robot's frame.
    pub fn sensor_offset(&self) -> Pose {
        self.sensor_offset
    }

    /// The world pose of the sensor in scan `i`.
    ///
    /// # Panics
    /// If `i >= self.len()`.
    pub fn sensor_pose(&self, i: usize) -> Pose {
        self.poses[i].compose(&self.sensor_offset)
    }

    /// The scans `range` of this log, as a log of their own.
    ///
    /// # Errors
    /// [`CovmapError::InvalidParameter`] if the range is reversed or ends
    /// beyond the log.
    pub fn slice(&self, range: Range<usize>) -> Result<Log> {
        check_parameter(
            range.start <= range.end && range.end <= self.len(),
            "range.end",
            range.end as f64,
            "a range of scans within the log",
        )?;
        let b = self.beams;
        let bearings_rad = match &self.bearings_rad {
            Bearings::Fixed(v) => Bearings::Fixed(v.clone()),
            Bearings::PerScan(v) => Bearings::PerScan(v[range.start * b..range.end * b].to_vec()),
        };
        Ok(Log {
            poses: self.poses[range.clone()].to_vec(),
            timestamps_s: self.timestamps_s[range.clone()].to_vec(),
            ranges_m: self.ranges_m[range.start * b..range.end * b].to_vec(),
            beams: b,
            bearings_rad,
            max_range_m: self.max_range_m,
            sensor_offset: self.sensor_offset,
        })
    }

    /// The bounds `[x_min, y_min, x_max, y_max]` of every robot and sensor
    /// position and every beam's end point, each beam cut at `reach_m`
    /// metres (a beam without echo ends at the maximum range); `None` for
    /// an empty log.
    ///
    /// # Errors
    /// [`CovmapError::InvalidParameter`] unless `reach_m` is non-negative
    /// (infinite is fine: every beam its full length).
    pub fn extent(&self, reach_m: f64) -> Result<Option<[f64; 4]>> {
        check_parameter(
            reach_m >= 0.0,
            "reach_m",
            reach_m,
            "a non-negative distance (metres)",
        )?;
        let mut bounds: Option<[f64; 4]> = None;
        let mut add = |x: f64, y: f64| {
            let b = bounds.get_or_insert([x, y, x, y]);
            *b = [b[0].min(x), b[1].min(y), b[2].max(x), b[3].max(y)];
        };
        for i in 0..self.len() {
            let (robot, sensor) = (self.poses[i], self.sensor_pose(i));
            add(robot.x_m, robot.y_m);
            add(sensor.x_m, sensor.y_m);
            for (&r, &b) in self.scan_ranges(i).iter().zip(self.scan_bearings(i)) {
                if r.is_nan() {
                    continue;
                }
                let d = r.min(self.max_range_m).min(reach_m);
                let (sin, cos) = (sensor.theta_rad + b).sin_cos();
                add(sensor.x_m + d * cos, sensor.y_m + d * sin);
            }
        }
        Ok(bounds)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn two_scans() -> Log {
        Log::new(
            vec![
                Pose::new(0.0, 0.0, 0.0),
                Pose::new(1.0, 2.0, std::f64::consts::FRAC_PI_2),
            ],
            vec![0.0, 1.0],
            vec![1.0, 9.0, 0.5, 3.0],
            Bearings::PerScan(vec![0.0, 0.5, -0.5, 0.0]),
            5.0,
        )
        .unwrap()
    }

    #[test]
    fn bad_logs_name_the_scan_and_the_value() {
        let p = vec![Pose::default(); 2];
        let fixed = || Bearings::Fixed(vec![0.0, 1.0]);
        let e = Log::new(
            p.clone(),
            vec![0.0, 1.0],
            vec![1.0, 1.0, 1.0, f64::NAN],
            fixed(),
            5.0,
        )
        .unwrap_err();
        assert!(
            matches!(&e, CovmapError::InScan { scan: 1, source } if matches!(**source, CovmapError::InvalidRange { index: 1, .. })),
            "{e}"
        );
        let e = Log::new(
            p.clone(),
            vec![0.0, 1.0],
            vec![1.0, -1.0, 1.0, 1.0],
            fixed(),
            5.0,
        )
        .unwrap_err();
        assert!(matches!(&e, CovmapError::InScan { scan: 0, .. }), "{e}");
        let e = Log::new(p.clone(), vec![0.0, f64::NAN], vec![1.0; 4], fixed(), 5.0).unwrap_err();
        assert!(matches!(&e, CovmapError::InScan { scan: 1, .. }), "{e}");
        let e = Log::new(p.clone(), vec![0.0], vec![1.0; 4], fixed(), 5.0).unwrap_err();
        assert!(matches!(e, CovmapError::LengthMismatch { .. }));
        let e = Log::new(p.clone(), vec![0.0, 1.0], vec![1.0; 3], fixed(), 5.0).unwrap_err();
        assert!(matches!(e, CovmapError::LengthMismatch { .. }));
        let e = Log::new(p.clone(), vec![0.0, 1.0], vec![1.0; 4], fixed(), 0.0).unwrap_err();
        assert!(matches!(
            e,
            CovmapError::InvalidParameter {
                name: "max_range_m",
                ..
            }
        ));
        let e = Log::new(
            p,
            vec![0.0, 1.0],
            vec![1.0; 4],
            Bearings::Fixed(vec![0.0, f64::INFINITY]),
            5.0,
        )
        .unwrap_err();
        assert!(
            matches!(&e, CovmapError::InScan { scan: 0, source } if matches!(**source, CovmapError::InvalidBearing { index: 1, .. })),
            "{e}"
        );
    }

    #[test]
    fn slices_keep_their_scans_and_bearings() {
        let log = two_scans();
        let tail = log.slice(1..2).unwrap();
        assert_eq!(tail.len(), 1);
        assert_eq!(tail.scan_ranges(0), &[0.5, 3.0]);
        assert_eq!(tail.scan_bearings(0), &[-0.5, 0.0]);
        assert_eq!(tail.poses()[0], log.poses()[1]);
        assert!(log.slice(1..3).is_err());
        assert!(log.slice(0..0).unwrap().is_empty());
    }

    #[test]
    fn extent_covers_poses_and_end_points_within_reach() {
        let log = two_scans()
            .with_sensor_offset(Pose::new(0.5, 0.0, 0.0))
            .unwrap();
        let [x0, y0, x1, y1] = log.extent(f64::INFINITY).unwrap().unwrap();
        // Scan 0's no-echo beam (9 >= 5) along 0.5 rad ends at 5 m.
        let far_x = 0.5 + 5.0 * 0.5f64.cos();
        assert!((x1 - far_x).abs() < 1e-12, "{x1}");
        // Scan 1's sensor sits 0.5 m along +y from (1, 2); its beam along
        // pi/2 reads 3 m.
        assert!((y1 - 5.5).abs() < 1e-12, "{y1}");
        assert_eq!((x0, y0), (0.0, 0.0));
        let [_, _, x1_cut, _] = log.extent(1.0).unwrap().unwrap();
        // Scan 0's beam straight ahead reads 1 m from the sensor at (0.5, 0).
        assert!((x1_cut - 1.5).abs() < 1e-12, "{x1_cut}");
        assert!(log.extent(-1.0).is_err());
        assert_eq!(log.slice(0..0).unwrap().extent(1.0).unwrap(), None);
    }

    #[test]
    fn serde_round_trip_checks_on_the_way_in() {
        let log = two_scans()
            .with_sensor_offset(Pose::new(0.1, 0.2, 0.3))
            .unwrap();
        let json = serde_json::to_string(&log).unwrap();
        assert_eq!(serde_json::from_str::<Log>(&json).unwrap(), log);
        let broken = json.replace("\"max_range_m\":5.0", "\"max_range_m\":-5.0");
        assert_ne!(broken, json);
        assert!(serde_json::from_str::<Log>(&broken).is_err());
    }

    /// A log with dropped beams (NaN ranges, as laser drivers report them)
    /// goes through its serialised form and back, the beams still dropped.
    #[test]
    fn dropped_beams_round_trip() {
        let log = Log::with_dropped(
            vec![Pose::new(0.0, 0.0, 0.0)],
            vec![0.0],
            vec![1.0, f64::NAN, 2.0],
            Bearings::Fixed(vec![-0.1, 0.0, 0.1]),
            5.0,
        )
        .unwrap();
        let json = serde_json::to_string(&log).unwrap();
        assert!(json.contains("[1.0,null,2.0]"), "{json}");
        let back: Log = serde_json::from_str(&json).unwrap();
        assert_eq!(back.scan_ranges(0)[0], 1.0);
        assert!(back.scan_ranges(0)[1].is_nan());
        assert_eq!(back.scan_ranges(0)[2], 2.0);
    }
}
