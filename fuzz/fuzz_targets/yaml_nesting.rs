//! The nesting bound of the map_server YAML reader: a valid file with a
//! value under a key map_server ignores, written by the fuzzer in YAML's
//! structural characters (brackets, braces, commas, colons, quotes, dashes,
//! line breaks). A file holding more than `MAX_FLOW_COLLECTIONS` flow
//! collections that hold something is refused before it is parsed; any
//! other is parsed, within libFuzzer's time limit.
#![no_main]

use std::path::Path;

use covmap::sim::{MAX_FLOW_COLLECTIONS, flow_collections, parse_ros_map_yaml};
use libfuzzer_sys::fuzz_target;

/// What the fuzzer's bytes spell the ignored value in.
const ALPHABET: &[u8] = b"[]{},: \"'a-\n#";

fuzz_target!(|data: &[u8]| {
    let value: String = data
        .iter()
        .map(|b| char::from(ALPHABET[usize::from(*b) % ALPHABET.len()]))
        .collect();
    let text = format!(
        "image: map.pgm\nresolution: 0.05\norigin: [0.0, 0.0, 0.0]\nignored: {value}\n"
    );
    let result = parse_ros_map_yaml(&text, Path::new("fuzz.yaml"));
    if flow_collections(&text) > MAX_FLOW_COLLECTIONS {
        assert!(result.is_err(), "a file over the bound was parsed");
    }
});
