//! `covmap.Robot`: a disc robot's collision checks.

use covmap::sim::Robot;
use numpy::PyArray1;
use pyo3::prelude::*;

use crate::convert;
use crate::errors::OrRaise;
use crate::numbers::Float;
use crate::world::PyWorld;

/// A disc-shaped robot of radius ``radius_m`` (metres; the default matches
/// ``Planner``'s).
///
/// Points are ``(x, y)`` in metres; where a pose ``(x, y, theta)`` is given
/// instead, its heading is ignored (a disc looks the same either way).
#[pyclass(frozen, eq, name = "Robot", module = "covmap._native")]
#[derive(Clone, Copy, PartialEq)]
pub(crate) struct PyRobot(Robot);

/// The ends of a straight move, `(start, goal)`: points, or poses whose
/// headings are ignored.
fn ends(start: &Bound<'_, PyAny>, goal: &Bound<'_, PyAny>) -> PyResult<([f64; 2], [f64; 2])> {
    Ok((
        convert::point(start, "start", true)?,
        convert::point(goal, "goal", true)?,
    ))
}

#[pymethods]
impl PyRobot {
    #[new]
    #[pyo3(signature = (*, radius_m=Float(0.25)), text_signature = "(*, radius_m=0.25)")]
    fn new(py: Python<'_>, radius_m: Float) -> PyResult<Self> {
        Robot::new(radius_m.0).map(Self).or_raise(py)
    }

    /// The disc's radius, metres.
    #[getter]
    fn radius_m(&self) -> f64 {
        self.0.radius_m()
    }

    /// Pickle and copy support: the keyword arguments that rebuild the robot.
    fn __getnewargs_ex__<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(
        Bound<'py, pyo3::types::PyTuple>,
        Bound<'py, pyo3::types::PyDict>,
    )> {
        let kwargs = pyo3::types::PyDict::new(py);
        kwargs.set_item("radius_m", self.0.radius_m())?;
        Ok((pyo3::types::PyTuple::empty(py), kwargs))
    }

    /// Whether the disc at ``pose`` overlaps or touches an obstacle of
    /// ``world``. A pose with a non-finite position collides.
    fn collides(&self, world: Bound<'_, PyWorld>, pose: &Bound<'_, PyAny>) -> PyResult<bool> {
        let [x, y] = convert::point(pose, "pose", true)?;
        Ok(self
            .0
            .collides(&world.get().0, &covmap::Pose::new(x, y, 0.0)))
    }

    /// Whether driving straight from ``start`` to ``goal`` touches an
    /// obstacle (either end in contact counts).
    fn move_collides(
        &self,
        world: Bound<'_, PyWorld>,
        start: &Bound<'_, PyAny>,
        goal: &Bound<'_, PyAny>,
    ) -> PyResult<bool> {
        let (a, b) = ends(start, goal)?;
        Ok(self.0.move_collides(&world.get().0, a, b))
    }

    /// How far the disc can drive straight from ``start`` towards ``goal``
    /// before it touches an obstacle, metres: the whole length when the way is
    /// free, 0 when it starts in contact. A coordinate that is not finite
    /// raises ``InvalidValueError``.
    fn free_travel(
        &self,
        world: Bound<'_, PyWorld>,
        start: &Bound<'_, PyAny>,
        goal: &Bound<'_, PyAny>,
    ) -> PyResult<f64> {
        let (a, b) = ends(start, goal)?;
        convert::finite_points(world.py(), &[a], "start")?;
        convert::finite_points(world.py(), &[b], "goal")?;
        Ok(self.0.free_travel_m(&world.get().0, a, b))
    }

    /// The gap between the disc at each of ``points`` (float64 ``(N, 2)``)
    /// and the nearest obstacle, metres: float64 ``(N,)``, negative where they
    /// overlap. A point that is not finite raises ``InvalidValueError``. Runs
    /// with the GIL released.
    fn clearance<'py>(
        &self,
        py: Python<'py>,
        world: Bound<'py, PyWorld>,
        points: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let points = convert::rows::<2>(points, "points", "point (x, y)")?;
        convert::finite_points(py, &points, "points")?;
        let (robot, world) = (self.0, &world.get().0);
        let gaps: Vec<f64> = py.detach(|| {
            points
                .iter()
                .map(|&p| robot.clearance_m(world, p))
                .collect()
        });
        Ok(PyArray1::from_vec(py, gaps))
    }

    fn __repr__(&self) -> String {
        format!("Robot(radius_m={:?})", self.0.radius_m())
    }
}
