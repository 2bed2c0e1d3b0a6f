//! Building worlds from files.
//!
//! | format | constructor | what becomes an obstacle |
//! | --- | --- | --- |
//! | GeoJSON ([`geojson`]) | [`World::from_geojson_file`](crate::World::from_geojson_file) | every `Polygon` / `MultiPolygon`, coordinates in metres |
//! | ARIA `.map` ([`aria`]) | [`World::from_aria_map_file`](crate::World::from_aria_map_file) | every `LINES` segment, as a wall of a given thickness |
//! | PGM / PNG + resolution ([`image`]) | [`World::from_image_file`](crate::World::from_image_file) | every run of dark pixels, as a rectangle |
//! | ROS map_server YAML ([`image`]) | [`World::from_ros_map_yaml`](crate::World::from_ros_map_yaml) | as above, with the YAML's resolution, origin and thresholds |
//!
//!
//! Written: the map_server pair, PGM + YAML ([`map_server`]:
//! [`write_ros_map`](crate::write_ros_map)), which the last row reads back.
//!
//! Each format has one reader, named in the table; images are read and
//! written through the `image` crate, YAML through `serde_norway`, JSON
//! through `serde_json`. Malformed or degenerate input is a
//! [`SimError::Parse`] naming the file and the place: a line, a feature, a
//! part of an image.

pub mod aria;
pub mod geojson;
pub mod image;
pub mod map_server;

use std::path::{Path, PathBuf};

use crate::error::{Result, SimError};

/// The largest world or image file read, bytes (1 GiB); a covmap map file
/// has its own, [`MAX_MAP_FILE_BYTES`](covmap_core::MAX_MAP_FILE_BYTES).
pub const MAX_FILE_BYTES: u64 = 1 << 30;

/// The bytes of the regular file at `path`, at most [`MAX_FILE_BYTES`].
/// Anything else (a directory, a pipe that may never open or never end, a
/// device) is refused before it is opened, and a file that grows past the
/// limit while it is read is refused too.
pub fn read_bytes(path: &Path) -> Result<Vec<u8>> {
    read_bytes_at_most(path, MAX_FILE_BYTES)
}

/// [`read_bytes`] with the limit `max_bytes` in place of
/// [`MAX_FILE_BYTES`]: for files whose writer has a limit of its own (a
/// covmap map file, up to
/// [`MAX_MAP_FILE_BYTES`](covmap_core::MAX_MAP_FILE_BYTES)), so that what
/// was written can be read back.
pub fn read_bytes_at_most(path: &Path, max_bytes: u64) -> Result<Vec<u8>> {
    use std::io::Read;
    let io = |source| SimError::Io {
        path: path.to_path_buf(),
        source,
    };
    let refuse = |reason: String| {
        io(std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            reason,
        ))
    };
    let metadata = std::fs::metadata(path).map_err(io)?;
    if !metadata.is_file() {
        return Err(refuse("not a regular file".into()));
    }
    if metadata.len() > max_bytes {
        return Err(refuse(format!(
            "{} bytes is larger than the limit of {max_bytes} bytes",
            metadata.len()
        )));
    }
    let file = std::fs::File::open(path).map_err(io)?;
    let mut bytes = Vec::new();
    file.take(max_bytes.saturating_add(1))
        .read_to_end(&mut bytes)
        .map_err(io)?;
    if bytes.len() as u64 > max_bytes {
        return Err(refuse(format!(
            "the file grew past the limit of {max_bytes} bytes while it was read"
        )));
    }
    Ok(bytes)
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
pub(crate) fn parse_error(
    path: &Path,
    place: impl Into<String>,
    reason: impl Into<String>,
) -> SimError {
    SimError::Parse {
        path: PathBuf::from(path),
        place: place.into(),
        reason: reason.into(),
    }
}

