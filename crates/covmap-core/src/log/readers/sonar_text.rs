//! Plain-text sonar logs in two files, line by line in step: poses
//! (`timestamp x y theta`) and measurements (`timestamp r_0 … r_{B-1}`),
//! in whatever length and angle units the recording used.

use std::io::Read;
use std::path::Path;

use super::source::{self, Fields, Lines};
use crate::error::{CovmapError, Result, check_parameter};
use crate::log::{Bearings, Log};
use crate::pose::Pose;

/// What a plain-text sonar log does not say about itself: its units, its
/// sonars' bearings, and which readings are echoes.
///
/// A reading (in the file's units) is, in the [`Log`]:
///
/// | reading | in the log |
/// | --- | --- |
/// | equal to `no_echo` | no echo (the maximum range) |
/// | from `min_range_m` to `max_range_m` | the range |
/// | at or above `max_range_m` | no echo |
/// | below `min_range_m` | dropped (NaN; integrating skips it) |
/// | negative (and not `no_echo`) | an error naming the line |
#[derive(Clone, Debug, PartialEq)]
pub struct SonarTextOptions {
    /// Every sonar's bearing, radians relative to the robot's heading, in the
    /// order of the measurement columns.
    pub bearings_rad: Vec<f64>,
    /// Metres per length unit of the poses file's `x` and `y` (0.001 for
    /// millimetres).
    pub length_unit_m: f64,
    /// Metres per length unit of the measurements file's ranges.
    pub range_unit_m: f64,
    /// Radians per angle unit of the pose file's heading (`pi / 1800` for
    /// tenths of a degree).
    pub angle_unit_rad: f64,
    /// The shortest valid reading, metres: shorter ones are dropped.
    pub min_range_m: f64,
    /// The sonars' maximum range, metres: a reading at or above it has no
    /// echo.
    pub max_range_m: f64,
    /// The reading, in the file's units, that a sonar writes when it heard
    /// no echo (5110 in a log whose sonars write 5110 mm for none), if any.
    pub no_echo: Option<f64>,
}

impl SonarTextOptions {
    /// Options for `bearings_rad` and readings up to `max_range_m`, with
    /// every length in metres, the heading in radians, no minimum range and
    /// no no-echo value.
    pub fn new(bearings_rad: Vec<f64>, max_range_m: f64) -> Self {
        SonarTextOptions {
            bearings_rad,
            length_unit_m: 1.0,
            range_unit_m: 1.0,
            angle_unit_rad: 1.0,
            min_range_m: 0.0,
            max_range_m,
            no_echo: None,
        }
    }

    /// One reading of the file as the log holds it (see the type's
    /// documentation); `Err` for a negative one.
    fn convert(&self, raw: f64) -> std::result::Result<f64, String> {
        if self.no_echo == Some(raw) {
            return Ok(self.max_range_m);
        }
        if raw < 0.0 {
            return Err(format!("the reading {raw} is negative"));
        }
        // At or above the maximum range the log reads it as no echo.
        let r = raw * self.range_unit_m;
        Ok(if r >= self.min_range_m { r } else { f64::NAN })
    }
}

impl Log {
    /// The sonar log of `poses_path` and `measurements_path` (plain or
    /// gzip): line `i` of one and of the other are scan `i`, with the same
    /// timestamp.
    ///
    /// # Errors
    /// [`CovmapError::InvalidParameter`] for a unit that is not positive and
    /// finite, a maximum range that is not, or a non-finite bearing;
    /// [`CovmapError::Io`] if a file cannot be opened;
    /// [`CovmapError::Parse`] naming the file and the line of a line that
    /// does not hold its numbers (the wrong count of ranges, a negative
    /// range), whose timestamp differs from the other file's, or that has no
    /// partner in the other file.
    pub fn from_sonar_text(
        poses_path: impl AsRef<Path>,
        measurements_path: impl AsRef<Path>,
        options: &SonarTextOptions,
    ) -> Result<Log> {
        check(options)?;
        read(
            source::open(poses_path.as_ref())?,
            source::open(measurements_path.as_ref())?,
            options,
        )
    }

    /// [`Log::from_sonar_text`] from two readers, named `poses_name` and
    /// `measurements_name` in errors.
    ///
    /// # Errors
    /// As [`Log::from_sonar_text`].
    pub fn read_sonar_text<P: Read + 'static, M: Read + 'static>(
        poses: P,
        poses_name: &str,
        measurements: M,
        measurements_name: &str,
        options: &SonarTextOptions,
    ) -> Result<Log> {
        check(options)?;
        read(
            source::lines(poses, poses_name)?,
            source::lines(measurements, measurements_name)?,
            options,
        )
    }
}

