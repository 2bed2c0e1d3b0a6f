//! `covmap.SonarModel` and `covmap.LaserModel`: the inverse sensor models.
//!
//! Both are a range model and, for the sonar, the opening angle of its
//! cone; [`sensor_model_class!`] writes their Python methods once for both,
//! one keyword and attribute for each parameter the core declares
//! (`covmap::range_parameters!`, `covmap::sonar_parameters!`).

use covmap::exploration::AnySensorModel;
use covmap::{LaserModel, RangeModel, SensorModel, SonarModel};
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple, PyType};

use crate::errors::{Exception, OrRaise};
use crate::grid::hash_f64s;
use crate::keywords::keyword_class;
use crate::numbers::{Bins, Float, Int};

/// `model.kernel(...)` as a float32 array.
fn kernel_array<'py, M: SensorModel + Sync>(
    py: Python<'py>,
    model: &M,
    (cell_distance, measured_distance): (f64, f64),
    resolution: f64,
    bins: usize,
) -> PyResult<Option<Bound<'py, PyArray1<f32>>>> {
    // Tabulating the kernels takes a millisecond or so: let other threads run.
    let k = py
        .detach(|| model.kernel(cell_distance, measured_distance, resolution, bins))
        .or_raise(py)?;
    Ok(k.map(|k| PyArray1::from_vec(py, k)))
}

/// `d`, a model's parameters as a dict, without the removed parameters
/// (`covmap::sensor::REMOVED_PARAMETERS`) it names at their off values, as
/// a dict stored before their removal holds them; one at any other value
/// raises `InvalidParameterError`.
fn without_removed<'py>(d: &Bound<'py, PyDict>) -> PyResult<Bound<'py, PyDict>> {
    let py = d.py();
    let kept = d.copy()?;
    for removed in &covmap::sensor::REMOVED_PARAMETERS {
        if let Some(value) = kept.get_item(removed.name)? {
            let Float(value) = value.extract()?;
            covmap::sensor::parameters::check_removed(removed, value).or_raise(py)?;
            kept.del_item(removed.name)?;
        }
    }
    Ok(kept)
}

