//! `covmap.CoverageMap`: one histogram over coverage values per cell.

use covmap::ScanMap;
use covmap::histogram::DEFAULT_BINS;
use covmap::{CoverageMap, HistoryState, STAGNATION_MEASUREMENTS};
use numpy::{PyArray1, PyArray2, PyArray3};
use pyo3::prelude::*;
use pyo3::types::{PyTuple, PyType};

use crate::convert::{self, cell_array};
use crate::errors::{Exception, OrRaise};
use crate::grid::PyGrid;
use crate::numbers::{Bins, Float, Int};
use crate::scan::Scan;

// The text signature spells the default out so that Python shows it; keep
// it the core's.
const _: () = assert!(DEFAULT_BINS == 16);

/// The entropy history as `__reduce__` saves it: each cell's ring of entropies,
/// float32 `(rows, cols, STAGNATION_MEASUREMENTS + 1)`, and its measurement
/// count, uint32 `(rows, cols)`.
type HistoryArrays<'py> = (Bound<'py, PyArray3<f32>>, Bound<'py, PyArray2<u32>>);

/// What `__reduce__` returns: a constructor, its arguments and the state for
/// `__setstate__`: the entropy history (if kept) and the evidence.
type Reduce<'py> = (
    Bound<'py, PyAny>,
    (PyGrid, Bound<'py, PyArray3<f32>>),
    (Option<HistoryArrays<'py>>, Bound<'py, PyArray3<f32>>),
);

/// A grid whose every cell holds a histogram over how much of it is covered by
/// obstacles (0 = empty, 1 = fully covered), starting at the uniform prior.
///
/// ``bins`` (2 to 256) is the number of coverage values; bin ``b`` stands for
/// coverage ``b / (bins - 1)``. Per-cell arrays are indexed ``[row, col]`` as
/// in ``Grid``.
#[pyclass(name = "CoverageMap", module = "covmap._native")]
pub(crate) struct PyCoverageMap(pub(crate) CoverageMap);

#[pymethods]
impl PyCoverageMap {
    #[new]
    #[pyo3(signature = (grid, bins=Int(DEFAULT_BINS)), text_signature = "(grid, bins=16)")]
    fn new(py: Python<'_>, grid: Bound<'_, PyGrid>, bins: Bins) -> PyResult<Self> {
        CoverageMap::with_bins(grid.get().0, bins.0)
            .map(Self)
            .or_raise(py)
    }

    /// A map over ``grid`` from stored histograms: a float32 array of shape
    /// ``(rows, cols, bins)`` whose every histogram is finite, non-negative and
    /// sums to 1 within 1e-3 (``.histograms`` of another map, for instance).
    #[classmethod]
    fn from_histograms(
        _cls: &Bound<'_, PyType>,
        grid: Bound<'_, PyGrid>,
        histograms: &Bound<'_, PyAny>,
    ) -> PyResult<Self> {
        let py = histograms.py();
        let grid = grid.get().0;
        let (values, bins) = convert::histograms(histograms, &grid)?;
        CoverageMap::from_histograms(grid, bins, values)
            .map(Self)
            .or_raise(py)
    }

