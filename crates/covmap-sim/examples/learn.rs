//! The sensor-model fit of `covmap learn`, from Rust: a training drive in
//! one built-in world, a test drive in another, the fit, and the scores.
//!
//! `cargo run --release -p covmap-sim --example learn -- [--train corridor]
//! [--test office] [--laser] [--evaluations 300] [--scans 300]
//! [--parameters a,b,...] [--set name=value ...] [--seed 0] [--test-seed 1]
//! [--clear-no-echo] [--breakdown]`
//!
//! The maps are built as the exploration loop builds them, each no-echo
//! reading occluded by the map (it clears only what its line of sight
//! reaches past the cells the map holds covered and is certain of); `--clear-no-echo` lets every no-echo reading clear
//! its whole footprint instead, as the sensor model alone has it.
//!
//! `--set` changes a parameter of the starting model (after `--laser`); the
//! drives are simulated with the starting model's cone and range, so a
//! changed `opening_angle_rad` changes the drives too. `--seed` seeds the
//! fit's restarts, `--test-seed` the test drive.
//!
//! `--breakdown` also prints where the starting model's log-likelihood of
//! the training drive comes from: the cells scoring below -20 nats (and how
//! many of them a wall face cuts), and the likelihood of the same map with
//! every bin floored at 1e-4 (and renormalised).
//!
//! `--true-occluders` also maps both drives with the starting model and
//! each no-echo reading occluded by the true obstacles (every cell that
//! holds some obstacle in the true world) instead of by the map: what
//! occlusion costs where the map's occluders are not at fault.

use covmap_core::exploration::AnySensorModel;
use covmap_sim::experiments::{LearnConfig, learn};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut config = LearnConfig::default();
    let mut breakdown = false;
    let mut true_occluders = false;
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        let mut value = || args.next().ok_or(format!("{a} needs a value"));
        match a.as_str() {
            "--train" => config.train_world = value()?,
            "--test" => config.test_world = value()?,
            "--laser" => config.model = AnySensorModel::laser(),
            "--set" => {
                let v = value()?;
                let (name, x) = v
                    .split_once('=')
                    .ok_or(format!("--set {v}: expected NAME=VALUE"))?;
                let x: f64 = x.parse()?;
                use covmap_core::learn::Fittable;
                let known = match &mut config.model {
                    AnySensorModel::Sonar(m) => m.set(name, x),
                    AnySensorModel::Laser(m) => m.set(name, x),
                };
                if !known {
                    return Err(format!("--set: the model has no parameter {name}").into());
                }
            }
            "--evaluations" => config.fit.max_evaluations = value()?.parse()?,
            "--judged" => config.judged_only = true,
            "--breakdown" => breakdown = true,
            "--true-occluders" => true_occluders = true,
            "--clear-no-echo" => config.fit.occlude_no_echo = false,
            "--seed" => config.fit.seed = value()?.parse()?,
            "--test-seed" => config.test_seed = value()?.parse()?,
            "--restarts" => config.fit.restarts = value()?.parse()?,
            "--scans" => config.scans = value()?.parse()?,
            "--parameters" => {
                config.fit.parameters = Some(value()?.split(',').map(String::from).collect())
            }
            other => return Err(format!("unknown argument {other}").into()),
        }
    }
    let started = std::time::Instant::now();
    let report = learn(&config, &|_| {})?;
    let seconds = started.elapsed().as_secs_f64();
    let fit = &report.fit;
    println!(
        "fit: {} evaluations in {seconds:.1} s ({:.0} ms each), training log-likelihood {:.0} -> {:.0}",
        fit.evaluations,
        1e3 * seconds / fit.evaluations as f64,
        fit.initial_log_likelihood,
        fit.log_likelihood
    );
    for (name, value) in fit.parameters.iter().zip(&fit.trace[0].values) {
        use covmap_core::learn::Fittable;
        println!(
            "  {name:18} {value:8.4} -> {:8.4}",
            fit.model.get(name).unwrap_or(f64::NAN)
        );
    }
    for (k, drive) in report.drives.iter().enumerate() {
        let (d, l) = (report.default_scores[k], report.learned_scores[k]);
        println!(
            "{} drive ({}, {} cells reached): log-likelihood {:.0} -> {:.0} (judged cells {:.0} -> {:.0}); mean-map error {:.4} -> {:.4} (free {:.4} -> {:.4}, obstacle {:.4} -> {:.4}; occupancy grid {:.4})",
            ["training", "test"][k],
            drive.world,
            d.cells_reached,
            d.log_likelihood,
            l.log_likelihood,
            d.judged_log_likelihood,
            l.judged_log_likelihood,
            d.mean_error,
            l.mean_error,
            d.free_error,
            l.free_error,
            d.obstacle_error,
            l.obstacle_error,
            d.occupancy_error
        );
        println!(
            "  faced walls' mean coverage {:.3} -> {:.3} (occupancy grid {:.3})",
            d.wall_coverage, l.wall_coverage, d.occupancy_wall
        );
    }
    if breakdown {
        print_breakdown(&report.drives[0], &config.model, config.fit.occlude_no_echo)?;
    }
    if true_occluders {
        for drive in &report.drives {
            print_true_occluders(drive, &config.model)?;
        }
    }
    Ok(())
}