/// The methods of a sensor model's class `$class` (wrapping the core's
/// `$model`): one keyword argument and attribute per parameter of the range
/// model and per parameter of the model's own (`[$own]`: entries of the
/// core's declaration, `covmap::sonar_parameters!`), validated on
/// construction; `kernel`, `to_dict`/`from_dict`, `repr`, hash and pickling;
/// and the methods of the `more { ... }` block, the class's own. Invoked
/// through `covmap::range_parameters!`, which appends the range model's
/// entries: the parameters are listed only in the core's declaration.
macro_rules! sensor_model_class {
    (
        impl $class:ident as $name:literal for $model:ident {
            keywords $keywords:ident;
            more { $($more:tt)* }
        }
        [ $( $(#[doc = $extra_doc:literal])* $extra:ident { $($extra_spec:tt)* } )* ]
        [ $( $(#[doc = $range_doc:literal])* $range:ident { $($range_spec:tt)* } )* ]
    ) => {
        impl $class {
            /// The model the keywords describe, a parameter left out the
            /// default's; an invalid one raises `InvalidParameterError`.
            fn from_keywords(py: Python<'_>, keywords: $keywords) -> PyResult<Self> {
                let default = $model::default();
                let model = $model {
                    range: RangeModel {
                        $($range: keywords.$range.unwrap_or(default.range.$range),)*
                    },
                    $($extra: keywords.$extra.unwrap_or(default.$extra),)*
                };
                model.validate().or_raise(py)?;
                Ok(Self(model))
            }

            /// The parameters by their Python names, in signature order.
            fn fields(&self) -> Vec<(&'static str, f64)> {
                vec![
                    $((stringify!($range), self.0.range.$range),)*
                    $((stringify!($extra), self.0.$extra),)*
                ]
            }
        }

        keyword_class! {
            impl $class as $name {
                keywords $keywords => $class::from_keywords;
                settings(&self) {
                    $( $(#[doc = $range_doc])* $range(f64) -> f64 { self.0.range.$range } )*
                    $( $(#[doc = $extra_doc])* $extra(f64) -> f64 { self.0.$extra } )*
                }
                methods {
                    /// The kernel a map multiplies into a cell at ``cell_distance`` (metres)
                    /// for a reading of ``measured_distance`` (metres), on a grid of
                    /// ``resolution`` (metres) with ``bins`` bins: a float32 array of shape
                    /// ``(bins,)`` summing to 1, or ``None`` where the cell is not updated.
                    /// A NaN, infinite or negative distance raises ``InvalidParameterError``.
                    #[pyo3(
                        signature = (cell_distance, measured_distance, *, resolution=Float(0.05), bins=Int(16)),
                        text_signature = "($self, cell_distance, measured_distance, *, resolution=0.05, bins=16)"
                    )]
                    fn kernel<'py>(
                        &self,
                        py: Python<'py>,
                        cell_distance: Float,
                        measured_distance: Float,
                        resolution: Float,
                        bins: Bins,
                    ) -> PyResult<Option<Bound<'py, PyArray1<f32>>>> {
                        let distances = (cell_distance.0, measured_distance.0);
                        kernel_array(py, &self.0, distances, resolution.0, bins.0)
                    }

                    /// The parameters as a dict of keyword arguments.
                    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
                        let d = PyDict::new(py);
                        for (k, v) in self.fields() {
                            d.set_item(k, v)?;
                        }
                        Ok(d)
                    }
                    /// The model with the parameters of ``d`` (missing ones take the defaults).
                    /// The parameters covmap removed (``posterior_floor``, ``end_attribution``,
                    /// ``free_yield`` at 0; ``no_echo_reach``, ``no_echo_weight`` at 1: each at its
                    /// old default) may appear and are ignored; any other value of them raises
                    /// ``InvalidParameterError``.
                    #[classmethod]
                    fn from_dict<'py>(
                        cls: &Bound<'py, PyType>,
                        d: Bound<'py, PyDict>,
                    ) -> PyResult<Bound<'py, PyAny>> {
                        let py = cls.py();
                        let d = without_removed(&d)?;
                        // An unknown or non-string key is a bad value of `d`:
                        // a covmap error, as any bad setting.
                        cls.call((), Some(&d)).map_err(|e| {
                            match e.get_type(py).is(py.get_type::<pyo3::exceptions::PyTypeError>()) {
                                true => Exception::InvalidType
                                    .err(py, format!("d holds no model's parameters: {}", e.value(py))),
                                false => e,
                            }
                        })
                    }
                    /// The names of the model's parameters, in the order of its
                    /// keyword arguments (the core's declaration of them).
                    #[classattr]
                    #[allow(non_snake_case, reason = "a class constant")]
                    fn PARAMETERS(py: Python<'_>) -> PyResult<Bound<'_, PyTuple>> {
                        PyTuple::new(py, [$(stringify!($range),)* $(stringify!($extra),)*])
                    }
                    fn __hash__(&self) -> u64 {
                        hash_f64s(self.fields().into_iter().map(|(_, v)| v), &[])
                    }
                    /// Pickle and copy support: the keyword arguments that rebuild the model.
                    fn __getnewargs_ex__<'py>(
                        &self,
                        py: Python<'py>,
                    ) -> PyResult<(Bound<'py, PyTuple>, Bound<'py, PyDict>)> {
                        Ok((PyTuple::empty(py), self.to_dict(py)?))
                    }
                    $($more)*
                }
            }
        }
    };
}

/// [`sensor_model_class!`] with the sonar's own parameters and then the
/// range model's appended, from the core's declarations.
macro_rules! sonar_model_class {
    ($($args:tt)*) => {
        covmap::range_parameters!(sensor_model_class! { $($args)* });
    };
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

covmap::sonar_parameters!(sonar_model_class! {
    impl PySonarModel as "SonarModel" for SonarModel {
        keywords SonarKeywords;
        more {}
    }
});

/// The laser inverse model: a range model along a thin beam.
///
/// Every cell the ray crosses up to the reach of the reading is updated once,
/// with the distance of its centre projected on the ray. Distances are in
/// metres. Arguments left out (or ``None``) take the defaults of a SICK-class
/// laser (30 m, sharp readings); an invalid parameter raises
/// ``InvalidParameterError``.
#[pyclass(frozen, eq, name = "LaserModel", module = "covmap._native")]
#[derive(Clone, PartialEq)]
pub(crate) struct PyLaserModel(pub(crate) LaserModel);

covmap::range_parameters!(sensor_model_class! {
    impl PyLaserModel as "LaserModel" for LaserModel {
        keywords LaserKeywords;
        more {}
    }
    []
});

/// A `model` argument: a `SonarModel` or a `LaserModel`, copied out of
/// Python as the core's either-model type.
pub(crate) fn any_model(obj: &Bound<'_, PyAny>) -> PyResult<AnySensorModel> {
    if let Ok(m) = obj.cast::<PySonarModel>() {
        Ok(AnySensorModel::Sonar(m.get().0))
    } else if let Ok(m) = obj.cast::<PyLaserModel>() {
        Ok(AnySensorModel::Laser(m.get().0))
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

/// The Python object of a core model: a `SonarModel` or a `LaserModel`.
pub(crate) fn model_object<'py>(
    py: Python<'py>,
    model: &AnySensorModel,
) -> PyResult<Bound<'py, PyAny>> {
    Ok(match model {
        AnySensorModel::Sonar(m) => Bound::new(py, PySonarModel(*m))?.into_any(),
        AnySensorModel::Laser(m) => Bound::new(py, PyLaserModel(*m))?.into_any(),
    })
}