/// Whether covmap may write `path`: nothing is there yet, or a regular file
/// is (which a write replaces whole). Anything else is refused, since the
/// rename that puts a new file in place would replace it by a regular file:
/// a directory, a device (`/dev/null`), a FIFO, a socket, and a symlink,
/// whatever it leads to. A symlink is not followed: covmap replaces only the
/// files it sees at the paths it is given (following a link would replace a
/// file anywhere the link leads, replacing the link would cut it), so write
/// to the path the link leads to instead. A path that names no file
/// (`dir/..`) is refused too.
///
/// # Errors
/// [`SimError::Io`] naming the path and what is there (an `InvalidInput`
/// error), or the error of reading the path's metadata.
pub fn check_write_target(path: &Path) -> Result<()> {
    let refuse = |reason: String| SimError::Io {
        path: path.to_path_buf(),
        source: std::io::Error::new(std::io::ErrorKind::InvalidInput, reason),
    };
    if path.file_name().is_none() {
        return Err(refuse("the path names no file".into()));
    }
    let metadata = match std::fs::symlink_metadata(path) {
        Ok(m) => m,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(()),
        Err(source) => {
            return Err(SimError::Io {
                path: path.to_path_buf(),
                source,
            });
        }
    };
    let kind = metadata.file_type();
    if kind.is_file() {
        return Ok(());
    }
    Err(refuse(format!(
        "the path is {}, not a regular file: covmap replaces only regular files{}",
        file_kind(&kind),
        if kind.is_symlink() {
            " (a symlink is not followed: write to the file it leads to)"
        } else {
            ""
        }
    )))
}

/// What a file type is, for a message: "a directory", "a FIFO"...
fn file_kind(kind: &std::fs::FileType) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if kind.is_fifo() {
            return "a FIFO";
        }
        if kind.is_char_device() {
            return "a character device";
        }
        if kind.is_block_device() {
            return "a block device";
        }
        if kind.is_socket() {
            return "a socket";
        }
    }
    if kind.is_dir() {
        "a directory"
    } else if kind.is_symlink() {
        "a symlink"
    } else {
        "not a regular file"
    }
}

/// Write `bytes` to `path` atomically: a temporary file in the same directory,
/// then a rename, so a reader never sees half a file. Every call creates a
/// temporary file of its own, with a short name (so that the longest valid
/// file name still has room) that no existing file has: writes of one path
/// from several threads or processes at once each land whole (the last
/// rename wins), and a temporary file left over by a crash is stepped
/// around, never reused. A path that is not a regular file or absent (a
/// directory, a device, a FIFO, a symlink: see [`check_write_target`]) is
/// refused before anything is written, and checked again just before the
/// rename.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    write_atomic_all(&[(path, bytes)])
}

/// Write each `(path, bytes)` of `files` as [`write_atomic`] does, all or
/// none as far as the file system allows: every path is checked first
/// ([`check_write_target`]), every file is written whole to a
/// temporary file beside its path first, and only when all are complete are
/// they renamed into place, in order. If a rename fails, the files already
/// renamed are put back as they were (the old file kept under a temporary
/// hard link until then, or removed if there was none) and the temporary
/// files are removed.
pub(crate) fn write_atomic_all(files: &[(&Path, &[u8])]) -> Result<()> {
    write_atomic_all_with(files, |from, to| std::fs::rename(from, to))
}

/// [`write_atomic_all`], renaming by `rename` (a test's can fail).
fn write_atomic_all_with(
    files: &[(&Path, &[u8])],
    rename: impl Fn(&Path, &Path) -> std::io::Result<()>,
) -> Result<()> {
    let io = |path: &Path, source| SimError::Io {
        path: path.to_path_buf(),
        source,
    };
    for &(path, _) in files {
        check_write_target(path)?;
    }
    let remove = |paths: &[PathBuf]| {
        for p in paths {
            let _ = std::fs::remove_file(p);
        }
    };
    let mut temporaries = Vec::with_capacity(files.len());
    for &(path, bytes) in files {
        match write_temporary(path, bytes) {
            Ok(tmp) => temporaries.push(tmp),
            Err(e) => {
                remove(&temporaries);
                return Err(io(path, e));
            }
        }
    }
    // Each file put in place but the last, with its old file if it had one.
    let mut placed: Vec<(&Path, Option<PathBuf>)> = Vec::new();
    for (i, (&(path, _), tmp)) in files.iter().zip(&temporaries).enumerate() {
        // The last file needs no way back: nothing after it can fail.
        let last = i + 1 == files.len();
        let step = (|| {
            // Again: something may have been put there while the files were
            // written.
            check_write_target(path).map_err(|e| match e {
                SimError::Io { source, .. } => source,
                other => std::io::Error::other(other.to_string()),
            })?;
            let old = if last { None } else { keep_old(path)? };
            if let Err(e) = rename(tmp, path) {
                remove(old.as_slice());
                return Err(e);
            }
            Ok(old)
        })();
        match step {
            Ok(old) if !last => placed.push((path, old)),
            Ok(_) => {}
            Err(e) => {
                for (done, old) in placed.into_iter().rev() {
                    let _ = match old {
                        Some(old) => std::fs::rename(old, done),
                        None => std::fs::remove_file(done),
                    };
                }
                remove(&temporaries[i..]);
                return Err(io(path, e));
            }
        }
    }
    for (_, old) in placed {
        remove(old.as_slice());
    }
    Ok(())
}

