//! The map_server YAML reader on any text, naming a small valid PGM beside
//! it (the file is the reader's input: it reads from a path).
#![no_main]

use covmap::sim::World;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let dir = std::env::temp_dir().join(format!("covmap-fuzz-yaml-{}", std::process::id()));
    if std::fs::create_dir_all(&dir).is_err() {
        return;
    }
    let pgm = b"P5\n4 2\n255\n\x00\xff\xff\x00\xff\x00\x00\xff".to_vec();
    if std::fs::write(dir.join("map.pgm"), pgm).is_err()
        || std::fs::write(dir.join("map.yaml"), data).is_err()
    {
        return;
    }
    let _ = World::from_ros_map_yaml(dir.join("map.yaml"));
});
