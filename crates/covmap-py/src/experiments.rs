//! `covmap.run_fig3`: the paper's Fig. 3 experiment, run by the simulator.
//!
//! Its result is a dataclass of the Python package
//! (`covmap.experiments.fig3.Fig3Result`, beside the experiment's table), as
//! `covmap.experiments.fig1`'s runs are.

use covmap::learn::{MAX_EVALUATIONS, MAX_RESTARTS};
use covmap::sim::experiments::{self, MapErrors};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::convert::{cell_array, poses_array};
use crate::errors::OrRaise;
use crate::grid::PyGrid;
use crate::numbers::{Float, Int, Seed};

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

/// Learn the sensor model in simulation (``covmap learn``): simulate a
/// training drive of ``scans`` scans through the built-in ``train_world``
/// and a test drive through ``test_world`` (the 24-sonar ring for a
/// ``SonarModel``, a 180-degree laser for a ``LaserModel``; each along
/// shortest paths to seeded waypoints), fit ``model`` on the training drive
/// (as ``fit_sensor_model``), and score the starting and the learned model
/// on both drives. With ``judged_only`` the fit scores the training drive's
/// judged cells only, not every cell of its grid. With ``occlude_no_echo``
/// (the default) every map, the fit's and the scores', is built as the
/// exploration loop builds its maps: each no-echo reading clears only what
/// its line of sight reaches past the cells the map holds covered and is
/// certain of
/// (``CoverageMap.integrate_log``'s
/// ``occlude_no_echo``), and the drives' occupancy grids take the same
/// beams; ``False`` lets no-echo readings clear their whole footprint.
/// Runs with the GIL released.
///
/// Returns a dict: ``fit`` (``SensorFit``); ``drives``, one dict per drive
/// (training first) of ``world``, ``log`` (``Log``), ``grid`` (``Grid``) and
/// ``truth`` (float64 ``(rows, cols)``), ``reached`` (uint32 ``(rows,
/// cols)``: how many of its scans' sound reached each cell in the true
/// world), ``judged`` (bool: the cells the drive is judged on, reached and
/// observable from its free space) and ``faced_walls`` (bool: the wall
/// cells behind a face that 20 or more scans reached); ``default`` and
/// ``learned``, one dict per drive of ``log_likelihood`` (of the truth,
/// every cell), ``judged_log_likelihood`` (over the judged cells),
/// ``mean_error`` (of the mean map, over the judged cells),
/// ``free_error`` and ``obstacle_error`` (the same over the judged free and
/// obstacle cells), ``occupancy_error`` (the occupancy grid's),
/// ``cells_reached``, ``wall_coverage`` (the mean map's mean over the faced
/// walls) and ``occupancy_wall`` (the occupancy grid's).
#[pyfunction]
#[pyo3(signature = (
    model, *, train_world="corridor", test_world="office", scans=Int(300), step=Float(0.15),
    resolution=Float(0.05), train_seed=Seed(0), test_seed=Seed(1), max_evaluations=Int(300),
    restarts=Int(2), seed=Seed(0), parameters=None, judged_only=false, occlude_no_echo=true,
    progress=crate::log::ProgressArg::Flag(false)
), text_signature = "(model, *, train_world='corridor', test_world='office', scans=300, step=0.15, resolution=0.05, train_seed=0, test_seed=1, max_evaluations=300, restarts=2, seed=0, parameters=None, judged_only=False, occlude_no_echo=True, progress=False)")]
#[allow(clippy::too_many_arguments)]
pub(crate) fn run_learn<'py>(
    py: Python<'py>,
    model: &Bound<'py, PyAny>,
    train_world: &str,
    test_world: &str,
    scans: Int<usize, 1, { experiments::MAX_DRIVE_SCANS as i128 }>,
    step: Float,
    resolution: Float,
    train_seed: Seed,
    test_seed: Seed,
    max_evaluations: Int<usize, 1, { MAX_EVALUATIONS as i128 }>,
    restarts: Int<usize, 1, { MAX_RESTARTS as i128 }>,
    seed: Seed,
    parameters: Option<Bound<'py, PyAny>>,
    judged_only: bool,
    occlude_no_echo: bool,
    progress: crate::log::ProgressArg,
) -> PyResult<Bound<'py, PyDict>> {
    let config = experiments::LearnConfig {
        train_world: train_world.into(),
        test_world: test_world.into(),
        model: crate::sensor::any_model(model)?,
        scans: scans.0,
        step_m: step.0,
        resolution_m: resolution.0,
        train_seed: train_seed.0,
        test_seed: test_seed.0,
        fit: covmap::learn::FitOptions {
            parameters: crate::learn::parameter_names(parameters.as_ref())?,
            max_evaluations: max_evaluations.0,
            restarts: restarts.0,
            seed: seed.0,
            occlude_no_echo,
            ..covmap::learn::FitOptions::default()
        },
        judged_only,
    };
    let steps = (max_evaluations.0, " evaluations");
    let report = crate::log::with_progress(py, progress, steps, |show| {
        experiments::learn(&config, show)
    })?;
    let out = PyDict::new(py);
    let drives = pyo3::types::PyList::empty(py);
    for d in &report.drives {
        let drive = PyDict::new(py);
        drive.set_item("world", &d.world)?;
        drive.set_item("log", crate::log::PyLog(d.log.clone()))?;
        drive.set_item("grid", PyGrid(d.grid))?;
        drive.set_item("truth", cell_array(py, &d.grid, d.truth.clone())?)?;
        drive.set_item("reached", cell_array(py, &d.grid, d.reached.clone())?)?;
        drive.set_item("judged", cell_array(py, &d.grid, d.judged.clone())?)?;
        drive.set_item("faced_walls", cell_array(py, &d.grid, d.faced_walls())?)?;
        drives.append(drive)?;
    }
    out.set_item("drives", drives)?;
    for (key, scores) in [
        ("default", report.default_scores),
        ("learned", report.learned_scores),
    ] {
        let list = pyo3::types::PyList::empty(py);
        for s in scores {
            let d = PyDict::new(py);
            d.set_item("log_likelihood", s.log_likelihood)?;
            d.set_item("judged_log_likelihood", s.judged_log_likelihood)?;
            d.set_item("mean_error", s.mean_error)?;
            d.set_item("free_error", s.free_error)?;
            d.set_item("obstacle_error", s.obstacle_error)?;
            d.set_item("occupancy_error", s.occupancy_error)?;
            d.set_item("cells_reached", s.cells_reached)?;
            d.set_item("wall_coverage", s.wall_coverage)?;
            d.set_item("occupancy_wall", s.occupancy_wall)?;
            list.append(d)?;
        }
        out.set_item(key, list)?;
    }
    out.set_item("fit", crate::learn::PySensorFit(report.fit))?;
    Ok(out)
}
