//! CARMEN log files: one message a line, the laser's scans in `FLASER`,
//! `ROBOTLASER1` or `RAWLASER1` messages, the robot's odometry in `ODOM`.
//!
//! What the reader takes from each message:
//!
//! | message | ranges and bearings | pose | time |
//! | --- | --- | --- | --- |
//! | `FLASER n r_1 … r_n x y theta odom_x odom_y odom_theta t host t_log` | `n` ranges over the 180 degrees in front, the first at -90 degrees | `x y theta`, the laser's pose (CARMEN writes the laser's pose there, the robot's odometry after it) | `t` |
//! | `ROBOTLASER1 type start fov res max acc mode n r_1 … r_n m e_1 … e_m lx ly lth rx ry rth tv rv fsd ssd ta t host t_log` | start + k res | `lx ly lth`, the laser's pose | `t` |
//! | `RAWLASER1 type start fov res max acc mode n r_1 … r_n m e_1 … e_m t host t_log` | start + k res | `ODOM` interpolated at `t`, the front laser's offset (`PARAM robot_frontlaser_offset`, `_side_offset`, `_angular_offset`) applied when integrated | `t` |
//!
//! `ODOM x y theta tv rv accel t host t_log` gives the robot's pose at `t`
//! (taken in the order of `t`: real logs hold some a few milliseconds out of
//! the file's order); a `RAWLASER1` scan between two takes the pose linearly between them (the
//! heading the short way round), one before the first or after the last
//! the nearest. `PARAM`, `SYNC`, `NEFF`, `#` comments, blank lines and
//! messages of other sensors are skipped. A log holds the scans of one
//! kind: the first laser message decides which, the other kinds are
//! skipped.
//!
//! One laser a log. [`CarmenLaser::Front`] (the default) reads the
//! messages above; [`CarmenLaser::Rear`] reads the rear laser's instead:
//! `RLASER` (laid out as `FLASER`, its pose the rear laser's own, its 180
//! degrees in front of the rear laser), `ROBOTLASER2` and `RAWLASER2` (as
//! `ROBOTLASER1` and `RAWLASER1`), with the rear laser's mounting
//! (`PARAM robot_rearlaser_offset`, `_side_offset`, `_angular_offset`) for
//! `RAWLASER2` and its maximum range `PARAM robot_rear_laser_max`. (None
//! of the four logs in `../shared/data/carmen/` holds rear-laser
//! messages; the rear reading follows the format CARMEN's logger writes
//! and is tested on written lines.) A rear scan is never mixed into a
//! front log: the two lasers look different ways from different places.
//!
//! Spacing of `FLASER` beams. The message says only how many beams there
//! are; the 180 degrees and the first bearing at -90 degrees are CARMEN's
//! convention for the SICK scanners of these logs, whose steps are 1 or
//! 0.5 degrees. An odd count spans both ends (181 beams at 1 degree, 361
//! at 0.5), an even count stops one step short of +90 degrees (180 beams
//! at 1 degree, 360 at 0.5), so the step is `pi / (n - 1)` for odd `n` and
//! `pi / n` for even `n`. (The other reading of an even count, `pi / (n -
//! 1)`, bends walls seen at the edge of the scan by half a degree. Checked
//! on the logs (`tests/core/logs.rs`, `flaser_spacing_…`): the share of
//! echoes ending in a cell the log's own occupancy map (5 cm) holds
//! occupied is 0.692 for Intel's 180 beams at `pi / 180`, 0.655 at `pi /
//! 179`, 0.644 at `pi / 181`; 0.805 for Seattle's 361 at `pi / 360`, 0.798
//! at `pi / 359`, 0.788 at `pi / 361`: walls drawn by the chosen fan
//! agree best from scan to scan.)
//!
//! The maximum range: [`CarmenOptions::max_range_m`] if given, else
//! `PARAM robot_front_laser_max` (`robot_rear_laser_max`) if the log has it, else the largest
//! `max` of the `ROBOTLASER1`/`RAWLASER1` messages, else the largest
//! `FLASER` reading (the value the scanner reports for no return).

use std::io::Read;
use std::path::Path;

use super::source::{self, Fields, Lines};
use crate::error::{CovmapError, Result, check_parameter};
use crate::log::{Bearings, Log};
use crate::pose::Pose;

/// The most beams a CARMEN scan may claim (far above any scanner's), so
/// that a corrupt count cannot make the reader reserve memory for it.
pub const MAX_CARMEN_BEAMS: usize = 100_000;

