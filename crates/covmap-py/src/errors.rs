//! Core and simulator errors as Python exceptions.
//!
//! The classes live in Python, in `covmap/_errors.py`: each bad-value error
//! derives from both `covmap.CovmapError` and a builtin (`ValueError`,
//! `IndexError`, `TypeError`, `OSError`), and `create_exception!` takes a
//! single base.

use covmap::CovmapError;
use covmap::sim::SimError;
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::PyType;

/// One Python exception class of `covmap._errors`.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Exception {
    /// `CovmapError`: a core error variant this binding does not know yet.
    Base,
    InvalidGrid,
    InvalidParameter,
    InvalidRange,
    InvalidBearing,
    InvalidPose,
    PoseOutsideMap,
    LengthMismatch,
    CellOutOfBounds,
    InvalidHistogram,
    InvalidHistory,
    /// A start pose the robot cannot take, or none found (a `ValueError`).
    InvalidStart,
    /// A goal given to a run that the robot cannot go to (a `ValueError`).
    InvalidGoal,
    /// The robot's scan source or motion failed during a run.
    Robot,
    /// An array argument has the wrong number of dimensions or shape.
    ArrayShape,
    /// An array argument has the wrong element type.
    ArrayDtype,
    InvalidPolygon,
    /// A file could not be read or written (an `OSError`).
    FileIO,
    /// A file's content is malformed.
    FileFormat,
    UnknownWorld,
    /// One element of an input array is unusable (a NaN origin, say).
    InvalidValue,
    /// An argument of the wrong type (a `TypeError`).
    InvalidType,
    /// An integer argument beyond what covmap takes (an `OverflowError`).
    IntegerOverflow,
    /// Memory for a map or a result could not be had (a `MemoryError`).
    OutOfMemory,
    /// A map was used inside its own `integrate_log`'s progress callback.
    MapBusy,
}

impl Exception {
    fn class_name(self) -> &'static str {
        match self {
            Self::Base => "CovmapError",
            Self::InvalidGrid => "InvalidGridError",
            Self::InvalidParameter => "InvalidParameterError",
            Self::InvalidRange => "InvalidRangeError",
            Self::InvalidBearing => "InvalidBearingError",
            Self::InvalidPose => "InvalidPoseError",
            Self::PoseOutsideMap => "PoseOutsideMapError",
            Self::LengthMismatch => "LengthMismatchError",
            Self::CellOutOfBounds => "CellOutOfBoundsError",
            Self::InvalidHistogram => "InvalidHistogramError",
            Self::InvalidHistory => "InvalidHistoryError",
            Self::InvalidStart => "InvalidStartError",
            Self::InvalidGoal => "InvalidGoalError",
            Self::Robot => "RobotError",
            Self::ArrayShape => "ArrayShapeError",
            Self::ArrayDtype => "ArrayDtypeError",
            Self::InvalidPolygon => "InvalidPolygonError",
            Self::FileIO => "FileIOError",
            Self::FileFormat => "FileFormatError",
            Self::UnknownWorld => "UnknownWorldError",
            Self::InvalidValue => "InvalidValueError",
            Self::InvalidType => "InvalidTypeError",
            Self::IntegerOverflow => "IntegerOverflowError",
            Self::OutOfMemory => "OutOfMemoryError",
            Self::MapBusy => "MapBusyError",
        }
    }

    /// The class a core error is raised as.
    fn of(err: &CovmapError) -> Self {
        match err {
            CovmapError::InvalidGrid(_) => Self::InvalidGrid,
            CovmapError::InvalidParameter { .. } | CovmapError::InvalidSetting { .. } => {
                Self::InvalidParameter
            }
            CovmapError::InvalidRange { .. } => Self::InvalidRange,
            CovmapError::InvalidBearing { .. } => Self::InvalidBearing,
            CovmapError::InvalidPose { .. } => Self::InvalidPose,
            CovmapError::PoseOutsideMap { .. } => Self::PoseOutsideMap,
            CovmapError::LengthMismatch { .. } => Self::LengthMismatch,
            CovmapError::CellOutOfBounds { .. } => Self::CellOutOfBounds,
            CovmapError::InvalidHistogram(_) => Self::InvalidHistogram,
            CovmapError::InvalidHistory { .. } => Self::InvalidHistory,
            CovmapError::InvalidStart { .. } => Self::InvalidStart,
            CovmapError::InvalidGoal { .. } => Self::InvalidGoal,
            CovmapError::Robot(_) => Self::Robot,
            // A bad scan of a log is the error of what is wrong with it.
            CovmapError::InScan { source, .. } => Self::of(source),
            CovmapError::Io { .. } => Self::FileIO,
            CovmapError::Parse { .. } | CovmapError::InvalidMapFile(_) => Self::FileFormat,
            CovmapError::OutOfMemory { .. } => Self::OutOfMemory,
            // The core enum is non-exhaustive: a new variant is still a CovmapError.
            _ => Self::Base,
        }
    }

    /// The Python class, looked up by its name in `covmap._errors` (imported
    /// once; an error is the rare path, a lookup costs nothing beside it).
    fn class<'py>(self, py: Python<'py>) -> PyResult<Bound<'py, PyType>> {
        static MODULE: PyOnceLock<Py<PyModule>> = PyOnceLock::new();
        let module =
            MODULE.get_or_try_init(py, || py.import("covmap._errors").map(Bound::unbind))?;
        Ok(module
            .bind(py)
            .getattr(self.class_name())?
            .cast_into::<PyType>()?)
    }

    /// An exception of this class carrying `message`.
    pub(crate) fn err(self, py: Python<'_>, message: impl Into<String>) -> PyErr {
        match self.class(py) {
            Ok(ty) => PyErr::from_type(ty, message.into()),
            Err(import_failed) => import_failed,
        }
    }

    /// An exception of this class built from `args` (as `cls(*args)`), with
    /// the attributes `attrs` set on it.
    fn err_with<'py, A>(self, py: Python<'py>, args: A, attrs: &[(&str, String)]) -> PyErr
    where
        A: pyo3::call::PyCallArgs<'py>,
    {
        let build = || -> PyResult<PyErr> {
            let value = self.class(py)?.call1(args)?;
            for (name, v) in attrs {
                value.setattr(*name, v)?;
            }
            Ok(PyErr::from_value(value))
        };
        build().unwrap_or_else(|failed| failed)
    }
}

