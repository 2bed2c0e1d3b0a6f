//! Building worlds from files.
//!
//! | format | constructor | what becomes an obstacle |
//! | --- | --- | --- |
//! | GeoJSON ([`geojson`]) | [`World::from_geojson_file`](crate::World::from_geojson_file) | every `Polygon` / `MultiPolygon`, coordinates in metres |
//! | ARIA `.map` ([`aria`]) | [`World::from_aria_map_file`](crate::World::from_aria_map_file) | every `LINES` segment, as a wall of a given thickness |
//! | PGM / PNG + resolution ([`image`]) | [`World::from_image_file`](crate::World::from_image_file) | every run of dark pixels, as a rectangle |
//! | ROS map_server YAML ([`image`]) | [`World::from_ros_map_yaml`](crate::World::from_ros_map_yaml) | as above, with the YAML's resolution, origin and thresholds |
//!
//! Malformed or degenerate input is a [`SimError::Parse`]
//! naming the file and the place: a line, a feature, a pixel.

pub mod aria;
pub mod geojson;
pub mod image;

use std::path::{Path, PathBuf};

use crate::error::{Result, SimError};

pub(crate) fn read_bytes(path: &Path) -> Result<Vec<u8>> {
    std::fs::read(path).map_err(|source| SimError::Io { path: path.to_path_buf(), source })
}

pub(crate) fn read_text(path: &Path) -> Result<String> {
    let bytes = read_bytes(path)?;
    String::from_utf8(bytes).map_err(|e| SimError::Parse {
        path: path.to_path_buf(),
        place: format!("byte {}", e.utf8_error().valid_up_to()),
        reason: "the file is not UTF-8 text".into(),
    })
}

/// A parse error at `place` of `path`.
pub(crate) fn parse_error(path: &Path, place: impl Into<String>, reason: impl Into<String>) -> SimError {
    SimError::Parse { path: PathBuf::from(path), place: place.into(), reason: reason.into() }
}

/// Write `bytes` to `path` atomically: a temporary file in the same directory,
/// then a rename, so a reader never sees half a file.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    let io = |source| SimError::Io { path: path.to_path_buf(), source };
    let name = path
        .file_name()
        .ok_or_else(|| io(std::io::Error::new(std::io::ErrorKind::InvalidInput, "the path names no file")))?;
    let mut tmp_name = std::ffi::OsString::from(".");
    tmp_name.push(name);
    tmp_name.push(format!(".tmp{}", std::process::id()));
    let tmp = path.with_file_name(tmp_name);
    let result = (|| {
        use std::io::Write;
        let mut f = std::fs::File::create(&tmp)?;
        f.write_all(bytes)?;
        f.sync_all()?;
        std::fs::rename(&tmp, path)
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result.map_err(io)
}
