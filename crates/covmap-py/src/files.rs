//! `covmap._native.write_atomic`: a file written whole or not at all, by the
//! simulator's writer (the one its GeoJSON files and pictures go through).
//! `covmap.plot.save_figure` writes its PNGs through it, so that the package
//! has one atomic write.

use std::path::PathBuf;

use pyo3::prelude::*;

use crate::errors::OrRaise;

/// Write ``data`` to ``path`` atomically: a temporary file of a short name of
/// its own in the same directory, flushed to disk, then renamed over
/// ``path``, so a reader never sees a partial file; on failure nothing is
/// left behind. The directory must exist. A file that cannot be written
/// raises ``FileIOError`` (an ``OSError``). Runs with the GIL released.
#[pyfunction]
pub(crate) fn write_atomic(py: Python<'_>, path: PathBuf, data: &[u8]) -> PyResult<()> {
    py.detach(|| covmap::sim::write_atomic(&path, data))
        .or_raise(py)
}
