//! The CARMEN reader on any bytes (plain or gzip): a log or an error, never
//! a panic, a hang or an allocation the input does not pay for.
#![no_main]

use covmap::{CarmenOptions, Log};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let _ = Log::read_carmen(
        std::io::Cursor::new(data.to_vec()),
        "fuzz",
        &CarmenOptions::default(),
    );
});
