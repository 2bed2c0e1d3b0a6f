//! The error type of the core crate.

use thiserror::Error;

/// Everything that can go wrong in `covmap-core`.
///
/// Every variant names the offending value and what was expected. A function
/// returning an error has not changed any map it was given.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum CovmapError {
    /// A setting is unknown or unusable where a number range cannot say
    /// why: a fit's parameter names and bounds, an empty log.
    #[error("invalid `{name}`: {reason}")]
    InvalidSetting {
        /// The setting's name.
        name: &'static str,
        /// What is wrong with it, naming the value.
        reason: String,
    },
    /// A grid was described with an unusable geometry.
    #[error("invalid grid: {0}")]
    InvalidGrid(String),
    /// A sensor-model or map parameter is out of its valid range.
    #[error("invalid parameter `{name}` = {value}: expected {expected}")]
    InvalidParameter {
        /// The parameter's name.
        name: &'static str,
        /// The rejected value.
        value: f64,
        /// What the parameter must satisfy.
        expected: &'static str,
    },
    /// A range reading is NaN, infinite or negative.
    #[error(
        "invalid range at index {index}: {value} (expected a finite, non-negative distance in metres)"
    )]
    InvalidRange {
        /// Position of the reading in the scan.
        index: usize,
        /// The rejected reading.
        value: f64,
    },
    /// A bearing is NaN or infinite, or the beam's direction (the pose's
    /// heading plus the bearing) overflows to infinity.
    #[error(
        "invalid bearing at index {index}: {value} (expected a finite angle in radians, finite when added to the heading)"
    )]
    InvalidBearing {
        /// Position of the bearing in the scan.
        index: usize,
        /// The rejected bearing.
        value: f64,
    },
    /// A pose has a non-finite component.
    #[error("invalid pose ({x}, {y}, {theta}): every component must be finite")]
    InvalidPose {
        /// x in metres.
        x: f64,
        /// y in metres.
        y: f64,
        /// Heading in radians.
        theta: f64,
    },
    /// A pose lies outside the map.
    #[error("pose ({x}, {y}) lies outside the map [{x_min}, {x_max}) x [{y_min}, {y_max})")]
    PoseOutsideMap {
        /// x in metres.
        x: f64,
        /// y in metres.
        y: f64,
        /// The map's extent.
        x_min: f64,
        /// The map's extent.
        x_max: f64,
        /// The map's extent.
        y_min: f64,
        /// The map's extent.
        y_max: f64,
    },
    /// Two inputs that must have the same length do not.
    #[error("length mismatch: {what} ({left} vs {right})")]
    LengthMismatch {
        /// Which inputs disagree.
        what: &'static str,
        /// The first length.
        left: usize,
        /// The second length.
        right: usize,
    },
    /// A cell index lies outside the grid.
    #[error("cell (row {row}, col {col}) lies outside a grid of {rows} x {cols} cells")]
    CellOutOfBounds {
        /// Requested row.
        row: usize,
        /// Requested column.
        col: usize,
        /// Grid rows.
        rows: usize,
        /// Grid columns.
        cols: usize,
    },
    /// Histogram data handed in does not describe a valid map.
    #[error("invalid histogram data: {0}")]
    InvalidHistogram(String),
    /// A stored entropy history holds an entropy no map can have (NaN,
    /// infinite, negative, or above the prior's `ln bins`).
    #[error(
        "invalid entropy history at cell {cell}: {value} (expected an entropy from 0 to ln(bins) nats)"
    )]
    InvalidHistory {
        /// Row-major index of the cell.
        cell: usize,
        /// The rejected entropy.
        value: f64,
    },
    /// A start pose the robot cannot take (its disc overlaps an obstacle),
    /// or no start pose could be found.
    #[error("invalid start pose ({x}, {y}): {reason}")]
    InvalidStart {
        /// x in metres.
        x: f64,
        /// y in metres.
        y: f64,
        /// Why the robot cannot start there.
        reason: String,
    },
    /// A goal given to a run ([`Exploration::step_to`](crate::exploration::Exploration::step_to))
    /// that the robot cannot go to; the run is as it was.
    #[error("invalid goal ({x}, {y}): {reason}")]
    InvalidGoal {
        /// x in metres.
        x: f64,
        /// y in metres.
        y: f64,
        /// Why the robot cannot go there.
        reason: String,
    },
    /// The robot failed: its scan source or its motion could not do what the
    /// exploration loop asked (a sensor or drive error, of a real robot or a
    /// simulator).
    #[error("the robot failed: {0}")]
    Robot(String),
    /// A scan of a log is unusable; `source` says how (its range, bearing,
    /// pose or length), `scan` which one.
    #[error("scan {scan} of the log: {source}")]
    InScan {
        /// Position of the scan in the log, from 0.
        scan: usize,
        /// What is wrong with it.
        source: Box<CovmapError>,
    },
    /// A file could not be opened or read (the operating system's reason).
    #[error("cannot read {file}: {reason}")]
    Io {
        /// The file's path as given.
        file: String,
        /// The system's message.
        reason: String,
        /// The system's error number (`ENOENT` for a missing file), if the
        /// system gave the error.
        errno: Option<i32>,
    },
    /// Bytes that are not a whole, unchanged covmap map file (see
    /// `CoverageMap::from_file_bytes`).
    #[error("not a valid covmap map file: {0}")]
    InvalidMapFile(String),
    /// A line of a text file does not say what its format requires.
    #[error("{file}:{line}: {reason}")]
    Parse {
        /// The file's path as given.
        file: String,
        /// The line, from 1.
        line: usize,
        /// What the line should have held.
        reason: String,
    },
    /// The memory for a map or a result could not be had: it asked more
    /// than the allocator gave (or more than an address can span).
    #[error("{what} needs {bytes} bytes, more than can be allocated")]
    OutOfMemory {
        /// What was being allocated (`"the occupancy grid's log-odds"`).
        what: String,
        /// The bytes asked for.
        bytes: u128,
    },
}