/// How to read a CARMEN log where the file leaves a choice.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CarmenOptions {
    /// The sensor's maximum range, metres (readings at or above it have no
    /// echo); `None`: as the module documentation says.
    pub max_range_m: Option<f64>,
    /// The step between `FLASER` (or `RLASER`) beams, radians; `None`:
    /// CARMEN's convention (see the module documentation).
    pub flaser_step_rad: Option<f64>,
    /// Which laser's scans to read.
    pub laser: CarmenLaser,
}

/// The laser of a CARMEN log whose scans a [`Log`] holds.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum CarmenLaser {
    /// The front laser: `FLASER`, `ROBOTLASER1`, `RAWLASER1`.
    #[default]
    Front,
    /// The rear laser: `RLASER`, `ROBOTLASER2`, `RAWLASER2`.
    Rear,
}

impl CarmenLaser {
    /// This laser's messages: as `FLASER`, `ROBOTLASER1`, `RAWLASER1`.
    fn messages(self) -> [&'static str; 3] {
        match self {
            Self::Front => ["FLASER", "ROBOTLASER1", "RAWLASER1"],
            Self::Rear => ["RLASER", "ROBOTLASER2", "RAWLASER2"],
        }
    }

    /// This laser's `PARAM`s: its offset forward, sideways, its angle, its
    /// maximum range.
    fn params(self) -> [&'static str; 4] {
        match self {
            Self::Front => [
                "robot_frontlaser_offset",
                "robot_frontlaser_side_offset",
                "robot_frontlaser_angular_offset",
                "robot_front_laser_max",
            ],
            Self::Rear => [
                "robot_rearlaser_offset",
                "robot_rearlaser_side_offset",
                "robot_rearlaser_angular_offset",
                "robot_rear_laser_max",
            ],
        }
    }
}

#[derive(Clone, Copy, PartialEq, Debug)]
enum Kind {
    Flaser,
    RobotLaser,
    RawLaser,
}

/// One laser message as read.
struct Scan {
    t: f64,
    pose: Option<Pose>,
    start_rad: f64,
    step_rad: f64,
    line: usize,
}

#[derive(Default)]
struct State {
    kind: Option<Kind>,
    scans: Vec<Scan>,
    ranges: Vec<f64>,
    beams: Option<usize>,
    odom: Vec<(f64, Pose)>,
    offset: Pose,
    param_max_m: Option<f64>,
    message_max_m: Option<f64>,
    largest_m: f64,
}

impl Log {
    /// The log in the CARMEN file at `path` (plain or gzip), read as
    /// [`CarmenOptions::default`] says.
    ///
    /// # Errors
    /// [`CovmapError::InvalidParameter`] for an option that is not positive
    /// and finite; [`CovmapError::Io`] if the file cannot be opened;
    /// [`CovmapError::Parse`] naming the file and the line of the first
    /// message that does not read (a missing or non-numeric field, a
    /// negative range, a beam count unlike the earlier scans'), or of the
    /// end if there is no laser scan.
    pub fn from_carmen(path: impl AsRef<Path>) -> Result<Log> {
        Self::from_carmen_with(path, &CarmenOptions::default())
    }

    /// [`Log::from_carmen`] with `options`.
    ///
    /// # Errors
    /// As [`Log::from_carmen`].
    pub fn from_carmen_with(path: impl AsRef<Path>, options: &CarmenOptions) -> Result<Log> {
        read(source::open(path.as_ref())?, options)
    }

    /// The CARMEN log `reader` yields (plain or gzip), `name` naming it in
    /// errors.
    ///
    /// # Errors
    /// As [`Log::from_carmen`].
    pub fn read_carmen<R: Read + 'static>(
        reader: R,
        name: &str,
        options: &CarmenOptions,
    ) -> Result<Log> {
        read(source::lines(reader, name)?, options)
    }
}

fn read(mut lines: Lines, options: &CarmenOptions) -> Result<Log> {
    for (name, value) in [
        ("max_range_m", options.max_range_m),
        ("flaser_step_rad", options.flaser_step_rad),
    ] {
        if let Some(v) = value {
            check_parameter(v.is_finite() && v > 0.0, name, v, "positive and finite")?;
        }
    }
    let mut state = State::default();
    loop {
        let number = lines.line() + 1;
        let outcome = match lines.next_line()? {
            None => break,
            Some(line) => read_line(line, number, &mut state, options),
        };
        outcome.map_err(|r| lines.error(r))?;
    }
    finish(state, &lines, options)
}

