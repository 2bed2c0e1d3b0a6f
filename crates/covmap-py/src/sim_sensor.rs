//! `covmap.SonarRing` and `covmap.Laser`: simulated range sensors.
//!
//! Both are a `RangeSensor` of the simulator: [`range_sensor_class!`] writes
//! what they share (bearings, maximum range, simulating scans) once.

use covmap::sim::{
    Laser, MAX_BEAMS, MAX_RAYS_PER_CONE, RangeSensor, SonarRing, World, sim_rng, simulate,
};
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1, PyArray2};
use pyo3::prelude::*;

use crate::convert;
use crate::errors::{Exception, OrRaise};
use crate::numbers::{Float, Int, Seed};
use crate::sensor::PySonarModel;
use crate::world::PyWorld;

/// A pair of float64 arrays `(ranges, bearings)`.
type Readings<'py> = (Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<f64>>);

/// One scan of `sensor` in `world` from `pose`, drawn from a generator seeded
/// with `seed`, as `(ranges, bearings)`; the GIL is released meanwhile.
fn scan_one<'py, S: RangeSensor + Sync>(
    py: Python<'py>,
    sensor: &S,
    world: &Bound<'py, PyWorld>,
    pose: &Bound<'py, PyAny>,
    seed: u64,
) -> PyResult<Readings<'py>> {
    let pose = convert::pose(pose)?;
    let world: &World = &world.get().0;
    let scan = py
        .detach(|| sensor.scan(world, &pose, &mut sim_rng(seed)))
        .or_raise(py)?;
    Ok((
        PyArray1::from_vec(py, scan.ranges_m),
        PyArray1::from_vec(py, scan.bearings_rad),
    ))
}

/// One scan from each of `poses`, scan `i` from stream `i` of `seed`, as a
/// `(len(poses), len(bearings))` array of ranges; in parallel, GIL released.
fn scan_many<'py, S: RangeSensor + Sync>(
    py: Python<'py>,
    sensor: &S,
    world: &Bound<'py, PyWorld>,
    poses: &Bound<'py, PyAny>,
    seed: u64,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let poses = convert::poses(poses, "poses")?;
    let world: &World = &world.get().0;
    let scans = py
        .detach(|| simulate(sensor, world, &poses, seed))
        .or_raise(py)?;
    let beams = sensor.bearings_rad().len();
    let ranges = Array2::from_shape_fn((scans.len(), beams), |(i, j)| scans[i].ranges_m[j]);
    Ok(ranges.into_pyarray(py))
}

/// `sensor` if its parameters are valid, else the error as a Python exception.
fn checked<S: RangeSensor>(py: Python<'_>, sensor: S) -> PyResult<S> {
    sensor.validate().or_raise(py)?;
    Ok(sensor)
}

