//! `covmap.explore` and `covmap.Exploration`: a simulated robot explores a
//! world until its strategy is done (the core's loop, run by the simulator).
//!
//! What they return, `ExplorationResult` and `Step`, are dataclasses of the
//! Python package (`covmap/_exploration.py`), built here from the run.
//!
//! Longer than most files (about 650 lines): `Exploration`'s methods must sit
//! in one `#[pymethods]` block (pyo3 without its `multiple-pymethods`
//! feature), and most of the file is their documentation, which Python shows.

use std::sync::Arc;

use covmap::exploration::{ExplorationConfig, StepReport, Strategy, Trajectory};
use covmap::sim::exploration::{ExplorationRun, ExploreOptions, SimExploration, SimSensor};
use numpy::{PyArray1, PyArray2};
use pyo3::exceptions::PyStopIteration;
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::PyDict;

use crate::convert::{self, cell_array, poses_array, rows_array};
use crate::coverage_map::PyCoverageMap;
use crate::errors::{Exception, OrRaise};
use crate::grid::PyGrid;
use crate::numbers::{Bins, Float, Int, Seed};
use crate::occupancy::PyOccupancyGrid;
use crate::plan::PyPlan;
use crate::sensor::any_model;
use crate::sim_sensor::{PyLaser, PySonarRing};
use crate::strategy::PyStrategy;
use crate::world::PyWorld;

impl Keywords<'_> {
    /// The simulator's options. Only the conversions (and the resolution,
    /// under its Python name) are checked here; the values are checked by
    /// the run before anything starts.
    fn options(&self, py: Python<'_>) -> PyResult<ExploreOptions> {
        let d = ExploreOptions::default();
        let sensor = match &self.sensor {
            None => d.sensor,
            Some(s) => sim_sensor(s)?,
        };
        // Named as Python names it (the simulator's option is `resolution_m`).
        let resolution = self.resolution.0;
        if !(resolution > 0.0 && resolution.is_finite()) {
            return Err(Exception::InvalidParameter.err(
                py,
                format!(
                    "invalid parameter `resolution` = {resolution}: expected a positive, finite resolution (metres)"
                ),
            ));
        }
        Ok(ExploreOptions {
            start: self.start.as_ref().map(convert::pose).transpose()?,
            seed: self.seed.0,
            sensor,
            model: self.model.as_ref().map(any_model).transpose()?,
            resolution_m: resolution,
            bins: self.bins.0,
            config: ExplorationConfig {
                epsilon: self.epsilon.0,
                robot_radius_m: self.robot_radius_m.0,
                candidate_stride_m: self.candidate_stride_m.0,
                scan_spacing_m: self.scan_spacing_m.0,
                max_path_m: self.max_path_m.0,
                max_steps: self.max_steps.0,
                occlude_no_echo: self.occlude_no_echo,
                ..d.config
            },
            ..d
        })
    }
}

/// A `sensor` argument: a `SonarRing` or a `Laser`.
fn sim_sensor(obj: &Bound<'_, PyAny>) -> PyResult<SimSensor> {
    if let Ok(s) = obj.cast::<PySonarRing>() {
        Ok(SimSensor::Sonar(s.get().0.clone()))
    } else if let Ok(l) = obj.cast::<PyLaser>() {
        Ok(SimSensor::Laser(l.get().0.clone()))
    } else {
        Err(Exception::InvalidType.err(
            obj.py(),
            format!(
                "sensor must be a SonarRing or a Laser, got {}",
                obj.get_type()
            ),
        ))
    }
}

/// The keyword arguments' defaults, as a dict, for the package's test that
/// the signature's defaults are the simulator's (`_EXPLORE_DEFAULTS`).
pub(crate) fn defaults(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let d = ExploreOptions::default();
    let c = d.config;
    let dict = PyDict::new(py);
    dict.set_item("start", py.None())?;
    dict.set_item("seed", d.seed)?;
    dict.set_item("sensor", py.None())?;
    dict.set_item("model", py.None())?;
    dict.set_item("resolution", d.resolution_m)?;
    dict.set_item("bins", d.bins)?;
    dict.set_item("epsilon", c.epsilon)?;
    dict.set_item("robot_radius_m", c.robot_radius_m)?;
    dict.set_item("candidate_stride_m", c.candidate_stride_m)?;
    dict.set_item("scan_spacing_m", c.scan_spacing_m)?;
    dict.set_item("max_path_m", c.max_path_m)?;
    dict.set_item("max_steps", c.max_steps)?;
    dict.set_item("occlude_no_echo", c.occlude_no_echo)?;
    Ok(dict)
}

