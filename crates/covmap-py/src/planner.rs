//! `covmap.Planner`: the choice of the next viewpoint (paper eq. 14), and its
//! answers `Plan`, `Candidates` and `ExplorationStatus`.

use covmap::gain::GainOptions;
use covmap::planner::{Candidates, ExplorationStatus, Plan, Planner, PlannerConfig};
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;

use crate::convert::{self, cell_array, poses_array, rows_array};
use crate::coverage_map::PyCoverageMap;
use crate::errors::OrRaise;
use crate::sensor::AnyModel;

/// The decision-theoretic exploration planner.
///
/// A cell *blocks* when its coverage on the ML map exceeds
/// ``blocked_coverage`` and is *unknown* while its entropy is at least
/// ``unknown_entropy_fraction`` of the prior's; the robot (a disc of
/// ``robot_radius_m``) keeps its disc clear of blocked cells and, unless
/// ``unknown_is_free``, of unknown ones; paths are 8-connected between cell
/// centres (from where the robot stands, it may also cross the unblocked
/// cells its disc overlaps there). Candidates are the reachable free cells on a
/// lattice of ``candidate_stride_m``, at least ``min_travel_m`` away, whose
/// expected gain exceeds ``min_gain_nats``; the chosen one maximises
/// ``alpha * gain / max gain - (1 - alpha) * cost / max cost`` (``alpha = 0``:
/// nearest, ``1``: most informative). Exploration is done when every
/// reachable cell has entropy below ``epsilon`` or has stagnated.
/// ``range_step_m`` and ``stop_coverage`` configure the gain as in
/// ``expected_information_gain``.
///
/// Arguments left out (or ``None``) take the defaults, readable as
/// attributes; an invalid one raises ``InvalidParameterError``.
#[pyclass(frozen, name = "Planner", module = "covmap._native")]
pub(crate) struct PyPlanner(Planner);

impl PyPlanner {
    fn config(&self) -> &PlannerConfig {
        self.0.config()
    }
}