/// The error of `drive`'s map built with `model`, each no-echo reading
/// occluded by the true obstacles: its line of sight stops, sector by
/// sector, before the first cell holding some obstacle in the true world.
fn print_true_occluders(
    drive: &covmap_sim::experiments::Drive,
    model: &AnySensorModel,
) -> Result<(), Box<dyn std::error::Error>> {
    use covmap_core::histogram::DEFAULT_BINS;
    use covmap_core::{CoverageMap, integrate_log_occluded_by};
    let mut map = CoverageMap::with_bins(drive.grid, DEFAULT_BINS)?;
    integrate_log_occluded_by(&mut map, &drive.log, model.as_dyn(), |c| {
        drive.truth[c] > 0.0
    })?;
    let mean = map.mean();
    let error = |keep: fn(f64) -> bool| drive.error_where(&mean, keep);
    println!(
        "{} drive, no-echo readings occluded by the true obstacles: mean-map error {:.4} (free {:.4}, obstacle {:.4})",
        drive.world,
        error(|_| true),
        error(|t| t == 0.0),
        error(|t| t > 0.0)
    );
    Ok(())
}

/// Where `model`'s log-likelihood of `drive`'s truth comes from.
fn print_breakdown(
    drive: &covmap_sim::experiments::Drive,
    model: &AnySensorModel,
    occlude_no_echo: bool,
) -> Result<(), Box<dyn std::error::Error>> {
    use covmap_core::CoverageMap;
    use covmap_core::histogram::DEFAULT_BINS;
    use covmap_core::learn::{cell_log_likelihoods, log_likelihood, map_of_log};
    let map = map_of_log(&drive.fit_data(None), DEFAULT_BINS, model, occlude_no_echo)?;
    let scores = cell_log_likelihoods(&map, &drive.truth)?;
    let total: f64 = scores.iter().sum();
    let low: Vec<usize> = (0..scores.len()).filter(|&i| scores[i] < -20.0).collect();
    let low_sum: f64 = low.iter().map(|&i| scores[i]).sum();
    let cut = low
        .iter()
        .filter(|&&i| drive.truth[i] > 0.0 && drive.truth[i] < 1.0)
        .count();
    println!(
        "breakdown ({}, starting model): log-likelihood {total:.0} over {} cells; {} cells below -20 nats ({:.1} %) make {low_sum:.0} ({:.0} % of it), {cut} of them cut by a wall face",
        drive.world,
        scores.len(),
        low.len(),
        100.0 * low.len() as f64 / scores.len() as f64,
        100.0 * low_sum / total
    );
    let mut floored = map.histograms().to_vec();
    for h in floored.chunks_exact_mut(DEFAULT_BINS) {
        h.iter_mut().for_each(|v| *v = v.max(1e-4));
        let sum: f32 = h.iter().sum();
        h.iter_mut().for_each(|v| *v /= sum);
    }
    let floored = CoverageMap::from_histograms(drive.grid, DEFAULT_BINS, floored)?;
    println!(
        "  the same map, every bin floored at 1e-4: log-likelihood {:.0}",
        log_likelihood(&floored, &drive.truth, None)?
    );
    Ok(())
}
