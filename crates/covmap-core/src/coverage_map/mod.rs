//! The coverage map: one histogram over coverage values per cell.

mod history;
mod storage;
mod update;

pub use history::{HistoryState, STAGNATION_MEASUREMENTS, STAGNATION_NATS};
pub use storage::CoverageMap;
