//! One evaluation of a sensor-model fit: the map of a 300-scan drive of the
//! 24-sonar ring through the built-in corridor at 5 cm, built and scored
//! against the exact ground truth (what `fit_sensor_model` does per
//! parameter set). The default scan integration is measured beside the
//! occluded one (no-echo readings stopped by the map), the one
//! `covmap learn` fits in.
//!
//! Run: `cargo bench --bench learn`. A whole fit is timed by
//! `cargo run --release -p covmap-sim --example learn` (see BENCHMARKS.md).

use covmap::CoverageMap;
use covmap::ScanMap;
use covmap::exploration::AnySensorModel;
use covmap::learn::log_likelihood;
use covmap::sim::experiments::Drive;
use criterion::{Criterion, criterion_group, criterion_main};

/// One evaluation: `drive`'s map built with `model` (no-echo readings
/// occluded by the map if `occlude`) and the truth scored under it.
fn evaluate(drive: &Drive, model: &AnySensorModel, occlude: bool) -> f64 {
    let mut map = CoverageMap::new(drive.grid);
    if occlude {
        map.occluding().integrate_log(&drive.log, model)
    } else {
        map.integrate_log(&drive.log, model)
    }
    .expect("valid log");
    log_likelihood(&map, &drive.truth, None).expect("valid truth")
}

fn evaluation(c: &mut Criterion) {
    let model = AnySensorModel::default();
    let drive = Drive::simulate("corridor", &model, (300, 0.15, 0.05), 0, false)
        .expect("the corridor drive");
    let mut group = c.benchmark_group("fit_evaluation");
    group.sample_size(20);
    for (name, occlude) in [
        ("corridor_300_scans_24_sonars", false),
        ("corridor_300_scans_24_sonars_occluded", true),
    ] {
        group.bench_function(name, |b| b.iter(|| evaluate(&drive, &model, occlude)));
    }
    group.finish();
}

criterion_group!(benches, evaluation);
criterion_main!(benches);
