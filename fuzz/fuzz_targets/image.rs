//! PGM and PNG occupancy images on any bytes (a header claiming a huge
//! image must be refused before anything of its size is allocated).
#![no_main]

use covmap::sim::{ImageOptions, World};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let _ = World::from_image_bytes(data, "fuzz", &ImageOptions::new(0.05));
});
