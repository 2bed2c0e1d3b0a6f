//! Python arguments to core values and back: readings, poses, points,
//! histogram arrays, counts, cells, option names; per-cell arrays.
//!
//! Arrays are copied out of Python before any work starts. The copy of a scan
//! costs nothing next to its update, and it lets the update run with the GIL
//! released without another thread being able to write into its input.

use covmap::gain::{GainMethod, StopCoverage};
use covmap::{Cell, CovmapError, Grid, Pose, histogram};
use numpy::ndarray::{Array2, Array3};
use numpy::{
    Element, IntoPyArray, PyArray2, PyArray3, PyArrayDyn, PyArrayMethods, PyUntypedArray,
    PyUntypedArrayMethods,
};
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;

use crate::errors::{Exception, to_py};

/// The values of a numpy array of `ndim` dimensions and element type `T`, in
/// row-major order, with its shape. Other dimensions or dtypes, and masked
/// arrays with masked values, are errors: nothing is converted or dropped
/// silently.
fn numpy_values<T: Element + Copy>(
    array: &Bound<'_, PyUntypedArray>,
    name: &str,
    ndim: usize,
    expected: &str,
) -> PyResult<(Vec<T>, Vec<usize>)> {
    let py = array.py();
    // A masked array with masked values would lose its mask without a word:
    // refuse it (one with nothing masked is its data). A plain ndarray, the
    // common case, is not asked for a mask it cannot have.
    if !array.is_exact_instance_of::<PyUntypedArray>()
        && array.hasattr(pyo3::intern!(py, "mask"))?
        && py
            .import(pyo3::intern!(py, "numpy.ma"))?
            .call_method1(pyo3::intern!(py, "is_masked"), (array,))?
            .is_truthy()?
    {
        return Err(Exception::ArrayDtype.err(
            py,
            format!("{name} has masked values, which covmap would ignore: pass .filled(value) or .compressed()"),
        ));
    }
    let shape = array.shape().to_vec();
    if shape.len() != ndim {
        return Err(Exception::ArrayShape.err(
            py,
            format!("{name} must be a {ndim}-D array of {expected}, got shape {shape:?}"),
        ));
    }
    let Ok(typed) = array.cast::<PyArrayDyn<T>>() else {
        return Err(Exception::ArrayDtype.err(
            py,
            format!(
                "{name} must have dtype {}, got {} (convert with .astype)",
                numpy::dtype::<T>(py),
                array.dtype()
            ),
        ));
    };
    let values = typed.try_readonly()?.as_array().iter().copied().collect();
    Ok((values, shape))
}

/// The values of a float64 or float32 numpy array of `ndim` dimensions as
/// float64 (each float32 exactly), with its shape; other dtypes as
/// [`numpy_values`] refuses them.
fn float_values(
    array: &Bound<'_, PyUntypedArray>,
    name: &str,
    ndim: usize,
    expected: &str,
) -> PyResult<(Vec<f64>, Vec<usize>)> {
    if array.cast::<PyArrayDyn<f32>>().is_ok() {
        let (values, shape) = numpy_values::<f32>(array, name, ndim, expected)?;
        return Ok((values.into_iter().map(f64::from).collect(), shape));
    }
    numpy_values::<f64>(array, name, ndim, expected)
}