    /// The grid.
    #[getter]
    fn grid(&self) -> PyGrid {
        PyGrid(*self.0.grid())
    }
    /// Bins per cell.
    #[getter]
    fn bins(&self) -> usize {
        self.0.bins()
    }
    /// The coverage value of each bin, ``b / (bins - 1)``: float64, ``(bins,)``.
    #[getter]
    fn bin_values<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_vec(py, self.0.bin_values())
    }
    /// A copy of all histograms: float32, ``(rows, cols, bins)``.
    #[getter]
    fn histograms<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray3<f32>>> {
        convert::cell_stack_array(
            py,
            self.0.grid(),
            self.0.bins(),
            self.0.try_histograms_vec().or_raise(py)?,
        )
    }
    /// One cell's histogram: float32, ``(bins,)``.
    fn histogram<'py>(
        &self,
        py: Python<'py>,
        row: &Bound<'py, PyAny>,
        col: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArray1<f32>>> {
        let cell = convert::cell(self.0.grid(), row, col)?;
        let h = self.0.histogram(cell).or_raise(py)?;
        Ok(PyArray1::from_slice(py, h))
    }

    /// The maximum-likelihood map: each cell's most probable coverage value,
    /// float32, ``(rows, cols)``.
    fn ml<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f32>>> {
        cell_array(py, self.0.grid(), self.0.try_ml().or_raise(py)?)
    }
    /// The mean map: each cell's expected coverage, float32, ``(rows, cols)``.
    fn mean<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f32>>> {
        cell_array(py, self.0.grid(), self.0.try_mean().or_raise(py)?)
    }
    /// The entropy map in nats (``ln(bins)`` at the prior, 0 when certain),
    /// float32, ``(rows, cols)``.
    fn entropy<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f32>>> {
        cell_array(py, self.0.grid(), self.0.try_entropy().or_raise(py)?)
    }

    /// Which cells some evidence reached (a reading, or the robot touching an
    /// obstacle): those whose histogram is no longer the uniform prior, bool,
    /// ``(rows, cols)``. Unknown is a value of its own: an unobserved cell
    /// reads 0 on ``ml()``, as an empty cell does, and this tells them apart.
    fn observed<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<bool>>> {
        cell_array(py, self.0.grid(), self.0.try_observed().or_raise(py)?)
    }

    /// Integrate one scan taken from ``pose = (x, y, theta)`` (metres, radians):
    /// reading ``ranges[i]`` (metres) along ``theta + bearings[i]`` (radians).
    /// ``ranges`` and ``bearings`` are 1-D float64 or float32 arrays (or sequences of
    /// numbers) of equal length; a reading at or beyond the model's maximum
    /// range means "no echo". ``model`` is a ``SonarModel`` or a
    /// ``LaserModel``. Returns the number of cell updates.
    ///
    /// Everything is checked before anything changes: after an error the map
    /// is exactly as it was. The update runs with the GIL released; touching
    /// the same map from another thread meanwhile raises ``RuntimeError``.
    fn integrate(
        &mut self,
        py: Python<'_>,
        pose: &Bound<'_, PyAny>,
        ranges: &Bound<'_, PyAny>,
        bearings: &Bound<'_, PyAny>,
        model: &Bound<'_, PyAny>,
    ) -> PyResult<usize> {
        let scan = Scan::extract(pose, ranges, bearings, model)?;
        let map = &mut self.0;
        py.detach(|| map.integrate(&scan.pose, &scan.ranges, &scan.bearings, &scan.model))
            .or_raise(py)
    }

    /// Integrate every scan of ``log`` (a ``Log``) with ``model``, in order;
    /// returns the number of cell updates. Each scan is taken from its sensor pose (the robot's
    /// pose with the log's sensor offset); dropped beams (NaN) are skipped; a
    /// reading without echo clears up to the lesser of the log's and the
    /// model's maximum range. With ``occlude_no_echo`` every echo reading
    /// goes first into a copy of the map (as much memory again); then every
    /// scan goes in read against the cells that copy holds covered and is
    /// certain of (entropy at most 0.65 nats, the default epsilon; the
    /// exploration loop's rule, with every echo known; the map does not
    /// depend on the order of the scans): a no-echo reading clears only
    /// what its line of sight reaches past them (through a wall the echoes
    /// found it is taken for a specular miss), and an echo off one of them
    /// marks only the cells at its bearing and the certain ones, not the
    /// rest of its arc (model.md, section 5). Every
    /// scan is checked first: a scan whose
    /// sensor pose lies outside the map raises (``PoseOutsideMapError``, the
    /// message naming the scan) and leaves the map exactly as it was.
    /// ``progress``: ``True`` shows a bar (tqdm's if installed), a callable
    /// is called as ``progress(done, total)``; if it raises (or Ctrl-C
    /// interrupts the bar), the error is raised once the scans are in and
    /// the map is left as it was (with a progress display the scans go into
    /// a copy, which takes as much memory again). Runs with the GIL
    /// released.
    #[pyo3(signature = (log, model, *, occlude_no_echo=false, progress=crate::log::ProgressArg::Flag(false)), text_signature = "($self, log, model, *, occlude_no_echo=False, progress=False)")]
    fn integrate_log(
        &mut self,
        py: Python<'_>,
        log: Bound<'_, crate::log::PyLog>,
        model: &Bound<'_, PyAny>,
        occlude_no_echo: bool,
        progress: crate::log::ProgressArg,
    ) -> PyResult<usize> {
        let model = crate::sensor::any_model(model)?;
        let log = &log.get().0;
        crate::log::integrate_log_shown(
            py,
            &mut self.0,
            covmap::CoverageMap::try_clone,
            (progress, log.len()),
            |map, show| {
                if occlude_no_echo {
                    map.occluding()
                        .integrate_log_with_progress(log, &model, show)
                } else {
                    map.integrate_log_with_progress(log, &model, show)
                }
            },
        )
    }

    /// Keep (``True``) or stop keeping (``False``) each cell's entropy after
    /// its last measurements, for ``stagnated()`` and ``Planner.status``. A
    /// scan that updates a cell counts as one measurement of it. Off by
    /// default; turning it on (again) starts an empty history. Pickling and
    /// copying keep the history.
    fn track_history(&mut self, py: Python<'_>, on: bool) -> PyResult<()> {
        self.0.try_track_history(on).or_raise(py)
    }
    /// Whether the entropy history is kept.
    #[getter]
    fn tracks_history(&self) -> bool {
        self.0.tracks_history()
    }
    /// How many scans updated each cell since the history was turned on:
    /// uint32, ``(rows, cols)`` (all zero while it is off).
    fn measurements<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<u32>>> {
        let values = self.0.try_measurement_counts().or_raise(py)?;
        cell_array(py, self.0.grid(), values)
    }
    /// Whether each cell's entropy changed by less than 0.001 nats over its
    /// last five measurements: bool, ``(rows, cols)`` (all ``False`` while the
    /// history is off or shorter).
    fn stagnated<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<bool>>> {
        let values = self.0.try_stagnation().or_raise(py)?;
        cell_array(py, self.0.grid(), values)
    }

    fn __repr__(&self) -> String {
        format!(
            "CoverageMap({}, bins={})",
            self.grid().__repr__(),
            self.0.bins()
        )
    }
    /// Save the whole posterior (grid, bins, histograms, the entropy history
    /// if kept) to ``path``: a versioned ``.npz`` archive that
    /// ``numpy.load`` opens without covmap (``covmap_version``, ``grid`` =
    /// origin x, origin y, resolution, ``histograms`` (rows, cols, bins),
    /// ``history_entropies`` and ``history_counts``), each entry with a
    /// CRC-32; deflated (``compress``, as ``numpy.savez_compressed``
    /// writes) or stored as they are. Written atomically: a reader never
    /// sees half a file, and a failed write leaves ``path`` as it was
    /// (``FileIOError``). Runs with the GIL released.
    #[pyo3(signature = (path, *, compress=true), text_signature = "($self, path, *, compress=True)")]
    fn save(&self, py: Python<'_>, path: std::path::PathBuf, compress: bool) -> PyResult<()> {
        let map = &self.0;
        let bytes = py
            .detach(|| map.to_file_bytes_with(compress))
            .or_raise(py)?;
        py.detach(|| covmap::sim::write_atomic(&path, &bytes))
            .or_raise(py)
    }
    /// The map ``save`` wrote to ``path``, bit for bit. A file that is not a
    /// whole, unchanged map file (empty, cut short, a byte changed, a newer
    /// version) raises ``FileFormatError``, one that cannot be read
    /// ``FileIOError``; never a wrong map. Runs with the GIL released.
    #[staticmethod]
    fn load(py: Python<'_>, path: std::path::PathBuf) -> PyResult<Self> {
        // The map file's own limit, not other files': what `save` wrote
        // (up to 4 GiB) must load.
        let bytes = py
            .detach(|| covmap::sim::read_bytes_at_most(&path, covmap::MAX_MAP_FILE_BYTES))
            .or_raise(py)?;
        py.detach(|| CoverageMap::from_file_bytes(&bytes))
            .map(Self)
            .map_err(|e| crate::errors::file_to_py(py, &path, e))
    }
    /// The map as ``nav_msgs/OccupancyGrid`` data: int8 ``(rows, cols)``,
    /// ``source``'s coverage (``"ml"`` or ``"mean"``) in percent, ``-1``
    /// (unknown) for every cell whose entropy is still within
    /// ``unknown_within_nats`` of the prior's ``ln(bins)`` (0: only cells no
    /// evidence reached). Row 0 is the grid's row 0, as in the message.
    #[pyo3(
        signature = (*, source="ml", unknown_within_nats=Float(0.05)),
        text_signature = "($self, *, source='ml', unknown_within_nats=0.05)"
    )]
    fn ros_occupancy<'py>(
        &self,
        py: Python<'py>,
        source: &str,
        unknown_within_nats: Float,
    ) -> PyResult<Bound<'py, PyArray2<i8>>> {
        let value = crate::ros_map::coverage_value(py, source)?;
        let data = self
            .0
            .ros_occupancy(value, unknown_within_nats.0)
            .or_raise(py)?;
        crate::ros_map::array(py, self.0.grid(), data)
    }
    /// Write the map as ROS map_server / nav2 map_saver do: ``yaml_path``
    /// and the PGM of the same name beside it, from ``ros_occupancy(source=,
    /// unknown_within_nats=)``; ``mode`` ``"trinary"`` (black at or above
    /// ``occupied_thresh``, white at or below ``free_thresh``, grey between
    /// and unknown) or ``"scale"`` (grey by occupancy, unknown 205).
    /// ``World.from_file(yaml_path)`` reads the pair back. The pair is
    /// written together: both files whole to temporary files first, then
    /// renamed into place, the old pair kept if either fails
    /// (``FileIOError``); a ``yaml_path`` ending in ``.pgm`` is refused.
    #[pyo3(
        signature = (
            yaml_path, *, mode="trinary", occupied_thresh=Float(0.65), free_thresh=Float(0.196),
            source="ml", unknown_within_nats=Float(0.05)
        ),
        text_signature = "($self, yaml_path, *, mode='trinary', occupied_thresh=0.65, free_thresh=0.196, source='ml', unknown_within_nats=0.05)"
    )]
    #[allow(
        clippy::too_many_arguments,
        reason = "map_saver's settings and the read-out's"
    )]
    fn to_ros_map(
        &self,
        py: Python<'_>,
        yaml_path: std::path::PathBuf,
        mode: &str,
        occupied_thresh: Float,
        free_thresh: Float,
        source: &str,
        unknown_within_nats: Float,
    ) -> PyResult<()> {
        let value = crate::ros_map::coverage_value(py, source)?;
        let data = self
            .0
            .ros_occupancy(value, unknown_within_nats.0)
            .or_raise(py)?;
        let grid = *self.0.grid();
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
    /// Pickle and copy support: rebuilt from the grid and the histograms,
    /// the entropy history (if kept) and the evidence behind the histograms
    /// (each cell's log-likelihoods, which hold more than the histograms
    /// do) restored by ``__setstate__``, so that a copy goes on as the
    /// original does.
    fn __reduce__<'py>(&self, py: Python<'py>) -> PyResult<Reduce<'py>> {
        let rebuild = py.get_type::<Self>().getattr("from_histograms")?;
        let grid = self.0.grid();
        let history = match self.0.history_state() {
            Some(h) => Some((
                convert::cell_stack_array(py, grid, STAGNATION_MEASUREMENTS + 1, h.entropies)?,
                cell_array(py, grid, h.count)?,
            )),
            None => None,
        };
        let evidence =
            covmap::memory::try_collect(self.0.evidence().iter().copied(), "the evidence")
                .or_raise(py)?;
        let evidence = convert::cell_stack_array(py, grid, self.0.bins(), evidence)?;
        Ok((
            rebuild,
            (self.grid(), self.histograms(py)?),
            (history, evidence),
        ))
    }
    /// Unpickling support: restore the state ``__reduce__`` saves,
    /// ``(history, evidence)``: the entropy history, ``None`` or
    /// ``(entropies, counts)`` (float32 ``(rows, cols,
    /// STAGNATION_MEASUREMENTS + 1)`` and uint32 ``(rows, cols)``), kept
    /// tracking, and the evidence, float32 ``(rows, cols, bins)``, which must
    /// give the map's histograms. ``None`` or ``(entropies, counts)`` alone
    /// (what earlier versions saved) restore the history only. After an
    /// error the map is exactly as it was.
    fn __setstate__(&mut self, py: Python<'_>, state: &Bound<'_, PyAny>) -> PyResult<()> {
        if state.is_none() {
            return Ok(());
        }
        let (first, second) = pair(
            py,
            state,
            "state must be None, (history, evidence) or (entropies, counts)",
        )?;
        // (history, evidence): the history is None or a tuple; else the
        // earlier (entropies, counts).
        if first.is_none() || first.cast::<PyTuple>().is_ok() {
            let grid = *self.0.grid();
            let evidence = convert::cell_values::<f32>(
                &second,
                &grid,
                "evidence",
                "float32",
                Some(self.0.bins()),
            )?;
            let before = self.0.evidence().to_vec();
            self.0.restore_evidence(evidence).or_raise(py)?;
            if first.is_none() {
                return Ok(());
            }
            return match self.restore_history(py, &first) {
                Ok(()) => Ok(()),
                Err(refused) => {
                    // The history is refused: the evidence goes back too.
                    self.0.restore_evidence(before).or_raise(py)?;
                    Err(refused)
                }
            };
        }
        self.restore_history(py, state)
    }
}

