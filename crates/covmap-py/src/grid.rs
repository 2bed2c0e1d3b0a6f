//! `covmap.Grid`: where cells are in the world.

use std::hash::{DefaultHasher, Hash, Hasher};

use covmap::Grid;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};

use crate::convert;
use crate::errors::OrRaise;
use crate::numbers::{Float, Int};

/// A regular grid of square cells.
///
/// ``origin`` is the world position (metres) of the lower-left corner of cell
/// ``(row 0, col 0)``, ``resolution`` the side of a cell (metres), ``shape`` the
/// number of cells as ``(rows, cols)``. Rows run along y and columns along x:
/// cell ``(row, col)`` covers ``[ox + col*r, ox + (col+1)*r) x [oy + row*r,
/// oy + (row+1)*r)``, and every per-cell array of this package is indexed
/// ``[row, col]``. A resolution below 1e-6 m, more than 2**31 cells, or a
/// corner more than 2**32 cells from zero raises ``InvalidGridError``.
#[pyclass(frozen, eq, name = "Grid", module = "covmap._native")]
#[derive(Clone, Copy, PartialEq)]
pub(crate) struct PyGrid(pub(crate) Grid);

/// Hash of floats consistent with `==`: `0.0` and `-0.0` hash alike.
pub(crate) fn hash_f64s(values: impl IntoIterator<Item = f64>, extra: &[usize]) -> u64 {
    let mut h = DefaultHasher::new();
    for v in values {
        (if v == 0.0 { 0.0f64 } else { v }).to_bits().hash(&mut h);
    }
    extra.hash(&mut h);
    h.finish()
}

#[pymethods]
impl PyGrid {
    #[new]
    #[pyo3(signature = (*, origin, resolution, shape))]
    fn new(
        py: Python<'_>,
        origin: &Bound<'_, PyAny>,
        resolution: Float,
        shape: convert::Shape,
    ) -> PyResult<Self> {
        let origin = convert::point(origin, "origin", false)?;
        Grid::new(origin, resolution.0, shape.0, shape.1)
            .map(Self)
            .or_raise(py)
    }

    /// The grid covering ``bounds = (x_min, y_min, x_max, y_max)`` (metres),
    /// rounded up to whole cells of side ``resolution``.
    #[staticmethod]
    #[pyo3(signature = (bounds, *, resolution))]
    fn covering(py: Python<'_>, bounds: &Bound<'_, PyAny>, resolution: Float) -> PyResult<Self> {
        let [x_min, y_min, x_max, y_max] =
            convert::fixed_numbers::<4>(bounds, "bounds", "(x_min, y_min, x_max, y_max)")?;
        Grid::covering(x_min, y_min, x_max, y_max, resolution.0)
            .map(Self)
            .or_raise(py)
    }

    /// World position of the lower-left corner, metres.
    #[getter]
    fn origin(&self) -> (f64, f64) {
        let [x, y] = self.0.origin_m();
        (x, y)
    }
    /// Side of a cell, metres.
    #[getter]
    fn resolution(&self) -> f64 {
        self.0.resolution_m()
    }
    /// ``(rows, cols)``.
    #[getter]
    fn shape(&self) -> (usize, usize) {
        self.0.shape()
    }
    /// Number of rows (cells along y).
    #[getter]
    fn rows(&self) -> usize {
        self.0.rows()
    }
    /// Number of columns (cells along x).
    #[getter]
    fn cols(&self) -> usize {
        self.0.cols()
    }
    /// ``(x_min, y_min, x_max, y_max)`` of the covered rectangle, metres.
    #[getter]
    fn bounds(&self) -> convert::Rectangle {
        convert::rectangle(self.0.bounds_m())
    }

    /// Whether the world point lies in a cell of the grid: the rectangle with
    /// its upper edges excluded, up to rounding (a point on an upper edge may
    /// round into the last cell).
    fn contains(&self, x: Float, y: Float) -> bool {
        self.0.contains(x.0, y.0)
    }
    /// The ``(row, col)`` of the cell containing a world point, or ``None``
    /// outside the grid.
    fn world_to_cell(&self, x: Float, y: Float) -> Option<(usize, usize)> {
        self.0.world_to_cell(x.0, y.0).map(|c| (c.row, c.col))
    }
    /// World position ``(x, y)`` of a cell's centre, metres (the cell need not
    /// lie inside the grid: a negative index counts on past the first row or
    /// column).
    fn cell_center(
        &self,
        row: Int<i64, { i64::MIN as i128 }, { i64::MAX as i128 }>,
        col: Int<i64, { i64::MIN as i128 }, { i64::MAX as i128 }>,
    ) -> (f64, f64) {
        let (row, col) = (row.0, col.0);
        let ([ox, oy], r) = (self.0.origin_m(), self.0.resolution_m());
        (ox + (col as f64 + 0.5) * r, oy + (row as f64 + 0.5) * r)
    }

    pub(crate) fn __repr__(&self) -> String {
        let [ox, oy] = self.0.origin_m();
        format!(
            "Grid(origin=({ox:?}, {oy:?}), resolution={:?}, shape=({}, {}))",
            self.0.resolution_m(),
            self.0.rows(),
            self.0.cols()
        )
    }
    fn __hash__(&self) -> u64 {
        let [ox, oy] = self.0.origin_m();
        hash_f64s(
            [ox, oy, self.0.resolution_m()],
            &[self.0.rows(), self.0.cols()],
        )
    }
    /// Pickle and copy support: the keyword arguments that rebuild the grid.
    fn __getnewargs_ex__<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyTuple>, Bound<'py, PyDict>)> {
        let kwargs = PyDict::new(py);
        kwargs.set_item("origin", self.origin())?;
        kwargs.set_item("resolution", self.resolution())?;
        kwargs.set_item("shape", self.shape())?;
        Ok((PyTuple::empty(py), kwargs))
    }
}
