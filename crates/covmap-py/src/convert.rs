//! Python arguments to core values and back: readings, poses, points,
//! histogram arrays, counts, cells, option names; per-cell arrays.
//!
//! Arrays are copied out of Python before any work starts. The copy of a scan
//! costs nothing next to its update, and it lets the update run with the GIL
//! released without another thread being able to write into its input.
#![cfg_attr(not(test), warn(clippy::indexing_slicing))]

use covmap::gain::{GainMethod, StopCoverage};
use covmap::{Cell, CovmapError, Grid, Pose, histogram};
use numpy::ndarray::{Array2, Array3};
use numpy::{
    Element, IntoPyArray, PyArray2, PyArray3, PyArrayDyn, PyArrayMethods, PyUntypedArray,
    PyUntypedArrayMethods,
};
use pyo3::exceptions::{PyOverflowError, PyRuntimeError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyBytes, PyString};

use crate::errors::{Exception, to_py};
use crate::numbers;

/// The values of a numpy array of `ndim` dimensions and element type `T`, in
/// row-major order, with its shape. Other dimensions or dtypes, and masked
/// arrays with masked values, are errors: nothing is converted or dropped
/// silently. `check` sees the shape before anything is copied (a broadcast
/// array may claim far more elements than its memory holds), and the copy's
/// memory is asked for first (`OutOfMemoryError` where it cannot be had).
fn numpy_values<T: Element + Copy>(
    array: &Bound<'_, PyUntypedArray>,
    name: &str,
    ndim: usize,
    expected: &str,
    check: &dyn Fn(&[usize]) -> PyResult<()>,
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
    check(&shape)?;
    let readonly = typed.try_readonly()?;
    let view = readonly.as_array();
    let mut values = Vec::new();
    values
        .try_reserve_exact(view.len())
        .map_err(|_| out_of_memory::<T>(py, &format!("a copy of {name}"), view.len()))?;
    values.extend(view.iter().copied());
    Ok((values, shape))
}

/// `OutOfMemoryError`: `len` values of `T` for `what` could not be had.
fn out_of_memory<T>(py: Python<'_>, what: &str, len: usize) -> PyErr {
    to_py(
        py,
        CovmapError::OutOfMemory {
            what: what.to_owned(),
            bytes: len as u128 * size_of::<T>() as u128,
        },
    )
}

/// A copy of `values` (`what` names them), in memory asked for first:
/// `OutOfMemoryError` where it cannot be had.
pub(crate) fn copied<T: Copy>(py: Python<'_>, values: &[T], what: &str) -> PyResult<Vec<T>> {
    let mut copy = Vec::new();
    copy.try_reserve_exact(values.len())
        .map_err(|_| out_of_memory::<T>(py, what, values.len()))?;
    copy.extend_from_slice(values);
    Ok(copy)
}

/// The values of a float64 or float32 numpy array of `ndim` dimensions as
/// float64 (each float32 exactly), with its shape; other dtypes as
/// [`numpy_values`] refuses them.
fn float_values(
    array: &Bound<'_, PyUntypedArray>,
    name: &str,
    ndim: usize,
    expected: &str,
    check: &dyn Fn(&[usize]) -> PyResult<()>,
) -> PyResult<(Vec<f64>, Vec<usize>)> {
    if array.cast::<PyArrayDyn<f32>>().is_ok() {
        let (values, shape) = numpy_values::<f32>(array, name, ndim, expected, check)?;
        return Ok((values.into_iter().map(f64::from).collect(), shape));
    }
    numpy_values::<f64>(array, name, ndim, expected, check)
}

/// `shape`, of an array that [`numpy_values`] read as `N`-D, as its `N`
/// lengths.
fn dims<const N: usize>(py: Python<'_>, name: &str, shape: &[usize]) -> PyResult<[usize; N]> {
    shape.try_into().map_err(|_| {
        Exception::ArrayShape.err(
            py,
            format!("{name} must be a {N}-D array, got shape {shape:?}"),
        )
    })
}

/// The most values covmap reads from one Python sequence or array argument
/// that no tighter limit bounds (a list of poses, the rays of a cast, a
/// log's timestamps): 2**26. Sequences are read element by element, never
/// reserved by what their `len()` claims.
pub(crate) const MAX_VALUES: usize = 1 << 26;