fn check(o: &SonarTextOptions) -> Result<()> {
    for (name, v) in [
        ("length_unit_m", o.length_unit_m),
        ("range_unit_m", o.range_unit_m),
        ("angle_unit_rad", o.angle_unit_rad),
        ("max_range_m", o.max_range_m),
    ] {
        check_parameter(v.is_finite() && v > 0.0, name, v, "positive and finite")?;
    }
    check_parameter(
        o.min_range_m.is_finite() && o.min_range_m >= 0.0 && o.min_range_m < o.max_range_m,
        "min_range_m",
        o.min_range_m,
        "a finite distance from 0 to below max_range_m (metres)",
    )?;
    if let Some(v) = o.no_echo {
        check_parameter(v.is_finite(), "no_echo", v, "a finite reading")?;
    }
    match o
        .bearings_rad
        .iter()
        .enumerate()
        .find(|(_, b)| !b.is_finite())
    {
        Some((index, &value)) => Err(CovmapError::InvalidBearing { index, value }),
        None => Ok(()),
    }
}

fn read(mut poses_in: Lines, mut ranges_in: Lines, o: &SonarTextOptions) -> Result<Log> {
    let beams = o.bearings_rad.len();
    let (mut poses, mut times, mut ranges) = (Vec::new(), Vec::new(), Vec::new());
    loop {
        let pose_line = next_data_line(&mut poses_in)?;
        let range_line = next_data_line(&mut ranges_in)?;
        let (pose_line, range_line) = match (pose_line, range_line) {
            (None, None) => break,
            (Some(_), None) => {
                return Err(ranges_in.error(format!(
                    "the measurements end where {} has line {}",
                    poses_in.file(),
                    poses_in.line()
                )));
            }
            (None, Some(_)) => {
                return Err(poses_in.error(format!(
                    "the poses end where {} has line {}",
                    ranges_in.file(),
                    ranges_in.line()
                )));
            }
            (Some(p), Some(r)) => (p, r),
        };
        let (t, pose) = pose_fields(&pose_line, o).map_err(|e| poses_in.error(e))?;
        let mut f = Fields::new(&range_line);
        let at = ranges.len();
        let read_ranges = (|| {
            let t_ranges = f.number("timestamp")?;
            if t_ranges != t {
                return Err(format!(
                    "timestamp {t_ranges} where {} line {} has {t}",
                    poses_in.file(),
                    poses_in.line()
                ));
            }
            if f.remaining() != beams {
                return Err(format!(
                    "{} ranges where there are {beams} bearings",
                    f.remaining()
                ));
            }
            for k in 0..beams {
                let r = f.number("range")?;
                ranges.push(o.convert(r).map_err(|e| format!("range {k}: {e}"))?);
            }
            Ok(())
        })();
        if let Err(e) = read_ranges {
            ranges.truncate(at);
            return Err(ranges_in.error(e));
        }
        poses.push(pose);
        times.push(t);
    }
    let log = Log::with_dropped(
        poses,
        times,
        ranges,
        Bearings::Fixed(o.bearings_rad.clone()),
        o.max_range_m,
    );
    // The numbers were checked line by line; what is left is the file as a
    // whole (no scan at all).
    match log {
        Ok(log) if !log.is_empty() => Ok(log),
        Ok(_) => Err(poses_in.error("no scan in the files".into())),
        Err(e) => Err(poses_in.error(e.to_string())),
    }
}

/// The next line that is not blank, owned (the two files are read in step).
fn next_data_line(lines: &mut Lines) -> Result<Option<String>> {
    while let Some(line) = lines.next_line()? {
        if !line.trim().is_empty() {
            return Ok(Some(line.to_string()));
        }
    }
    Ok(None)
}

