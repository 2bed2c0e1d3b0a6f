//! `covmap.log_likelihood`, `covmap.fit_sensor_model` and `SensorFit`:
//! learning the sensor model by maximum likelihood.

use covmap::Grid;
use covmap::SensorModel;
use covmap::exploration::AnySensorModel;
use covmap::learn::{
    FitData, FitEvaluation, FitOptions, Fittable, MAX_EVALUATIONS, MAX_RESTARTS, SensorFit,
    fit_sensor_model as fit,
};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyList};

use crate::convert;
use crate::coverage_map::PyCoverageMap;
use crate::errors::{Exception, OrRaise};
use crate::grid::PyGrid;
use crate::log::{ProgressArg, PyLog, with_progress};
use crate::numbers::{self, Bins, Int, Seed};
use crate::sensor::{any_model, model_object};
use crate::world::PyWorld;

/// A ground truth for `grid`: a float64 or float32 array of shape
/// `(rows, cols)`, or a `World` (its exact coverage on the grid).
fn truth_values(py: Python<'_>, truth: &Bound<'_, PyAny>, grid: &Grid) -> PyResult<Vec<f64>> {
    if let Ok(world) = truth.cast::<PyWorld>() {
        let world = &world.get().0;
        return py.detach(|| world.try_coverage(grid)).or_raise(py);
    }
    let (values, shape) = convert::matrix(truth, "truth")?;
    let (rows, cols) = grid.shape();
    if shape != [rows, cols] {
        return Err(Exception::ArrayShape.err(
            py,
            format!(
                "truth must have the grid's shape ({rows}, {cols}), got ({}, {})",
                shape[0], shape[1]
            ),
        ));
    }
    Ok(values)
}

/// The most names a `parameters` or `bounds` argument may hold (a model has
/// a dozen parameters).
const MAX_NAMES: usize = 64;

/// A `parameters` argument: a sequence of parameter names, if given.
pub(crate) fn parameter_names(obj: Option<&Bound<'_, PyAny>>) -> PyResult<Option<Vec<String>>> {
    let Some(obj) = obj else { return Ok(None) };
    let py = obj.py();
    let not_names = || {
        Exception::InvalidType.err(
            py,
            format!(
                "parameters must be a sequence of parameter names, got {}",
                obj.get_type()
            ),
        )
    };
    let name = |(i, item): (usize, &Bound<'_, PyAny>)| {
        item.extract::<String>().map_err(|_| {
            Exception::InvalidType.err(
                py,
                format!(
                    "parameters[{i}] must be a parameter name (a str), got {}",
                    numbers::quoted(item)
                ),
            )
        })
    };
    convert::items(obj, "parameters", MAX_NAMES, &not_names)?
        .iter()
        .enumerate()
        .map(name)
        .collect::<PyResult<Vec<_>>>()
        .map(Some)
}

/// A `bounds` argument: `(name, (low, high))` pairs (or a dict of them).
fn parameter_bounds(obj: Option<&Bound<'_, PyAny>>) -> PyResult<Vec<(String, [f64; 2])>> {
    let Some(obj) = obj else {
        return Ok(Vec::new());
    };
    let py = obj.py();
    let pairs = match obj.cast::<PyDict>() {
        Ok(d) => d.items().into_any(),
        Err(_) => obj.clone(),
    };
    let not_pairs = || {
        Exception::InvalidType.err(
            py,
            format!(
                "bounds must be (name, (low, high)) pairs or a dict of them, got {}",
                obj.get_type()
            ),
        )
    };
    let pair = |(i, item): (usize, &Bound<'_, PyAny>)| {
        let (name, range) = item.extract::<(String, Bound<'_, PyAny>)>().map_err(|_| {
            Exception::InvalidType.err(
                py,
                format!(
                    "bounds[{i}] must be a pair (name, (low, high)), got {}",
                    numbers::quoted(item)
                ),
            )
        })?;
        let range = convert::fixed_numbers::<2>(&range, &format!("bounds[{i}][1]"), "(low, high)")?;
        Ok((name, range))
    };
    convert::items(&pairs, "bounds", MAX_NAMES, &not_pairs)?
        .iter()
        .enumerate()
        .map(pair)
        .collect()
}

/// A cell mask for `grid`, if given: a bool array of shape `(rows, cols)`.
fn mask(cells: Option<&Bound<'_, PyAny>>, grid: &Grid) -> PyResult<Option<Vec<bool>>> {
    cells
        .map(|c| convert::cell_values::<bool>(c, grid, "cells", "bool", None))
        .transpose()
}