/// `ArrayShapeError`: `name` holds `len` values, more than `max_len`.
fn too_long(py: Python<'_>, name: &str, len: usize, max_len: usize) -> PyErr {
    Exception::ArrayShape.err(
        py,
        format!("{name} holds {len} values, more than the {max_len} covmap takes"),
    )
}

/// A check for [`numpy_values`]: at most `max_len` elements.
fn at_most<'a>(
    py: Python<'a>,
    name: &'a str,
    max_len: usize,
) -> impl Fn(&[usize]) -> PyResult<()> + 'a {
    move |shape: &[usize]| {
        let len = shape.iter().try_fold(1usize, |n, &d| n.checked_mul(d));
        match len {
            Some(len) if len <= max_len => Ok(()),
            _ => Err(too_long(py, name, len.unwrap_or(usize::MAX), max_len)),
        }
    }
}

/// Calls `each(i, item)` on the items of a Python sequence (a list, a
/// tuple, anything with a length and an iterator that is not a string), at
/// most `max_len` of them: its `len()` is checked first and the items are
/// read one by one, so that neither a huge claimed length nor an endless
/// iterator makes covmap hold more than `max_len` items. A value that is no
/// such sequence raises `not_a_sequence()`; more items `ArrayShapeError`.
fn each_item<'py>(
    obj: &Bound<'py, PyAny>,
    name: &str,
    max_len: usize,
    not_a_sequence: &dyn Fn() -> PyErr,
    mut each: impl FnMut(usize, Bound<'py, PyAny>) -> PyResult<()>,
) -> PyResult<()> {
    let py = obj.py();
    if obj.is_instance_of::<PyString>() || obj.is_instance_of::<PyBytes>() {
        return Err(not_a_sequence());
    }
    let len = match obj.len() {
        Ok(len) => len,
        // A length beyond isize: more than any limit.
        Err(e) if e.is_instance_of::<PyOverflowError>(py) => usize::MAX,
        Err(_) => return Err(not_a_sequence()),
    };
    if len > max_len {
        return Err(too_long(py, name, len, max_len));
    }
    for (i, item) in obj.try_iter().map_err(|_| not_a_sequence())?.enumerate() {
        if i == max_len {
            return Err(too_long(py, name, i + 1, max_len));
        }
        each(i, item?)?;
    }
    Ok(())
}

/// The items of a Python sequence, at most `max_len` of them, as
/// [`each_item`] reads them.
pub(crate) fn items<'py>(
    obj: &Bound<'py, PyAny>,
    name: &str,
    max_len: usize,
    not_a_sequence: &dyn Fn() -> PyErr,
) -> PyResult<Vec<Bound<'py, PyAny>>> {
    let mut items = Vec::new();
    each_item(obj, name, max_len, not_a_sequence, |_, item| {
        items.push(item);
        Ok(())
    })?;
    Ok(items)
}

/// The numbers of a Python sequence, at most `max_len` of them, as
/// [`each_item`] reads them. `expected` describes the argument for the
/// message of a value that is no such sequence (`ArrayDtypeError`).
fn number_sequence(
    obj: &Bound<'_, PyAny>,
    name: &str,
    max_len: usize,
    expected: &str,
) -> PyResult<Vec<f64>> {
    let py = obj.py();
    let not_numbers = || {
        Exception::ArrayDtype.err(
            py,
            format!("{name} must be {expected}, got {}", obj.get_type()),
        )
    };
    let mut values = Vec::new();
    each_item(obj, name, max_len, &not_numbers, |i, item| {
        if item.is_instance_of::<PyBool>() {
            return Err(Exception::ArrayDtype.err(
                py,
                format!("{name}[{i}] must be a number, got the bool {item}"),
            ));
        }
        let value = item.extract::<f64>().map_err(|e| {
            let message = format!("{name}[{i}] must be a number, got {}: {e}", item.get_type());
            match e.is_instance_of::<PyOverflowError>(py) {
                true => Exception::IntegerOverflow.err(py, message),
                false => Exception::ArrayDtype.err(py, message),
            }
        })?;
        values.push(value);
        Ok(())
    })?;
    Ok(values)
}

