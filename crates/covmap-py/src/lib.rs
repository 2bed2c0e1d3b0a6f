//! Python bindings of covmap: the `covmap._native` extension module.
//!
//! Thin wrappers only: every method converts its arguments, calls the core and
//! converts the result. The Python package around it lives in `python/covmap`.
#![warn(missing_docs)]

mod convert;
mod coverage_map;
mod errors;
mod grid;
mod occupancy;
mod scan;
mod sensor;

use pyo3::prelude::*;

/// Native core of covmap (coverage maps, Stachniss and Burgard 2003). Import
/// from ``covmap`` instead.
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("DEFAULT_BINS", covmap::histogram::DEFAULT_BINS)?;
    m.add("MIN_BINS", covmap::histogram::MIN_BINS)?;
    m.add("MAX_BINS", covmap::histogram::MAX_BINS)?;
    m.add_class::<grid::PyGrid>()?;
    m.add_class::<sensor::PySonarModel>()?;
    m.add_class::<sensor::PyLaserModel>()?;
    m.add_class::<coverage_map::PyCoverageMap>()?;
    m.add_class::<occupancy::PyOccupancyGrid>()?;
    Ok(())
}
