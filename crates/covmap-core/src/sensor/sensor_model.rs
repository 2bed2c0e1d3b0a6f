//! What a range sensor is to the map: an inverse model and the footprint of
//! one reading.

use super::RangeModel;
use crate::error::Result;

/// The shape of the region a reading covers.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Footprint {
    /// A sonar cone: every cell whose centre lies within `half_angle_rad` of the
    /// beam axis, at its Euclidean distance from the sensor.
    Cone {
        /// Half the opening angle, radians, in `(0, pi/2)`.
        half_angle_rad: f64,
    },
    /// A thin beam: every cell the ray crosses, each once, at the distance of its
    /// centre projected on the ray.
    Ray,
}

/// A range sensor: an inverse model plus the footprint of one reading.
pub trait SensorModel {
    /// The inverse model along the beam.
    fn range_model(&self) -> &RangeModel;
    /// The region one reading covers.
    fn footprint(&self) -> Footprint;
    /// Errors unless every parameter lies in its valid range.
    fn validate(&self) -> Result<()>;

    /// The kernel the map multiplies in for a cell at `cell_distance_m` and a
    /// reading of `measured_distance_m`, on a grid of `resolution_m` with
    /// `bins` bins, or `None` where the cell is not updated; see
    /// [`RangeModel::kernel`]. Errors if the model is invalid, and as
    /// [`RangeModel::kernel`] does.
    fn kernel(
        &self,
        cell_distance_m: f64,
        measured_distance_m: f64,
        resolution_m: f64,
        bins: usize,
    ) -> Result<Option<Vec<f32>>> {
        self.validate()?;
        self.range_model()
            .kernel(cell_distance_m, measured_distance_m, resolution_m, bins)
    }
}
