//! `covmap.SonarModel` and `covmap.LaserModel`: the inverse sensor models.

use covmap::{Footprint, LaserModel, RangeModel, SensorModel, SonarModel};
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple, PyType};

use crate::convert;
use crate::errors::{Exception, OrRaise};
use crate::grid::hash_f64s;

/// The keyword arguments shared by both models; `None` keeps the default.
struct RangeArgs {
    max_range_m: Option<f64>,
    band_m: Option<f64>,
    sigma_min: Option<f64>,
    sigma_per_m: Option<f64>,
    sigma_end: Option<f64>,
    xi_min: Option<f64>,
    xi_per_m: Option<f64>,
}

impl RangeArgs {
    fn over(self, d: RangeModel) -> RangeModel {
        RangeModel {
            max_range_m: self.max_range_m.unwrap_or(d.max_range_m),
            band_m: self.band_m.unwrap_or(d.band_m),
            sigma_min: self.sigma_min.unwrap_or(d.sigma_min),
            sigma_per_m: self.sigma_per_m.unwrap_or(d.sigma_per_m),
            sigma_end: self.sigma_end.unwrap_or(d.sigma_end),
            xi_min: self.xi_min.unwrap_or(d.xi_min),
            xi_per_m: self.xi_per_m.unwrap_or(d.xi_per_m),
        }
    }
}

