//! `covmap.Planner`: the choice of the next viewpoint (paper eq. 14). Its
//! answers, `Plan` and `ExplorationStatus`, are in `plan.rs`.

use covmap::gain::GainOptions;
use covmap::planner::{Planner, PlannerConfig};
use numpy::PyArray2;
use pyo3::prelude::*;

use crate::convert::{self, cell_array};
use crate::coverage_map::PyCoverageMap;
use crate::errors::OrRaise;
use crate::keywords::keyword_class;
use crate::plan::{PyExplorationStatus, PyPlan};
use crate::sensor::any_model;

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

    /// The planner the keywords describe: each setting given, or the default.
    fn from_keywords(py: Python<'_>, keywords: PlannerKeywords) -> PyResult<Self> {
        let d = PlannerConfig::default();
        let gain = GainOptions {
            range_step_m: keywords.range_step_m.or(d.gain.range_step_m),
            stop_coverage: match keywords.stop_coverage {
                Some(name) => convert::stop_coverage(py, &name)?,
                None => d.gain.stop_coverage,
            },
        };
        // `..d`: settings the core gains later keep their defaults here until
        // the binding takes them (today it may name every one).
        #[allow(clippy::needless_update)]
        let config = PlannerConfig {
            alpha: keywords.alpha.unwrap_or(d.alpha),
            robot_radius_m: keywords.robot_radius_m.unwrap_or(d.robot_radius_m),
            candidate_stride_m: keywords.candidate_stride_m.unwrap_or(d.candidate_stride_m),
            min_travel_m: keywords.min_travel_m.unwrap_or(d.min_travel_m),
            min_gain_nats: keywords.min_gain_nats.or(d.min_gain_nats),
            blocked_coverage: keywords.blocked_coverage.unwrap_or(d.blocked_coverage),
            unknown_entropy_fraction: keywords
                .unknown_entropy_fraction
                .unwrap_or(d.unknown_entropy_fraction),
            unknown_is_free: keywords.unknown_is_free.unwrap_or(d.unknown_is_free),
            epsilon: keywords.epsilon.unwrap_or(d.epsilon),
            gain,
            // The settings this binding does not take keep their defaults.
            ..d
        };
        Planner::new(config).map(Self).or_raise(py)
    }
}

keyword_class! {
    impl PyPlanner as "Planner" {
        keywords PlannerKeywords => PyPlanner::from_keywords;
        settings(&self) {
            /// Weight of information against travel, in ``[0, 1]``.
            alpha(f64) -> f64 { self.config().alpha }
            /// Radius of the disc robot, metres; paths keep a cell more (at least 5 cm)
            /// from blocked cells.
            robot_radius_m(f64) -> f64 { self.config().robot_radius_m }
            /// Spacing of the candidate lattice, metres.
            candidate_stride_m(f64) -> f64 { self.config().candidate_stride_m }
            /// Candidates closer than this along the path are not goals, metres.
            min_travel_m(f64) -> f64 { self.config().min_travel_m }
            /// Candidates whose expected gain is at most this are not goals, nats;
            /// ``None`` (the default): what making one cell at the prior certain is
            /// worth, ``ln(bins) - epsilon``, at least 1 nat (the exploration loop's rule).
            min_gain_nats(f64) -> Option<f64> { self.config().min_gain_nats }
            /// Coverage on the ML map above which a cell blocks the robot.
            blocked_coverage(f64) -> f64 { self.config().blocked_coverage }
            /// A cell is unknown while its entropy is at least this fraction of the prior's.
            unknown_entropy_fraction(f64) -> f64 { self.config().unknown_entropy_fraction }
            /// Whether the robot may plan through unknown cells.
            unknown_is_free(bool) -> bool { self.config().unknown_is_free }
            /// Entropy below which a cell counts as explored, nats.
            epsilon(f64) -> f64 { self.config().epsilon }
            /// Spacing of the predicted readings, metres (``None``: the grid resolution).
            range_step_m(f64) -> Option<f64> { self.config().gain.range_step_m }
            /// Which coverage stops a predicted beam: ``"ml"`` or ``"mean"``.
            stop_coverage(String) -> &'static str {
                convert::stop_coverage_name(self.config().gain.stop_coverage)
            }
        }
        methods {
            /// Pickle and copy support: the keyword arguments that rebuild the planner.
            fn __getnewargs_ex__<'py>(
                &self,
                py: Python<'py>,
            ) -> PyResult<(Bound<'py, pyo3::types::PyTuple>, Bound<'py, pyo3::types::PyDict>)> {
                let kwargs = pyo3::types::PyDict::new(py);
                kwargs.set_item("alpha", self.alpha())?;
                kwargs.set_item("robot_radius_m", self.robot_radius_m())?;
                kwargs.set_item("candidate_stride_m", self.candidate_stride_m())?;
                kwargs.set_item("min_travel_m", self.min_travel_m())?;
                kwargs.set_item("min_gain_nats", self.min_gain_nats())?;
                kwargs.set_item("blocked_coverage", self.blocked_coverage())?;
                kwargs.set_item("unknown_entropy_fraction", self.unknown_entropy_fraction())?;
                kwargs.set_item("unknown_is_free", self.unknown_is_free())?;
                kwargs.set_item("epsilon", self.epsilon())?;
                kwargs.set_item("range_step_m", self.range_step_m())?;
                kwargs.set_item("stop_coverage", self.stop_coverage())?;
                Ok((pyo3::types::PyTuple::empty(py), kwargs))
            }
            /// The least expected gain a candidate must promise to be a goal on a
            /// map of ``bins`` bins, nats: ``min_gain_nats``, or by default what
            /// making one cell at the prior certain is worth, ``ln(bins) - epsilon``,
            /// at least 1 nat.
            #[pyo3(signature = (bins=crate::numbers::Int(covmap::histogram::DEFAULT_BINS)), text_signature = "(self, bins=16)")]
            fn least_gain_nats(&self, bins: crate::numbers::Bins) -> f64 {
                self.0.min_gain_nats(bins.0)
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
                let bearings = convert::readings(bearings, "bearings", covmap::sim::MAX_BEAMS)?;
                let model = any_model(model)?;
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
        }
    }
}
