//! The log readers against the real logs in `../shared/data` (CARMEN laser
//! logs, the 8-sonar ring), each checked against a parse of its own here: a
//! plain split of every line.

use covmap::ScanMap;
use std::io::Read;
use std::path::PathBuf;

use covmap::{Bearings, CarmenOptions, Log, OccupancyGrid, Pose, SonarTextOptions};

/// The shared data folder `../shared/data/<sub>`, if present; absent, the
/// test is skipped with a message, except under `CI=true`, where it fails.
fn shared(sub: &str) -> Option<PathBuf> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../shared/data")
        .join(sub);
    if dir.is_dir() {
        return Some(dir);
    }
    let message = format!("the shared data folder {} is absent", dir.display());
    if std::env::var("CI").is_ok_and(|v| v == "true") {
        panic!("{message}; under CI=true this is a failure");
    }
    eprintln!("SKIPPED: {message}");
    None
}

/// Every FLASER line of a gzipped CARMEN log, split: (ranges, pose, time).
fn split_flaser(path: &PathBuf) -> Vec<(Vec<f64>, [f64; 3], f64)> {
    let mut text = String::new();
    flate2::read::GzDecoder::new(std::fs::File::open(path).unwrap())
        .read_to_string(&mut text)
        .unwrap();
    text.lines()
        .filter(|l| l.starts_with("FLASER "))
        .map(|l| {
            let t: Vec<f64> = l
                .split(' ')
                .skip(1)
                .filter_map(|w| w.parse().ok())
                .collect();
            let n = t[0] as usize;
            let ranges = t[1..=n].to_vec();
            let pose = [t[n + 1], t[n + 2], t[n + 3]];
            (ranges, pose, t[n + 7])
        })
        .collect()
}

#[test]
fn every_carmen_log_reads_its_scans_poses_and_ranges() {
    let Some(dir) = shared("carmen") else { return };
    // (file, scans and beams as the data's README gives them, no-echo value)
    let logs = [
        ("intel-corrected.log.gz", 910, 180, 81.83),
        ("seattle-corrected.log.gz", 241, 361, 81.91),
        ("aces-corrected.log.gz", 440, 180, 50.0),
        ("freiburg-079-corrected.log.gz", 4791, 360, 80.99),
    ];
    for (name, scans, beams, max_range_m) in logs {
        let path = dir.join(name);
        let log = Log::from_carmen(&path).unwrap();
        let split = split_flaser(&path);
        assert_eq!((log.len(), log.beams()), (scans, beams), "{name}");
        assert_eq!(split.len(), scans, "{name}");
        assert_eq!(log.max_range_m(), max_range_m, "{name}");
        for (i, (ranges, [x, y, theta], t)) in split.iter().enumerate() {
            assert_eq!(log.scan_ranges(i), &ranges[..], "{name} scan {i}");
            assert_eq!(log.poses()[i], Pose::new(*x, *y, *theta), "{name} scan {i}");
            assert_eq!(log.timestamps_s()[i], *t, "{name} scan {i}");
        }
        let Bearings::Fixed(b) = log.bearings() else {
            panic!("{name}: FLASER beams share one fan")
        };
        let step_deg = if beams < 300 { 1.0 } else { 0.5 };
        assert!((b[0].to_degrees() + 90.0).abs() < 1e-12, "{name}");
        assert!(
            ((b[1] - b[0]).to_degrees() - step_deg).abs() < 1e-12,
            "{name}"
        );
    }
}