/// The parameters of a range model, by their Python names, in signature order.
fn range_fields(r: &RangeModel) -> [(&'static str, f64); 7] {
    [
        ("max_range_m", r.max_range_m),
        ("band_m", r.band_m),
        ("sigma_min", r.sigma_min),
        ("sigma_per_m", r.sigma_per_m),
        ("sigma_end", r.sigma_end),
        ("xi_min", r.xi_min),
        ("xi_per_m", r.xi_per_m),
    ]
}

fn repr(class: &str, fields: &[(&'static str, f64)]) -> String {
    let args: Vec<String> = fields.iter().map(|(k, v)| format!("{k}={v:?}")).collect();
    format!("{class}({})", args.join(", "))
}

fn to_dict<'py>(py: Python<'py>, fields: &[(&'static str, f64)]) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    for (k, v) in fields {
        d.set_item(k, v)?;
    }
    Ok(d)
}

/// `model.kernel(...)` as a float32 array, `bins` checked first.
fn kernel_array<'py, M: SensorModel + Sync>(
    py: Python<'py>,
    model: &M,
    cell_distance: f64,
    measured_distance: f64,
    resolution: f64,
    bins: i64,
) -> PyResult<Option<Bound<'py, PyArray1<f32>>>> {
    let bins = convert::bins(py, bins)?;
    // Tabulating the kernels takes a millisecond or so: let other threads run.
    let k = py
        .detach(|| model.kernel(cell_distance, measured_distance, resolution, bins))
        .or_raise(py)?;
    Ok(k.map(|k| PyArray1::from_vec(py, k)))
}

/// The sonar inverse model: a range model spread over a cone.
///
/// Every cell whose centre lies within half the opening angle of the beam axis
/// and no further than the reach of the reading is updated, with its centre's
/// Euclidean distance from the sensor. Distances are in metres, angles in
/// radians. Arguments left out (or ``None``) take the defaults of a
/// Polaroid-class ultrasound sensor (15 degree cone, 5 m); every parameter is
/// validated, and an invalid one raises ``InvalidParameterError``.
#[pyclass(frozen, eq, name = "SonarModel", module = "covmap._native")]
#[derive(Clone, PartialEq)]
pub(crate) struct PySonarModel(pub(crate) SonarModel);

impl PySonarModel {
    fn fields(&self) -> [(&'static str, f64); 8] {
        let [a, b, c, d, e, f, g] = range_fields(&self.0.range);
        [
            a,
            b,
            c,
            d,
            e,
            f,
            g,
            ("opening_angle_rad", self.0.opening_angle_rad),
        ]
    }
}

#[pymethods]
impl PySonarModel {
    #[new]
    #[pyo3(signature = (
        *, max_range_m=None, band_m=None, sigma_min=None, sigma_per_m=None,
        sigma_end=None, xi_min=None, xi_per_m=None, opening_angle_rad=None
    ))]
    #[allow(clippy::too_many_arguments, reason = "one keyword per model parameter")]
    fn new(
        py: Python<'_>,
        max_range_m: Option<f64>,
        band_m: Option<f64>,
        sigma_min: Option<f64>,
        sigma_per_m: Option<f64>,
        sigma_end: Option<f64>,
        xi_min: Option<f64>,
        xi_per_m: Option<f64>,
        opening_angle_rad: Option<f64>,
    ) -> PyResult<Self> {
        let default = SonarModel::default();
        let args = RangeArgs {
            max_range_m,
            band_m,
            sigma_min,
            sigma_per_m,
            sigma_end,
            xi_min,
            xi_per_m,
        };
        let model = SonarModel {
            range: args.over(default.range),
            opening_angle_rad: opening_angle_rad.unwrap_or(default.opening_angle_rad),
        };
        model.validate().or_raise(py)?;
        Ok(Self(model))
    }

    /// Readings at or beyond this distance mean "no echo", metres.
    #[getter]
    fn max_range_m(&self) -> f64 {
        self.0.range.max_range_m
    }
    /// How far behind the end point cells are updated (as covered), metres.
    #[getter]
    fn band_m(&self) -> f64 {
        self.0.range.band_m
    }
    /// Standard deviation of the coverage mean at zero distance, outside the end band.
    #[getter]
    fn sigma_min(&self) -> f64 {
        self.0.range.sigma_min
    }
    /// Growth of that standard deviation per metre of distance min(d_l, d).
    #[getter]
    fn sigma_per_m(&self) -> f64 {
        self.0.range.sigma_per_m
    }
    /// The constant standard deviation inside the end band (the largest of all).
    #[getter]
    fn sigma_end(&self) -> f64 {
        self.0.range.sigma_end
    }
    /// Weight of the uniform component at zero distance.
    #[getter]
    fn xi_min(&self) -> f64 {
        self.0.range.xi_min
    }
    /// Growth of the uniform weight per metre of distance min(d_l, d).
    #[getter]
    fn xi_per_m(&self) -> f64 {
        self.0.range.xi_per_m
    }
    /// Full opening angle of the cone, radians.
    #[getter]
    fn opening_angle_rad(&self) -> f64 {
        self.0.opening_angle_rad
    }

    /// The kernel a map multiplies into a cell at ``cell_distance`` (metres)
    /// for a reading of ``measured_distance`` (metres), on a grid of
    /// ``resolution`` (metres) with ``bins`` bins: a float32 array of shape
    /// ``(bins,)`` summing to 1, or ``None`` where the cell is not updated.
    /// A NaN, infinite or negative distance raises ``InvalidParameterError``.
    #[pyo3(signature = (cell_distance, measured_distance, *, resolution=0.05, bins=16))]
    fn kernel<'py>(
        &self,
        py: Python<'py>,
        cell_distance: f64,
        measured_distance: f64,
        resolution: f64,
        bins: i64,
    ) -> PyResult<Option<Bound<'py, PyArray1<f32>>>> {
        kernel_array(
            py,
            &self.0,
            cell_distance,
            measured_distance,
            resolution,
            bins,
        )
    }

    /// The parameters as a dict of keyword arguments.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        to_dict(py, &self.fields())
    }
    /// The model with the parameters of ``d`` (missing ones take the defaults).
    #[classmethod]
    fn from_dict<'py>(
        cls: &Bound<'py, PyType>,
        d: &Bound<'py, PyDict>,
    ) -> PyResult<Bound<'py, PyAny>> {
        cls.call((), Some(d))
    }
    fn __repr__(&self) -> String {
        repr("SonarModel", &self.fields())
    }
    fn __hash__(&self) -> u64 {
        hash_f64s(self.fields().map(|(_, v)| v), &[])
    }
    /// Pickle and copy support: the keyword arguments that rebuild the model.
    fn __getnewargs_ex__<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyTuple>, Bound<'py, PyDict>)> {
        Ok((PyTuple::empty(py), self.to_dict(py)?))
    }
}

/// The laser inverse model: a range model along a thin beam.
///
/// Every cell the ray crosses up to the reach of the reading is updated once,
/// with the distance of its centre projected on the ray. Distances are in
/// metres. Arguments left out (or ``None``) take the defaults of a SICK-class
/// laser (30 m, sharp readings); an invalid parameter raises
/// ``InvalidParameterError``.
#[pyclass(frozen, eq, name = "LaserModel", module = "covmap._native")]
#[derive(Clone, PartialEq)]
pub(crate) struct PyLaserModel(LaserModel);