/// A temporary file beside `path` holding `bytes`, written and synced;
/// removed again if that fails.
fn write_temporary(path: &Path, bytes: &[u8]) -> std::io::Result<PathBuf> {
    use std::io::Write;
    let (tmp, mut f) = create_temporary(path)?;
    let written = f.write_all(bytes).and_then(|()| f.sync_all());
    match written {
        Ok(()) => Ok(tmp),
        Err(e) => {
            let _ = std::fs::remove_file(&tmp);
            Err(e)
        }
    }
}

/// The file at `path`, if there is one, kept under a new temporary name
/// beside it (a hard link, a copy where the file system has none), so that
/// replacing `path` can be undone.
fn keep_old(path: &Path) -> std::io::Result<Option<PathBuf>> {
    match std::fs::symlink_metadata(path) {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        Err(e) => return Err(e),
        Ok(_) => {}
    }
    if let Ok((link, ())) = with_temporary_name(path, |tmp| std::fs::hard_link(path, tmp)) {
        return Ok(Some(link));
    }
    let (copy, mut f) = create_temporary(path)?;
    let copied = std::fs::File::open(path)
        .and_then(|mut old| std::io::copy(&mut old, &mut f))
        .and_then(|_| f.sync_all());
    match copied {
        Ok(()) => Ok(Some(copy)),
        Err(e) => {
            let _ = std::fs::remove_file(&copy);
            Err(e)
        }
    }
}

/// A new file beside `path`, `.covmap-<16 hex digits>.tmp`, created where
/// no file of that name exists.
fn create_temporary(path: &Path) -> std::io::Result<(PathBuf, std::fs::File)> {
    with_temporary_name(path, |tmp| {
        std::fs::File::options()
            .write(true)
            .create_new(true)
            .open(tmp)
    })
}

