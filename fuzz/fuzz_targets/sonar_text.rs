//! The plain-text sonar reader on any two files: the input split at its
//! first zero byte into the poses and the measurements.
#![no_main]

use covmap::{Log, SonarTextOptions};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let at = data.iter().position(|&b| b == 0).unwrap_or(data.len());
    let (poses, measurements) = (
        data[..at].to_vec(),
        data[(at + 1).min(data.len())..].to_vec(),
    );
    let options = SonarTextOptions {
        bearings_rad: [-90.0, -37.5, -22.5, -7.5, 7.5, 22.5, 37.5, 90.0_f64]
            .iter()
            .map(|d| d.to_radians())
            .collect(),
        length_unit_m: 0.001,
        range_unit_m: 0.001,
        angle_unit_rad: std::f64::consts::PI / 1800.0,
        min_range_m: 0.17,
        max_range_m: 5.0,
        no_echo: Some(5110.0),
    };
    let cursor = std::io::Cursor::new;
    let _ = Log::read_sonar_text(
        cursor(poses),
        "poses",
        cursor(measurements),
        "measurements",
        &options,
    );
});
