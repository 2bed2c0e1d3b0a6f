//! `covmap.Log`: a recorded drive, from numpy arrays or a log file, and its
//! contents as numpy arrays.

use std::path::PathBuf;
use std::sync::Mutex;

use covmap::log::laser_scan::LaserScanFan;
use covmap::{Bearings, CarmenLaser, CarmenOptions, Log, Pose, SonarTextOptions};
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1, PyArray2};

use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PySlice};

use crate::convert;
use crate::errors::{Exception, OrRaise};
use crate::numbers::Float;

/// A recorded drive: scan ``i`` taken at ``timestamps[i]`` from robot pose
/// ``poses[i]`` (x, y metres, theta radians), reading ``ranges[i, k]``
/// metres along ``bearings[k]`` (or ``bearings[i, k]``, bearings of each
/// scan), radians from the heading of a sensor mounted at
/// ``sensor_offset`` on the robot.
///
/// A range at or above ``max_range_m`` has no echo; a NaN range is a beam
/// without a reading (``from_laser_scans`` makes them of REP 117's NaN and
/// ``-inf``), which integrating skips. The constructor itself refuses NaN,
/// infinite and negative ranges. ``len(log)`` counts scans; ``log[a:b]`` is
/// a log of those scans. Logs pickle.
#[pyclass(name = "Log", module = "covmap._native", frozen)]
pub(crate) struct PyLog(pub(crate) Log);

fn bearings_from(obj: &Bound<'_, PyAny>, scans: usize) -> PyResult<Bearings> {
    if let Ok((values, [n, _])) = convert::matrix(obj, "bearings") {
        if n != scans {
            return Err(Exception::ArrayShape.err(
                obj.py(),
                format!(
                    "bearings of shape (N, B) must have a row a scan: {n} rows for {scans} scans"
                ),
            ));
        }
        return Ok(Bearings::PerScan(values));
    }
    Ok(Bearings::Fixed(convert::readings(
        obj,
        "bearings",
        convert::MAX_VALUES,
    )?))
}

/// Poses `(N, 3)` and ranges `(N, B)`, a row of ranges a pose.
fn scans(
    py: Python<'_>,
    poses: &Bound<'_, PyAny>,
    ranges: &Bound<'_, PyAny>,
) -> PyResult<(Vec<Pose>, Vec<f64>)> {
    let poses = convert::poses(poses, "poses")?;
    let (ranges, [n, _]) = convert::matrix(ranges, "ranges")?;
    if n != poses.len() {
        return Err(
            Exception::ArrayShape.err(py, format!("ranges has {n} rows for {} poses", poses.len()))
        );
    }
    Ok((poses, ranges))
}

/// A sensor's mounting on the robot, `(x, y, theta)` (metres, radians):
/// any sequence of three numbers, as [`convert::fixed_numbers`] reads it.
struct SensorOffset([f64; 3]);

impl<'a, 'py> FromPyObject<'a, 'py> for SensorOffset {
    type Error = PyErr;
    fn extract(obj: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        convert::fixed_numbers::<3>(&obj, "sensor_offset", "(x, y, theta)").map(Self)
    }
}

