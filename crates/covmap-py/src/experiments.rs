//! `covmap.run_fig3`: the paper's Fig. 3 experiment, run by the simulator.

use covmap::sim::experiments::{self, MapErrors};
use numpy::PyArray2;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::convert::{Seed, cell_array, poses_array};
use crate::errors::OrRaise;
use crate::grid::PyGrid;

fn errors_dict<'py>(py: Python<'py>, e: MapErrors) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("all", e.all)?;
    d.set_item("partial", e.partial)?;
    Ok(d)
}

/// Run the paper's Fig. 3 with ``seed``: 24 simulated sonars driven along a
/// seeded path through the built-in ``corridor``, every scan integrated into
/// a coverage map and an occupancy grid, both measured against the exact
/// ground truth on the cells the readings reached.
///
/// Returns a dict: ``grid`` (``Grid``), ``poses`` (float64 ``(N, 3)``),
/// ``readings`` and ``cells_reached`` (int), the per-cell maps ``truth``
/// (float64), ``ml``, ``mean``, ``entropy``, ``occupancy`` (float32) and
/// ``reached`` (bool), each ``(rows, cols)``; the mean absolute errors
/// ``mae_ml``, ``mae_mean``, ``mae_occupancy`` (dicts of ``all`` and
/// ``partial``: over all reached cells and over those a wall face cuts); and
/// ``log_likelihood`` of the truth under the coverage map with
/// ``log_likelihood_prior`` under the uniform prior. Runs with the GIL released.
#[pyfunction]
#[pyo3(signature = (seed=Seed(0)), text_signature = "(seed=0)")]
pub(crate) fn run_fig3(py: Python<'_>, seed: Seed) -> PyResult<Bound<'_, PyDict>> {
    let r = py.detach(|| experiments::fig3(seed.0)).or_raise(py)?;
    let grid = r.grid;
    let d = PyDict::new(py);
    d.set_item("grid", PyGrid(grid))?;
    d.set_item("poses", poses_array(py, &r.poses))?;
    d.set_item("readings", r.readings)?;
    d.set_item("cells_reached", r.cells_reached)?;
    let truth: Bound<'_, PyArray2<f64>> = cell_array(py, &grid, r.truth)?;
    d.set_item("truth", truth)?;
    d.set_item("ml", cell_array(py, &grid, r.ml)?)?;
    d.set_item("mean", cell_array(py, &grid, r.mean)?)?;
    d.set_item("entropy", cell_array(py, &grid, r.entropy)?)?;
    d.set_item("occupancy", cell_array(py, &grid, r.occupancy)?)?;
    d.set_item("reached", cell_array(py, &grid, r.reached)?)?;
    d.set_item("mae_ml", errors_dict(py, r.mae_ml)?)?;
    d.set_item("mae_mean", errors_dict(py, r.mae_mean)?)?;
    d.set_item("mae_occupancy", errors_dict(py, r.mae_occupancy)?)?;
    d.set_item("log_likelihood", r.log_likelihood)?;
    d.set_item("log_likelihood_prior", r.log_likelihood_prior)?;
    Ok(d)
}
