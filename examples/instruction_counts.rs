//! A fixed amount of the hot work (scan integration with the sonar and the
//! laser model, the fast expected gain of 200 candidates), for counting
//! instructions with valgrind: the counts are repeatable whatever else the
//! machine is doing, so two builds can be compared on a busy machine where
//! wall-clock benchmarks are not. `tools/compare_instructions.sh` runs it at
//! two commits. Each phase prints a checksum of its result, which must agree
//! between builds that claim the same behaviour.
//!
//! Run: `cargo run --release --example instruction_counts -- gain` (phases:
//! `setup`, `gain`, `integrate`, `laser`).

use covmap::ScanMap;
use covmap::gain::{GainEvaluator, GainMethod, GainOptions};
use covmap::{CoverageMap, Grid, LaserModel, Pose, SonarModel};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn scans(
    map: &mut CoverageMap,
    bearings: &[f64],
    n: usize,
    max: f64,
    model: &dyn Fn(&mut CoverageMap, &Pose, &[f64]),
) {
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    for _ in 0..n {
        let pose = Pose::new(
            rng.random_range(2.0..18.0),
            rng.random_range(2.0..18.0),
            rng.random_range(-3.1..3.1),
        );
        let ranges: Vec<f64> = bearings
            .iter()
            .map(|_| rng.random_range(0.5..max))
            .collect();
        model(map, &pose, &ranges);
    }
}

fn main() {
    let phase = std::env::args().nth(1).unwrap();
    let sonar = SonarModel::default();
    let ring: Vec<f64> = (0..24)
        .map(|i| i as f64 * std::f64::consts::TAU / 24.0)
        .collect();
    let mut map = CoverageMap::new(Grid::new([0.0, 0.0], 0.05, 400, 400).unwrap());
    let sonar_integrate = |m: &mut CoverageMap, p: &Pose, r: &[f64]| {
        m.integrate(p, r, &ring, &sonar).unwrap();
    };
    match phase.as_str() {
        "setup" | "gain" => {
            scans(&mut map, &ring, 60, 6.0, &sonar_integrate);
            if phase == "gain" {
                let poses: Vec<Pose> = (0..200)
                    .map(|i| {
                        Pose::new(
                            1.0 + 0.9 * (i % 20) as f64,
                            1.0 + 1.8 * (i / 20) as f64,
                            0.0,
                        )
                    })
                    .collect();
                let g = GainEvaluator::new(&map, &sonar, GainOptions::default())
                    .unwrap()
                    .evaluate(&poses, &ring, GainMethod::Fast)
                    .unwrap();
                println!("{}", g.iter().sum::<f64>());
            }
        }
        "integrate" => scans(&mut map, &ring, 200, 6.0, &sonar_integrate),
        "laser" => {
            let laser = LaserModel::default();
            let beams: Vec<f64> = (0..360).map(|i| (i as f64).to_radians()).collect();
            scans(&mut map, &beams, 20, 11.0, &|m, p, r| {
                m.integrate(p, r, &beams, &laser).unwrap();
            });
        }
        _ => {}
    }
    println!("{}", map.entropy().iter().map(|&e| e as f64).sum::<f64>());
}
