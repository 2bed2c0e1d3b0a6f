//! Learning the inverse sensor model from data by maximum likelihood, as the
//! paper does (section 5 of [the model](crate::model); paper Fig. 2).
//!
//! A map is built from a recorded drive ([`crate::Log`]) with a candidate
//! model, and the ground truth (the exact coverage of every cell, from
//! surveyed polygons or a simulated world) is scored under the map's
//! histograms ([`log_likelihood`]). [`fit_sensor_model`] searches the
//! model's parameters ([`Fittable`]) for the highest score with Nelder-Mead
//! (from `argmin`), restarted from seeded points, the restarts in parallel.
//!
//! # Example
//! ```
//! use covmap_core::learn::{FitData, FitOptions, fit_sensor_model};
//! use covmap_core::{Bearings, Grid, LaserModel, Log, Pose};
//! // A wall at x = 2 m, seen from three poses by a two-beam laser.
//! let grid = Grid::new([0.0, 0.0], 0.1, 20, 30).unwrap();
//! let mut truth = vec![0.0; grid.len()];
//! for row in 0..20 {
//!     truth[row * 30 + 20] = 1.0;
//! }
//! let poses: Vec<Pose> = (0..3).map(|i| Pose::new(0.5, 0.5 + 0.4 * i as f64, 0.0)).collect();
//! let ranges: Vec<f64> = (0..3).flat_map(|_| [1.5, 1.5]).collect();
//! let bearings = Bearings::Fixed(vec![0.0, 0.05]);
//! let log = Log::new(poses, vec![0.0, 1.0, 2.0], ranges, bearings, 30.0).unwrap();
//! let data = FitData { log: &log, grid, truth: &truth, cells: None };
//! let options = FitOptions {
//!     parameters: Some(vec!["sigma_min".into(), "xi_min".into()]),
//!     max_evaluations: 40,
//!     ..FitOptions::default()
//! };
//! let fit = fit_sensor_model(&data, &LaserModel::default(), &options, &|_| {}).unwrap();
//! assert!(fit.log_likelihood >= fit.initial_log_likelihood);
//! assert!(fit.evaluations <= 40);
//! ```

mod fit;
mod likelihood;
mod parameters;
mod point;

pub use fit::{
    FitData, FitEvaluation, FitOptions, MAX_EVALUATIONS, MAX_RESTARTS, SensorFit, fit_sensor_model,
    map_of_log,
};
pub use likelihood::{cell_log_likelihoods, check_truth, log_likelihood};
pub use parameters::{Fittable, Parameter};
