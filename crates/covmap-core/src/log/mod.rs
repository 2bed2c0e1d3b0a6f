//! Recorded drives: the [`Log`] record (a pose, a timestamp and ranges a
//! scan), its readers ([`readers`]: CARMEN, plain-text sonar logs), the
//! conversion of ROS `sensor_msgs/LaserScan` conventions ([`laser_scan`]),
//! and `integrate_log` on the three maps (`integrate.rs`).
//!
//! A log is the edge between the world's files and the maps: readers turn
//! each format's conventions (units, no-echo values, dropped beams, where
//! the pose comes from) into one record, and the maps take that record
//! through their own per-scan update, checked as a whole first.

mod integrate;
pub mod laser_scan;
pub mod readers;
mod record;

pub(crate) use integrate::integrate_scans;
pub use readers::carmen::{CarmenLaser, CarmenOptions};
pub use readers::sonar_text::SonarTextOptions;
pub use record::{Bearings, Log};
