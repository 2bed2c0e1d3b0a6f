//! `covmap.OccupancyGrid`: the log-odds occupancy baseline.

use covmap::OccupancyGrid;
use covmap::ScanMap;
use numpy::PyArray2;
use pyo3::prelude::*;
use pyo3::types::PyBytes;

use crate::convert::{self, cell_array};
use crate::errors::{Exception, OrRaise};
use crate::grid::PyGrid;
use crate::numbers::Float;
use crate::scan::Scan;

/// A standard log-odds occupancy grid (every cell at p = 0.5 to start), fed by
/// the same beams as a ``CoverageMap``, with the scan counts of those beams.
///
/// A cell in front of the reading's end point is observed free (p = 0.35), the
/// end point's cell occupied (p = 0.7), cells behind are not touched; log-odds
/// are clamped to ``[-5, 5]``. Per-cell arrays are indexed ``[row, col]``.
#[pyclass(name = "OccupancyGrid", module = "covmap._native")]
pub(crate) struct PyOccupancyGrid(pub(crate) OccupancyGrid);

#[pymethods]
impl PyOccupancyGrid {
    #[new]
    fn new(py: Python<'_>, grid: Bound<'_, PyGrid>) -> PyResult<Self> {
        OccupancyGrid::try_new(grid.get().0).map(Self).or_raise(py)
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
            .map(drop)
            .or_raise(py)
    }

    /// Integrate every scan of ``log`` (a ``Log``) with ``model``, in order;
    /// returns the number of scans. Each scan is taken from its sensor pose (the robot's
    /// pose with the log's sensor offset); dropped beams (NaN) are skipped; a
    /// reading without echo clears up to the lesser of the log's and the
    /// model's maximum range. Every scan is checked first: a scan whose
    /// sensor pose lies outside the map raises (``PoseOutsideMapError``, the
    /// message naming the scan) and leaves the map exactly as it was.
    /// ``progress``: ``True`` shows a bar (tqdm's if installed), a callable
    /// is called as ``progress(done, total)``; if it raises (or Ctrl-C
    /// interrupts the bar), the error is raised once the scans are in and
    /// the grid is left as it was (with a progress display the scans go into
    /// a copy, which takes as much memory again). Runs with the GIL
    /// released.
    #[pyo3(signature = (log, model, *, progress=crate::log::ProgressArg::Flag(false)), text_signature = "($self, log, model, *, progress=False)")]
    fn integrate_log(
        &mut self,
        py: Python<'_>,
        log: Bound<'_, crate::log::PyLog>,
        model: &Bound<'_, PyAny>,
        progress: crate::log::ProgressArg,
    ) -> PyResult<usize> {
        let model = crate::sensor::any_model(model)?;
        let log = &log.get().0;
        crate::log::integrate_log_shown(
            py,
            &mut self.0,
            covmap::OccupancyGrid::try_clone,
            (progress, log.len()),
            |map, show| {
                map.integrate_log_with_progress(log, &model, show)
                    .map(|_| log.len())
            },
        )
    }

    /// Probability of occupancy, float32, ``(rows, cols)``.
    fn probabilities<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f32>>> {
        cell_array(py, self.0.grid(), self.0.try_probabilities().or_raise(py)?)
    }
    /// Log-odds of occupancy, float32, ``(rows, cols)``.
    fn log_odds<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f32>>> {
        cell_array(
            py,
            self.0.grid(),
            convert::copied(py, self.0.log_odds(), "the log-odds")?,
        )
    }
    /// How many beams intercepted each cell (up to its end point), float32,
    /// ``(rows, cols)``.
    fn counts<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f32>>> {
        cell_array(
            py,
            self.0.grid(),
            convert::copied(py, self.0.counts().counts(), "the scan counts")?,
        )
    }

    /// Which cells some evidence reached (a beam intercepted them, or the
    /// robot touched an obstacle there): bool, ``(rows, cols)``. The others are
    /// unknown, whatever ``probabilities()`` reads there (0.5).
    fn observed<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<bool>>> {
        cell_array(py, self.0.grid(), self.0.try_observed().or_raise(py)?)
    }

    /// The grid as ``nav_msgs/OccupancyGrid`` data: int8 ``(rows, cols)``,
    /// the probability of occupancy in percent, ``-1`` (unknown) where no
    /// evidence reached.
    fn ros_occupancy<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<i8>>> {
        crate::ros_map::array(py, self.0.grid(), self.0.ros_occupancy())
    }
    /// Write the grid as ROS map_server / nav2 map_saver do: ``yaml_path``
    /// and the PGM of the same name beside it, from ``ros_occupancy()``;
    /// ``mode`` as ``CoverageMap.to_ros_map``. ``World.from_file(yaml_path)``
    /// reads the pair back.
    #[pyo3(
        signature = (yaml_path, *, mode="trinary", occupied_thresh=Float(0.65), free_thresh=Float(0.196)),
        text_signature = "($self, yaml_path, *, mode='trinary', occupied_thresh=0.65, free_thresh=0.196)"
    )]
    fn to_ros_map(
        &self,
        py: Python<'_>,
        yaml_path: std::path::PathBuf,
        mode: &str,
        occupied_thresh: Float,
        free_thresh: Float,
    ) -> PyResult<()> {
        let grid = *self.0.grid();
        let data = self.0.ros_occupancy();
        crate::ros_map::write(
            py,
            &yaml_path,
            &grid,
            &data,
            mode,
            occupied_thresh.0,
            free_thresh.0,
        )
    }

    fn __repr__(&self) -> String {
        format!("OccupancyGrid({})", self.grid().__repr__())
    }
    /// Pickle and copy support: the grid, for ``__new__``.
    fn __getnewargs__(&self) -> (PyGrid,) {
        (self.grid(),)
    }
    /// Pickle and copy support: the model, log-odds and counts, as the
    /// core's serialised form (JSON bytes; every float32 value exact).
    fn __getstate__<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyBytes>> {
        crate::pickling::state(py, &self.0, "occupancy grid")
    }
    /// Unpickling support: restore the state saved by ``__getstate__``
    /// (validated: a valid model, one log-odds value within its limit and one
    /// finite, non-negative count per cell of this grid). After an error the
    /// grid is exactly as it was.
    fn __setstate__(&mut self, py: Python<'_>, state: &Bound<'_, PyAny>) -> PyResult<()> {
        let Ok(bytes) = state.cast::<PyBytes>() else {
            return Err(Exception::InvalidType
                .err(py, format!("state must be bytes, got {}", state.get_type())));
        };
        let restored: OccupancyGrid =
            crate::pickling::restored(py, bytes.as_bytes(), "occupancy grid")?;
        if restored.grid() != self.0.grid() {
            return Err(Exception::InvalidValue.err(
                py,
                format!(
                    "the saved occupancy grid lies on {}, not on this grid {}",
                    PyGrid(*restored.grid()).__repr__(),
                    self.grid().__repr__()
                ),
            ));
        }
        self.0 = restored;
        Ok(())
    }
}
