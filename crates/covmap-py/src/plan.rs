//! `covmap.Plan`, `covmap.Candidates` and `covmap.ExplorationStatus`: the
//! planner's answers.

use covmap::planner::{Candidates, ExplorationStatus, Plan};
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;

use crate::convert::{poses_array, rows_array};
use crate::keywords::PyRepr;

/// The planner's answer: the chosen viewpoint, the path to it and every
/// candidate considered.
#[pyclass(frozen, name = "Plan", module = "covmap._native")]
pub(crate) struct PyPlan(pub(crate) Plan);

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
pub(crate) struct PyExplorationStatus(pub(crate) ExplorationStatus);

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
            s.done.py_repr()
        )
    }
}