#[pymethods]
impl PyLog {
    /// A log of ``poses`` ((N, 3)), ``ranges`` ((N, B), metres, float64 or
    /// float32), ``bearings`` ((B,) or (N, B), radians), ``max_range_m``;
    /// ``timestamps`` ((N,), seconds) default to each scan's index,
    /// ``sensor_offset`` to the robot's own pose.
    #[new]
    #[pyo3(
        signature = (poses, ranges, bearings, *, max_range_m, timestamps=None, sensor_offset=SensorOffset([0.0; 3])),
        text_signature = "(poses, ranges, bearings, *, max_range_m, timestamps=None, sensor_offset=(0.0, 0.0, 0.0))"
    )]
    fn new(
        py: Python<'_>,
        poses: &Bound<'_, PyAny>,
        ranges: &Bound<'_, PyAny>,
        bearings: &Bound<'_, PyAny>,
        max_range_m: Float,
        timestamps: Option<&Bound<'_, PyAny>>,
        sensor_offset: SensorOffset,
    ) -> PyResult<Self> {
        let (poses, ranges) = scans(py, poses, ranges)?;
        let n = poses.len();
        let bearings = bearings_from(bearings, n)?;
        let timestamps = match timestamps {
            Some(t) => convert::readings(t, "timestamps", convert::MAX_VALUES)?,
            None => (0..n).map(|i| i as f64).collect(),
        };
        Log::new(poses, timestamps, ranges, bearings, max_range_m.0)
            .and_then(|log| log.with_sensor_offset(Pose::from(sensor_offset.0)))
            .map(Self)
            .or_raise(py)
    }

    /// The log in a CARMEN file (plain or gzip): ``FLASER``, ``ROBOTLASER1``
    /// or ``RAWLASER1`` scans (poses from ``ODOM`` interpolated for the
    /// last); with ``laser="rear"`` the rear laser's ``RLASER``,
    /// ``ROBOTLASER2`` or ``RAWLASER2`` scans and mounting instead.
    /// ``max_range_m`` overrides the log's maximum range. A malformed line
    /// raises ``FileFormatError`` naming the file and the line. Reads with
    /// the GIL released.
    #[staticmethod]
    #[pyo3(signature = (path, *, max_range_m=None, laser="front"))]
    fn from_carmen(
        py: Python<'_>,
        path: PathBuf,
        max_range_m: Option<Float>,
        laser: &str,
    ) -> PyResult<Self> {
        let laser = match laser {
            "front" => CarmenLaser::Front,
            "rear" => CarmenLaser::Rear,
            other => {
                return Err(Exception::InvalidParameter.err(
                    py,
                    format!(
                        "invalid parameter `laser` = {}: expected \"front\" or \"rear\"",
                        covmap::quoted(other)
                    ),
                ));
            }
        };
        let options = CarmenOptions {
            max_range_m: max_range_m.map(|m| m.0),
            laser,
            ..Default::default()
        };
        py.detach(|| Log::from_carmen_with(&path, &options))
            .map(Self)
            .or_raise(py)
    }

    /// The sonar log of two text files read in step: ``poses_path`` lines
    /// ``timestamp x y theta``, ``measurements_path`` lines ``timestamp r_0
    /// … r_{B-1}`` (plain or gzip). ``bearings_deg`` gives each column's
    /// sonar, degrees from the heading. The poses' ``x`` and ``y`` are in
    /// units of ``length_unit_m`` metres, the ranges in units of
    /// ``range_unit_m`` (default: ``length_unit_m``), the heading in
    /// ``angle_unit_rad`` radians. A reading equal to ``no_echo`` (in the
    /// file's units), or at or above ``max_range_m``, has no echo; one below
    /// ``min_range_m`` is dropped (NaN); a negative one is an error.
    #[staticmethod]
    #[pyo3(
        signature = (
            poses_path, measurements_path, *, bearings_deg, length_unit_m=Float(1.0),
            range_unit_m=None, angle_unit_rad=Float(1.0), min_range_m=Float(0.0), max_range_m,
            no_echo=None
        ),
        text_signature = "(poses_path, measurements_path, *, bearings_deg, length_unit_m=1.0, range_unit_m=None, angle_unit_rad=1.0, min_range_m=0.0, max_range_m, no_echo=None)"
    )]
    #[allow(clippy::too_many_arguments)]
    fn from_sonar_text(
        py: Python<'_>,
        poses_path: PathBuf,
        measurements_path: PathBuf,
        bearings_deg: &Bound<'_, PyAny>,
        length_unit_m: Float,
        range_unit_m: Option<Float>,
        angle_unit_rad: Float,
        min_range_m: Float,
        max_range_m: Float,
        no_echo: Option<Float>,
    ) -> PyResult<Self> {
        let options = SonarTextOptions {
            bearings_rad: convert::readings(bearings_deg, "bearings_deg", covmap::sim::MAX_BEAMS)?
                .into_iter()
                .map(f64::to_radians)
                .collect(),
            length_unit_m: length_unit_m.0,
            range_unit_m: range_unit_m.unwrap_or(length_unit_m).0,
            angle_unit_rad: angle_unit_rad.0,
            min_range_m: min_range_m.0,
            max_range_m: max_range_m.0,
            no_echo: no_echo.map(|v| v.0),
        };
        py.detach(|| Log::from_sonar_text(&poses_path, &measurements_path, &options))
            .map(Self)
            .or_raise(py)
    }

    /// Scans as ROS ``sensor_msgs/LaserScan`` hands them: ``ranges`` (N, B)
    /// float32 or float64, beam ``k`` at ``angle_min + k angle_increment``.
    /// REP 117 is converted here: ``+inf`` and readings above ``range_max``
    /// have no echo; NaN, ``-inf`` and readings below ``range_min`` are
    /// dropped (NaN in ``ranges``). ``range_max`` is the log's maximum range.
    #[staticmethod]
    #[pyo3(signature = (poses, ranges, *, angle_min, angle_increment, range_min, range_max, timestamps=None))]
    #[allow(clippy::too_many_arguments)]
    fn from_laser_scans(
        py: Python<'_>,
        poses: &Bound<'_, PyAny>,
        ranges: &Bound<'_, PyAny>,
        angle_min: Float,
        angle_increment: Float,
        range_min: Float,
        range_max: Float,
        timestamps: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        let (poses, ranges) = scans(py, poses, ranges)?;
        let timestamps = timestamps
            .map(|t| convert::readings(t, "timestamps", convert::MAX_VALUES))
            .transpose()?;
        let fan = LaserScanFan {
            angle_min_rad: angle_min.0,
            angle_increment_rad: angle_increment.0,
            range_min_m: range_min.0,
            range_max_m: range_max.0,
        };
        Log::from_laser_scans(poses, &ranges, &fan, timestamps)
            .map(Self)
            .or_raise(py)
    }

    /// The log of one sensor in a ROS 1 (``.bag``) or ROS 2 bag, read with
    /// the ``rosbags`` package (``pip install 'covmap[rosbags]'``): the
    /// ``sensor_msgs/LaserScan`` or ``sensor_msgs/Range`` messages on
    /// ``topic`` (default: the bag's only such topic), REP 117 converted as
    /// ``from_laser_scans`` does; the robot's poses from the
    /// ``nav_msgs/Odometry`` on ``odom_topic``, else from ``/tf``
    /// (``base_frame``, default ``base_link``, in ``fixed_frame``, default
    /// the tree's root), interpolated at each message's stamp; the sensor's
    /// mounting from ``/tf_static``. ``max_range_m`` overrides the messages'
    /// maximum range. A bag that cannot be read or lacks what is asked
    /// raises ``FileFormatError`` naming the file (see ``covmap._bag``).
    #[staticmethod]
    #[pyo3(signature = (path, *, topic=None, odom_topic=None, base_frame=None, fixed_frame=None, max_range_m=None))]
    fn from_bag<'py>(
        py: Python<'py>,
        path: &Bound<'py, PyAny>,
        topic: Option<&str>,
        odom_topic: Option<&str>,
        base_frame: Option<&str>,
        fixed_frame: Option<&str>,
        max_range_m: Option<Float>,
    ) -> PyResult<Bound<'py, PyAny>> {
        // The reading is Python's (rosbags is a Python package).
        let kwargs = pyo3::types::PyDict::new(py);
        kwargs.set_item("topic", topic)?;
        kwargs.set_item("odom_topic", odom_topic)?;
        kwargs.set_item("base_frame", base_frame)?;
        kwargs.set_item("fixed_frame", fixed_frame)?;
        kwargs.set_item("max_range_m", max_range_m.map(|m| m.0))?;
        py.import("covmap._bag")?
            .getattr("read_bag")?
            .call((path,), Some(&kwargs))
    }

    /// The robot's pose of every scan, float64, ``(N, 3)``.
    #[getter]
    fn poses<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        convert::poses_array(py, self.0.poses())
    }
    /// Every range, metres, float64, ``(N, B)`` (NaN: a dropped beam).
    #[getter]
    fn ranges<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let shape = (self.0.len(), self.0.beams());
        Array2::from_shape_vec(shape, self.0.ranges_m().to_vec())
            .map(|a| a.into_pyarray(py))
            .map_err(|e| Exception::Base.err(py, e.to_string()))
    }
    /// The bearings, radians from the sensor's heading, float64: ``(B,)``,
    /// or ``(N, B)`` for a log whose scans have bearings of their own.
    #[getter]
    fn bearings<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        match self.0.bearings() {
            Bearings::Fixed(b) => Ok(PyArray1::from_slice(py, b).into_any()),
            Bearings::PerScan(b) => {
                Array2::from_shape_vec((self.0.len(), self.0.beams()), b.clone())
                    .map(|a| a.into_pyarray(py).into_any())
                    .map_err(|e| Exception::Base.err(py, e.to_string()))
            }
        }
    }
    /// The time of every scan, seconds, float64, ``(N,)``.
    #[getter]
    fn timestamps<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, self.0.timestamps_s())
    }
    /// The sensor's maximum range, metres: a reading at or above it has no echo.
    #[getter]
    fn max_range_m(&self) -> f64 {
        self.0.max_range_m()
    }
    /// Where the sensor sits on the robot, ``(x, y, theta)`` in the robot's frame.
    #[getter]
    fn sensor_offset(&self) -> (f64, f64, f64) {
        let o = self.0.sensor_offset();
        (o.x_m, o.y_m, o.theta_rad)
    }
    /// The number of beams a scan.
    #[getter]
    fn beams(&self) -> usize {
        self.0.beams()
    }

    /// ``(x_min, y_min, x_max, y_max)`` covering every pose and every beam's
    /// end point, each beam cut at ``reach_m`` metres (no-echo beams end at
    /// the maximum range); ``None`` for an empty log.
    fn extent(&self, py: Python<'_>, reach_m: Float) -> PyResult<Option<(f64, f64, f64, f64)>> {
        let bounds = self.0.extent(reach_m.0).or_raise(py)?;
        Ok(bounds.map(|[a, b, c, d]| (a, b, c, d)))
    }

    /// This log with its sensor mounted at ``offset`` ``(x, y, theta)`` on
    /// the robot.
    fn with_sensor_offset(&self, py: Python<'_>, offset: &Bound<'_, PyAny>) -> PyResult<Self> {
        let offset = convert::pose(offset)?;
        self.0
            .clone()
            .with_sensor_offset(offset)
            .map(Self)
            .or_raise(py)
    }

    fn __len__(&self) -> usize {
        self.0.len()
    }

    /// ``log[a:b]``: the scans ``a`` to ``b`` as a log (a step other than 1
    /// raises ``InvalidValueError``, an index that is no slice
    /// ``InvalidTypeError``).
    fn __getitem__(&self, py: Python<'_>, key: &Bound<'_, PyAny>) -> PyResult<Self> {
        let Ok(slice) = key.cast::<PySlice>() else {
            return Err(Exception::InvalidType.err(
                py,
                format!(
                    "a log is sliced (log[a:b]), not indexed by {}",
                    key.get_type()
                ),
            ));
        };
        // Python's own check of the slice raises a bare ValueError for step 0
        // and a TypeError for bounds that are no integers.
        let indices = slice.indices(self.0.len() as isize).map_err(|e| {
            let said = e.value(py).to_string();
            match e.is_instance_of::<pyo3::exceptions::PyTypeError>(py) {
                true => Exception::InvalidType.err(py, format!("a log's slice: {said}")),
                false => Exception::InvalidValue.err(py, format!("a log's slice: {said}")),
            }
        })?;
        if indices.step != 1 {
            return Err(Exception::InvalidValue.err(
                py,
                format!(
                    "a log's slice takes consecutive scans, not step {}",
                    indices.step
                ),
            ));
        }
        let (start, stop) = (
            indices.start as usize,
            (indices.stop.max(indices.start)) as usize,
        );
        self.0.slice(start..stop).map(Self).or_raise(py)
    }

    fn __repr__(&self) -> String {
        format!(
            "Log({} scans of {} beams, max_range_m={})",
            self.0.len(),
            self.0.beams(),
            self.0.max_range_m()
        )
    }

    /// Pickle support: rebuilt by ``Log._from_state`` from the core's
    /// serialised form (JSON bytes, every float64 exact).
    fn __reduce__<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyAny>, (Bound<'py, PyBytes>,))> {
        crate::pickling::reduce::<Self, _>(py, &self.0, "log")
    }

    /// Unpickling support: the log saved by ``__reduce__`` (validated).
    #[staticmethod]
    fn _from_state(py: Python<'_>, state: Bound<'_, PyBytes>) -> PyResult<Self> {
        crate::pickling::restored(py, state.as_bytes(), "log").map(Self)
    }
}

