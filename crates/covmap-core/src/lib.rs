//! # covmap-core
//!
//! Coverage maps (Stachniss and Burgard, 2003): a grid whose every cell holds a
//! histogram posterior over *how much* of the cell is covered by obstacles,
//! updated by Bayes' rule with an inverse sensor model for sonar cones and laser
//! beams; the occupancy-grid and scan-counting baselines fed by the same beams.
//!
//! ```
//! use covmap_core::{CoverageMap, Grid, Pose, ScanMap, SonarModel};
//! let grid = Grid::new([0.0, 0.0], 0.05, 200, 200).unwrap();
//! let mut map = CoverageMap::new(grid);
//! // A ring of 24 sonars in the middle of a round room of radius 2.5 m.
//! let bearings: Vec<f64> = (0..24).map(|i| i as f64 * std::f64::consts::TAU / 24.0).collect();
//! let ranges = vec![2.5; 24];
//! for _ in 0..5 {
//!     map.integrate(&Pose::new(5.0, 5.0, 0.0), &ranges, &bearings, &SonarModel::default()).unwrap();
//! }
//! let (ml, entropy) = (map.ml(), map.entropy());
//! let at = |x: f64, y: f64| grid.index(grid.world_to_cell(x, y).unwrap()).unwrap();
//! assert_eq!(ml[at(6.0, 5.0)], 0.0); // inside the room: empty
//! assert_eq!(ml[at(7.6, 5.0)], 1.0); // just behind the wall: covered
//! assert!(entropy[at(6.0, 5.0)] < 0.5 * 16f32.ln());
//! assert!((entropy[at(9.0, 9.0)] - 16f32.ln()).abs() < 1e-6); // never seen: the prior
//! ```
#![warn(missing_docs)]
#![cfg_attr(not(test), deny(clippy::unwrap_used, clippy::expect_used))]

mod aligned;
mod counting;
mod coverage_map;
mod echo_sources;
mod error;
pub mod exploration;
mod footprint;
pub mod gain;
mod grid;
pub mod histogram;
pub mod learn;
pub mod log;
mod map_file;
pub mod memory;
#[doc = include_str!("model.md")]
pub mod model {}
mod numeric;
mod occupancy;
pub mod parallel;
pub mod planner;
mod pose;
mod ros_occupancy;
mod scan_map;
pub mod sensor;
mod sight;
mod stamp;
#[cfg(test)]
mod test_rng;

pub use counting::ScanCounts;
pub use coverage_map::{
    CONTACT_COVERAGE, ChangeCursor, Changes, CoverageMap, HistoryState, Occluding,
    STAGNATION_MEASUREMENTS, STAGNATION_NATS, ScanReading, integrate_log_occluded,
    integrate_log_occluded_by,
};
pub use echo_sources::EchoSources;
pub use error::{CovmapError, QUOTED_CHARS, Result, quoted};
pub use grid::{Cell, Grid, MAX_CELLS, MAX_CELLS_FROM_ZERO, MIN_RESOLUTION_M};
pub use log::{Bearings, CarmenLaser, CarmenOptions, Log, SonarTextOptions};
pub use map_file::{MAP_FILE_VERSION, MAX_MAP_FILE_BYTES};
pub use occupancy::{OccupancyGrid, OccupancyModel};
pub use pose::Pose;
pub use ros_occupancy::{CoverageValue, ROS_UNKNOWN};
pub use scan_map::{ScanBeams, ScanMap};
pub use sensor::{Footprint, KernelTable, LaserModel, RangeModel, SensorModel, SonarModel};
pub use sight::NoEchoSight;