impl PyCoverageMap {
    /// Restore the entropy history from ``(entropies, counts)``; after an
    /// error the map is exactly as it was.
    fn restore_history(&mut self, py: Python<'_>, state: &Bound<'_, PyAny>) -> PyResult<()> {
        let (entropies, counts) = pair(
            py,
            state,
            "the history must be a tuple (entropies, counts) of two numpy arrays",
        )?;
        let grid = *self.0.grid();
        let depth = Some(STAGNATION_MEASUREMENTS + 1);
        let entropies =
            convert::cell_values::<f32>(&entropies, &grid, "history entropies", "float32", depth)?;
        let count = convert::cell_values::<u32>(&counts, &grid, "history counts", "uint32", None)?;
        self.0
            .restore_history(HistoryState { entropies, count })
            .or_raise(py)
    }
}

/// The two items of a 2-tuple, or an `InvalidTypeError` that says `expected`
/// and what was given instead.
fn pair<'py>(
    py: Python<'py>,
    value: &Bound<'py, PyAny>,
    expected: &str,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
    value
        .extract::<(Bound<'py, PyAny>, Bound<'py, PyAny>)>()
        .map_err(|_| {
            let got = match value.cast::<PyTuple>() {
                Ok(tuple) => format!("a tuple of length {}", tuple.len()),
                Err(_) => value.get_type().to_string(),
            };
            Exception::InvalidType.err(py, format!("{expected}, got {got}"))
        })
}
