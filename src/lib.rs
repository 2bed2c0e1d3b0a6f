//! # covmap
//!
//! Coverage maps for mobile robots: probabilistic grid mapping where every cell
//! holds a histogram over how much of it is covered by obstacles, and
//! information-driven exploration on top of them (Stachniss and Burgard, 2003).
//!
//! This facade re-exports the whole library: [`covmap_core`] (maps, sensor
//! models, updates, baselines).
#![warn(missing_docs)]

pub use covmap_core::*;
