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
/// then a rename, so a reader never sees half a file. Every call writes its
/// own temporary file (named by the process and a count of the calls), so
/// writes of one path from several threads or processes at once each land
/// whole; the last rename wins.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    use std::sync::atomic::{AtomicU64, Ordering};
    static CALLS: AtomicU64 = AtomicU64::new(0);
    let io = |source| SimError::Io { path: path.to_path_buf(), source };
    let name = path
        .file_name()
        .ok_or_else(|| io(std::io::Error::new(std::io::ErrorKind::InvalidInput, "the path names no file")))?;
    let mut tmp_name = std::ffi::OsString::from(".");
    tmp_name.push(name);
    tmp_name.push(format!(".tmp{}-{}", std::process::id(), CALLS.fetch_add(1, Ordering::Relaxed)));
    let tmp = path.with_file_name(tmp_name);
    let result = (|| {
        use std::io::Write;
        // Never another writer's file: a name left over by a crash is an error.
        let mut f = std::fs::File::options().write(true).create_new(true).open(&tmp)?;
        f.write_all(bytes)?;
        f.sync_all()?;
        std::fs::rename(&tmp, path)
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result.map_err(io)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Writers of one path at once each write their own temporary file: every
    /// write succeeds and the file holds one of them whole.
    #[test]
    fn concurrent_writes_of_one_path_each_land_whole() {
        let dir = std::env::temp_dir().join(format!("covmap-sim-write-atomic-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("out.bin");
        for _ in 0..5 {
            std::thread::scope(|s| {
                let writes: Vec<_> = [b'a', b'b', b'c']
                    .map(|byte| {
                        s.spawn({
                            let path = &path;
                            move || write_atomic(path, &vec![byte; 1 << 20])
                        })
                    })
                    .into();
                for w in writes {
                    w.join().unwrap().unwrap();
                }
            });
            let bytes = std::fs::read(&path).unwrap();
            assert_eq!(bytes.len(), 1 << 20);
            assert!(bytes.iter().all(|&b| b == bytes[0]), "a file mixed from two writes");
        }
        let left: Vec<_> = std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().file_name()).collect();
        assert_eq!(left, [std::ffi::OsString::from("out.bin")], "temporary files left behind");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
