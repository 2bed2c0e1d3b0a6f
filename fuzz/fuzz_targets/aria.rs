//! The ARIA `.map` world reader on any text.
#![no_main]

use covmap::sim::World;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        let _ = World::from_aria_map_str(text, "fuzz.map", 0.1);
    }
});
