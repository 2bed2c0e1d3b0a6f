//! `covmap.OccupancyGrid`: the log-odds occupancy baseline.

use covmap::OccupancyGrid;
use numpy::PyArray2;
use pyo3::prelude::*;

use crate::convert::cell_array;
use crate::errors::OrRaise;
use crate::grid::PyGrid;
use crate::scan::Scan;

/// A standard log-odds occupancy grid (every cell at p = 0.5 to start), fed by
/// the same beams as a ``CoverageMap``, with the scan counts of those beams.
///
/// A cell in front of the reading's end point is observed free (p = 0.35), the
/// end point's cell occupied (p = 0.7), cells behind are not touched; log-odds
/// are clamped to ``[-5, 5]``. Per-cell arrays are indexed ``[row, col]``.
#[pyclass(name = "OccupancyGrid", module = "covmap._native")]
pub(crate) struct PyOccupancyGrid(OccupancyGrid);

#[pymethods]
impl PyOccupancyGrid {
    #[new]
    fn new(grid: &Bound<'_, PyGrid>) -> Self {
        Self(OccupancyGrid::new(grid.get().0))
    }

    /// The grid.
    #[getter]
    fn grid(&self) -> PyGrid {
        PyGrid(*self.0.grid())
    }

    /// Integrate one scan; arguments and checks as ``CoverageMap.integrate``.
    /// After an error the grid is exactly as it was. The update runs with the
    /// GIL released.
    fn integrate(
        &mut self,
        py: Python<'_>,
        pose: &Bound<'_, PyAny>,
        ranges: &Bound<'_, PyAny>,
        bearings: &Bound<'_, PyAny>,
        model: &Bound<'_, PyAny>,
    ) -> PyResult<()> {
        let scan = Scan::extract(pose, ranges, bearings, model)?;
        let grid = &mut self.0;
        py.detach(|| grid.integrate(&scan.pose, &scan.ranges, &scan.bearings, &scan.model))
            .or_raise(py)
    }

    /// Probability of occupancy, float32, ``(rows, cols)``.
    fn probabilities<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f32>>> {
        cell_array(py, self.0.grid(), self.0.probabilities())
    }
    /// Log-odds of occupancy, float32, ``(rows, cols)``.
    fn log_odds<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f32>>> {
        cell_array(py, self.0.grid(), self.0.log_odds().to_vec())
    }
    /// How many beams intercepted each cell (up to its end point), float32,
    /// ``(rows, cols)``.
    fn counts<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f32>>> {
        cell_array(py, self.0.grid(), self.0.counts().counts().to_vec())
    }

    fn __repr__(&self) -> String {
        format!("OccupancyGrid({})", self.grid().__repr__())
    }
}