/// A 2-D float64 or float32 numpy array as float64 values, row-major, and
/// its shape.
pub(crate) fn matrix(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<(Vec<f64>, [usize; 2])> {
    let Ok(array) = obj.cast::<PyUntypedArray>() else {
        return Err(Exception::ArrayDtype.err(
            obj.py(),
            format!(
                "{name} must be a 2-D float64 or float32 numpy array, got {}",
                obj.get_type()
            ),
        ));
    };
    let (values, shape) = float_values(array, name, 2, "float64 or float32")?;
    Ok((values, [shape[0], shape[1]]))
}

/// A pose: any sequence of three numbers `(x, y, theta)`, metres and radians.
/// Another length raises `ArrayShapeError`, anything else `ArrayDtypeError`.
pub(crate) fn pose(obj: &Bound<'_, PyAny>) -> PyResult<Pose> {
    let py = obj.py();
    obj.extract::<[f64; 3]>().map(Pose::from).map_err(|e| {
        sequence_error(
            py,
            &e,
            format!("pose must be a sequence of three numbers (x, y, theta): {e}"),
        )
    })
}

/// The error for a sequence of numbers that could not be read (`cause`): of
/// the wrong length (a `ValueError` from the extraction) `ArrayShapeError`,
/// else `ArrayDtypeError`.
fn sequence_error(py: Python<'_>, cause: &PyErr, message: String) -> PyErr {
    if cause.is_instance_of::<PyValueError>(py) {
        Exception::ArrayShape.err(py, message)
    } else {
        Exception::ArrayDtype.err(py, message)
    }
}

/// A scan's ranges or bearings: a 1-D float64 or float32 numpy array (a ROS
/// `LaserScan`'s ranges are float32), or a sequence of numbers.
pub(crate) fn readings(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<Vec<f64>> {
    if let Ok(array) = obj.cast::<PyUntypedArray>() {
        return Ok(float_values(array, name, 1, "float64 or float32")?.0);
    }
    obj.extract::<Vec<f64>>().map_err(|_| {
        Exception::ArrayDtype.err(
            obj.py(),
            format!(
                "{name} must be a 1-D float64 or float32 numpy array or a sequence of numbers, got {}",
                obj.get_type()
            ),
        )
    })
}

/// Histograms for a map over `grid`: a float32 array of shape `(rows, cols, bins)`.
/// Returns the values cell-major and the bin count.
pub(crate) fn histograms(obj: &Bound<'_, PyAny>, grid: &Grid) -> PyResult<(Vec<f32>, usize)> {
    let (values, shape) = per_cell::<f32>(obj, grid, "histograms", "float32", &[None])?;
    Ok((values, shape[2]))
}

/// A per-cell array for a map over `grid`: a numpy array of element type `T`
/// (`dtype` names it for messages) and shape `(rows, cols)`, or
/// `(rows, cols, depth)` with `Some(depth)`. Returns the values row-major.
pub(crate) fn cell_values<T: Element + Copy>(
    obj: &Bound<'_, PyAny>,
    grid: &Grid,
    name: &str,
    dtype: &str,
    depth: Option<usize>,
) -> PyResult<Vec<T>> {
    let more = depth.map(Some);
    Ok(per_cell::<T>(obj, grid, name, dtype, more.as_slice())?.0)
}

/// A numpy array of element type `T` of shape `(rows, cols, more..)` for
/// `grid` (a `None` in `more`: any length): its values in order, and its shape.
fn per_cell<T: Element + Copy>(
    obj: &Bound<'_, PyAny>,
    grid: &Grid,
    name: &str,
    dtype: &str,
    more: &[Option<usize>],
) -> PyResult<(Vec<T>, Vec<usize>)> {
    let py = obj.py();
    let (rows, cols) = grid.shape();
    let expected: Vec<Option<usize>> = [Some(rows), Some(cols)]
        .into_iter()
        .chain(more.iter().copied())
        .collect();
    let spelled: Vec<String> = expected
        .iter()
        .map(|n| n.map_or_else(|| "any".to_owned(), |n| n.to_string()))
        .collect();
    let spelled = format!("({})", spelled.join(", "));
    let Ok(array) = obj.cast::<PyUntypedArray>() else {
        return Err(Exception::ArrayDtype.err(
            py,
            format!(
                "{name} must be a {dtype} numpy array of shape {spelled}, got {}",
                obj.get_type()
            ),
        ));
    };
    let (values, shape) = numpy_values::<T>(array, name, expected.len(), dtype)?;
    if shape
        .iter()
        .zip(&expected)
        .any(|(&n, want)| want.is_some_and(|w| w != n))
    {
        return Err(Exception::ArrayShape.err(
            py,
            format!("{name} must have shape {spelled}, got {shape:?}"),
        ));
    }
    Ok((values, shape))
}

/// A seed for the random generators, from a Python integer (an `int`, a
/// numpy integer, anything with `__index__`): 0 to 2**64 - 1. Anything else
/// raises `InvalidTypeError`, an integer out of that range
/// `InvalidParameterError`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Seed(pub(crate) u64);

impl<'a, 'py> FromPyObject<'a, 'py> for Seed {
    type Error = PyErr;
    fn extract(obj: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        let py = obj.py();
        if let Ok(seed) = obj.extract::<u64>() {
            return Ok(Self(seed));
        }
        match obj.call_method0(pyo3::intern!(py, "__index__")) {
            Ok(value) => Err(Exception::InvalidParameter.err(
                py,
                format!(
                    "invalid parameter `seed` = {value}: expected an integer from 0 to 2**64 - 1"
                ),
            )),
            Err(_) => Err(Exception::InvalidType.err(
                py,
                format!("seed must be an integer, got {}", obj.get_type()),
            )),
        }
    }
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
            format!(
                "cell (row {row}, col {col}) lies outside a grid of {} x {} cells",
                grid.rows(),
                grid.cols()
            ),
        )),
    }
}

