//! Core errors as Python exceptions.
//!
//! The classes live in Python, in `covmap/_errors.py`: each bad-value error
//! derives from both `covmap.CovmapError` and a builtin (`ValueError`,
//! `IndexError`, `TypeError`), and `create_exception!` takes a single base.

use covmap::CovmapError;
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
    /// An array argument has the wrong number of dimensions or shape.
    ArrayShape,
    /// An array argument has the wrong element type.
    ArrayDtype,
}

const CLASSES: usize = 12;

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
            Self::ArrayShape => "ArrayShapeError",
            Self::ArrayDtype => "ArrayDtypeError",
        }
    }

    /// The class a core error is raised as.
    fn of(err: &CovmapError) -> Self {
        match err {
            CovmapError::InvalidGrid(_) => Self::InvalidGrid,
            CovmapError::InvalidParameter { .. } => Self::InvalidParameter,
            CovmapError::InvalidRange { .. } => Self::InvalidRange,
            CovmapError::InvalidBearing { .. } => Self::InvalidBearing,
            CovmapError::InvalidPose { .. } => Self::InvalidPose,
            CovmapError::PoseOutsideMap { .. } => Self::PoseOutsideMap,
            CovmapError::LengthMismatch { .. } => Self::LengthMismatch,
            CovmapError::CellOutOfBounds { .. } => Self::CellOutOfBounds,
            CovmapError::InvalidHistogram(_) => Self::InvalidHistogram,
            // The core enum is non-exhaustive: a new variant is still a CovmapError.
            _ => Self::Base,
        }
    }

    /// An exception of this class carrying `message`.
    pub(crate) fn err(self, py: Python<'_>, message: impl Into<String>) -> PyErr {
        static TYPES: [PyOnceLock<Py<PyType>>; CLASSES] = [const { PyOnceLock::new() }; CLASSES];
        match TYPES[self as usize].import(py, "covmap._errors", self.class_name()) {
            Ok(ty) => PyErr::from_type(ty.clone(), message.into()),
            Err(import_failed) => import_failed,
        }
    }
}

/// A core error as the matching Python exception.
pub(crate) fn to_py(py: Python<'_>, err: CovmapError) -> PyErr {
    Exception::of(&err).err(py, err.to_string())
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