/// The `#[pymethods]` block of `$class`, a simulated range sensor: its own
/// methods as given, then what every range sensor has (`bearings_rad` and its
/// alias `bearings`, `max_range_m`, `simulate` and `simulate_path`).
macro_rules! range_sensor_class {
    (impl $class:ident { $($methods:tt)* }) => {
        #[pymethods]
        impl $class {
            $($methods)*

            /// Bearing of each beam relative to the heading, radians: float64
            /// ``(n,)`` (a ring's sensors are mounted at these bearings).
            #[getter]
            fn bearings_rad<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
                PyArray1::from_slice(py, self.0.bearings_rad())
            }
            /// The same as ``bearings_rad``, under the name ``CoverageMap.integrate`` uses.
            #[getter]
            fn bearings<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
                self.bearings_rad(py)
            }
            /// Readings at or beyond this are "no echo", metres.
            #[getter]
            fn max_range_m(&self) -> f64 {
                self.0.max_range_m()
            }

            /// One scan of ``world`` from ``pose = (x, y, theta)``, every random draw
            /// from a generator seeded with ``seed``: ``(ranges, bearings)``, float64
            /// ``(n,)`` each, ready for ``CoverageMap.integrate(pose, ranges,
            /// bearings, model)`` with the sensor's model (``SonarModel()`` for a
            /// ``SonarRing``, ``LaserModel()`` for a ``Laser``). The same seed gives
            /// the same readings.
            #[pyo3(signature = (world, pose, *, seed=Seed(0)), text_signature = "($self, world, pose, *, seed=0)")]
            fn simulate<'py>(&self, py: Python<'py>, world: Bound<'py, PyWorld>, pose: &Bound<'py, PyAny>, seed: Seed) -> PyResult<Readings<'py>> {
                scan_one(py, &self.0, &world, pose, seed.0)
            }
            /// One scan from each pose of ``poses`` (float64 ``(N, 3)``): the ranges
            /// as float64 ``(N, n)``. Scan ``i`` draws from its own stream ``i`` of
            /// ``seed`` (scan 0 equals ``simulate(world, poses[0], seed=seed)``), so
            /// the result depends on the seed alone; scans run in parallel.
            #[pyo3(signature = (world, poses, *, seed=Seed(0)), text_signature = "($self, world, poses, *, seed=0)")]
            fn simulate_path<'py>(&self, py: Python<'py>, world: Bound<'py, PyWorld>, poses: &Bound<'py, PyAny>, seed: Seed) -> PyResult<Bound<'py, PyArray2<f64>>> {
                scan_many(py, &self.0, &world, poses, seed.0)
            }
            /// ``simulate_path``'s scans as a ``Log``: scan ``i`` from
            /// ``poses[i]`` at time ``i`` seconds, this sensor's bearings and
            /// maximum range, ready for ``CoverageMap.integrate_log``.
            #[pyo3(signature = (world, poses, *, seed=Seed(0)), text_signature = "($self, world, poses, *, seed=0)")]
            fn record(&self, py: Python<'_>, world: Bound<'_, PyWorld>, poses: &Bound<'_, PyAny>, seed: Seed) -> PyResult<crate::log::PyLog> {
                let poses = convert::poses(poses, "poses")?;
                let world: &World = &world.get().0;
                py.detach(|| covmap::sim::record(&self.0, world, &poses, seed.0))
                    .map(crate::log::PyLog)
                    .or_raise(py)
            }
        }
    };
}

/// A ring of simulated ultrasound sensors, all at the robot's centre.
///
/// Sensor ``i`` looks along ``theta + bearings_rad[i]``. A reading casts
/// ``rays_per_cone`` rays across the cone; a ray echoes when it meets a
/// surface at an incidence no larger than the material's critical angle
/// (walls ``critical_angle_wall_rad``, glass ``critical_angle_glass_rad``);
/// the nearest echo is the reading. A cone with only specular misses returns a
/// longer multipath reading with ``multipath_probability``, else no echo.
/// Echoes get Gaussian noise of standard deviation ``noise_std_m +
/// noise_std_per_m * range`` and are at least ``min_range_m``; with
/// ``outlier_probability`` a reading is replaced by a short outlier. No echo
/// reads exactly ``max_range_m``, as ``CoverageMap.integrate`` expects.
///
/// Arguments left out (or ``None``) take the defaults: 24 sensors 15 degrees
/// apart, the first straight ahead, with the cone and range of the default
/// ``SonarModel``. Distances in metres, angles in radians; an invalid value
/// raises ``InvalidParameterError`` (or ``InvalidValueError`` for a bearing).
#[pyclass(frozen, eq, name = "SonarRing", module = "covmap._native")]
#[derive(Clone, PartialEq)]
pub(crate) struct PySonarRing(pub(crate) SonarRing);