/// Take one line's message into `state`.
fn read_line(
    line: &str,
    number: usize,
    state: &mut State,
    options: &CarmenOptions,
) -> std::result::Result<(), String> {
    let mut f = Fields::new(line);
    let Ok(word) = f.word("message") else {
        return Ok(());
    };
    let kinds = [Kind::Flaser, Kind::RobotLaser, Kind::RawLaser];
    let kind = match word {
        "ODOM" => {
            state.odom.push(read_odom(&mut f)?);
            return Ok(());
        }
        "PARAM" => return read_param(&mut f, state, options.laser),
        _ => match options
            .laser
            .messages()
            .into_iter()
            .zip(kinds)
            .find(|(m, _)| *m == word)
        {
            Some((_, kind)) => kind,
            None => return Ok(()),
        },
    };
    if *state.kind.get_or_insert(kind) != kind {
        return Ok(());
    }
    read_scan(&mut f, kind, state, options, number)
}

fn read_odom(f: &mut Fields) -> std::result::Result<(f64, Pose), String> {
    let pose = Pose::new(f.number("x")?, f.number("y")?, f.number("theta")?);
    for what in ["tv", "rv", "accel"] {
        f.number(what)?;
    }
    Ok((f.number("timestamp")?, pose))
}

fn read_param(
    f: &mut Fields,
    state: &mut State,
    laser: CarmenLaser,
) -> std::result::Result<(), String> {
    let name = f.word("parameter name")?;
    let slot = match laser.params().iter().position(|p| *p == name) {
        Some(0) => &mut state.offset.x_m,
        Some(1) => &mut state.offset.y_m,
        Some(2) => &mut state.offset.theta_rad,
        Some(_) => state.param_max_m.get_or_insert(0.0),
        None => return Ok(()),
    };
    *slot = f.number(name)?;
    Ok(())
}

fn read_scan(
    f: &mut Fields,
    kind: Kind,
    state: &mut State,
    options: &CarmenOptions,
    line: usize,
) -> std::result::Result<(), String> {
    let (start_rad, step_rad, n) = if kind == Kind::Flaser {
        let n = f.count("number of readings", MAX_CARMEN_BEAMS)?;
        let step = options.flaser_step_rad.unwrap_or(flaser_step_rad(n));
        (-std::f64::consts::FRAC_PI_2, step, n)
    } else {
        f.word("laser type")?;
        let start = f.number("start angle")?;
        f.number("field of view")?;
        let step = f.number("angular resolution")?;
        let max = f.number("maximum range")?;
        if !(max > 0.0) {
            return Err(format!("maximum range {max} is not positive"));
        }
        state.message_max_m = Some(state.message_max_m.map_or(max, |m: f64| m.max(max)));
        f.number("accuracy")?;
        f.word("remission mode")?;
        (
            start,
            step,
            f.count("number of readings", MAX_CARMEN_BEAMS)?,
        )
    };
    match state.beams {
        Some(b) if b != n => {
            return Err(format!("{n} readings where the earlier scans have {b}"));
        }
        _ => state.beams = Some(n),
    }
    let at = state.ranges.len();
    // A long log of wide scans can need more memory than there is: an
    // error naming the line, not an abort.
    state.ranges.try_reserve(n).map_err(|_| {
        format!(
            "{n} more readings (after {at}) need more memory than can be allocated ({} bytes)",
            (at + n).saturating_mul(std::mem::size_of::<f64>())
        )
    })?;
    for k in 0..n {
        let r = f.number("range")?;
        if r < 0.0 {
            state.ranges.truncate(at);
            return Err(format!("range {k} is negative: {r}"));
        }
        state.largest_m = state.largest_m.max(r);
        state.ranges.push(r);
    }
    let read_pose = |f: &mut Fields| -> std::result::Result<Pose, String> {
        Ok(Pose::new(
            f.number("x")?,
            f.number("y")?,
            f.number("theta")?,
        ))
    };
    let rest = (|| {
        let pose = match kind {
            Kind::Flaser => {
                let pose = read_pose(f)?;
                read_pose(f)?; // the odometry
                Some(pose)
            }
            Kind::RobotLaser | Kind::RawLaser => {
                let m = f.count("number of remissions", MAX_CARMEN_BEAMS)?;
                for _ in 0..m {
                    f.number("remission")?;
                }
                if kind == Kind::RobotLaser {
                    let pose = read_pose(f)?;
                    read_pose(f)?; // the robot's
                    for what in ["tv", "rv", "forward safety", "side safety", "turn axis"] {
                        f.number(what)?;
                    }
                    Some(pose)
                } else {
                    None
                }
            }
        };
        Ok::<_, String>((pose, f.number("timestamp")?))
    })();
    match rest {
        Ok((pose, t)) => {
            state.scans.push(Scan {
                t,
                pose,
                start_rad,
                step_rad,
                line,
            });
            Ok(())
        }
        Err(e) => {
            state.ranges.truncate(at);
            Err(e)
        }
    }
}