/// Exactly `N` numbers from a Python sequence (`what` says what they are,
/// `"(x, y, theta)"`): another length raises `ArrayShapeError`, anything
/// else `ArrayDtypeError`.
pub(crate) fn fixed_numbers<const N: usize>(
    obj: &Bound<'_, PyAny>,
    name: &str,
    what: &str,
) -> PyResult<[f64; N]> {
    let count = match N {
        2 => "two".to_owned(),
        3 => "three".to_owned(),
        n => n.to_string(),
    };
    let expected = format!("a sequence of {count} numbers {what}");
    let values = number_sequence(obj, name, N, &expected)?;
    <[f64; N]>::try_from(values.as_slice()).map_err(|_| {
        Exception::ArrayShape.err(
            obj.py(),
            format!("{name} must be {expected}, got {} numbers", values.len()),
        )
    })
}

/// A 2-D float64 or float32 numpy array as float64 values, row-major, and
/// its shape; at most [`MAX_VALUES`] of them.
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
    let check = at_most(obj.py(), name, MAX_VALUES);
    let (values, shape) = float_values(array, name, 2, "float64 or float32", &check)?;
    Ok((values, dims(obj.py(), name, &shape)?))
}

/// A pose: any sequence of three numbers `(x, y, theta)`, metres and radians.
/// Another length raises `ArrayShapeError`, anything else `ArrayDtypeError`.
pub(crate) fn pose(obj: &Bound<'_, PyAny>) -> PyResult<Pose> {
    fixed_numbers::<3>(obj, "pose", "(x, y, theta)").map(Pose::from)
}

/// A scan's ranges or bearings, or another list of numbers: a 1-D float64
/// or float32 numpy array (a ROS `LaserScan`'s ranges are float32), or a
/// sequence of numbers; at most `max_len` of them (`ArrayShapeError`).
pub(crate) fn readings(obj: &Bound<'_, PyAny>, name: &str, max_len: usize) -> PyResult<Vec<f64>> {
    if let Ok(array) = obj.cast::<PyUntypedArray>() {
        let check = at_most(obj.py(), name, max_len);
        return Ok(float_values(array, name, 1, "float64 or float32", &check)?.0);
    }
    number_sequence(
        obj,
        name,
        max_len,
        "a 1-D float64 or float32 numpy array or a sequence of numbers",
    )
}

/// Histograms for a map over `grid`: a float32 array of shape `(rows, cols, bins)`.
/// Returns the values cell-major and the bin count.
pub(crate) fn histograms(obj: &Bound<'_, PyAny>, grid: &Grid) -> PyResult<(Vec<f32>, usize)> {
    let (values, shape) = per_cell::<f32>(obj, grid, "histograms", "float32", &[None])?;
    let [_, _, bins] = dims(obj.py(), "histograms", &shape)?;
    Ok((values, bins))
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
    let check = |shape: &[usize]| {
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
        // Any bin count: the map checks it; the copy is bounded by it.
        at_most(py, name, rows * cols * histogram::MAX_BINS)(shape)
    };
    numpy_values::<T>(array, name, expected.len(), dtype, &check)
}

/// The cell `(row, col)` of `grid`, from Python integers (anything else
/// raises `InvalidTypeError`); a cell outside the grid raises
/// `CellOutOfBoundsError` naming it and the grid's shape.
pub(crate) fn cell(grid: &Grid, row: &Bound<'_, PyAny>, col: &Bound<'_, PyAny>) -> PyResult<Cell> {
    let index = |obj, n: usize| numbers::integer(obj, 0, n as i128 - 1);
    match (index(row, grid.rows())?, index(col, grid.cols())?) {
        (Some(r), Some(c)) => Ok(Cell {
            row: r as usize,
            col: c as usize,
        }),
        _ => Err(Exception::CellOutOfBounds.err(
            row.py(),
            format!(
                "cell (row {}, col {}) lies outside a grid of {} x {} cells",
                numbers::quoted(row),
                numbers::quoted(col),
                grid.rows(),
                grid.cols()
            ),
        )),
    }
}

/// A grid's shape, `(rows, cols)`: a sequence of two integers, each from 0
/// to 2**64 - 1 (`InvalidGridError` outside; the grid checks the rest).
pub(crate) struct Shape(pub(crate) usize, pub(crate) usize);