/// The keyword arguments of a run after `(world, strategy)`, written once
/// for `explore` and `Exploration` so that they cannot drift apart: hands
/// `$callback!` the pyo3 signature, the text signature Python shows, the
/// parameters (of a function with the lifetime `'py`) and the expression
/// that gathers them into [`Keywords`], then `$rest`; `@list
/// keywords_struct` declares [`Keywords`] from the same list. (The defaults
/// are the simulator's, `_EXPLORE_DEFAULTS`, as a test of the package
/// checks.)
macro_rules! run_keywords {
    ($callback:ident! { $($rest:tt)* }) => {
        run_keywords! { @list $callback! { $($rest)* } }
    };
    (@list $($then:tt)*) => {
        run_keywords! { @expand [$($then)*] (
            start: Option<Bound<'py, PyAny>>,
            seed: Seed,
            sensor: Option<Bound<'py, PyAny>>,
            model: Option<Bound<'py, PyAny>>,
            resolution: Float,
            bins: Bins,
            epsilon: Float,
            robot_radius_m: Float,
            candidate_stride_m: Float,
            scan_spacing_m: Float,
            max_path_m: Float,
            max_steps: Int<usize, 1, { usize::MAX as i128 }>,
            occlude_no_echo: bool,
        ) }
    };
    (@expand [keywords_struct] ($($name:ident: $ty:ty,)*)) => {
        /// The keyword arguments of `explore` and `Exploration`, as Python
        /// gave them.
        struct Keywords<'py> {
            $($name: $ty,)*
        }
    };
    (@expand [$callback:ident! { $($rest:tt)* }] ($($name:ident: $ty:ty,)*)) => {
        $callback! {
            signature: (
                world, strategy, *, start=None, seed=Seed(0), sensor=None, model=None,
                resolution=Float(0.05), bins=Int(16), epsilon=Float(0.65),
                robot_radius_m=Float(0.25), candidate_stride_m=Float(0.5),
                scan_spacing_m=Float(0.25), max_path_m=Float(10000.0), max_steps=Int(20000),
                occlude_no_echo=true
            ),
            text: "(world, strategy, *, start=None, seed=0, sensor=None, model=None, resolution=0.05, bins=16, epsilon=0.65, robot_radius_m=0.25, candidate_stride_m=0.5, scan_spacing_m=0.25, max_path_m=10000.0, max_steps=20000, occlude_no_echo=True)",
            params: ($($name: $ty,)*),
            keywords: (Keywords { $($name),* }),
            $($rest)*
        }
    };
}

run_keywords! { @list keywords_struct }

/// A run of `strategy` in `world` set up, nothing scanned yet; every option
/// checked first. The world is copied (the run owns what it drives through).
/// `strategy` is a `Strategy`, or a `CustomStrategy` (`Strategy.custom`)
/// whose goals come from Python (the run's strategy is then the core's
/// `Strategy::Custom`).
fn start_run(
    py: Python<'_>,
    world: &Bound<'_, PyWorld>,
    strategy: &Bound<'_, PyAny>,
    keywords: &Keywords,
) -> PyResult<PyExploration> {
    let (core, custom) = if let Ok(s) = strategy.cast::<PyStrategy>() {
        (s.get().0, false)
    } else if strategy.is_instance(&custom_class(py)?)? {
        (Strategy::Custom, true)
    } else {
        return Err(Exception::InvalidType.err(
            py,
            format!(
                "strategy must be a Strategy (Strategy.coverage(), Strategy.counting(), Strategy.frontier() or \
                 Strategy.custom(choose)), got {}",
                strategy.get_type()
            ),
        ));
    };
    let options = keywords.options(py)?;
    let world = &world.get().0;
    let run = py
        .detach(|| SimExploration::new(Arc::new(world.clone()), core, &options))
        .or_raise(py)?;
    Ok(PyExploration {
        run,
        strategy: strategy.clone().unbind(),
        custom,
    })
}

