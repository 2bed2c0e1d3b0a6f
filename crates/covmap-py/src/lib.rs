//! Python bindings of covmap: the `covmap._native` extension module.
//!
//! Thin wrappers only: every method converts its arguments, calls the core and
//! converts the result. The Python package around it lives in `python/covmap`.
#![warn(missing_docs)]
#![cfg_attr(not(test), deny(clippy::unwrap_used, clippy::expect_used))]

mod building;
mod convert;
mod coverage_map;
mod errors;
mod experiments;
mod exploration;
mod files;
mod gain;
mod grid;
mod keywords;
mod learn;
mod log;
mod numbers;
mod occupancy;
mod pickling;
mod plan;
mod planner;
mod robot;
mod ros_map;
mod scan;
mod sensor;
mod sim_sensor;
mod strategy;
mod world;

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
    m.add_class::<log::PyLog>()?;
    m.add("STAGNATION_MEASUREMENTS", covmap::STAGNATION_MEASUREMENTS)?;
    m.add("STAGNATION_NATS", f64::from(covmap::STAGNATION_NATS))?;
    m.add("MAP_FILE_VERSION", covmap::MAP_FILE_VERSION)?;
    m.add_function(wrap_pyfunction!(gain::expected_information_gain, m)?)?;
    m.add_class::<planner::PyPlanner>()?;
    m.add_class::<plan::PyPlan>()?;
    m.add_class::<plan::PyCandidates>()?;
    m.add_class::<plan::PyExplorationStatus>()?;
    m.add_class::<world::PyWorld>()?;
    m.add_class::<building::PyBuilding>()?;
    m.add_class::<building::PyRoom>()?;
    m.add_class::<building::PyDoor>()?;
    m.add_class::<sim_sensor::PySonarRing>()?;
    m.add_class::<sim_sensor::PyLaser>()?;
    m.add_class::<robot::PyRobot>()?;
    m.add_function(wrap_pyfunction!(experiments::run_fig3, m)?)?;
    m.add_function(wrap_pyfunction!(experiments::run_learn, m)?)?;
    m.add_function(wrap_pyfunction!(learn::log_likelihood, m)?)?;
    m.add_function(wrap_pyfunction!(learn::fit_sensor_model, m)?)?;
    m.add_class::<learn::PySensorFit>()?;
    m.add_class::<strategy::PyStrategy>()?;
    m.add(
        "DEFAULT_DISCOUNT_BEYOND_M",
        covmap::exploration::DEFAULT_DISCOUNT_BEYOND_M,
    )?;
    m.add_function(wrap_pyfunction!(exploration::explore, m)?)?;
    m.add_class::<exploration::PyExploration>()?;
    // Not in `__all__`: the defaults of `explore`'s keywords, for the
    // package's test that its signature shows the simulator's.
    m.setattr("_EXPLORE_DEFAULTS", exploration::defaults(m.py())?)?;
    // Not in `__all__`: a helper of the package (covmap.plot), not its API.
    m.setattr("write_atomic", wrap_pyfunction!(files::write_atomic, m)?)?;
    m.setattr(
        "check_write_target",
        wrap_pyfunction!(files::check_write_target, m)?,
    )?;
    m.setattr(
        "flow_collections",
        wrap_pyfunction!(files::flow_collections, m)?,
    )?;
    m.setattr("MAX_FLOW_COLLECTIONS", covmap::sim::MAX_FLOW_COLLECTIONS)?;
    Ok(())
}