impl<'a, 'py> FromPyObject<'a, 'py> for Shape {
    type Error = PyErr;
    fn extract(obj: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        shape(&obj).map(|(rows, cols)| Self(rows, cols))
    }
}

/// The `(rows, cols)` of a [`Shape`].
fn shape(obj: &Bound<'_, PyAny>) -> PyResult<(usize, usize)> {
    let py = obj.py();
    let expected = "a sequence of two integers (rows, cols)";
    let not_a_shape = || {
        Exception::ArrayDtype.err(
            py,
            format!("shape must be {expected}, got {}", obj.get_type()),
        )
    };
    let items = items(obj, "shape", 2, &not_a_shape)?;
    let [rows, cols] = items.as_slice() else {
        return Err(Exception::ArrayShape.err(
            py,
            format!("shape must be {expected}, got {} items", items.len()),
        ));
    };
    let count = |n| numbers::integer(n, 0, usize::MAX as i128);
    match (count(rows)?, count(cols)?) {
        (Some(r), Some(c)) => Ok((r as usize, c as usize)),
        _ => Err(to_py(
            py,
            CovmapError::InvalidGrid(format!(
                "shape must be two non-negative counts, got ({}, {})",
                numbers::quoted(rows),
                numbers::quoted(cols)
            )),
        )),
    }
}

/// Rows of `K` numbers: a float64 numpy array of shape `(N, K)`, or a sequence
/// of `N` sequences of `K` numbers, `N` at most [`MAX_VALUES`] / `K`. `what`
/// describes one row for messages (`"(x, y)"`).
pub(crate) fn rows<const K: usize>(
    obj: &Bound<'_, PyAny>,
    name: &str,
    what: &str,
) -> PyResult<Vec<[f64; K]>> {
    let py = obj.py();
    let max_rows = MAX_VALUES / K;
    let expected = format!("float64 or float32 with shape (N, {K}), one {what} a row");
    if let Ok(array) = obj.cast::<PyUntypedArray>() {
        let check = at_most(py, name, MAX_VALUES);
        let (values, shape) = float_values(array, name, 2, &expected, &check)?;
        if dims::<2>(py, name, &shape)?[1] != K {
            return Err(Exception::ArrayShape.err(
                py,
                format!("{name} must have shape (N, {K}), got {shape:?}"),
            ));
        }
        return Ok(values.as_chunks::<K>().0.to_vec());
    }
    let not_rows = || {
        Exception::ArrayDtype.err(
            py,
            format!(
                "{name} must be a {expected} numpy array or a sequence of {what}, got {}",
                obj.get_type()
            ),
        )
    };
    let mut rows = Vec::new();
    each_item(obj, name, max_rows, &not_rows, |i, row| {
        rows.push(fixed_numbers::<K>(&row, &format!("{name}[{i}]"), what)?);
        Ok(())
    })?;
    Ok(rows)
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
        .enumerate()
        .find(|(_, [x, y])| !(x.is_finite() && y.is_finite()))
    {
        None => Ok(()),
        Some((i, [x, y])) => {
            Err(Exception::InvalidValue
                .err(py, format!("{name}: point {i} ({x}, {y}) is not finite")))
        }
    }
}

/// A point: any sequence of two numbers `(x, y)`, metres; with `heading_ok`,
/// also a pose `(x, y, theta)` whose heading is ignored. `name` names the
/// argument in messages.
pub(crate) fn point(obj: &Bound<'_, PyAny>, name: &str, heading_ok: bool) -> PyResult<[f64; 2]> {
    let expected = match heading_ok {
        true => "a sequence of two numbers (x, y) or a pose (x, y, theta)",
        false => "a sequence of two numbers (x, y)",
    };
    let values = number_sequence(obj, name, 3, expected)?;
    match *values.as_slice() {
        [x, y] => Ok([x, y]),
        [x, y, _] if heading_ok => Ok([x, y]),
        _ => Err(Exception::ArrayShape.err(
            obj.py(),
            format!("{name} must be {expected}, got {} numbers", values.len()),
        )),
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
    Array2::from(rows.to_vec()).into_pyarray(py)
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
            format!(
                "method must be \"fast\" or \"exact\", got {}",
                covmap::quoted(name)
            ),
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
            format!(
                "stop_coverage must be \"ml\" or \"mean\", got {}",
                covmap::quoted(name)
            ),
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