/// `covmap._custom`, where a custom strategy's view and answer are made.
fn custom_module(py: Python<'_>) -> PyResult<&Bound<'_, PyModule>> {
    static MODULE: PyOnceLock<Py<PyModule>> = PyOnceLock::new();
    Ok(MODULE
        .get_or_try_init(py, || py.import("covmap._custom").map(Bound::unbind))?
        .bind(py))
}

/// `covmap._custom.CustomStrategy`.
fn custom_class(py: Python<'_>) -> PyResult<Bound<'_, PyAny>> {
    custom_module(py)?.getattr("CustomStrategy")
}

/// `explore`, from the keywords of [`run_keywords!`].
macro_rules! explore_function {
    (
        signature: ($($signature:tt)*), text: $text:literal, params: ($($param:tt)*),
        keywords: ($keywords:expr), $(#[$doc:meta])*
    ) => {
        $(#[$doc])*
        #[pyfunction]
        #[pyo3(signature = ($($signature)*), text_signature = $text)]
        #[allow(clippy::too_many_arguments, reason = "one keyword argument per setting")]
        pub(crate) fn explore<'py>(
            py: Python<'py>,
            world: Bound<'py, PyWorld>,
            strategy: &Bound<'py, PyAny>,
            $($param)*
        ) -> PyResult<Bound<'py, PyAny>> {
            let exploration = start_run(py, &world, strategy, &$keywords)?;
            if exploration.custom {
                return PyExploration::run(&Bound::new(py, exploration)?);
            }
            let PyExploration { mut run, strategy, .. } = exploration;
            let epsilon = run.exploration().config().epsilon;
            let run = py
                .detach(move || {
                    run.run()?;
                    run.into_result()
                })
                .or_raise(py)?;
            result_object(py, strategy.bind(py), epsilon, run)
        }
    };
}

run_keywords! { explore_function! {
    /// Explore ``world`` (a ``World``) with ``strategy`` (a ``Strategy``) until
    /// the strategy is done or a limit is reached; returns an
    /// ``ExplorationResult``. Runs with the GIL released.
    ///
    /// The robot is a disc of ``robot_radius_m`` starting at ``start``
    /// (``(x, y, theta)``; ``None``: a free pose drawn from ``seed``, the
    /// centre of a cell keeping twice the radius from every obstacle in the
    /// free region the world encloses most of (not the outside of a
    /// building, nor a map's unknown), facing a random heading). It scans
    /// with ``sensor``
    /// (a ``SonarRing`` or a ``Laser``; ``None``: the 24-sonar ring) into a
    /// ``CoverageMap`` of ``bins`` bins over the world's bounds plus 0.5 m at
    /// ``resolution`` metres, and into an ``OccupancyGrid`` and scan counts
    /// fed the same beams, integrating with ``model`` (a ``SonarModel`` or a
    /// ``LaserModel``; ``None``: the sensor's default). Each step the strategy
    /// picks a goal on the maps (candidates ``candidate_stride_m`` apart), the
    /// robot follows the planned path through the true world, scanning every
    /// ``scan_spacing_m`` of travel and at the goal; where the map was wrong
    /// it stops at the obstacle, scans, and the contact is integrated as
    /// covered. Poses are exact (no localisation error). A cell is certain
    /// below ``epsilon`` nats. The run stops by the strategy's rule, or after
    /// ``max_path_m`` metres or ``max_steps`` steps. A reading with no echo
    /// clears only what its line of sight reaches past the cells the
    /// coverage map holds covered and is certain of, in every map, and an
    /// echo off such a cell marks only the cells at its bearing and the
    /// certain ones (``occlude_no_echo``, the default); with ``occlude_no_echo=False``
    /// it clears its whole footprint, the paper's reading (which settles
    /// more cells but erodes walls: docs/experiments.md, "The paper's
    /// no-echo reading in the loop").
    ///
    /// Every random draw (start, sensor noise) comes from ``seed``: the same
    /// seed gives the same run at any thread count. Every option is checked
    /// before anything runs: a bad value raises ``InvalidParameterError``
    /// naming it, a start in an obstacle ``InvalidStartError``, one off the
    /// map ``PoseOutsideMapError`` (all ``ValueError``).
} }

/// An exploration run to watch or steer step by step.
///
/// ``Exploration(world, strategy, **options)`` takes the arguments of
/// ``explore`` and checks them all, but runs nothing: each ``step()`` (GIL
/// released) chooses a goal, drives there scanning on the way and returns a
/// ``Step``, or ``None`` once the run is over. Iterating yields the steps.
/// ``result()`` reports the run so far as an ``ExplorationResult``; stepping
/// to the end gives the same result as ``explore`` with the same arguments.
/// The maps read out (``map``, ``occupancy``) are copies. Touching the run
/// from another thread while a step runs raises ``RuntimeError``.
#[pyclass(name = "Exploration", module = "covmap._native")]
pub(crate) struct PyExploration {
    run: SimExploration,
    /// The strategy as given: a `Strategy`, or a `CustomStrategy`.
    strategy: Py<PyAny>,
    /// Whether `strategy` is a `CustomStrategy`, whose `choose` picks each
    /// goal.
    custom: bool,
}

/// `Exploration`'s methods, its constructor from the keywords of
/// [`run_keywords!`].
macro_rules! exploration_methods {
    (
        signature: ($($signature:tt)*), text: $text:literal, params: ($($param:tt)*),
        keywords: ($keywords:expr), methods { $($methods:tt)* }
    ) => {
        #[pymethods]
        impl PyExploration {
            #[new]
            #[pyo3(signature = ($($signature)*), text_signature = $text)]
            #[allow(clippy::too_many_arguments, reason = "one keyword argument per setting")]
            fn new<'py>(
                py: Python<'py>,
                world: Bound<'py, PyWorld>,
                strategy: &Bound<'py, PyAny>,
                $($param)*
            ) -> PyResult<Self> {
                start_run(py, &world, strategy, &$keywords)
            }

            $($methods)*
        }
    };
}

run_keywords! { exploration_methods! { methods {

    /// Take one step: a ``Step``, or ``None`` once the run is over. With
    /// ``goal`` (``(x, y, theta)``), a step to that goal, whatever the
    /// strategy: the path to it planned on the coverage map as the coverage
    /// strategy plans, then the drive, its scans and the scan at the goal.
    /// A goal that is not finite, lies off the map or that the robot cannot
    /// reach on its map raises ``InvalidGoalError`` and leaves the run as it
    /// was. Without it, a custom strategy's ``choose`` is asked (it may
    /// end the run: ``None``).
    #[pyo3(signature = (goal=None), text_signature = "($self, goal=None)")]
    fn step<'py>(
        slf: &Bound<'py, Self>,
        goal: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Option<Bound<'py, PyAny>>> {
        let py = slf.py();
        let goal = match goal {
            Some(g) => Some(convert::pose(g)?),
            None if slf.borrow().custom => {
                let ready = {
                    let mut this = slf.borrow_mut();
                    let run = &mut this.run;
                    py.detach(|| run.begin()).or_raise(py)?
                };
                if !ready {
                    return Ok(None);
                }
                let strategy = slf.borrow().strategy.clone_ref(py);
                let answer = custom_module(py)?.call_method1("decide", (slf, strategy))?;
                if answer.is_none() {
                    let mut this = slf.borrow_mut();
                    this.run.finish().or_raise(py)?;
                    return Ok(None);
                }
                Some(convert::pose(&answer)?)
            }
            None => None,
        };
        let mut this = slf.borrow_mut();
        let run = &mut this.run;
        let report = match goal {
            Some(goal) => py.detach(|| run.step_to(goal)),
            None => py.detach(|| run.step()),
        }
        .or_raise(py)?;
        report.map(|r| step_object(py, &r)).transpose()
    }

    /// The first scans where the robot stands, if it has taken none (GIL
    /// released): what a step takes first, so that the maps, ``region()``
    /// and ``viewpoints()`` show the start before any step. Returns whether
    /// the run may take a step (``False`` once it is over; a limit reached
    /// ends it).
    fn begin(&mut self, py: Python<'_>) -> PyResult<bool> {
        let run = &mut self.run;
        py.detach(|| run.begin()).or_raise(py)
    }

    /// Step to the end of the run; returns ``result()``.
    fn run<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyAny>> {
        let py = slf.py();
        if slf.borrow().custom {
            while Self::step(slf, None)?.is_some() {}
        } else {
            let mut this = slf.borrow_mut();
            let run = &mut this.run;
            py.detach(|| run.run()).or_raise(py)?;
        }
        slf.borrow().result(py)
    }

    /// End the run now, on the caller's word: by the paper's rule where it
    /// holds (``"certain"``, ``"stagnated"``), else ``"no_goal"``. Returns
    /// how the run ended (as it was, for a run already over).
    fn finish(&mut self, py: Python<'_>) -> PyResult<&'static str> {
        Ok(self.run.finish().or_raise(py)?.as_str())
    }

    /// The region the robot can reach on its coverage map now: bool ``(rows,
    /// cols)``, the cells the paper's rule is checked on.
    fn region<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<bool>>> {
        let region = self.run.exploration().region().or_raise(py)?;
        cell_array(py, self.grid_ref(), region)
    }

    /// The cells the robot can reach on its coverage map now, where a
    /// step's goal may lie (``step(goal=...)`` accepts a goal in one):
    /// bool ``(rows, cols)``. ``region()`` holds more: the cells a scan from
    /// them reaches.
    fn reachable<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<bool>>> {
        let run = self.run.exploration();
        let paths = py.detach(|| run.paths()).or_raise(py)?;
        let cells = self.grid_ref().len();
        cell_array(py, self.grid_ref(), (0..cells).map(|i| paths.reachable(i)).collect())
    }

    /// Whether the paper's rule holds now on ``region()``: ``"certain"``
    /// (every cell below ``epsilon``), ``"stagnated"`` (every cell certain or
    /// stagnated, some stagnated), ``None`` (some cell neither).
    fn rule(&self, py: Python<'_>) -> PyResult<Option<&'static str>> {
        Ok(self.run.exploration().rule().or_raise(py)?.map(|t| t.as_str()))
    }

    /// The candidate viewpoints the coverage strategy weighs now: a ``Plan``
    /// whose ``candidates`` hold every candidate's pose, expected gain
    /// (nats), path cost (metres) and eq. 14's utility for ``alpha``, and
    /// whose ``pose`` is the planner's choice (GIL released). Planned as the
    /// loop plans, the candidates' gains kept from call to call where the
    /// map did not change under them: the plan a full computation gives.
    #[pyo3(signature = (alpha=Float(0.5)), text_signature = "($self, alpha=0.5)")]
    fn viewpoints(&mut self, py: Python<'_>, alpha: Float) -> PyResult<PyPlan> {
        let run = &mut self.run;
        py.detach(|| run.viewpoints(alpha.0)).map(PyPlan).or_raise(py)
    }

    /// The path a step to ``goal`` would take: cell centres from the
    /// robot's cell, ``(K, 2)``; ``None`` where the robot cannot reach it on
    /// its map.
    fn path_to<'py>(&self, py: Python<'py>, goal: &Bound<'py, PyAny>) -> PyResult<Option<Bound<'py, PyArray2<f64>>>> {
        let goal = convert::pose(goal)?;
        let grid = self.grid_ref();
        let Some(index) = grid
            .world_to_cell(goal.x_m, goal.y_m)
            .and_then(|c| grid.index(c).ok())
        else {
            return Ok(None);
        };
        let run = self.run.exploration();
        let paths = py.detach(|| run.paths()).or_raise(py)?;
        Ok(paths.reachable(index).then(|| rows_array(py, &paths.path_to(index))))
    }

    /// The run so far as an ``ExplorationResult`` (its ``termination`` is
    /// ``None`` while the run goes on).
    fn result<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let run = &self.run;
        let result = py.detach(|| run.result()).or_raise(py)?;
        result_object(py, self.strategy.bind(py), run.exploration().config().epsilon, result)
    }

    fn __iter__(slf: PyRef<'_, Self>) -> PyRef<'_, Self> {
        slf
    }
    fn __next__<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyAny>> {
        Self::step(slf, None)?
            .ok_or_else(|| PyStopIteration::new_err(()))
    }

    /// A copy of the coverage map built so far.
    #[getter]
    fn map(&self) -> PyCoverageMap {
        PyCoverageMap(self.run.exploration().map().clone())
    }
    /// A copy of the occupancy grid built so far from the same beams.
    #[getter]
    fn occupancy(&self) -> PyOccupancyGrid {
        PyOccupancyGrid(self.run.exploration().occupancy().clone())
    }
    /// The robot's pose ``(x, y, theta)``: float64 ``(3,)``.
    #[getter]
    fn pose<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        pose_array(py, self.run.exploration().pose())
    }
    /// Every pose so far, the start first: float64 ``(K, 3)``.
    #[getter]
    fn trajectory<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        poses_array(py, &self.run.exploration().trajectory().poses)
    }
    /// Whether the run is over.
    #[getter]
    fn done(&self) -> bool {
        self.run.exploration().done()
    }
    /// How the run ended (``"certain"``, ``"stagnated"``, ``"no_goal"``,
    /// ``"limit"``), or ``None`` while it goes on.
    #[getter]
    fn termination(&self) -> Option<&'static str> {
        self.run.exploration().termination().map(|t| t.as_str())
    }
    /// Steps taken.
    #[getter]
    fn steps(&self) -> usize {
        self.run.exploration().steps()
    }
    /// Scans taken.
    #[getter]
    fn scans(&self) -> usize {
        self.run.exploration().scans()
    }
    /// Distance driven, metres.
    #[getter]
    fn path_length_m(&self) -> f64 {
        self.run.exploration().path_length_m()
    }
    /// Fraction of the evaluation cells whose entropy is above epsilon now.
    #[getter]
    fn uncertain_fraction(&self) -> f64 {
        self.run.exploration().uncertain_fraction()
    }
    /// The cells the run is judged on: bool ``(rows, cols)`` (see
    /// ``ExplorationResult.evaluation_cells``).
    #[getter]
    fn evaluation_cells<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<bool>>> {
        cell_array(py, self.grid_ref(), self.run.evaluation_cells().to_vec())
    }
    /// The grid of the maps.
    #[getter]
    fn grid(&self) -> PyGrid {
        PyGrid(*self.grid_ref())
    }
    /// The strategy: a ``Strategy``, or the ``CustomStrategy`` given.
    #[getter]
    fn strategy(&self, py: Python<'_>) -> Py<PyAny> {
        self.strategy.clone_ref(py)
    }

    fn __repr__(&self, py: Python<'_>) -> PyResult<String> {
        let e = self.run.exploration();
        Ok(format!(
            "<Exploration: {}, {} steps, {} scans, {:.2} m, {}>",
            self.strategy.bind(py).repr()?,
            e.steps(),
            e.scans(),
            e.path_length_m(),
            e.termination().map_or("running", |t| t.as_str())
        ))
    }
} } }

