//! One scan's arguments, converted and copied out of Python.

use covmap::Pose;
use covmap::exploration::AnySensorModel;
use pyo3::prelude::*;

use crate::convert;
use crate::sensor::any_model;

/// The arguments of `integrate`: pose, readings and model, owned by Rust so the
/// update can run with the GIL released.
pub(crate) struct Scan {
    pub(crate) pose: Pose,
    pub(crate) ranges: Vec<f64>,
    pub(crate) bearings: Vec<f64>,
    pub(crate) model: AnySensorModel,
}

impl Scan {
    pub(crate) fn extract(
        pose: &Bound<'_, PyAny>,
        ranges: &Bound<'_, PyAny>,
        bearings: &Bound<'_, PyAny>,
        model: &Bound<'_, PyAny>,
    ) -> PyResult<Self> {
        Ok(Self {
            pose: convert::pose(pose)?,
            ranges: convert::readings(ranges, "ranges", covmap::sim::MAX_BEAMS)?,
            bearings: convert::readings(bearings, "bearings", covmap::sim::MAX_BEAMS)?,
            model: any_model(model)?,
        })
    }
}