impl CovmapError {
    /// [`CovmapError::Io`] for `file` from the system's error `e`, its
    /// error number kept.
    pub(crate) fn io(file: impl Into<String>, e: &std::io::Error) -> Self {
        Self::Io {
            file: file.into(),
            reason: e.to_string(),
            errno: e.raw_os_error(),
        }
    }

    /// This error, as found in scan `scan` of a log.
    pub(crate) fn in_scan(self, scan: usize) -> Self {
        Self::InScan {
            scan,
            source: Box::new(self),
        }
    }
}

/// Shorthand for results of this crate.
pub type Result<T, E = CovmapError> = std::result::Result<T, E>;

/// The most characters of a text an error message quotes.
pub const QUOTED_CHARS: usize = 60;

/// `text` as an error message quotes it (a name given by a caller, which
/// may be of any length): at most [`QUOTED_CHARS`] characters, in quotes; a
/// longer one cut, with `...` and its length in characters.
///
/// ```
/// assert_eq!(covmap_core::quoted("corridor"), "\"corridor\"");
/// assert!(covmap_core::quoted(&"x".repeat(1000)).ends_with("... (1000 characters)"));
/// ```
pub fn quoted(text: &str) -> String {
    match text.char_indices().nth(QUOTED_CHARS) {
        Some((end, _)) => format!(
            "{:?}... ({} characters)",
            &text[..end],
            text.chars().count()
        ),
        None => format!("{text:?}"),
    }
}

/// `Ok` if `ok`, else [`CovmapError::InvalidParameter`]: parameter `name`
/// has `value`, and `expected` says what it must satisfy.
pub(crate) fn check_parameter(
    ok: bool,
    name: &'static str,
    value: f64,
    expected: &'static str,
) -> Result<()> {
    if ok {
        Ok(())
    } else {
        Err(CovmapError::InvalidParameter {
            name,
            value,
            expected,
        })
    }
}