impl PyExploration {
    fn grid_ref(&self) -> &covmap::Grid {
        self.run.exploration().map().grid()
    }
}

/// A pose as a float64 `(3,)` array.
fn pose_array(py: Python<'_>, pose: covmap::Pose) -> Bound<'_, PyArray1<f64>> {
    PyArray1::from_slice(py, &[pose.x_m, pose.y_m, pose.theta_rad])
}

/// A class of `covmap._exploration`, looked up once.
fn class<'py>(py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyAny>> {
    static MODULE: PyOnceLock<Py<PyModule>> = PyOnceLock::new();
    let module =
        MODULE.get_or_try_init(py, || py.import("covmap._exploration").map(Bound::unbind))?;
    module.bind(py).getattr(name)
}

/// A step report as a `Step`.
fn step_object<'py>(py: Python<'py>, report: &StepReport) -> PyResult<Bound<'py, PyAny>> {
    let fields = PyDict::new(py);
    fields.set_item("index", report.index)?;
    fields.set_item("goal", pose_array(py, report.goal))?;
    fields.set_item("path", rows_array(py, &report.path))?;
    fields.set_item("reached", report.reached)?;
    fields.set_item("contact", report.contact_m.map(|[x, y]| (x, y)))?;
    fields.set_item("travelled_m", report.travelled_m)?;
    fields.set_item("scans", report.scans)?;
    fields.set_item("pose", pose_array(py, report.pose))?;
    class(py, "Step")?.call((), Some(&fields))
}

