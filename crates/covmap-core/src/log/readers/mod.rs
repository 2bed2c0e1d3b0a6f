//! Readers of recorded logs, one format a file: [`carmen`] (CARMEN's
//! `FLASER`, `ROBOTLASER1`, `RAWLASER1` and `ODOM`), [`sonar_text`]
//! (plain-text sonar rings). Each streams its file line by line, plain or
//! gzip, and names the file and the line of any error.
#![cfg_attr(not(test), warn(clippy::indexing_slicing))]

pub mod carmen;
pub mod sonar_text;
mod source;

pub use source::{MAX_GZIP_RATIO, MAX_LINE_BYTES};