/// The log-probability of the ground truth ``truth`` (a float64 or float32
/// array of shape ``(rows, cols)`` of coverage values in [0, 1]) under the
/// map's histograms, summed over every cell or those where ``cells`` (a bool
/// array of the same shape) is true. A truth value between two bin values
/// is scored by linear interpolation of the two bins' probabilities; a cell
/// at the uniform prior scores ``ln(1 / bins)``.
#[pyfunction]
#[pyo3(signature = (map, truth, *, cells=None))]
pub(crate) fn log_likelihood(
    py: Python<'_>,
    map: Bound<'_, PyCoverageMap>,
    truth: &Bound<'_, PyAny>,
    cells: Option<&Bound<'_, PyAny>>,
) -> PyResult<f64> {
    let map = map.borrow();
    let map = &map.0;
    let grid = *map.grid();
    let truth = truth_values(py, truth, &grid)?;
    let cells = mask(cells, &grid)?;
    covmap::learn::log_likelihood(map, &truth, cells.as_deref()).or_raise(py)
}

/// Fit ``model``'s parameters to a recorded drive by maximum likelihood: the
/// model under whose map of ``log`` the ground truth scores highest
/// (``log_likelihood``), found by Nelder-Mead over the parameters scaled to
/// their bounds, from ``restarts`` starting points (the first ``model``
/// itself, the others drawn around it from ``seed``), in parallel, with the
/// GIL released. The result is the same whatever the thread count.
///
/// ``truth`` is a ``World`` (its exact coverage on ``grid``) or a float
/// array of shape ``(rows, cols)``; ``grid`` defaults to the world's bounds
/// and 0.5 m at 5 cm (required with an array). ``parameters`` names the
/// parameters fitted (default: all the model has but ``max_range_m``);
/// ``bounds`` maps names to ``(low, high)`` replacing the defaults.
/// ``max_evaluations`` bounds the maps built, the starting model's
/// included. With ``occlude_no_echo`` the maps are built as
/// ``CoverageMap.integrate_log(..., occlude_no_echo=True)`` builds them (as
/// the exploration loop does); by default every no-echo reading clears its
/// whole footprint. ``progress``: ``True`` for a bar over evaluations, or a
/// callable ``(done, total)``.
///
/// Unknown parameter names, bounds that exclude the starting model, a truth
/// of the wrong shape or an empty log raise ``InvalidParameterError`` (or the
/// array errors) before any map is built.
#[pyfunction]
#[pyo3(signature = (
    log, truth, model, *, grid=None, parameters=None, bounds=None, max_evaluations=Int(300),
    restarts=Int(2), seed=Seed(0), bins=Int(16), cells=None, occlude_no_echo=false,
    progress=ProgressArg::Flag(false)
), text_signature = "(log, truth, model, *, grid=None, parameters=None, bounds=None, max_evaluations=300, restarts=2, seed=0, bins=16, cells=None, occlude_no_echo=False, progress=False)")]
#[allow(clippy::too_many_arguments)]
pub(crate) fn fit_sensor_model(
    py: Python<'_>,
    log: Bound<'_, PyLog>,
    truth: &Bound<'_, PyAny>,
    model: &Bound<'_, PyAny>,
    grid: Option<Bound<'_, PyGrid>>,
    parameters: Option<Bound<'_, PyAny>>,
    bounds: Option<Bound<'_, PyAny>>,
    max_evaluations: Int<usize, 1, { MAX_EVALUATIONS as i128 }>,
    restarts: Int<usize, 1, { MAX_RESTARTS as i128 }>,
    seed: Seed,
    bins: Bins,
    cells: Option<&Bound<'_, PyAny>>,
    occlude_no_echo: bool,
    progress: ProgressArg,
) -> PyResult<PySensorFit> {
    let start = any_model(model)?;
    let grid = match (grid, truth.cast::<PyWorld>()) {
        (Some(g), _) => g.get().0,
        (None, Ok(world)) => {
            let [x0, y0, x1, y1] = world.get().0.bounds_m();
            Grid::covering(x0 - 0.5, y0 - 0.5, x1 + 0.5, y1 + 0.5, 0.05).or_raise(py)?
        }
        (None, Err(_)) => {
            return Err(Exception::InvalidValue.err(
                py,
                "grid is required when truth is an array (it gives the cells' positions)",
            ));
        }
    };
    let options = FitOptions {
        parameters: parameter_names(parameters.as_ref())?,
        bounds: parameter_bounds(bounds.as_ref())?,
        max_evaluations: max_evaluations.0,
        restarts: restarts.0,
        seed: seed.0,
        bins: bins.0,
        occlude_no_echo,
        ..FitOptions::default()
    };
    let truth = truth_values(py, truth, &grid)?;
    let cells = mask(cells, &grid)?;
    let log = &log.get().0;
    let data = FitData {
        log,
        grid,
        truth: &truth,
        cells: cells.as_deref(),
    };
    let steps = (options.max_evaluations, " evaluations");
    let result = with_progress(py, progress, steps, |show| {
        fit(&data, &start, &options, show)
    })?;
    Ok(PySensorFit(result))
}

