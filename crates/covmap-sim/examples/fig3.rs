//! The paper's Fig. 3 in simulation: a coverage map of the corridor from 24
//! sonars, against the exact ground truth and the occupancy-grid baseline.
//!
//! ```text
//! cargo run --release --example fig3 -- --out DIR [--seed N]
//! ```
//!
//! Prints the errors and writes `fig3_truth.png`, `fig3_ml.png`,
//! `fig3_mean.png` and `fig3_occupancy.png` to DIR (black = covered; cells no
//! reading reached are grey).

use std::path::PathBuf;
use std::process::ExitCode;

use covmap_sim::experiments::fig3;
use covmap_sim::write_map_png;

fn main() -> ExitCode {
    let mut out = None;
    let mut seed = 0u64;
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        match (a.as_str(), args.next()) {
            ("--out", Some(dir)) => out = Some(PathBuf::from(dir)),
            ("--seed", Some(s)) => match s.parse() {
                Ok(v) => seed = v,
                Err(_) => return usage(&format!("--seed needs an integer, got {s:?}")),
            },
            _ => return usage(&format!("unexpected argument {a:?}")),
        }
    }
    let Some(out) = out else {
        return usage("--out DIR is required");
    };
    match run(&out, seed) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("fig3: {e}");
            ExitCode::FAILURE
        }
    }
}

fn usage(problem: &str) -> ExitCode {
    eprintln!("fig3: {problem}\nusage: fig3 --out DIR [--seed N]");
    ExitCode::from(2)
}

fn run(out: &std::path::Path, seed: u64) -> Result<(), Box<dyn std::error::Error>> {
    std::fs::create_dir_all(out)?;
    let r = fig3(seed)?;
    let (rows, cols) = r.grid.shape();
    println!(
        "Fig. 3, seed {seed}: {} poses, {} sonar readings, grid {rows} x {cols} cells (rows x columns) at {} m, {} cells reached",
        r.poses.len(),
        r.readings,
        r.grid.resolution_m(),
        r.cells_reached
    );
    println!(
        "mean absolute error against the exact coverage (all reached cells / cells a wall face cuts):"
    );
    for (name, e) in [
        ("coverage map, ML", r.mae_ml),
        ("coverage map, mean", r.mae_mean),
        ("occupancy grid", r.mae_occupancy),
    ] {
        println!("  {name:<20} {:.4} / {:.4}", e.all, e.partial);
    }
    println!(
        "log-likelihood of the ground truth: {:.1} (uniform prior: {:.1}; per cell {:.3} vs {:.3})",
        r.log_likelihood,
        r.log_likelihood_prior,
        r.log_likelihood / r.cells_reached as f64,
        r.log_likelihood_prior / r.cells_reached as f64
    );
    let grey_unreached = |v: &[f32]| -> Vec<f64> {
        v.iter()
            .zip(&r.reached)
            .map(|(&x, &hit)| if hit { x as f64 } else { f64::NAN })
            .collect()
    };
    write_map_png(out.join("fig3_truth.png"), &r.grid, &r.truth)?;
    write_map_png(out.join("fig3_ml.png"), &r.grid, &grey_unreached(&r.ml))?;
    write_map_png(out.join("fig3_mean.png"), &r.grid, &grey_unreached(&r.mean))?;
    write_map_png(
        out.join("fig3_occupancy.png"),
        &r.grid,
        &grey_unreached(&r.occupancy),
    )?;
    println!(
        "wrote fig3_truth.png, fig3_ml.png, fig3_mean.png, fig3_occupancy.png to {}",
        out.display()
    );
    Ok(())
}
