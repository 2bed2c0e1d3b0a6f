//! The coverage map's file on any bytes: a map saved bit for bit again, or
//! an error.
#![no_main]

use covmap::CoverageMap;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(map) = CoverageMap::from_file_bytes(data) {
        // Whatever loads saves and loads as the same map.
        let again = CoverageMap::from_file_bytes(&map.to_file_bytes().unwrap()).unwrap();
        assert_eq!(again.histograms(), map.histograms());
    }
});