/// CARMEN's step between `n` `FLASER` beams over 180 degrees (see the
/// module documentation).
pub fn flaser_step_rad(n: usize) -> f64 {
    let pi = std::f64::consts::PI;
    match n {
        0 | 1 => pi,
        n if n % 2 == 1 => pi / (n - 1) as f64,
        n => pi / n as f64,
    }
}

fn finish(state: State, lines: &Lines, options: &CarmenOptions) -> Result<Log> {
    let end = |reason: String| CovmapError::Parse {
        file: lines.file().to_string(),
        line: lines.line(),
        reason,
    };
    let (Some(kind), Some(beams), Some(first)) = (state.kind, state.beams, state.scans.first())
    else {
        let [a, b, c] = options.laser.messages();
        return Err(end(format!("no {a}, {b} or {c} message")));
    };
    let max_range_m = options
        .max_range_m
        .or(state.param_max_m)
        .or(state.message_max_m)
        .unwrap_or(state.largest_m);
    if !(max_range_m > 0.0) {
        return Err(end(format!(
            "no positive maximum range (largest reading {})",
            state.largest_m
        )));
    }
    // Real logs hold ODOM messages a few milliseconds out of order.
    let mut odom = state.odom;
    odom.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut poses = Vec::with_capacity(state.scans.len());
    for scan in &state.scans {
        poses.push(match scan.pose {
            Some(p) => p,
            None => odom_at(&odom, scan.t).ok_or_else(|| CovmapError::Parse {
                file: lines.file().to_string(),
                line: scan.line,
                reason: "no ODOM message to take the scan's pose from".into(),
            })?,
        });
    }
    let same = state
        .scans
        .iter()
        .all(|s| s.start_rad == first.start_rad && s.step_rad == first.step_rad);
    let fan = |s: &Scan| -> Vec<f64> {
        (0..beams)
            .map(|k| s.start_rad + k as f64 * s.step_rad)
            .collect()
    };
    let bearings = if same {
        Bearings::Fixed(fan(first))
    } else {
        Bearings::PerScan(state.scans.iter().flat_map(fan).collect())
    };
    let timestamps = state.scans.iter().map(|s| s.t).collect();
    let offset = if kind == Kind::RawLaser {
        state.offset
    } else {
        Pose::default()
    };
    Log::new(poses, timestamps, state.ranges, bearings, max_range_m)
        .and_then(|log| log.with_sensor_offset(offset))
        .map_err(|e| match e {
            CovmapError::InScan { scan, source } => CovmapError::Parse {
                file: lines.file().to_string(),
                line: state.scans.get(scan).map_or(lines.line(), |s| s.line),
                reason: source.to_string(),
            },
            other => end(other.to_string()),
        })
}

/// The robot's pose at time `t` from the odometry `odom` (in the order of
/// the file): linear between the two around it, the heading the short way
/// round; the nearest outside them; `None` without odometry.
fn odom_at(odom: &[(f64, Pose)], t: f64) -> Option<Pose> {
    let after = odom.partition_point(|(s, _)| *s <= t);
    let before = after.checked_sub(1).and_then(|i| odom.get(i)).copied();
    match (before, odom.get(after)) {
        (Some((t0, a)), Some(&(t1, b))) if t1 > t0 => {
            let w = (t - t0) / (t1 - t0);
            let turn = (b.theta_rad - a.theta_rad + std::f64::consts::PI)
                .rem_euclid(std::f64::consts::TAU)
                - std::f64::consts::PI;
            Some(Pose::new(
                a.x_m + w * (b.x_m - a.x_m),
                a.y_m + w * (b.y_m - a.y_m),
                a.theta_rad + w * turn,
            ))
        }
        (Some((_, a)), _) => Some(a),
        (None, Some(&(_, b))) => Some(b),
        (None, None) => None,
    }
}

#[cfg(test)]
#[path = "carmen_tests.rs"]
mod tests;