range_sensor_class! {
    impl PySonarRing {
        #[new]
        #[pyo3(signature = (
            *, bearings_rad=None, opening_angle_rad=None, max_range_m=None, min_range_m=None,
            rays_per_cone=None, noise_std_m=None, noise_std_per_m=None, outlier_probability=None,
            multipath_probability=None, critical_angle_wall_rad=None, critical_angle_glass_rad=None
        ))]
        #[allow(clippy::too_many_arguments, reason = "one keyword per sensor parameter")]
        fn new(
            py: Python<'_>,
            bearings_rad: Option<&Bound<'_, PyAny>>,
            opening_angle_rad: Option<Float>,
            max_range_m: Option<Float>,
            min_range_m: Option<Float>,
            rays_per_cone: Option<Int<usize, 1, { MAX_RAYS_PER_CONE as i128 }>>,
            noise_std_m: Option<Float>,
            noise_std_per_m: Option<Float>,
            outlier_probability: Option<Float>,
            multipath_probability: Option<Float>,
            critical_angle_wall_rad: Option<Float>,
            critical_angle_glass_rad: Option<Float>,
        ) -> PyResult<Self> {
            let d = SonarRing::default();
            let or = |value: Option<Float>, default: f64| value.map_or(default, |v| v.0);
            let ring = SonarRing {
                bearings_rad: match bearings_rad {
                    Some(b) => convert::readings(b, "bearings_rad", covmap::sim::MAX_BEAMS)?,
                    None => d.bearings_rad,
                },
                opening_angle_rad: or(opening_angle_rad, d.opening_angle_rad),
                max_range_m: or(max_range_m, d.max_range_m),
                min_range_m: or(min_range_m, d.min_range_m),
                rays_per_cone: rays_per_cone.map_or(d.rays_per_cone, |n| n.0),
                noise_std_m: or(noise_std_m, d.noise_std_m),
                noise_std_per_m: or(noise_std_per_m, d.noise_std_per_m),
                outlier_probability: or(outlier_probability, d.outlier_probability),
                multipath_probability: or(multipath_probability, d.multipath_probability),
                critical_angle_wall_rad: or(critical_angle_wall_rad, d.critical_angle_wall_rad),
                critical_angle_glass_rad: or(critical_angle_glass_rad, d.critical_angle_glass_rad),
            };
            checked(py, ring).map(Self)
        }

        /// Pickle and copy support: the keyword arguments that rebuild the ring.
        fn __getnewargs_ex__<'py>(
            &self,
            py: Python<'py>,
        ) -> PyResult<(Bound<'py, pyo3::types::PyTuple>, Bound<'py, pyo3::types::PyDict>)> {
            let r = &self.0;
            let kwargs = pyo3::types::PyDict::new(py);
            kwargs.set_item("bearings_rad", PyArray1::from_slice(py, &r.bearings_rad))?;
            kwargs.set_item("opening_angle_rad", r.opening_angle_rad)?;
            kwargs.set_item("max_range_m", r.max_range_m)?;
            kwargs.set_item("min_range_m", r.min_range_m)?;
            kwargs.set_item("rays_per_cone", r.rays_per_cone)?;
            kwargs.set_item("noise_std_m", r.noise_std_m)?;
            kwargs.set_item("noise_std_per_m", r.noise_std_per_m)?;
            kwargs.set_item("outlier_probability", r.outlier_probability)?;
            kwargs.set_item("multipath_probability", r.multipath_probability)?;
            kwargs.set_item("critical_angle_wall_rad", r.critical_angle_wall_rad)?;
            kwargs.set_item("critical_angle_glass_rad", r.critical_angle_glass_rad)?;
            Ok((pyo3::types::PyTuple::empty(py), kwargs))
        }

        /// ``count`` sensors evenly spaced around the robot, the first straight
        /// ahead, with the default error model.
        #[staticmethod]
        fn ring(py: Python<'_>, count: Int<usize, 1, { MAX_BEAMS as i128 }>) -> PyResult<Self> {
            checked(py, SonarRing::ring(count.0)).map(Self)
        }
        /// The eight-sonar front array of the ``sonar-8ring`` data set: -90,
        /// -37.5, -22.5, -7.5, 7.5, 22.5, 37.5 and 90 degrees.
        #[staticmethod]
        fn front_eight() -> Self {
            Self(SonarRing::front_eight())
        }
        /// The same ring with the opening angle and maximum range of ``model``, so
        /// that the simulated cone is the one the map assumes.
        fn with_model(&self, model: Bound<'_, PySonarModel>) -> Self {
            Self(self.0.clone().with_model(&model.get().0))
        }

        /// Full opening angle of each cone, radians.
        #[getter]
        fn opening_angle_rad(&self) -> f64 {
            self.0.opening_angle_rad
        }
        /// The shortest reading the sensor produces, metres.
        #[getter]
        fn min_range_m(&self) -> f64 {
            self.0.min_range_m
        }
        /// Rays cast across each cone.
        #[getter]
        fn rays_per_cone(&self) -> usize {
            self.0.rays_per_cone
        }
        /// Standard deviation of the range noise at zero range, metres.
        #[getter]
        fn noise_std_m(&self) -> f64 {
            self.0.noise_std_m
        }
        /// Growth of that standard deviation per metre of range.
        #[getter]
        fn noise_std_per_m(&self) -> f64 {
            self.0.noise_std_per_m
        }
        /// Probability that a reading is replaced by a short outlier.
        #[getter]
        fn outlier_probability(&self) -> f64 {
            self.0.outlier_probability
        }
        /// Probability that a specular miss returns a longer multipath reading.
        #[getter]
        fn multipath_probability(&self) -> f64 {
            self.0.multipath_probability
        }
        /// Largest angle of incidence at which a wall still echoes, radians.
        #[getter]
        fn critical_angle_wall_rad(&self) -> f64 {
            self.0.critical_angle_wall_rad
        }
        /// Largest angle of incidence at which glass still echoes, radians.
        #[getter]
        fn critical_angle_glass_rad(&self) -> f64 {
            self.0.critical_angle_glass_rad
        }

        fn __repr__(&self) -> String {
            format!(
                "SonarRing({} sensors, opening_angle_rad={:?}, max_range_m={:?})",
                self.0.bearings_rad.len(),
                self.0.opening_angle_rad,
                self.0.max_range_m
            )
        }
    }
}

