//! # covmap-sim
//!
//! The simulator of covmap: polygon worlds, their exact ground-truth coverage
//! on any [`covmap_core::Grid`], ray casting on parry2d, simulated sonar rings
//! and lasers whose scans feed [`covmap_core::ScanMap::integrate`]
//! directly, a disc robot's collision checks, and the paper's experiments.
//!
//! ```
//! use covmap_core::{CoverageMap, Grid, Pose, ScanMap, SonarModel};
//! use covmap_sim::{sim_rng, RangeSensor, SonarRing, World};
//!
//! let world = World::builtin("corridor").unwrap();
//! let grid = Grid::covering(-0.5, -0.5, 17.5, 6.5, 0.05).unwrap();
//! let truth = world.coverage(&grid); // exact fraction of each cell covered
//! let mut map = CoverageMap::new(grid);
//! let sonar = SonarRing::default(); // 24 sensors, the default SonarModel's cone
//! let mut rng = sim_rng(1);
//! for i in 0..20 {
//!     let pose = Pose::new(1.0 + 0.2 * i as f64, 1.3, 0.0);
//!     let scan = sonar.scan(&world, &pose, &mut rng).unwrap();
//!     map.integrate(&pose, &scan.ranges_m, &scan.bearings_rad, &SonarModel::default()).unwrap();
//! }
//! assert_eq!(truth.len(), map.ml().len());
//! ```
//!
//! Geometry is `f64` throughout; angles are radians; every random draw comes
//! from a seeded [`SimRng`]. parry2d types never appear in the API: points are
//! `[f64; 2]` in metres.
#![warn(missing_docs)]
#![cfg_attr(not(test), deny(clippy::unwrap_used, clippy::expect_used))]

pub mod building;
mod builtin;
mod error;
pub mod experiments;
pub mod exploration;
mod laser;
pub mod load;
mod material;
mod picture;
mod polygon;
mod ray_tree;
mod raycast;
pub mod reached;
mod rng;
mod robot;
mod scan;
mod simulate;
mod sonar;
pub mod truth;
mod world;

pub use building::{Building, BuildingOptions};
pub use error::{MAX_BEAMS, Result, SimError};
pub use laser::Laser;
pub use load::image::ImageOptions;
pub use load::map_server::{
    MAX_FLOW_COLLECTIONS, RosMapMode, flow_collections, parse_ros_map_yaml, write_ros_map,
};
pub use load::{MAX_FILE_BYTES, check_write_target, read_bytes, read_bytes_at_most, write_atomic};
pub use material::Material;
pub use picture::write_map_png;
pub use polygon::Polygon;
pub use raycast::RayHit;
pub use rng::{SimRng, sim_rng, sim_rng_stream};
pub use robot::Robot;
pub use scan::Scan;
pub use simulate::{Beam, RangeSensor, record, simulate};
pub use sonar::{MAX_RAYS_PER_CONE, SonarRing};
pub use world::World;