/// How `integrate_log` shows its progress: nothing, a bar (tqdm's if it is
/// installed, else a line on standard error that rewrites itself), or the
/// caller's `progress(done, total)`.
enum Progress {
    Bar(Option<Py<PyAny>>, &'static str),
    Call(Py<PyAny>),
}

/// The `progress` argument of `integrate_log`: a flag or a callable.
#[derive(FromPyObject)]
pub(crate) enum ProgressArg {
    /// `True`: a bar; `False`: nothing.
    Flag(bool),
    /// Called as `progress(done, total)`.
    Call(Py<PyAny>),
}

impl Progress {
    fn new(
        py: Python<'_>,
        progress: ProgressArg,
        total: usize,
        unit: &'static str,
    ) -> PyResult<Option<Self>> {
        match progress {
            ProgressArg::Flag(false) => Ok(None),
            ProgressArg::Call(f) if f.bind(py).is_callable() => Ok(Some(Self::Call(f))),
            ProgressArg::Call(f) => Err(Exception::InvalidType.err(
                py,
                format!(
                    "progress must be a bool or a callable (done, total), got {}",
                    f.bind(py).get_type()
                ),
            )),
            ProgressArg::Flag(true) => {
                let bar = match py.import("tqdm") {
                    Ok(tqdm) => {
                        let kwargs = pyo3::types::PyDict::new(py);
                        kwargs.set_item("total", total)?;
                        kwargs.set_item("unit", unit)?;
                        Some(tqdm.getattr("tqdm")?.call((), Some(&kwargs))?.unbind())
                    }
                    Err(_) => None,
                };
                Ok(Some(Self::Bar(bar, unit)))
            }
        }
    }