/// Rows of `K` numbers: a float64 numpy array of shape `(N, K)`, or a sequence
/// of `N` sequences of `K` numbers. `what` describes one row for messages
/// (`"(x, y)"`).
pub(crate) fn rows<const K: usize>(
    obj: &Bound<'_, PyAny>,
    name: &str,
    what: &str,
) -> PyResult<Vec<[f64; K]>> {
    let py = obj.py();
    let expected = format!("float64 or float32 with shape (N, {K}), one {what} a row");
    if let Ok(array) = obj.cast::<PyUntypedArray>() {
        let (values, shape) = float_values(array, name, 2, &expected)?;
        if shape[1] != K {
            return Err(Exception::ArrayShape.err(
                py,
                format!("{name} must have shape (N, {K}), got {shape:?}"),
            ));
        }
        return Ok(values
            .chunks_exact(K)
            .map(|c| std::array::from_fn(|k| c[k]))
            .collect());
    }
    let Ok(nested) = obj.extract::<Vec<Vec<f64>>>() else {
        return Err(Exception::ArrayDtype.err(
            py,
            format!(
                "{name} must be a {expected} numpy array or a sequence of {what}, got {}",
                obj.get_type()
            ),
        ));
    };
    nested
        .into_iter()
        .enumerate()
        .map(|(i, row)| {
            <[f64; K]>::try_from(row.as_slice()).map_err(|_| {
                Exception::ArrayShape.err(
                    py,
                    format!(
                        "{name}[{i}] has {} numbers, expected {K}: {what}",
                        row.len()
                    ),
                )
            })
        })
        .collect()
}

/// Poses: a float64 array of shape `(N, 3)` (or a sequence of `(x, y, theta)`).
pub(crate) fn poses(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<Vec<Pose>> {
    Ok(rows::<3>(obj, name, "(x, y, theta)")?
        .into_iter()
        .map(Pose::from)
        .collect())
}

/// Raises `InvalidValueError` for the first of `points` with a coordinate
/// that is not finite; `name` names the argument.
pub(crate) fn finite_points(py: Python<'_>, points: &[[f64; 2]], name: &str) -> PyResult<()> {
    match points
        .iter()
        .position(|p| !(p[0].is_finite() && p[1].is_finite()))
    {
        None => Ok(()),
        Some(i) => {
            let [x, y] = points[i];
            Err(Exception::InvalidValue
                .err(py, format!("{name}: point {i} ({x}, {y}) is not finite")))
        }
    }
}

/// A point: any sequence of two numbers `(x, y)`, metres; with `heading_ok`,
/// also a pose `(x, y, theta)` whose heading is ignored. `name` names the
/// argument in messages.
pub(crate) fn point(obj: &Bound<'_, PyAny>, name: &str, heading_ok: bool) -> PyResult<[f64; 2]> {
    let py = obj.py();
    let fail = |e: PyErr| {
        let what = if heading_ok {
            "(x, y) or a pose (x, y, theta)"
        } else {
            "(x, y)"
        };
        sequence_error(
            py,
            &e,
            format!("{name} must be a sequence of two numbers {what}: {e}"),
        )
    };
    match obj.extract::<Vec<f64>>() {
        Ok(v) if v.len() == 2 || (heading_ok && v.len() == 3) => Ok([v[0], v[1]]),
        Ok(v) => Err(fail(PyValueError::new_err(format!(
            "got {} numbers",
            v.len()
        )))),
        Err(e) => Err(fail(e)),
    }
}

/// A per-cell array of `grid` as a `(rows, cols)` numpy array.
pub(crate) fn cell_array<'py, T: Element>(
    py: Python<'py>,
    grid: &Grid,
    values: Vec<T>,
) -> PyResult<Bound<'py, PyArray2<T>>> {
    let array = Array2::from_shape_vec(grid.shape(), values)
        .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
    Ok(array.into_pyarray(py))
}