/// Whether each pose of `trajectory` was scanned from: bool `(K,)`.
fn scanned_array<'py>(py: Python<'py>, trajectory: &Trajectory) -> Bound<'py, PyArray1<bool>> {
    PyArray1::from_slice(py, &trajectory.scanned)
}

/// A simulated run as an `ExplorationResult`.
fn result_object<'py>(
    py: Python<'py>,
    strategy: &Bound<'py, PyAny>,
    epsilon: f64,
    run: ExplorationRun,
) -> PyResult<Bound<'py, PyAny>> {
    let ExplorationRun {
        result: r,
        start,
        seed,
        grid,
        truth,
        evaluation_cells,
        high_entropy_fraction,
        errors,
        seconds,
    } = run;
    let trace = PyDict::new(py);
    trace.set_item(
        "path_length_m",
        PyArray1::from_slice(py, &r.trace.path_length_m),
    )?;
    let scans: Vec<i64> = r.trace.scans.iter().map(|&s| s as i64).collect();
    trace.set_item("scans", PyArray1::from_vec(py, scans))?;
    trace.set_item(
        "uncertain_fraction",
        PyArray1::from_slice(py, &r.trace.uncertain_fraction),
    )?;
    trace.set_item("contact", PyArray1::from_slice(py, &r.trace.contact))?;
    trace.set_item("planning_s", PyArray1::from_slice(py, &r.trace.planning_s))?;
    let timing = class(py, "Timing")?.call1((
        r.timing.planning_s,
        r.timing.sensing_s,
        r.timing.integration_s,
    ))?;
    let map_errors =
        class(py, "ExplorationErrors")?.call1((errors.coverage_map, errors.occupancy))?;
    let fields = PyDict::new(py);
    fields.set_item("strategy", strategy)?;
    fields.set_item("seed", seed)?;
    fields.set_item("start", pose_array(py, start))?;
    fields.set_item("grid", PyGrid(grid))?;
    fields.set_item("termination", r.termination.map(|t| t.as_str()))?;
    fields.set_item("path_length_m", r.path_length_m)?;
    fields.set_item("scans", r.scans)?;
    fields.set_item("steps", r.steps)?;
    fields.set_item("contacts", r.contacts)?;
    fields.set_item("trajectory", poses_array(py, &r.trajectory.poses))?;
    fields.set_item("scanned", scanned_array(py, &r.trajectory))?;
    fields.set_item("trace", trace)?;
    fields.set_item(
        "counts",
        cell_array(py, &grid, r.occupancy.counts().counts().to_vec())?,
    )?;
    fields.set_item("map", PyCoverageMap(r.map))?;
    fields.set_item("occupancy", PyOccupancyGrid(r.occupancy))?;
    fields.set_item("truth", cell_array(py, &grid, truth)?)?;
    fields.set_item("evaluation_cells", cell_array(py, &grid, evaluation_cells)?)?;
    fields.set_item("epsilon", epsilon)?;
    fields.set_item("high_entropy_fraction", high_entropy_fraction)?;
    fields.set_item("coverage_error", map_errors)?;
    fields.set_item("seconds", seconds)?;
    fields.set_item("timing", timing)?;
    class(py, "ExplorationResult")?.call((), Some(&fields))
}