#[test]
fn the_sonar_ring_reads_its_413_steps_in_metres_and_radians() {
    let Some(dir) = shared("sonar-8ring") else {
        return;
    };
    let options = SonarTextOptions {
        bearings_rad: [-90.0, -37.5, -22.5, -7.5, 7.5, 22.5, 37.5, 90.0_f64]
            .iter()
            .map(|d| d.to_radians())
            .collect(),
        length_unit_m: 0.001,
        range_unit_m: 0.001,
        angle_unit_rad: std::f64::consts::PI / 1800.0,
        min_range_m: 0.0,
        max_range_m: 5.0,
        no_echo: None,
    };
    let log =
        Log::from_sonar_text(dir.join("poses.txt"), dir.join("measurement.txt"), &options).unwrap();
    let split = |f: &str| -> Vec<Vec<f64>> {
        std::fs::read_to_string(dir.join(f))
            .unwrap()
            .lines()
            .map(|l| l.split_whitespace().map(|w| w.parse().unwrap()).collect())
            .collect()
    };
    let (poses, ranges) = (split("poses.txt"), split("measurement.txt"));
    assert_eq!((log.len(), log.beams()), (413, 8));
    assert_eq!(poses.len(), 413);
    for i in 0..413 {
        let p = log.poses()[i];
        assert!((p.x_m - poses[i][1] / 1000.0).abs() < 1e-12);
        assert!((p.y_m - poses[i][2] / 1000.0).abs() < 1e-12);
        assert!((p.theta_rad - (poses[i][3] / 10.0).to_radians()).abs() < 1e-12);
        for k in 0..8 {
            assert!((log.scan_ranges(i)[k] - ranges[i][k + 1] / 1000.0).abs() < 1e-12);
        }
    }
    // The robot moves in a region of about 30 x 15 m.
    let [x0, y0, x1, y1] = log.extent(0.0).unwrap().unwrap();
    assert!(
        (x1 - x0) > 10.0 && (x1 - x0) < 40.0 && (y1 - y0) < 25.0,
        "{x0} {y0} {x1} {y1}"
    );
}

/// The share of a log's echoes, beams `step_rad` apart, that end
/// in a cell its own occupancy map holds occupied: beams at the wrong
/// bearings draw each wall a little apart from scan to scan, so that the
/// later scans' beams clear what the earlier ones' ends marked.
fn consistency(path: &PathBuf, step_rad: f64) -> f64 {
    let options = CarmenOptions {
        flaser_step_rad: Some(step_rad),
        ..Default::default()
    };
    let log = Log::from_carmen_with(path, &options).unwrap();
    let [x0, y0, x1, y1] = log.extent(30.0).unwrap().unwrap();
    let grid = covmap::Grid::covering(x0 - 1.0, y0 - 1.0, x1 + 1.0, y1 + 1.0, 0.05).unwrap();
    let mut map = OccupancyGrid::new(grid);
    map.integrate_log(&log, &covmap::LaserModel::default())
        .unwrap();
    let p = map.probabilities();
    let (mut hits, mut echoes) = (0usize, 0usize);
    for i in 0..log.len() {
        let pose = log.sensor_pose(i);
        for (&r, &b) in log.scan_ranges(i).iter().zip(log.scan_bearings(i)) {
            if r >= 30.0 {
                continue;
            }
            let (sin, cos) = (pose.theta_rad + b).sin_cos();
            let cell = grid
                .world_to_cell(pose.x_m + r * cos, pose.y_m + r * sin)
                .unwrap();
            echoes += 1;
            hits += usize::from(p[grid.index(cell).unwrap()] > 0.5);
        }
    }
    hits as f64 / echoes as f64
}

#[test]
fn flaser_spacing_maps_sharper_than_the_alternative() {
    let Some(dir) = shared("carmen") else { return };
    let pi = std::f64::consts::PI;
    // Intel's 180 beams at 1 degree, Seattle's 361 at 0.5 degree: each
    // against the steps a beam more or fewer over the half turn would give.
    for (name, beams, others) in [
        ("intel-corrected.log.gz", 180, [pi / 179.0, pi / 181.0]),
        ("seattle-corrected.log.gz", 361, [pi / 359.0, pi / 361.0]),
    ] {
        let path = dir.join(name);
        let step = covmap::log::readers::carmen::flaser_step_rad(beams);
        let chosen = consistency(&path, step);
        for other_step in others {
            let other = consistency(&path, other_step);
            eprintln!(
                "{name}: echoes on occupied cells {chosen:.4} at pi/{:.0}, {other:.4} at pi/{:.0}",
                pi / step,
                pi / other_step
            );
            assert!(
                chosen > other,
                "{name}: {chosen} at the chosen step, {other} at {other_step}"
            );
        }
    }
}
