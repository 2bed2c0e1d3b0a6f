//! The maps as `nav_msgs/OccupancyGrid` data and as map_server files: what
//! `CoverageMap` and `OccupancyGrid` share for `ros_occupancy` and
//! `to_ros_map`.

use std::path::Path;

use covmap::sim::RosMapMode;
use covmap::{CoverageValue, Grid};
use numpy::PyArray2;
use pyo3::prelude::*;

use crate::convert::cell_array;
use crate::errors::{Exception, OrRaise};

/// The coverage read-out by name: `"ml"` or `"mean"`.
pub(crate) fn coverage_value(py: Python<'_>, name: &str) -> PyResult<CoverageValue> {
    match name {
        "ml" => Ok(CoverageValue::Ml),
        "mean" => Ok(CoverageValue::Mean),
        other => Err(Exception::InvalidValue.err(
            py,
            format!(
                "source must be \"ml\" or \"mean\", got {}",
                covmap::quoted(other)
            ),
        )),
    }
}

/// `data` as an int8 `(rows, cols)` array.
pub(crate) fn array<'py>(
    py: Python<'py>,
    grid: &Grid,
    data: Vec<i8>,
) -> PyResult<Bound<'py, PyArray2<i8>>> {
    cell_array(py, grid, data)
}

/// Write `data` as the map_server pair at `yaml_path`, mode by name, with
/// the GIL released.
pub(crate) fn write(
    py: Python<'_>,
    yaml_path: &Path,
    grid: &Grid,
    data: &[i8],
    mode: &str,
    occupied_thresh: f64,
    free_thresh: f64,
) -> PyResult<()> {
    let mode = match mode {
        "trinary" => RosMapMode::Trinary,
        "scale" => RosMapMode::Scale,
        other => {
            return Err(Exception::InvalidValue.err(
                py,
                format!(
                    "mode must be \"trinary\" or \"scale\", got {}",
                    covmap::quoted(other)
                ),
            ));
        }
    };
    py.detach(|| {
        covmap::sim::write_ros_map(yaml_path, grid, data, mode, occupied_thresh, free_thresh)
    })
    .or_raise(py)
}
