//! The coverage map: one histogram over coverage values per cell.

mod changes;
mod contact;
mod evidence;
mod history;
mod occlusion;
mod storage;
mod update;

pub use changes::{ChangeCursor, Changes};
pub use contact::CONTACT_COVERAGE;
pub use history::{HistoryState, STAGNATION_MEASUREMENTS, STAGNATION_NATS};
pub use occlusion::{Occluding, ScanReading, integrate_log_occluded, integrate_log_occluded_by};
pub use storage::CoverageMap;
pub(crate) use update::{check_reaches, check_sight};
