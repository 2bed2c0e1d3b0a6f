//! Python arguments to core values: readings, histogram arrays, counts, cells.
//!
//! Arrays are copied out of Python before any work starts. The copy of a scan
//! costs nothing next to its update, and it lets the update run with the GIL
//! released without another thread being able to write into its input.

use covmap::{Cell, CovmapError, Grid, Pose, histogram};
use numpy::{Element, PyArrayDyn, PyArrayMethods, PyUntypedArray, PyUntypedArrayMethods};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;

use crate::errors::{Exception, to_py};

/// The values of a numpy array of `ndim` dimensions and element type `T`, in
/// row-major order, with its shape. Other dimensions or dtypes are errors:
/// nothing is converted silently.
fn numpy_values<T: Element + Copy>(
    array: &Bound<'_, PyUntypedArray>,
    name: &str,
    ndim: usize,
    expected: &str,
) -> PyResult<(Vec<T>, Vec<usize>)> {
    let py = array.py();
    let shape = array.shape().to_vec();
    if shape.len() != ndim {
        return Err(Exception::ArrayShape
            .err(py, format!("{name} must be a {ndim}-D array of {expected}, got shape {shape:?}")));
    }
    let Ok(typed) = array.cast::<PyArrayDyn<T>>() else {
        return Err(Exception::ArrayDtype.err(
            py,
            format!("{name} must have dtype {}, got {} (convert with .astype)", numpy::dtype::<T>(py), array.dtype()),
        ));
    };
    let values = typed.try_readonly()?.as_array().iter().copied().collect();
    Ok((values, shape))
}

/// A pose: any sequence of three numbers `(x, y, theta)`, metres and radians.
pub(crate) fn pose(obj: &Bound<'_, PyAny>) -> PyResult<Pose> {
    let py = obj.py();
    obj.extract::<[f64; 3]>().map(Pose::from).map_err(|e| {
        let message = format!("pose must be a sequence of three numbers (x, y, theta): {e}");
        if e.is_instance_of::<PyValueError>(py) {
            Exception::ArrayShape.err(py, message)
        } else {
            PyTypeError::new_err(message)
        }
    })
}

/// A scan's ranges or bearings: a 1-D float64 numpy array, or a sequence of
/// numbers.
pub(crate) fn readings(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<Vec<f64>> {
    if let Ok(array) = obj.cast::<PyUntypedArray>() {
        return Ok(numpy_values::<f64>(array, name, 1, "float64")?.0);
    }
    obj.extract::<Vec<f64>>().map_err(|_| {
        Exception::ArrayDtype.err(
            obj.py(),
            format!("{name} must be a 1-D float64 numpy array or a sequence of numbers, got {}", obj.get_type()),
        )
    })
}

/// Histograms for a map over `grid`: a float32 array of shape `(rows, cols, bins)`.
/// Returns the values cell-major and the bin count.
pub(crate) fn histograms(obj: &Bound<'_, PyAny>, grid: &Grid) -> PyResult<(Vec<f32>, usize)> {
    let py = obj.py();
    let Ok(array) = obj.cast::<PyUntypedArray>() else {
        return Err(
            Exception::ArrayDtype.err(py, format!("histograms must be a float32 numpy array, got {}", obj.get_type()))
        );
    };
    let (values, shape) = numpy_values::<f32>(array, "histograms", 3, "float32")?;
    if (shape[0], shape[1]) != grid.shape() {
        return Err(Exception::ArrayShape.err(
            py,
            format!("histograms of shape {shape:?} do not fit a grid of {} x {} cells", grid.rows(), grid.cols()),
        ));
    }
    Ok((values, shape[2]))
}

/// A bin count from a Python int: `MIN_BINS..=MAX_BINS`.
pub(crate) fn bins(py: Python<'_>, bins: i64) -> PyResult<usize> {
    let checked = usize::try_from(bins)
        .map_err(|_| CovmapError::InvalidParameter {
            name: "bins",
            value: bins as f64,
            expected: "a bin count from 2 to 256",
        })
        .and_then(|b| histogram::check_bins(b).map(|()| b));
    checked.map_err(|e| to_py(py, e))
}

/// A cell of `grid` from Python ints; negative or too large is out of bounds.
pub(crate) fn cell(py: Python<'_>, grid: &Grid, row: i64, col: i64) -> PyResult<Cell> {
    match (usize::try_from(row), usize::try_from(col)) {
        (Ok(row), Ok(col)) if row < grid.rows() && col < grid.cols() => Ok(Cell { row, col }),
        _ => Err(Exception::CellOutOfBounds.err(
            py,
            format!("cell (row {row}, col {col}) lies outside a grid of {} x {} cells", grid.rows(), grid.cols()),
        )),
    }
}
