//! `covmap.expected_information_gain`: the expected gain of viewpoints.

use covmap::gain::{GainEvaluator, GainOptions};
use numpy::PyArray1;
use pyo3::prelude::*;

use crate::convert;
use crate::coverage_map::PyCoverageMap;
use crate::errors::OrRaise;
use crate::numbers::Float;
use crate::sensor::any_model;

/// The expected information gain (nats) of scanning ``map`` from each of
/// ``poses`` (float64 ``(N, 3)`` of ``(x, y, theta)``) with beams at
/// ``bearings`` (radians, relative to each heading) through ``model``: float64
/// ``(N,)`` (paper eq. 11-13).
///
/// ``method`` is ``"fast"`` (the production evaluator) or ``"exact"`` (the
/// equation as written, equal to rounding). Predicted readings are spaced
/// ``range_step_m`` apart (default: the grid resolution; between 1/1024 of
/// it and it), and
/// a predicted beam is stopped by each cell's ``stop_coverage``: ``"ml"``
/// (most probable coverage, the paper's choice) or ``"mean"``. A pose outside
/// the map or not finite raises; the map is never changed. Runs with the GIL
/// released, candidates in parallel.
#[pyfunction]
#[pyo3(signature = (map, poses, bearings, model, method="fast", *, range_step_m=None, stop_coverage="ml"))]
#[allow(
    clippy::too_many_arguments,
    reason = "the evaluator's inputs and its three options"
)]
pub(crate) fn expected_information_gain<'py>(
    py: Python<'py>,
    map: PyRef<'py, PyCoverageMap>,
    poses: &Bound<'py, PyAny>,
    bearings: &Bound<'py, PyAny>,
    model: &Bound<'py, PyAny>,
    method: &str,
    range_step_m: Option<Float>,
    stop_coverage: &str,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let method = convert::gain_method(py, method)?;
    let options = GainOptions {
        range_step_m: range_step_m.map(|r| r.0),
        stop_coverage: convert::stop_coverage(py, stop_coverage)?,
    };
    let poses = convert::poses(poses, "poses")?;
    let bearings = convert::readings(bearings, "bearings", covmap::sim::MAX_BEAMS)?;
    let model = any_model(model)?;
    let map = &map.0;
    let gains = py
        .detach(|| {
            GainEvaluator::new(map, &model, options)
                .and_then(|e| e.evaluate(&poses, &bearings, method))
        })
        .or_raise(py)?;
    Ok(PyArray1::from_vec(py, gains))
}
