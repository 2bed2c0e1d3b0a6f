//! `covmap._native.write_atomic`: a file written whole or not at all, by the
//! simulator's writer (the one its GeoJSON files and pictures go through).
//! `covmap.plot.save_figure` writes its PNGs through it, so that the package
//! has one atomic write; `check_write_target`, its rule for what a write
//! may replace, for a command to check all its files before it writes one;
//! `flow_collections`, the simulator's bound on a YAML file's nesting, for
//! the YAML files read on the Python side (a ROS 2 bag's metadata).

use std::path::PathBuf;

use pyo3::prelude::*;

use crate::errors::OrRaise;

/// Write ``data`` to ``path`` atomically: a temporary file of a short name of
/// its own in the same directory, flushed to disk, then renamed over
/// ``path``, so a reader never sees a partial file; on failure nothing is
/// left behind. The directory must exist. A path where something other
/// than a regular file is (a directory, a device, a FIFO, a socket, a
/// symlink) is refused before anything is written, as is a file that cannot
/// be written: ``FileIOError`` (an ``OSError``). Runs with the GIL released.
#[pyfunction]
pub(crate) fn write_atomic(py: Python<'_>, path: PathBuf, data: &[u8]) -> PyResult<()> {
    py.detach(|| covmap::sim::write_atomic(&path, data))
        .or_raise(py)
}

/// Raise ``FileIOError`` unless ``write_atomic(path, ...)`` may write
/// ``path``: nothing is there, or a regular file is (a directory, a device,
/// a FIFO, a socket or a symlink is never replaced).
#[pyfunction]
pub(crate) fn check_write_target(py: Python<'_>, path: PathBuf) -> PyResult<()> {
    covmap::sim::check_write_target(&path).or_raise(py)
}

/// How many flow collections that hold something a YAML ``text`` may
/// open, at most: its ``[`` and ``{`` not closed at once (the bound of
/// ``MAX_FLOW_COLLECTIONS`` that map_server files are held to).
#[pyfunction]
pub(crate) fn flow_collections(text: &str) -> usize {
    covmap::sim::flow_collections(text)
}