impl PyLaserModel {
    fn fields(&self) -> [(&'static str, f64); 7] {
        range_fields(&self.0.range)
    }
}

#[pymethods]
impl PyLaserModel {
    #[new]
    #[pyo3(signature = (
        *, max_range_m=None, band_m=None, sigma_min=None, sigma_per_m=None,
        sigma_end=None, xi_min=None, xi_per_m=None
    ))]
    #[allow(clippy::too_many_arguments, reason = "one keyword per model parameter")]
    fn new(
        py: Python<'_>,
        max_range_m: Option<f64>,
        band_m: Option<f64>,
        sigma_min: Option<f64>,
        sigma_per_m: Option<f64>,
        sigma_end: Option<f64>,
        xi_min: Option<f64>,
        xi_per_m: Option<f64>,
    ) -> PyResult<Self> {
        let args = RangeArgs {
            max_range_m,
            band_m,
            sigma_min,
            sigma_per_m,
            sigma_end,
            xi_min,
            xi_per_m,
        };
        let model = LaserModel {
            range: args.over(LaserModel::default().range),
        };
        model.validate().or_raise(py)?;
        Ok(Self(model))
    }

    /// Readings at or beyond this distance mean "no echo", metres.
    #[getter]
    fn max_range_m(&self) -> f64 {
        self.0.range.max_range_m
    }
    /// How far behind the end point cells are updated (as covered), metres.
    #[getter]
    fn band_m(&self) -> f64 {
        self.0.range.band_m
    }
    /// Standard deviation of the coverage mean at zero distance, outside the end band.
    #[getter]
    fn sigma_min(&self) -> f64 {
        self.0.range.sigma_min
    }
    /// Growth of that standard deviation per metre of distance min(d_l, d).
    #[getter]
    fn sigma_per_m(&self) -> f64 {
        self.0.range.sigma_per_m
    }
    /// The constant standard deviation inside the end band (the largest of all).
    #[getter]
    fn sigma_end(&self) -> f64 {
        self.0.range.sigma_end
    }
    /// Weight of the uniform component at zero distance.
    #[getter]
    fn xi_min(&self) -> f64 {
        self.0.range.xi_min
    }
    /// Growth of the uniform weight per metre of distance min(d_l, d).
    #[getter]
    fn xi_per_m(&self) -> f64 {
        self.0.range.xi_per_m
    }

    /// The kernel a map multiplies into a cell at ``cell_distance`` (metres)
    /// for a reading of ``measured_distance`` (metres), on a grid of
    /// ``resolution`` (metres) with ``bins`` bins: a float32 array of shape
    /// ``(bins,)`` summing to 1, or ``None`` where the cell is not updated.
    /// A NaN, infinite or negative distance raises ``InvalidParameterError``.
    #[pyo3(signature = (cell_distance, measured_distance, *, resolution=0.05, bins=16))]
    fn kernel<'py>(
        &self,
        py: Python<'py>,
        cell_distance: f64,
        measured_distance: f64,
        resolution: f64,
        bins: i64,
    ) -> PyResult<Option<Bound<'py, PyArray1<f32>>>> {
        kernel_array(
            py,
            &self.0,
            cell_distance,
            measured_distance,
            resolution,
            bins,
        )
    }

    /// The parameters as a dict of keyword arguments.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        to_dict(py, &self.fields())
    }
    /// The model with the parameters of ``d`` (missing ones take the defaults).
    #[classmethod]
    fn from_dict<'py>(
        cls: &Bound<'py, PyType>,
        d: &Bound<'py, PyDict>,
    ) -> PyResult<Bound<'py, PyAny>> {
        cls.call((), Some(d))
    }
    fn __repr__(&self) -> String {
        repr("LaserModel", &self.fields())
    }
    fn __hash__(&self) -> u64 {
        hash_f64s(self.fields().map(|(_, v)| v), &[])
    }
    /// Pickle and copy support: the keyword arguments that rebuild the model.
    fn __getnewargs_ex__<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyTuple>, Bound<'py, PyDict>)> {
        Ok((PyTuple::empty(py), self.to_dict(py)?))
    }
}

/// A `model` argument: either sensor model, copied out of Python.
#[derive(Clone, Copy)]
pub(crate) enum AnyModel {
    Sonar(SonarModel),
    Laser(LaserModel),
}

impl AnyModel {
    pub(crate) fn extract(obj: &Bound<'_, PyAny>) -> PyResult<Self> {
        if let Ok(m) = obj.cast::<PySonarModel>() {
            Ok(Self::Sonar(m.get().0))
        } else if let Ok(m) = obj.cast::<PyLaserModel>() {
            Ok(Self::Laser(m.get().0))
        } else {
            Err(Exception::InvalidType.err(
                obj.py(),
                format!(
                    "model must be a SonarModel or a LaserModel, got {}",
                    obj.get_type()
                ),
            ))
        }
    }
}

impl SensorModel for AnyModel {
    fn range_model(&self) -> &RangeModel {
        match self {
            Self::Sonar(m) => m.range_model(),
            Self::Laser(m) => m.range_model(),
        }
    }
    fn footprint(&self) -> Footprint {
        match self {
            Self::Sonar(m) => m.footprint(),
            Self::Laser(m) => m.footprint(),
        }
    }
    fn validate(&self) -> covmap::Result<()> {
        match self {
            Self::Sonar(m) => m.validate(),
            Self::Laser(m) => m.validate(),
        }
    }
}