/// A `SensorFit` as pickling saves it.
#[derive(serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct SavedFit {
    model: AnySensorModel,
    parameters: Vec<String>,
    bounds: Vec<[f64; 2]>,
    log_likelihood: f64,
    initial_log_likelihood: f64,
    evaluations: usize,
    trace: Vec<(Vec<f64>, f64)>,
}

/// What ``fit_sensor_model`` found: ``model`` (the best model, the starting
/// one if nothing scored higher), ``log_likelihood`` and
/// ``initial_log_likelihood`` (the starting model's), ``evaluations`` (maps
/// built), ``parameters`` (the fitted names), ``bounds`` and ``trace``
/// (every evaluation in order, the starting model's first: a dict of the
/// fitted parameters and ``log_likelihood``).
#[pyclass(frozen, name = "SensorFit", module = "covmap._native")]
pub(crate) struct PySensorFit(pub(crate) SensorFit<AnySensorModel>);

#[pymethods]
impl PySensorFit {
    /// The best model found.
    #[getter]
    fn model<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        model_object(py, &self.0.model)
    }
    /// The log-likelihood of the truth under the best model's map.
    #[getter]
    fn log_likelihood(&self) -> f64 {
        self.0.log_likelihood
    }
    /// The same under the starting model's map.
    #[getter]
    fn initial_log_likelihood(&self) -> f64 {
        self.0.initial_log_likelihood
    }
    /// How many maps were built and scored.
    #[getter]
    fn evaluations(&self) -> usize {
        self.0.evaluations
    }
    /// The names of the fitted parameters.
    #[getter]
    fn parameters(&self) -> Vec<&'static str> {
        self.0.parameters.clone()
    }
    /// The bounds each was searched within, ``{name: (low, high)}``.
    #[getter]
    fn bounds<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        for (name, [lo, hi]) in self.0.parameters.iter().zip(&self.0.bounds) {
            d.set_item(name, (lo, hi))?;
        }
        Ok(d)
    }
    /// Every evaluation in order: a dict of the fitted parameters and
    /// ``log_likelihood``.
    #[getter]
    fn trace<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let list = PyList::empty(py);
        for e in &self.0.trace {
            let d = PyDict::new(py);
            for (name, v) in self.0.parameters.iter().zip(&e.values) {
                d.set_item(name, v)?;
            }
            d.set_item("log_likelihood", e.log_likelihood)?;
            list.append(d)?;
        }
        Ok(list)
    }
    /// Pickle support: rebuilt by ``SensorFit._from_state`` from JSON bytes
    /// (every float64 exact).
    fn __reduce__<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyAny>, (Bound<'py, PyBytes>,))> {
        let f = &self.0;
        let saved = SavedFit {
            model: f.model,
            parameters: f.parameters.iter().map(|p| p.to_string()).collect(),
            bounds: f.bounds.clone(),
            log_likelihood: f.log_likelihood,
            initial_log_likelihood: f.initial_log_likelihood,
            evaluations: f.evaluations,
            trace: f
                .trace
                .iter()
                .map(|e| (e.values.clone(), e.log_likelihood))
                .collect(),
        };
        crate::pickling::reduce::<Self, _>(py, &saved, "fit")
    }

    /// Unpickling support: the fit saved by ``__reduce__`` (checked).
    #[staticmethod]
    fn _from_state(py: Python<'_>, state: Bound<'_, PyBytes>) -> PyResult<Self> {
        let bad = |why: String| Exception::InvalidValue.err(py, format!("not a saved fit: {why}"));
        let saved: SavedFit = crate::pickling::restored(py, state.as_bytes(), "fit")?;
        saved.model.validate().or_raise(py)?;
        let known = saved.model.parameters();
        let parameters = saved
            .parameters
            .iter()
            .map(|n| {
                known
                    .iter()
                    .find(|p| p.name == n.as_str())
                    .map(|p| p.name)
                    .ok_or_else(|| bad(format!("unknown parameter `{n}`")))
            })
            .collect::<PyResult<Vec<_>>>()?;
        let n = parameters.len();
        if saved.bounds.len() != n
            || saved.evaluations != saved.trace.len()
            || saved.trace.iter().any(|(v, _)| v.len() != n)
        {
            return Err(bad("the parameters, bounds and trace do not match".into()));
        }
        Ok(Self(SensorFit {
            model: saved.model,
            parameters,
            bounds: saved.bounds,
            log_likelihood: saved.log_likelihood,
            initial_log_likelihood: saved.initial_log_likelihood,
            evaluations: saved.evaluations,
            trace: saved
                .trace
                .into_iter()
                .map(|(values, log_likelihood)| FitEvaluation {
                    values,
                    log_likelihood,
                })
                .collect(),
        }))
    }

    fn __repr__(&self) -> String {
        format!(
            "SensorFit(log_likelihood={:.1}, initial_log_likelihood={:.1}, evaluations={})",
            self.0.log_likelihood, self.0.initial_log_likelihood, self.0.evaluations
        )
    }
}
