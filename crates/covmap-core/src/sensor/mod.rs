//! Inverse sensor models: what a range reading says about a cell's coverage.
//!
//! As in [the model](crate::model), section 3 (paper eq. 9-10): for a cell
//! whose centre is `d_l` metres from the sensor and a reading of `d` metres,
//! the density over the coverage value `x` is
//!
//! ```text
//! p(x | d) ∝ xi(d_l, d) + N(x; mu(d_l - d), sigma(d_l, d))
//! ```
//!
//! evaluated at the bin values and normalised. With `o = d_l - d`, `r` the grid
//! resolution and `s = min(d_l, d)` the distance the beam travelled before it
//! reached the cell or ended, whichever came first:
//!
//! | region | `mu` | `sigma` |
//! | --- | --- | --- |
//! | free, `o < -r/2` | 0 | `sigma_min + sigma_per_m * s` |
//! | end band, `abs(o) <= r/2` | `1/2 + o/r` | `sigma_end` (the largest) |
//! | behind, `r/2 < o <= band_m` | 1 | `sigma_min + sigma_per_m * s` |
//!
//! In the end band the mean falls linearly from 1 (the beam ends at the cell's
//! near edge) to 0 (at its far edge): the more of the cell the beam travelled
//! through, the less of it is covered. An obstacle filling the far 20 % of a cell
//! stops the beam `0.3 r` past the centre, `o = -0.3 r`, so `mu = 0.2`.
//!
//! The uniform weight is `xi(d_l, d) = xi_min + xi_per_m * s`: far readings say
//! less. Both `sigma` and `xi` grow with `d_l` and with `d` as the paper asks
//! (`min` is non-decreasing in each). Through `s = min(d_l, d)` a cell in free
//! space (`d_l < d`) gets a kernel that does not depend on where the beam ends,
//! only on how far the cell is: that keeps the kernel table small (see
//! [`KernelTable`]) and lets the expected information gain sum over readings
//! with suffix sums (see [`crate::gain`]).
//!
//! Cells more than `band_m` behind the end point are not touched. A reading at or
//! beyond `max_range_m` is "no echo": every cell of the footprint up to
//! `max_range_m` gets the free kernel (with `d = max_range_m`), as the paper
//! reads it, and none is marked. The kernels of the end band and behind it
//! are mixed with the uniform prior by `end_weight`: the paper's kernels (no
//! mixing) by default.
//!
//! The update multiplies these kernels into the cells (adds their
//! logarithms to the cells' log-likelihoods) and reads nothing of the map: a
//! cell's histogram is the prior times the kernels of its readings, the same
//! whatever order they came in (but for float rounding). Parameters that made the update read the map were
//! removed ([`REMOVED_PARAMETERS`]).
//!
//! # Predicted readings, `p(d | map)`
//! The forward model, for the expected information gain ([`crate::gain`])
//! and for learning a sensor model from a map. Beams are independent (as the
//! map's cells are): each beam's readings are predicted on their own. A
//! beam's reading is predicted by tracing its axis through the map cell by
//! cell ([`StopCoverage`] picks the coverage value of each cell: the ML map
//! by default, as in the paper). A cell of coverage `c` stops the beam with
//! probability `c`; if it does, the beam is taken to end where an obstacle
//! filling the far `c` of the cell would stop it, `d = d_l + r/2 - c r` (so
//! that the reading reproduces the cell's coverage under the sensor model).
//! Readings are discretised on a grid of `range_step_m` (the grid resolution
//! by default); readings at or beyond the maximum range, and beams that reach
//! it or leave the map unstopped, are "no echo". A cone sensor is traced
//! along its axis. No extra noise blur is added: the sensor's uncertainty
//! enters through the kernels ([`reading_distribution`]).

mod kernel;
mod laser;
pub mod parameters;
mod range_model;
mod readings;
mod sensor_model;
mod sonar;

pub use kernel::KernelTable;
pub(crate) use kernel::ReadingLookup;
pub use laser::LaserModel;
pub use parameters::{
    FITTABLE_RANGE_PARAMETERS, FITTABLE_SONAR_PARAMETERS, Parameter, RANGE_PARAMETERS,
    REMOVED_PARAMETERS, SONAR_MODEL_PARAMETERS,
};
pub use range_model::RangeModel;
pub(crate) use range_model::kernel_values;
pub use readings::{
    MIN_STEP_FRACTION, ReadingDistribution, StopCoverage, check_range_step, reading_distribution,
};
pub(crate) use readings::{trace_readings, trace_readings_with};
pub use sensor_model::{Footprint, SensorModel};
pub use sonar::SonarModel;