#[pymethods]
impl PyPlanner {
    #[new]
    #[pyo3(signature = (
        *, alpha=None, robot_radius_m=None, candidate_stride_m=None, min_travel_m=None,
        min_gain_nats=None, blocked_coverage=None, unknown_entropy_fraction=None,
        unknown_is_free=None, epsilon=None, range_step_m=None, stop_coverage=None
    ))]
    #[allow(clippy::too_many_arguments, reason = "one keyword per planner setting")]
    fn new(
        py: Python<'_>,
        alpha: Option<f64>,
        robot_radius_m: Option<f64>,
        candidate_stride_m: Option<f64>,
        min_travel_m: Option<f64>,
        min_gain_nats: Option<f64>,
        blocked_coverage: Option<f64>,
        unknown_entropy_fraction: Option<f64>,
        unknown_is_free: Option<bool>,
        epsilon: Option<f64>,
        range_step_m: Option<f64>,
        stop_coverage: Option<&str>,
    ) -> PyResult<Self> {
        let d = PlannerConfig::default();
        let gain = GainOptions {
            range_step_m: range_step_m.or(d.gain.range_step_m),
            stop_coverage: match stop_coverage {
                Some(name) => convert::stop_coverage(py, name)?,
                None => d.gain.stop_coverage,
            },
        };
        if let Some(step) = gain.range_step_m
            && !(step > 0.0 && step.is_finite())
        {
            return Err(covmap::CovmapError::InvalidParameter {
                name: "range_step_m",
                value: step,
                expected: "a positive step no larger than the grid resolution",
            })
            .or_raise(py);
        }
        let config = PlannerConfig {
            alpha: alpha.unwrap_or(d.alpha),
            robot_radius_m: robot_radius_m.unwrap_or(d.robot_radius_m),
            candidate_stride_m: candidate_stride_m.unwrap_or(d.candidate_stride_m),
            min_travel_m: min_travel_m.unwrap_or(d.min_travel_m),
            min_gain_nats: min_gain_nats.unwrap_or(d.min_gain_nats),
            blocked_coverage: blocked_coverage.unwrap_or(d.blocked_coverage),
            unknown_entropy_fraction: unknown_entropy_fraction
                .unwrap_or(d.unknown_entropy_fraction),
            unknown_is_free: unknown_is_free.unwrap_or(d.unknown_is_free),
            epsilon: epsilon.unwrap_or(d.epsilon),
            gain,
        };
        Planner::new(config).map(Self).or_raise(py)
    }

    /// Weight of information against travel, in ``[0, 1]``.
    #[getter]
    fn alpha(&self) -> f64 {
        self.config().alpha
    }
    /// Radius of the disc robot, metres.
    #[getter]
    fn robot_radius_m(&self) -> f64 {
        self.config().robot_radius_m
    }
    /// Spacing of the candidate lattice, metres.
    #[getter]
    fn candidate_stride_m(&self) -> f64 {
        self.config().candidate_stride_m
    }
    /// Candidates closer than this along the path are not goals, metres.
    #[getter]
    fn min_travel_m(&self) -> f64 {
        self.config().min_travel_m
    }
    /// Candidates whose expected gain is at most this are not goals, nats.
    #[getter]
    fn min_gain_nats(&self) -> f64 {
        self.config().min_gain_nats
    }
    /// Coverage on the ML map above which a cell blocks the robot.
    #[getter]
    fn blocked_coverage(&self) -> f64 {
        self.config().blocked_coverage
    }
    /// A cell is unknown while its entropy is at least this fraction of the prior's.
    #[getter]
    fn unknown_entropy_fraction(&self) -> f64 {
        self.config().unknown_entropy_fraction
    }
    /// Whether the robot may plan through unknown cells.
    #[getter]
    fn unknown_is_free(&self) -> bool {
        self.config().unknown_is_free
    }
    /// Entropy below which a cell counts as explored, nats.
    #[getter]
    fn epsilon(&self) -> f64 {
        self.config().epsilon
    }
    /// Spacing of the predicted readings, metres (``None``: the grid resolution).
    #[getter]
    fn range_step_m(&self) -> Option<f64> {
        self.config().gain.range_step_m
    }
    /// Which coverage stops a predicted beam: ``"ml"`` or ``"mean"``.
    #[getter]
    fn stop_coverage(&self) -> &'static str {
        convert::stop_coverage_name(self.config().gain.stop_coverage)
    }

    /// Choose the next viewpoint for a robot at ``pose = (x, y, theta)`` on
    /// ``map``, scanning with beams at ``bearings`` through ``model``. Runs
    /// with the GIL released; the map is not changed.
    fn next_viewpoint(
        &self,
        py: Python<'_>,
        map: PyRef<'_, PyCoverageMap>,
        pose: &Bound<'_, PyAny>,
        bearings: &Bound<'_, PyAny>,
        model: &Bound<'_, PyAny>,
    ) -> PyResult<PyPlan> {
        let pose = convert::pose(pose)?;
        let bearings = convert::readings(bearings, "bearings")?;
        let model = AnyModel::extract(model)?;
        let (planner, map) = (&self.0, &map.0);
        py.detach(|| planner.next_viewpoint(map, &pose, &bearings, &model))
            .map(PyPlan)
            .or_raise(py)
    }

    /// How far exploration of ``map`` has come for a robot at ``pose``.
    fn status(
        &self,
        py: Python<'_>,
        map: PyRef<'_, PyCoverageMap>,
        pose: &Bound<'_, PyAny>,
    ) -> PyResult<PyExplorationStatus> {
        let pose = convert::pose(pose)?;
        let (planner, map) = (&self.0, &map.0);
        py.detach(|| planner.status(map, &pose))
            .map(PyExplorationStatus)
            .or_raise(py)
    }

    /// Where the robot's centre may be on ``map``: bool, ``(rows, cols)``.
    fn free_space<'py>(
        &self,
        py: Python<'py>,
        map: PyRef<'py, PyCoverageMap>,
    ) -> PyResult<Bound<'py, PyArray2<bool>>> {
        let (planner, map) = (&self.0, &map.0);
        let free = py.detach(|| planner.free_space(map));
        cell_array(py, map.grid(), free)
    }

    /// The length of a shortest path from ``pose`` to every cell over the
    /// robot's free space, metres: float64, ``(rows, cols)``, ``inf`` where
    /// unreachable.
    fn path_costs<'py>(
        &self,
        py: Python<'py>,
        map: PyRef<'py, PyCoverageMap>,
        pose: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let pose = convert::pose(pose)?;
        let (planner, map) = (&self.0, &map.0);
        let reach = py
            .detach(|| planner.reachability(map, &pose))
            .or_raise(py)?;
        cell_array(py, map.grid(), reach.costs().to_vec())
    }

    fn __repr__(&self) -> String {
        let c = self.config();
        format!(
            "Planner(alpha={:?}, robot_radius_m={:?}, candidate_stride_m={:?}, min_travel_m={:?}, \
             min_gain_nats={:?}, blocked_coverage={:?}, unknown_entropy_fraction={:?}, \
             unknown_is_free={}, epsilon={:?}, range_step_m={}, stop_coverage='{}')",
            c.alpha,
            c.robot_radius_m,
            c.candidate_stride_m,
            c.min_travel_m,
            c.min_gain_nats,
            c.blocked_coverage,
            c.unknown_entropy_fraction,
            if c.unknown_is_free { "True" } else { "False" },
            c.epsilon,
            c.gain
                .range_step_m
                .map_or_else(|| "None".to_string(), |s| format!("{s:?}")),
            convert::stop_coverage_name(c.gain.stop_coverage),
        )
    }
}