/// `depth` values per cell of `grid`, row-major, as a `(rows, cols, depth)`
/// numpy array.
pub(crate) fn cell_stack_array<'py, T: Element>(
    py: Python<'py>,
    grid: &Grid,
    depth: usize,
    values: Vec<T>,
) -> PyResult<Bound<'py, PyArray3<T>>> {
    let (rows, cols) = grid.shape();
    let array = Array3::from_shape_vec((rows, cols, depth), values)
        .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
    Ok(array.into_pyarray(py))
}

/// `(x_min, y_min, x_max, y_max)`, metres, as Python sees a rectangle: a tuple.
pub(crate) type Rectangle = (f64, f64, f64, f64);

/// A rectangle `[x_min, y_min, x_max, y_max]` as a [`Rectangle`].
pub(crate) fn rectangle([x_min, y_min, x_max, y_max]: [f64; 4]) -> Rectangle {
    (x_min, y_min, x_max, y_max)
}

/// Rows of `K` numbers as an `(N, K)` float64 numpy array.
pub(crate) fn rows_array<'py, const K: usize>(
    py: Python<'py>,
    rows: &[[f64; K]],
) -> Bound<'py, PyArray2<f64>> {
    Array2::from_shape_fn((rows.len(), K), |(i, k)| rows[i][k]).into_pyarray(py)
}

/// Poses as an `(N, 3)` float64 numpy array of `(x, y, theta)`.
pub(crate) fn poses_array<'py>(py: Python<'py>, poses: &[Pose]) -> Bound<'py, PyArray2<f64>> {
    let rows: Vec<[f64; 3]> = poses.iter().map(|p| [p.x_m, p.y_m, p.theta_rad]).collect();
    rows_array(py, &rows)
}

/// The gain evaluator by name: `"fast"` or `"exact"`.
pub(crate) fn gain_method(py: Python<'_>, name: &str) -> PyResult<GainMethod> {
    match name {
        "fast" => Ok(GainMethod::Fast),
        "exact" => Ok(GainMethod::Exact),
        _ => Err(Exception::InvalidParameter.err(
            py,
            format!("method must be \"fast\" or \"exact\", got {name:?}"),
        )),
    }
}

/// Which coverage stops a predicted beam, by name: `"ml"` (also
/// `"maximum_likelihood"`) or `"mean"`.
pub(crate) fn stop_coverage(py: Python<'_>, name: &str) -> PyResult<StopCoverage> {
    match name {
        "ml" | "maximum_likelihood" => Ok(StopCoverage::MaximumLikelihood),
        "mean" => Ok(StopCoverage::Mean),
        _ => Err(Exception::InvalidParameter.err(
            py,
            format!("stop_coverage must be \"ml\" or \"mean\", got {name:?}"),
        )),
    }
}

/// The Python name of a `StopCoverage`.
pub(crate) fn stop_coverage_name(stop: StopCoverage) -> &'static str {
    match stop {
        StopCoverage::MaximumLikelihood => "ml",
        StopCoverage::Mean => "mean",
    }
}