fn pose_fields(line: &str, o: &SonarTextOptions) -> std::result::Result<(f64, Pose), String> {
    let mut f = Fields::new(line);
    let t = f.number("timestamp")?;
    let pose = Pose::new(
        f.number("x")? * o.length_unit_m,
        f.number("y")? * o.length_unit_m,
        f.number("theta")? * o.angle_unit_rad,
    );
    if f.remaining() != 0 {
        return Err(format!("{} fields after the pose", f.remaining()));
    }
    Ok((t, pose))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn options() -> SonarTextOptions {
        SonarTextOptions {
            length_unit_m: 0.001,
            range_unit_m: 0.001,
            angle_unit_rad: std::f64::consts::PI / 1800.0,
            ..SonarTextOptions::new(vec![-1.0, 1.0], 5.0)
        }
    }

    fn parse(poses: &str, ranges: &str) -> Result<Log> {
        let cursor = |s: &str| std::io::Cursor::new(s.as_bytes().to_vec());
        Log::read_sonar_text(cursor(poses), "p.txt", cursor(ranges), "m.txt", &options())
    }

    #[test]
    fn units_scale_poses_and_ranges() {
        let log = parse("1 1000 -500 900\n2 0 0 0\n", "1 170 5110\n2 1 2\n").unwrap();
        assert_eq!(log.len(), 2);
        let p = log.poses()[0];
        assert!((p.x_m - 1.0).abs() < 1e-12 && (p.y_m + 0.5).abs() < 1e-12);
        assert!((p.theta_rad - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
        assert!((log.scan_ranges(0)[1] - 5.11).abs() < 1e-12);
        assert_eq!(log.timestamps_s(), &[1.0, 2.0]);
    }

    #[test]
    fn the_no_echo_value_and_the_valid_range_say_which_readings_are_echoes() {
        let o = SonarTextOptions {
            min_range_m: 0.17,
            no_echo: Some(5110.0),
            ..options()
        };
        let cursor = |s: &str| std::io::Cursor::new(s.as_bytes().to_vec());
        let read = |o: &SonarTextOptions, m: &str| {
            Log::read_sonar_text(cursor("1 0 0 0\n"), "p", cursor(m), "m", o)
        };
        let log = read(&o, "1 5110 169\n").unwrap();
        assert_eq!(log.scan_ranges(0)[0], 5.0);
        assert!(log.scan_ranges(0)[1].is_nan());
        let log = read(&o, "1 170 6000\n").unwrap();
        assert!((log.scan_ranges(0)[0] - 0.17).abs() < 1e-12);
        assert!(log.scan_ranges(0)[1] >= log.max_range_m());
        // A negative no-echo value is a reading like any other.
        let minus = SonarTextOptions {
            no_echo: Some(-1.0),
            ..options()
        };
        assert_eq!(read(&minus, "1 -1 2\n").unwrap().scan_ranges(0)[0], 5.0);
        assert!(matches!(
            read(&o, "1 -1 2\n"),
            Err(CovmapError::Parse { .. })
        ));
        // Ranges and poses in units of their own.
        let units = SonarTextOptions {
            range_unit_m: 0.01,
            ..options()
        };
        assert!((read(&units, "1 100 2\n").unwrap().scan_ranges(0)[0] - 1.0).abs() < 1e-12);
        for bad in [
            SonarTextOptions {
                min_range_m: 5.0,
                ..options()
            },
            SonarTextOptions {
                min_range_m: -0.1,
                ..options()
            },
            SonarTextOptions {
                no_echo: Some(f64::NAN),
                ..options()
            },
            SonarTextOptions {
                range_unit_m: 0.0,
                ..options()
            },
        ] {
            assert!(
                matches!(
                    read(&bad, "1 1 1\n"),
                    Err(CovmapError::InvalidParameter { .. })
                ),
                "{bad:?}"
            );
        }
    }

    #[test]
    fn mismatches_name_the_file_and_line() {
        let cases = [
            (
                "1 0 0 0\n2 0 0 0\n",
                "1 1 1\n3 1 1\n",
                "m.txt",
                2,
                "timestamp",
            ),
            ("1 0 0 0\n", "1 1 1 1\n", "m.txt", 1, "3 ranges"),
            ("1 0 0 0\n", "1 1 -1\n", "m.txt", 1, "negative"),
            ("1 0 0\n", "1 1 1\n", "p.txt", 1, "theta"),
            (
                "1 0 0 0\n2 0 0 0\n",
                "1 1 1\n",
                "m.txt",
                2,
                "measurements end",
            ),
            ("1 0 0 0\n", "1 1 1\n2 1 1\n", "p.txt", 2, "poses end"),
            ("", "", "p.txt", 1, "no scan"),
        ];
        for (p, m, file, line, says) in cases {
            match parse(p, m) {
                Err(CovmapError::Parse {
                    file: f,
                    line: l,
                    reason,
                }) => {
                    assert_eq!((f.as_str(), l), (file, line), "{reason}");
                    assert!(reason.contains(says), "{reason}");
                }
                other => panic!("{p:?} {m:?}: {other:?}"),
            }
        }
        let mut bad = options();
        bad.length_unit_m = 0.0;
        let cursor = || std::io::Cursor::new(b"1 0 0 0\n".to_vec());
        assert!(matches!(
            Log::read_sonar_text(cursor(), "p", cursor(), "m", &bad),
            Err(CovmapError::InvalidParameter {
                name: "length_unit_m",
                ..
            })
        ));
    }
}