/// The planner's answer: the chosen viewpoint, the path to it and every
/// candidate considered.
#[pyclass(frozen, name = "Plan", module = "covmap._native")]
pub(crate) struct PyPlan(Plan);

#[pymethods]
impl PyPlan {
    /// The chosen viewpoint ``(x, y, theta)``, float64 ``(3,)``; ``None`` when
    /// no candidate is worth visiting.
    #[getter]
    fn pose<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        self.0
            .pose
            .map(|p| PyArray1::from_slice(py, &[p.x_m, p.y_m, p.theta_rad]))
    }
    /// The path to it: cell centres from the robot's cell to the goal's,
    /// float64 ``(K, 2)`` (``K = 0`` without a goal).
    #[getter]
    fn path<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        rows_array(py, &self.0.path)
    }
    /// Index of the chosen candidate in ``candidates``, or ``None``.
    #[getter]
    fn chosen(&self) -> Option<usize> {
        self.0.chosen
    }
    /// Expected information gain of the chosen viewpoint, nats, or ``None``.
    #[getter]
    fn gain(&self) -> Option<f64> {
        self.0.chosen.map(|k| self.0.candidates.gains[k])
    }
    /// Path length to the chosen viewpoint, metres, or ``None``.
    #[getter]
    fn cost(&self) -> Option<f64> {
        self.0.chosen.map(|k| self.0.candidates.costs[k])
    }
    /// Every candidate considered.
    #[getter]
    fn candidates(&self) -> PyCandidates {
        PyCandidates(self.0.candidates.clone())
    }

    fn __repr__(&self) -> String {
        let n = self.0.candidates.poses.len();
        match (self.0.pose, self.0.chosen) {
            (Some(p), Some(k)) => format!(
                "<Plan: goal ({:.3}, {:.3}, {:.3}), gain {:.3} nats, cost {:.3} m, {n} candidates>",
                p.x_m, p.y_m, p.theta_rad, self.0.candidates.gains[k], self.0.candidates.costs[k]
            ),
            _ => format!("<Plan: no goal, {n} candidates>"),
        }
    }
}

/// The candidates a ``Plan`` considered, one entry per candidate.
#[pyclass(frozen, name = "Candidates", module = "covmap._native")]
pub(crate) struct PyCandidates(Candidates);

#[pymethods]
impl PyCandidates {
    /// Candidate poses ``(x, y, theta)``: float64 ``(M, 3)``.
    #[getter]
    fn poses<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        poses_array(py, &self.0.poses)
    }
    /// Expected information gain of each, nats: float64 ``(M,)``.
    #[getter]
    fn gains<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.0.gains)
    }
    /// Path length from the robot to each, metres: float64 ``(M,)``.
    #[getter]
    fn costs<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.0.costs)
    }
    /// Eq. 14's utility of each (``-inf`` for those that are no goal):
    /// float64 ``(M,)``.
    #[getter]
    fn utilities<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.0.utilities)
    }
    fn __len__(&self) -> usize {
        self.0.poses.len()
    }
    fn __repr__(&self) -> String {
        format!("<Candidates: {}>", self.0.poses.len())
    }
}

/// How far exploration has come (``Planner.status``).
#[pyclass(frozen, eq, name = "ExplorationStatus", module = "covmap._native")]
#[derive(PartialEq)]
pub(crate) struct PyExplorationStatus(ExplorationStatus);

#[pymethods]
impl PyExplorationStatus {
    /// Cells connected to the robot through cells not blocked.
    #[getter]
    fn reachable_cells(&self) -> usize {
        self.0.reachable_cells
    }
    /// Of those, cells with entropy below epsilon.
    #[getter]
    fn certain_cells(&self) -> usize {
        self.0.certain_cells
    }
    /// Of the rest, cells whose entropy stagnated.
    #[getter]
    fn stagnated_cells(&self) -> usize {
        self.0.stagnated_cells
    }
    /// Whether every reachable cell is certain or stagnated.
    #[getter]
    fn done(&self) -> bool {
        self.0.done
    }
    fn __repr__(&self) -> String {
        let s = self.0;
        format!(
            "ExplorationStatus(reachable_cells={}, certain_cells={}, stagnated_cells={}, done={})",
            s.reachable_cells,
            s.certain_cells,
            s.stagnated_cells,
            if s.done { "True" } else { "False" }
        )
    }
}
