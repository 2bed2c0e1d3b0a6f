//! Closed-loop exploration: a robot scans, chooses where to look next on
//! the maps it builds, drives there scanning on the way, and stops when its
//! strategy is done ([the model](crate::model), section 4; the paper's
//! Table I).
//!
//! The loop ([`Exploration`], in `exploration.rs`: one file to read from
//! scan to decision to motion) knows the robot through two small traits, a
//! [`ScanSource`] and a [`Motion`]; `covmap_sim` implements them with a
//! simulated sensor and a disc robot in a true world, and a log replay or a
//! real robot can be others. The strategies ([`Strategy`], one file each in
//! `strategy/`) choose on the maps only.
//!
//! # Example
//! A robot with one laser beam in an empty 4 m x 4 m room whose walls its
//! motion stops it at.
//! ```
//! use covmap_core::exploration::{
//!     AnySensorModel, Exploration, ExplorationSetup, Motion, ScanSource, Strategy, Travel,
//! };
//! use covmap_core::{Grid, Pose, Result};
//!
//! /// Distance from (x, y) along `angle` to the walls of the room [0, 4]^2.
//! fn to_wall(x: f64, y: f64, angle: f64) -> f64 {
//!     let (s, c) = angle.sin_cos();
//!     let tx = if c > 0.0 { (4.0 - x) / c } else if c < 0.0 { -x / c } else { f64::INFINITY };
//!     let ty = if s > 0.0 { (4.0 - y) / s } else if s < 0.0 { -y / s } else { f64::INFINITY };
//!     tx.min(ty)
//! }
//! struct Ring(Vec<f64>);
//! impl ScanSource for Ring {
//!     fn bearings(&self) -> &[f64] { &self.0 }
//!     fn scan(&mut self, p: &Pose) -> Result<Vec<f64>> {
//!         Ok(self.0.iter().map(|b| to_wall(p.x_m, p.y_m, p.theta_rad + b)).collect())
//!     }
//! }
//! struct Free;
//! impl Motion for Free {
//!     fn drive(&mut self, from: [f64; 2], to: [f64; 2]) -> Result<Travel> {
//!         Ok(Travel { travelled_m: (to[0] - from[0]).hypot(to[1] - from[1]), contact_m: None })
//!     }
//! }
//! let bearings = (0..90).map(|i| i as f64 * std::f64::consts::TAU / 90.0).collect();
//! let grid = Grid::covering(-0.5, -0.5, 4.5, 4.5, 0.05).unwrap();
//! let mut setup = ExplorationSetup::new(grid, Pose::new(1.0, 1.0, 0.0), Strategy::counting(1, None).unwrap());
//! setup.model = AnySensorModel::laser();
//! let mut run = Exploration::new(setup, Ring(bearings), Free).unwrap();
//! let termination = run.run().unwrap();
//! assert!(termination.by_rule(), "{termination}");
//! assert!(run.scans() > 1 && run.path_length_m() > 0.0);
//! ```

mod config;
mod evaluation;
#[allow(clippy::module_inception)]
mod exploration;
mod region;
mod result;
mod sensor;
mod source;
mod strategy;

pub use config::ExplorationConfig;
pub use evaluation::{high_entropy_fraction, mean_absolute_error};
pub use exploration::{Exploration, ExplorationSetup};
pub use region::dilate;
pub use result::{ExplorationResult, StepReport, Termination, Timing, Trace, Trajectory};
pub use sensor::AnySensorModel;
pub use source::{Motion, ScanSource, Travel};
pub use strategy::{DEFAULT_DISCOUNT_BEYOND_M, Strategy};