/// A simulated laser scanner: thin beams, small Gaussian noise.
///
/// ``beams`` beams spread evenly over ``fov_rad`` centred on the heading, the
/// first at ``-fov_rad / 2`` and the last at ``+fov_rad / 2`` (default 361
/// beams over pi: half a degree apart), or beams at ``bearings_rad``. A hit at
/// distance ``d`` reads ``d + noise_std_m * z``; a beam that meets nothing
/// before ``max_range_m`` (default 30 m, the default ``LaserModel``'s) reads
/// exactly ``max_range_m``. Every surface, glass included, reflects it.
#[pyclass(frozen, eq, name = "Laser", module = "covmap._native")]
#[derive(Clone, PartialEq)]
pub(crate) struct PyLaser(pub(crate) Laser);

range_sensor_class! {
    impl PyLaser {
        #[new]
        #[pyo3(signature = (beams=None, fov_rad=None, *, bearings_rad=None, max_range_m=None, noise_std_m=None))]
        fn new(
            py: Python<'_>,
            beams: Option<Int<usize, 2, { MAX_BEAMS as i128 }>>,
            fov_rad: Option<Float>,
            bearings_rad: Option<&Bound<'_, PyAny>>,
            max_range_m: Option<Float>,
            noise_std_m: Option<Float>,
        ) -> PyResult<Self> {
            let mut laser = match bearings_rad {
                Some(_) if beams.is_some() || fov_rad.is_some() => {
                    return Err(Exception::InvalidType.err(
                        py,
                        "give either beams and fov_rad or bearings_rad, not both",
                    ));
                }
                Some(b) => Laser::with_bearings(convert::readings(b, "bearings_rad", covmap::sim::MAX_BEAMS)?),
                None => {
                    let beams = beams.map_or(361, |b| b.0);
                    Laser::new(beams, fov_rad.map_or(std::f64::consts::PI, |f| f.0)).or_raise(py)?
                }
            };
            laser.max_range_m = max_range_m.map_or(laser.max_range_m, |m| m.0);
            laser.noise_std_m = noise_std_m.map_or(laser.noise_std_m, |n| n.0);
            checked(py, laser).map(Self)
        }

        /// Pickle and copy support: the keyword arguments that rebuild the laser.
        fn __getnewargs_ex__<'py>(
            &self,
            py: Python<'py>,
        ) -> PyResult<(Bound<'py, pyo3::types::PyTuple>, Bound<'py, pyo3::types::PyDict>)> {
            let kwargs = pyo3::types::PyDict::new(py);
            kwargs.set_item("bearings_rad", PyArray1::from_slice(py, &self.0.bearings_rad))?;
            kwargs.set_item("max_range_m", self.0.max_range_m)?;
            kwargs.set_item("noise_std_m", self.0.noise_std_m)?;
            Ok((pyo3::types::PyTuple::empty(py), kwargs))
        }

        /// 180 beams one degree apart from -90 degrees (to +89), the layout of
        /// the 180-beam CARMEN logs.
        #[staticmethod]
        fn sick_180() -> Self {
            Self(Laser::sick_180())
        }
        /// 361 beams half a degree apart from -90 to +90 degrees.
        #[staticmethod]
        fn sick_361() -> Self {
            Self(Laser::sick_361())
        }

        /// Standard deviation of the range noise, metres.
        #[getter]
        fn noise_std_m(&self) -> f64 {
            self.0.noise_std_m
        }

        fn __repr__(&self) -> String {
            format!(
                "Laser({} beams, max_range_m={:?}, noise_std_m={:?})",
                self.0.bearings_rad.len(),
                self.0.max_range_m,
                self.0.noise_std_m
            )
        }
    }
}