    pub(crate) fn show(
        &self,
        py: Python<'_>,
        done: usize,
        step: usize,
        total: usize,
    ) -> PyResult<()> {
        match self {
            Self::Call(f) => f.call1(py, (done, total)).map(drop),
            Self::Bar(Some(bar), _) => bar.call_method1(py, "update", (step,)).map(drop),
            Self::Bar(None, unit) => py
                .import("sys")?
                .getattr("stderr")?
                .call_method1("write", (format!("\r{} {done}/{total}", unit.trim()),))
                .map(drop),
        }
    }

    fn close(&self, py: Python<'_>) -> PyResult<()> {
        match self {
            Self::Bar(Some(bar), _) => bar.call_method0(py, "close").map(drop),
            Self::Bar(None, _) => py
                .import("sys")?
                .getattr("stderr")?
                .call_method1("write", ("\n",))
                .map(drop),
            Self::Call(_) => Ok(()),
        }
    }
}

/// A log's `scans` integrated into `map` by `integrate` (which calls its
/// second argument with the scans done so far), shown by `progress`. A
/// display can raise (the callable's exception, Ctrl-C in a bar) once scans
/// went in: with one, the scans go into a copy (`try_clone`) that replaces
/// `map` only if nothing raised, so that an error leaves `map` as it was;
/// without one, into `map` itself.
///
/// The map is borrowed for the whole call, so a progress callable that uses
/// it (reads it, integrates into it, saves it) fails to borrow it: pyo3's
/// `RuntimeError` of that borrow is raised as `MapBusyError`, which says so.
pub(crate) fn integrate_log_shown<M: Send>(
    py: Python<'_>,
    map: &mut M,
    try_clone: impl FnOnce(&M) -> covmap::Result<M>,
    (progress, scans): (ProgressArg, usize),
    integrate: impl FnOnce(&mut M, &mut dyn FnMut(usize)) -> covmap::Result<usize> + Send,
) -> PyResult<usize> {
    if matches!(progress, ProgressArg::Flag(false)) {
        return with_progress(py, progress, (scans, " scans"), |_| {
            integrate(map, &mut |_| {})
        });
    }
    let mut copy = try_clone(map).or_raise(py)?;
    let updates = with_progress(py, progress, (scans, " scans"), |show| {
        integrate(&mut copy, &mut |done| show(done))
    })
    .map_err(|e| busy(py, e))?;
    *map = copy;
    Ok(updates)
}

/// `error`, raised by a progress callable of `integrate_log`, as
/// `MapBusyError` if it is pyo3's failure to borrow a map (the map the call
/// holds: the callable used it), else as it is.
fn busy(py: Python<'_>, error: PyErr) -> PyErr {
    let borrow_failed = error.get_type(py).is(py.get_type::<PyRuntimeError>())
        && matches!(
            error.value(py).to_string().as_str(),
            "Already borrowed" | "Already mutably borrowed"
        );
    if !borrow_failed {
        return error;
    }
    let busy = Exception::MapBusy.err(
        py,
        "the map is busy in this call: integrate_log's progress callback cannot use the map it \
         integrates into (read it once integrate_log has returned); nothing was changed",
    );
    busy.set_cause(py, Some(error));
    busy
}

/// Run `work` with the GIL released, showing progress over `total` steps
/// counted in `unit` (a word with a leading space) as `progress` asks,
/// about once a percent: `work` reports the steps done so far, from any of
/// the threads it runs on (a log's scans, a fit's evaluations). An exception
/// the display raises is raised after the work is done.
pub(crate) fn with_progress<T, R: OrRaise<T> + Send>(
    py: Python<'_>,
    progress: ProgressArg,
    (total, unit): (usize, &'static str),
    work: impl FnOnce(&(dyn Fn(usize) + Sync)) -> R + Send,
) -> PyResult<T> {
    let display = Progress::new(py, progress, total, unit)?;
    let every = (total / 100).max(1);
    // The steps shown so far, and the display's error if it raised.
    let state: Mutex<(usize, Option<PyErr>)> = Mutex::new((0, None));
    let result = py.detach(|| {
        work(&|done| {
            let Some(d) = &display else { return };
            let mut state = state.lock().unwrap_or_else(|e| e.into_inner());
            if state.1.is_none() && done > state.0 && (done % every == 0 || done == total) {
                let step = done - state.0;
                state.0 = done;
                if let Err(e) = Python::attach(|py| d.show(py, done, step, total)) {
                    state.1 = Some(e);
                }
            }
        })
    });
    if let Some(d) = &display {
        d.close(py)?;
    }
    if let Some(e) = state.into_inner().unwrap_or_else(|e| e.into_inner()).1 {
        return Err(e);
    }
    result.or_raise(py)
}
