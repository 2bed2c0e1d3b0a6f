//! Exploration in simulation: the core's loop
//! ([`covmap_core::exploration`]) driving a simulated robot through a true
//! [`World`](crate::World).
//!
//! - [`WorldScans`]: the simulated sensor as the loop's scan source (scan
//!   `k`'s noise from stream `k` of the seed);
//! - [`WorldMotion`]: the disc [`Robot`](crate::Robot) against the world's
//!   obstacles as the loop's motion;
//! - [`explore`] / [`SimExploration`]: a run on a grid over the world's
//!   bounds plus a margin, from a given or a seeded start, measured on
//!   evaluation cells defined from the world alone ([`cells`]).
//!
//! The same seed gives the same run, bit for bit, at any thread count.

pub mod cells;
mod options;
mod robot_io;
mod run;
mod sensor;

pub use cells::{
    START_STREAM, check_start, choose_start, clearances, evaluation_cells, free_regions,
    start_region,
};
pub use options::ExploreOptions;
pub use robot_io::{STANDOFF_M, WorldMotion, WorldScans};
pub use run::{ExplorationErrors, ExplorationRun, SimExploration, WorldExploration, explore};
pub use sensor::SimSensor;
