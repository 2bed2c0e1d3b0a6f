//! One evaluation of a sensor-model fit: the map of a 300-scan drive of the
//! 24-sonar ring through the built-in corridor at 5 cm, built and scored
//! against the exact ground truth (what `fit_sensor_model` does per
//! parameter set). The default scan integration is measured beside the
//! occluded one (no-echo readings stopped by the map) and beside a model
//! whose update reads the map (attribution, yield and the contradiction
//! floor on, as fits choose them).
//!
//! Run: `cargo bench --bench learn`. A whole fit is timed by
//! `cargo run --release -p covmap-sim --example learn` (see BENCHMARKS.md).

use covmap::CoverageMap;
use covmap::exploration::AnySensorModel;
use covmap::learn::log_likelihood;
use covmap::sim::experiments::Drive;
use criterion::{Criterion, criterion_group, criterion_main};

fn evaluation(c: &mut Criterion) {
    let model = AnySensorModel::default();
    let drive = Drive::simulate("corridor", &model, (300, 0.15, 0.05), 0, false)
        .expect("the corridor drive");
    let mut group = c.benchmark_group("fit_evaluation");
    group.sample_size(20);
    group.bench_function("corridor_300_scans_24_sonars", |b| {
        b.iter(|| {
            let mut map = CoverageMap::new(drive.grid);
            map.integrate_log(&drive.log, &model).expect("valid log");
            log_likelihood(&map, &drive.truth, None).expect("valid truth")
        })
    });
    group.bench_function("corridor_300_scans_24_sonars_occluded", |b| {
        b.iter(|| {
            let mut map = CoverageMap::new(drive.grid);
            map.integrate_log_occluding(&drive.log, &model)
                .expect("valid log");
            log_likelihood(&map, &drive.truth, None).expect("valid truth")
        })
    });
    let mut reading = model;
    if let AnySensorModel::Sonar(m) = &mut reading {
        m.range.posterior_floor = 0.001;
        m.range.end_attribution = 0.05;
        m.range.free_yield = 0.09;
    }
    group.bench_function("corridor_300_scans_24_sonars_map_reading", |b| {
        b.iter(|| {
            let mut map = CoverageMap::new(drive.grid);
            map.integrate_log(&drive.log, &reading).expect("valid log");
            log_likelihood(&map, &drive.truth, None).expect("valid truth")
        })
    });
    group.finish();
}

criterion_group!(benches, evaluation);
criterion_main!(benches);
