//! The map_server YAML reader on any text: the image's name and the
//! options, or an error. The text is parsed as the reader parses a file's
//! (the image it names is the image target's), so nothing is written.
#![no_main]

use std::path::Path;

use covmap::sim::parse_ros_map_yaml;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        let _ = parse_ros_map_yaml(text, Path::new("fuzz.yaml"));
    }
});
