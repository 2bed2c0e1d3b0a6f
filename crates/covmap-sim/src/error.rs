//! The error type of the simulator crate.

use std::path::PathBuf;

use covmap_core::CovmapError;
use thiserror::Error;

/// Everything that can go wrong in `covmap-sim`.
///
/// Every variant names the offending value or place and what was expected.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum SimError {
    /// A polygon is not a usable obstacle (too few vertices, a non-finite
    /// coordinate, zero area, a self-intersecting ring).
    #[error("invalid polygon {index}: {reason}")]
    InvalidPolygon {
        /// Position of the polygon in the input (0 for a single polygon).
        index: usize,
        /// What is wrong with it.
        reason: String,
    },
    /// A file could not be read or written.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The operating system's error.
        #[source]
        source: std::io::Error,
    },
    /// A file's content is malformed or degenerate.
    #[error("{}, {place}: {reason}", path.display())]
    Parse {
        /// The file (or the name given to in-memory input).
        path: PathBuf,
        /// Where in it: a line, a feature, a pixel.
        place: String,
        /// What is wrong there and what was expected.
        reason: String,
    },
    /// No built-in world has this name.
    #[error("no built-in world named {name}; available: {available}")]
    UnknownWorld {
        /// The requested name, quoted (at most
        /// [`QUOTED_CHARS`](covmap_core::QUOTED_CHARS) characters of it).
        name: String,
        /// The names that exist, comma-separated.
        available: String,
    },
    /// A simulator parameter is out of its valid range.
    #[error("invalid parameter `{name}` = {value}: expected {expected}")]
    InvalidParameter {
        /// The parameter's name.
        name: &'static str,
        /// The rejected value.
        value: f64,
        /// What the parameter must satisfy.
        expected: &'static str,
    },
    /// One element of an input array is unusable (a NaN origin, an infinite angle).
    #[error("invalid {what} at index {index}: {value} (expected a finite number)")]
    InvalidValue {
        /// Which input.
        what: &'static str,
        /// Position of the element.
        index: usize,
        /// The rejected value.
        value: f64,
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
    /// Rooms of a generated building that the robot cannot reach: the
    /// generator failed its own check (a bug; the building is named).
    #[error("building {building}: rooms {rooms} cannot be reached by the robot")]
    UnreachableRooms {
        /// The building's name (its seed).
        building: String,
        /// The rooms, comma-separated.
        rooms: String,
    },
    /// An error of the core crate (an invalid grid, pose or sensor model).
    #[error(transparent)]
    Core(#[from] CovmapError),
}

/// Shorthand for results of this crate.
pub type Result<T, E = SimError> = std::result::Result<T, E>;

/// Errors unless `value` is finite and `ok` holds.
pub(crate) fn check_param(
    name: &'static str,
    value: f64,
    ok: bool,
    expected: &'static str,
) -> Result<()> {
    if ok && value.is_finite() {
        Ok(())
    } else {
        Err(SimError::InvalidParameter {
            name,
            value,
            expected,
        })
    }
}

/// The most beams one simulated sensor may have (2^16).
pub const MAX_BEAMS: usize = 1 << 16;

/// Errors unless a sensor has from 1 to [`MAX_BEAMS`] bearings and every
/// bearing is finite;
/// `what` names one bearing in the error ("bearing").
pub(crate) fn check_bearings(bearings_rad: &[f64], what: &'static str) -> Result<()> {
    if bearings_rad.is_empty() || bearings_rad.len() > MAX_BEAMS {
        return Err(SimError::InvalidParameter {
            name: "bearings_rad",
            value: bearings_rad.len() as f64,
            expected: "from 1 to 65536 bearings",
        });
    }
    if let Some((index, &value)) = bearings_rad
        .iter()
        .enumerate()
        .find(|(_, b)| !b.is_finite())
    {
        return Err(SimError::InvalidValue { what, index, value });
    }
    Ok(())
}