/// `create(name)` for a name beside `path`, `.covmap-<16 hex digits>.tmp`,
/// until it does not fail for a name that exists. The digits mix the
/// process, a count of the calls and the clock, and a name that is taken is
/// skipped for the next.
fn with_temporary_name<T>(
    path: &Path,
    mut create: impl FnMut(&Path) -> std::io::Result<T>,
) -> std::io::Result<(PathBuf, T)> {
    use std::hash::{BuildHasher, Hasher};
    use std::sync::atomic::{AtomicU64, Ordering};
    static CALLS: AtomicU64 = AtomicU64::new(0);
    let mut last = None;
    for _ in 0..64 {
        // A randomly keyed hasher (the standard library's), so that processes
        // that share a directory and a pid (in two containers, say) still
        // draw different names.
        let mut h = std::collections::hash_map::RandomState::new().build_hasher();
        h.write_u32(std::process::id());
        h.write_u64(CALLS.fetch_add(1, Ordering::Relaxed));
        h.write_u128(
            std::time::SystemTime::now()
                .duration_since(std::time::UNIX_EPOCH)
                .map_or(0, |d| d.as_nanos()),
        );
        let tmp = path.with_file_name(format!(".covmap-{:016x}.tmp", h.finish()));
        match create(&tmp) {
            Ok(made) => return Ok((tmp, made)),
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => last = Some(e),
            Err(e) => return Err(e),
        }
    }
    Err(last.unwrap_or_else(|| std::io::Error::other("no free temporary name")))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Only regular files are read: a device that never ends and a directory
    /// are refused before they are opened, with an error naming the path.
    #[test]
    fn files_that_are_not_regular_are_refused_before_they_are_opened() {
        let tmp = tempfile::tempdir().unwrap();
        let dir = tmp.path();
        // /dev/zero is only read.
        for path in [Path::new("/dev/zero"), dir] {
            if !path.exists() {
                continue;
            }
            let err = read_bytes(path).unwrap_err().to_string();
            assert!(err.contains("not a regular file"), "{err}");
            assert!(err.contains(&path.display().to_string()), "{err}");
        }
        let file = dir.join("read.txt");
        std::fs::write(&file, b"twelve bytes").unwrap();
        assert_eq!(read_bytes(&file).unwrap(), b"twelve bytes");
    }

    /// A file up to the limit is read, one byte over it refused before it
    /// is read, naming the limit.
    #[test]
    fn a_file_over_the_limit_is_refused() {
        let tmp = tempfile::tempdir().unwrap();
        let file = tmp.path().join("limit");
        std::fs::write(&file, b"twelve bytes").unwrap();
        assert_eq!(read_bytes_at_most(&file, 12).unwrap(), b"twelve bytes");
        let err = read_bytes_at_most(&file, 11).unwrap_err().to_string();
        assert!(err.contains("limit of 11 bytes"), "{err}");
    }

    /// Every map file the core writes is within what a reader of map
    /// files takes, and that is more than the limit of other files: the
    /// reader of map files must not use [`read_bytes`]' limit.
    #[test]
    fn map_files_up_to_the_writers_limit_can_be_read() {
        const {
            assert!(covmap_core::MAX_MAP_FILE_BYTES >= u32::MAX as u64);
            assert!(covmap_core::MAX_MAP_FILE_BYTES > MAX_FILE_BYTES);
        }
    }

    /// Writers of one path at once each write their own temporary file: every
    /// write succeeds and the file holds one of them whole.
    #[test]
    fn concurrent_writes_of_one_path_each_land_whole() {
        let tmp = tempfile::tempdir().unwrap();
        let dir = tmp.path();
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
            assert!(
                bytes.iter().all(|&b| b == bytes[0]),
                "a file mixed from two writes"
            );
        }
        let left: Vec<_> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(
            left,
            [std::ffi::OsString::from("out.bin")],
            "temporary files left behind"
        );
    }

    /// The longest valid file name can be written (the temporary name does
    /// not grow with it), and a temporary file left by an earlier crash is
    /// left alone.
    #[test]
    fn long_names_and_leftovers_do_not_stop_a_write() {
        let tmp = tempfile::tempdir().unwrap();
        let dir = tmp.path();
        let long = dir.join("a".repeat(255));
        write_atomic(&long, b"long").unwrap();
        assert_eq!(std::fs::read(&long).unwrap(), b"long");
        let (stale, _) = create_temporary(&dir.join("out.json")).unwrap();
        std::fs::write(&stale, b"left by a crash").unwrap();
        write_atomic(&dir.join("out.json"), b"{}").unwrap();
        assert_eq!(std::fs::read(dir.join("out.json")).unwrap(), b"{}");
        assert_eq!(std::fs::read(&stale).unwrap(), b"left by a crash");
    }

    /// A FIFO, a socket, a symlink (to a regular file or to nothing) or a
    /// directory at a path is refused, naming what it is, and left as it
    /// was; nothing is written beside it, not even the other file of a pair.
    #[cfg(unix)]
    #[test]
    fn only_regular_files_are_replaced() {
        use std::os::unix::fs::FileTypeExt;
        let tmp = tempfile::tempdir().unwrap();
        let dir = tmp.path();
        let fifo = dir.join("fifo.png");
        let status = std::process::Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .unwrap();
        assert!(status.success());
        let socket = dir.join("socket.png");
        let _listener = std::os::unix::net::UnixListener::bind(&socket).unwrap();
        let target = dir.join("target.png");
        std::fs::write(&target, b"the link's file").unwrap();
        let link = dir.join("link.png");
        std::os::unix::fs::symlink(&target, &link).unwrap();
        let dangling = dir.join("dangling.png");
        std::os::unix::fs::symlink(dir.join("nothing"), &dangling).unwrap();
        let sub = dir.join("sub.png");
        std::fs::create_dir(&sub).unwrap();
        let other = dir.join("other.pgm");
        for (path, kind) in [
            (&fifo, "a FIFO"),
            (&socket, "a socket"),
            (&link, "a symlink"),
            (&dangling, "a symlink"),
            (&sub, "a directory"),
        ] {
            let err = write_atomic(path, b"new").unwrap_err().to_string();
            assert!(
                err.contains(kind) && err.contains("not a regular file"),
                "{err}"
            );
            assert!(err.contains(&path.display().to_string()), "{err}");
            let err = write_atomic_all(&[(&other, b"new"), (path, b"new")]).unwrap_err();
            assert!(err.to_string().contains(kind), "{err}");
            assert!(!other.exists(), "the other file of the pair was written");
        }
        assert!(
            std::fs::symlink_metadata(&fifo)
                .unwrap()
                .file_type()
                .is_fifo()
        );
        assert!(
            std::fs::symlink_metadata(&socket)
                .unwrap()
                .file_type()
                .is_socket()
        );
        assert_eq!(std::fs::read_link(&link).unwrap(), target);
        assert_eq!(std::fs::read(&target).unwrap(), b"the link's file");
        assert!(sub.is_dir());
        // A regular file, and a new one, are written.
        write_atomic(&target, b"replaced").unwrap();
        assert_eq!(std::fs::read(&target).unwrap(), b"replaced");
        write_atomic(&other, b"new").unwrap();
        assert_eq!(std::fs::read(&other).unwrap(), b"new");
    }

    /// A pair whose second file cannot be put in place leaves the first as
    /// it was (or absent, if it was), and no temporary file behind.
    #[test]
    fn a_pair_whose_second_rename_fails_leaves_both_files_as_they_were() {
        let tmp = tempfile::tempdir().unwrap();
        let dir = tmp.path();
        let (first, second) = (dir.join("map.pgm"), dir.join("map.yaml"));
        let fail_second = |from: &Path, to: &Path| {
            if to.extension().is_some_and(|e| e == "yaml") {
                Err(std::io::Error::from(std::io::ErrorKind::PermissionDenied))
            } else {
                std::fs::rename(from, to)
            }
        };
        let files: [(&Path, &[u8]); 2] = [(&first, b"new image"), (&second, b"new yaml")];
        let names = || {
            let mut n: Vec<_> = std::fs::read_dir(dir)
                .unwrap()
                .map(|e| e.unwrap().file_name().into_string().unwrap())
                .collect();
            n.sort();
            n
        };
        let err = write_atomic_all_with(&files, fail_second).unwrap_err();
        assert!(err.to_string().contains("map.yaml"), "{err}");
        assert!(names().is_empty(), "{:?}", names());
        std::fs::write(&first, b"old image").unwrap();
        std::fs::write(&second, b"old yaml").unwrap();
        write_atomic_all_with(&files, fail_second).unwrap_err();
        assert_eq!(std::fs::read(&first).unwrap(), b"old image");
        assert_eq!(std::fs::read(&second).unwrap(), b"old yaml");
        assert_eq!(names(), ["map.pgm", "map.yaml"]);
        write_atomic_all(&files).unwrap();
        assert_eq!(std::fs::read(&first).unwrap(), b"new image");
        assert_eq!(std::fs::read(&second).unwrap(), b"new yaml");
        assert_eq!(names(), ["map.pgm", "map.yaml"]);
        // A directory in the way is refused before anything is written.
        std::fs::remove_file(&second).unwrap();
        std::fs::create_dir(&second).unwrap();
        let err = write_atomic_all(&[(&first, b"newer"), (&second, b"newer")]).unwrap_err();
        assert!(err.to_string().contains("is a directory"), "{err}");
        assert_eq!(std::fs::read(&first).unwrap(), b"new image");
        assert_eq!(names(), ["map.pgm", "map.yaml"]);
    }
}
