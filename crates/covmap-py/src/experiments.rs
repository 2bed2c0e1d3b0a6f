//! `covmap.run_fig3`: the paper's Fig. 3 experiment, run by the simulator.
//!
//! Its result is a dataclass of the Python package
//! (`covmap.experiments.fig3.Fig3Result`, beside the experiment's table), as
//! `covmap.experiments.fig1`'s runs are.

use covmap::sim::experiments::{self, MapErrors};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::convert::{Seed, cell_array, poses_array};
use crate::errors::OrRaise;
use crate::grid::PyGrid;

/// Run the paper's Fig. 3 with ``seed``: 24 simulated sonars driven along a
/// seeded path through the built-in ``corridor``, every scan integrated into
/// a coverage map and an occupancy grid, both measured against the exact
/// ground truth on the cells the readings reached.
///
/// Returns a ``Fig3Result`` (of ``covmap.experiments.fig3``): ``grid``
/// (``Grid``), ``poses`` (float64 ``(N, 3)``), ``readings`` and
/// ``cells_reached`` (int), the per-cell maps ``truth`` (float64), ``ml``,
/// ``mean``, ``entropy``, ``occupancy`` (float32) and ``reached`` (bool), each
/// ``(rows, cols)``; the mean absolute errors ``mae_ml``, ``mae_mean``,
/// ``mae_occupancy`` (``MapErrors`` of ``all`` and ``partial``: over all
/// reached cells and over those a wall face cuts); and ``log_likelihood`` of
/// the truth under the coverage map with ``log_likelihood_prior`` under the
/// uniform prior. Runs with the GIL released.
#[pyfunction]
#[pyo3(signature = (seed=Seed(0)), text_signature = "(seed=0)")]
pub(crate) fn run_fig3(py: Python<'_>, seed: Seed) -> PyResult<Bound<'_, PyAny>> {
    let r = py.detach(|| experiments::fig3(seed.0)).or_raise(py)?;
    let classes = py.import("covmap.experiments.fig3")?;
    let map_errors = classes.getattr("MapErrors")?;
    let errors = |e: MapErrors| map_errors.call1((e.all, e.partial));
    let grid = r.grid;
    let fields = PyDict::new(py);
    fields.set_item("grid", PyGrid(grid))?;
    fields.set_item("poses", poses_array(py, &r.poses))?;
    fields.set_item("readings", r.readings)?;
    fields.set_item("cells_reached", r.cells_reached)?;
    fields.set_item("truth", cell_array(py, &grid, r.truth)?)?;
    fields.set_item("ml", cell_array(py, &grid, r.ml)?)?;
    fields.set_item("mean", cell_array(py, &grid, r.mean)?)?;
    fields.set_item("entropy", cell_array(py, &grid, r.entropy)?)?;
    fields.set_item("occupancy", cell_array(py, &grid, r.occupancy)?)?;
    fields.set_item("reached", cell_array(py, &grid, r.reached)?)?;
    fields.set_item("mae_ml", errors(r.mae_ml)?)?;
    fields.set_item("mae_mean", errors(r.mae_mean)?)?;
    fields.set_item("mae_occupancy", errors(r.mae_occupancy)?)?;
    fields.set_item("log_likelihood", r.log_likelihood)?;
    fields.set_item("log_likelihood_prior", r.log_likelihood_prior)?;
    classes.getattr("Fig3Result")?.call((), Some(&fields))
}
