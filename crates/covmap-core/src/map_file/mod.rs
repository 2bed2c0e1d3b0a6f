//! The coverage map's file: the whole posterior (grid, bins, histograms,
//! the entropy history if tracked) as a versioned `.npz` archive that
//! `numpy.load` opens without covmap, every byte of it checked on the way
//! in.
//!
//! `npz.rs` writes and reads the two layers numpy defines (a zip archive of
//! stored entries, each a `.npy` array); `posterior.rs` says which arrays a
//! map file holds and checks them. See [`CoverageMap::to_file_bytes`]
//! for the layout.
//!
//! [`CoverageMap::to_file_bytes`]: crate::CoverageMap::to_file_bytes
#![cfg_attr(not(test), warn(clippy::indexing_slicing))]

mod npz;
mod posterior;

pub use npz::MAX_MAP_FILE_BYTES;
pub use posterior::MAP_FILE_VERSION;
