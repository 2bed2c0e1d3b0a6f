//! # covmap
//!
//! Coverage maps for mobile robots: probabilistic grid mapping where every cell
//! holds a histogram over how much of it is covered by obstacles, and
//! information-driven exploration on top of them (Stachniss and Burgard, 2003).
//!
//! This facade re-exports the whole library: [`covmap_core`] (maps, sensor
//! models, updates, baselines) at the top level and [`covmap_sim`] (polygon
//! worlds, ground truth, simulated sensors) as [`sim`].
#![warn(missing_docs)]

pub use covmap_core::*;
pub use covmap_sim as sim;
