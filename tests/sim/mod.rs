//! The simulator against the core and against real data.

mod exploration;
mod fig3;
mod worlds;

use std::path::PathBuf;

/// The shared real-data folder `../shared/data/worlds`, if present. When it is
/// absent the test is skipped with a message, except under `CI=true`, where a
/// missing data folder is a failure.
pub fn shared_worlds() -> Option<PathBuf> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../shared/data/worlds");
    if dir.is_dir() {
        return Some(dir);
    }
    let message = format!(
        "the shared data folder {} is absent (the real worlds live beside the checkout, in ../shared)",
        dir.display()
    );
    if std::env::var("CI").is_ok_and(|v| v == "true") {
        panic!("{message}; under CI=true this is a failure");
    }
    eprintln!("SKIPPED: {message}");
    None
}