/// A core error as the matching Python exception.
///
/// A file that cannot be read raises `FileIOError` with `filename` (and
/// `errno` and `strerror` where the system gave the error); a
/// malformed line `FileFormatError` with `filename`, `place` (`"line N"`)
/// and `reason`, as the simulator's file errors do.
pub(crate) fn to_py(py: Python<'_>, err: CovmapError) -> PyErr {
    let message = err.to_string();
    match err {
        CovmapError::Io {
            file,
            reason,
            errno,
        } => file_io_error(py, message, file, errno, &reason),
        CovmapError::Parse { file, line, reason } => Exception::FileFormat.err_with(
            py,
            (message,),
            &[
                ("filename", file),
                ("place", format!("line {line}")),
                ("reason", reason),
            ],
        ),
        other => Exception::of(&other).err(py, message),
    }
}

/// `FileIOError` for `filename`, which failed for `reason`. With the
/// system's error number it is built as `OSError(errno, strerror,
/// filename)` is (`[Errno 2] No such file or directory: 'x.log'`); without
/// one (a refusal of covmap's, "not a regular file") from `message`, which
/// names the file and the reason, with `filename` and `strerror` set.
fn file_io_error(
    py: Python<'_>,
    message: String,
    filename: String,
    errno: Option<i32>,
    reason: &str,
) -> PyErr {
    // The OS's message without Rust's " (os error N)" suffix.
    let strerror = reason
        .split(" (os error")
        .next()
        .unwrap_or(reason)
        .to_string();
    match errno {
        Some(errno) => Exception::FileIO.err_with(py, (errno, strerror, filename), &[]),
        None => Exception::FileIO.err_with(
            py,
            (message,),
            &[("filename", filename), ("strerror", strerror)],
        ),
    }
}

/// A core error reading the file at `path` as the matching Python
/// exception: a file that is not a map file raises `FileFormatError` with
/// `filename`, `place` (`"the archive"`) and `reason`.
pub(crate) fn file_to_py(py: Python<'_>, path: &std::path::Path, err: CovmapError) -> PyErr {
    match err {
        CovmapError::InvalidMapFile(reason) => {
            let filename = path.display().to_string();
            Exception::FileFormat.err_with(
                py,
                (format!("{filename}: not a valid covmap map file: {reason}"),),
                &[
                    ("filename", filename),
                    ("place", "the archive".to_string()),
                    ("reason", reason),
                ],
            )
        }
        other => to_py(py, other),
    }
}

/// `?` for core results inside Python methods.
pub(crate) trait OrRaise<T> {
    /// The value, or the error as the matching Python exception.
    fn or_raise(self, py: Python<'_>) -> PyResult<T>;
}

impl<T> OrRaise<T> for covmap::Result<T> {
    fn or_raise(self, py: Python<'_>) -> PyResult<T> {
        self.map_err(|e| to_py(py, e))
    }
}

/// A simulator error as the matching Python exception.
///
/// A malformed file raises `FileFormatError` with `filename`, `place` and
/// `reason` attributes; a file that cannot be read or written raises
/// `FileIOError`, an `OSError` with `errno`, `strerror` and `filename`.
pub(crate) fn sim_to_py(py: Python<'_>, err: SimError) -> PyErr {
    let message = err.to_string();
    match err {
        SimError::InvalidPolygon { .. } => Exception::InvalidPolygon.err(py, message),
        SimError::Io { path, source } => file_io_error(
            py,
            message,
            path.display().to_string(),
            source.raw_os_error(),
            &source.to_string(),
        ),
        SimError::Parse {
            path,
            place,
            reason,
        } => Exception::FileFormat.err_with(
            py,
            (message,),
            &[
                ("filename", path.display().to_string()),
                ("place", place),
                ("reason", reason),
            ],
        ),
        SimError::UnknownWorld { .. } => Exception::UnknownWorld.err(py, message),
        SimError::InvalidParameter { .. } => Exception::InvalidParameter.err(py, message),
        SimError::InvalidValue { .. } => Exception::InvalidValue.err(py, message),
        SimError::LengthMismatch { .. } => Exception::LengthMismatch.err(py, message),
        SimError::UnreachableRooms { .. } => Exception::InvalidValue.err(py, message),
        SimError::Core(core) => to_py(py, core),
        // The simulator's enum is non-exhaustive: a new variant is still a CovmapError.
        _ => Exception::Base.err(py, message),
    }
}

impl<T> OrRaise<T> for covmap::sim::Result<T> {
    fn or_raise(self, py: Python<'_>) -> PyResult<T> {
        self.map_err(|e| sim_to_py(py, e))
    }
}
