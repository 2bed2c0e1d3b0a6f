//! `covmap.Strategy`: how an exploring robot chooses where to go next.

use covmap::exploration::Strategy;
use pyo3::prelude::*;
use pyo3::types::PyTuple;

use crate::errors::OrRaise;
use crate::keywords::PyRepr;
use crate::numbers::{Float, Int};

/// How an exploring robot chooses where to go next (``explore``,
/// ``Exploration``). Build one with a static method:
///
/// - ``Strategy.coverage(alpha=0.5)``: the paper's decision-theoretic choice
///   (eq. 14) on the coverage map, ``alpha`` the weight of information
///   against travel in ``[0, 1]``; done when every cell of the reachable
///   region is certain (entropy below ``epsilon``) or has stagnated, or
///   when no candidate is worth visiting (a goal whose scans did not deliver
///   what it promised is not chosen again);
/// - ``Strategy.counting(n=50, discount_beyond_m=None)``: extended scan
///   counting, a cell explored once ``n`` beams intercepted it (a beam reading
///   ``d`` beyond ``discount_beyond_m`` counts ``discount_beyond_m / d``;
///   ``None``: every beam counts 1; Table I's row uses
///   ``DEFAULT_DISCOUNT_BEYOND_M``); the robot goes to the nearest candidate
///   that would intercept an unexplored cell;
/// - ``Strategy.frontier()``: nearest-frontier exploration (Yamauchi 1997) on
///   the occupancy grid.
///
/// Strategies compare equal when their settings are equal, hash, pickle and
/// show as the call that builds them.
#[pyclass(frozen, eq, hash, name = "Strategy", module = "covmap._native")]
#[derive(Clone, Copy, PartialEq)]
pub(crate) struct PyStrategy(pub(crate) Strategy);

impl std::hash::Hash for PyStrategy {
    fn hash<H: std::hash::Hasher>(&self, state: &mut H) {
        let (alpha, n, discount) = match self.0 {
            Strategy::Coverage { alpha } => (alpha, 0, None),
            Strategy::Counting {
                n,
                discount_beyond_m,
            } => (0.0, n, discount_beyond_m),
            Strategy::Frontier | Strategy::Custom => (0.0, 0, None),
        };
        let bits = |v: f64| (if v == 0.0 { 0.0f64 } else { v }).to_bits();
        (self.0.name(), bits(alpha), n, discount.map(bits)).hash(state);
    }
}

#[pymethods]
impl PyStrategy {
    /// The paper's decision-theoretic strategy (eq. 14) with weight ``alpha``
    /// in ``[0, 1]`` (0: the nearest candidate, 1: the most informative);
    /// another value, NaN included, raises ``InvalidParameterError``.
    #[staticmethod]
    #[pyo3(signature = (alpha=Float(0.5)), text_signature = "(alpha=0.5)")]
    fn coverage(py: Python<'_>, alpha: Float) -> PyResult<Self> {
        Strategy::coverage(alpha.0).map(Self).or_raise(py)
    }

    /// Extended scan counting to ``n`` (at least 1) interceptions, beams
    /// reading farther than ``discount_beyond_m`` (positive, finite; ``None``:
    /// no discount) counted ``discount_beyond_m / d``; a bad value raises
    /// ``InvalidParameterError``.
    #[staticmethod]
    #[pyo3(signature = (n=Int(50), discount_beyond_m=None), text_signature = "(n=50, discount_beyond_m=None)")]
    fn counting(
        py: Python<'_>,
        n: Int<u32, 1, { u32::MAX as i128 }>,
        discount_beyond_m: Option<Float>,
    ) -> PyResult<Self> {
        Strategy::counting(n.0, discount_beyond_m.map(|d| d.0))
            .map(Self)
            .or_raise(py)
    }

    /// Nearest-frontier exploration on the occupancy grid.
    #[staticmethod]
    fn frontier() -> Self {
        Self(Strategy::frontier())
    }

    /// ``"coverage"``, ``"counting"`` or ``"frontier"``.
    #[getter]
    fn name(&self) -> &'static str {
        self.0.name()
    }
    /// The weight of information against travel (``coverage``), else ``None``.
    #[getter]
    fn alpha(&self) -> Option<f64> {
        match self.0 {
            Strategy::Coverage { alpha } => Some(alpha),
            _ => None,
        }
    }
    /// The interceptions that make a cell explored (``counting``), else ``None``.
    #[getter]
    fn n(&self) -> Option<u32> {
        match self.0 {
            Strategy::Counting { n, .. } => Some(n),
            _ => None,
        }
    }
    /// The discount range of ``counting``, metres (``None``: no discount, or
    /// another strategy).
    #[getter]
    fn discount_beyond_m(&self) -> Option<f64> {
        match self.0 {
            Strategy::Counting {
                discount_beyond_m, ..
            } => discount_beyond_m,
            _ => None,
        }
    }

    /// A strategy written in Python: ``choose(view)`` is called before each
    /// step with a ``StrategyView`` (the maps, the pose, the reachable
    /// region, the candidate viewpoints with their expected gains and path
    /// costs, whether the paper's rule holds) and returns the goal,
    /// ``(x, y, theta)`` or the index of a candidate, or ``None`` when it is
    /// done. ``name`` names it in results (default: ``choose``'s name);
    /// ``alpha`` weighs the candidates' utilities it sees (eq. 14). Returns
    /// a ``CustomStrategy``, which ``explore``, ``Exploration``, ``sweep``
    /// and the benchmark take beside the built-in strategies (``sweep``
    /// needs a ``choose`` that pickles: a function defined at the top level
    /// of a module).
    #[staticmethod]
    #[pyo3(
        signature = (choose, *, name=None, alpha=Float(0.5)),
        text_signature = "(choose, *, name=None, alpha=0.5)"
    )]
    fn custom<'py>(
        py: Python<'py>,
        choose: &Bound<'py, PyAny>,
        name: Option<&Bound<'py, PyAny>>,
        alpha: Float,
    ) -> PyResult<Bound<'py, PyAny>> {
        let options = pyo3::types::PyDict::new(py);
        options.set_item("name", name)?;
        options.set_item("alpha", alpha.0)?;
        py.import("covmap._custom")?
            .getattr("CustomStrategy")?
            .call((choose,), Some(&options))
    }

    pub(crate) fn __repr__(&self) -> String {
        match self.0 {
            Strategy::Coverage { alpha } => format!("Strategy.coverage(alpha={})", alpha.py_repr()),
            Strategy::Counting {
                n,
                discount_beyond_m,
            } => format!(
                "Strategy.counting(n={n}, discount_beyond_m={})",
                discount_beyond_m.py_repr()
            ),
            Strategy::Frontier => "Strategy.frontier()".to_owned(),
            // Never a `Strategy` of Python's: a custom strategy is a
            // `CustomStrategy`.
            Strategy::Custom => "Strategy.custom(...)".to_owned(),
        }
    }

    /// Pickle and copy support: the static method that builds the strategy
    /// and its arguments.
    fn __reduce__<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyTuple>)> {
        let build = py.get_type::<Self>().getattr(self.0.name())?;
        let args = match self.0 {
            Strategy::Coverage { alpha } => PyTuple::new(py, [alpha])?,
            Strategy::Counting {
                n,
                discount_beyond_m,
            } => (n, discount_beyond_m).into_pyobject(py)?,
            Strategy::Frontier | Strategy::Custom => PyTuple::empty(py),
        };
        Ok((build, args))
    }
}
