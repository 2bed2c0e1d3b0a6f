//! The paper's Table I in simulation: every strategy on the built-in
//! worlds, over a few seeds.
//!
//! ```text
//! cargo run --release -p covmap-sim --example table1 -- [--worlds corridor,office] [--seeds N]
//!     [--strategies coverage,count1,count50,frontier] [--scan-spacing M] [--resolution M] [--max-path M] [--clear-no-echo]
//!     [--no-multipath] [--laser] [--verbose] [--digest] [--where]
//! ```
//!
//! Prints one row a run: path length, the fraction of evaluation cells whose
//! entropy is above epsilon at the end, the termination, steps, scans,
//! contacts, the maps' errors, wall time and the ratio of real time at
//! 0.5 m/s to wall time. `--clear-no-echo`: no-echo readings clear their
//! whole footprint, as the sensor model alone has it (`occlude_no_echo` off);
//! `--no-multipath`: the simulated sonar's specular misses never come back
//! over a second surface (`multipath_probability` 0). `--digest`: a last
//! column with a 64-bit digest of everything a run leaves but its timing
//! (the trajectory, the per-step trace, the coverage map's histograms and
//! entropy history, the occupancy grid, the scan counts), so that a change
//! meant to leave the runs as they were can be checked bit for bit.
//! `--where`: where the evaluation cells left uncertain lie, by their
//! distance from the nearest surface of the true world, and how many are
//! split between two neighbouring bins or have stagnated. `--max-path M`:
//! the run's path limit (`max_path_m`, default 10 km).

use std::process::ExitCode;
use std::sync::Arc;

use covmap_core::exploration::{DEFAULT_DISCOUNT_BEYOND_M, Strategy};
use covmap_sim::World;
use covmap_sim::exploration::{ExploreOptions, SimExploration, SimSensor};

fn strategy(name: &str) -> Option<Strategy> {
    Some(match name {
        "coverage" => Strategy::coverage(0.5).ok()?,
        "coverage0.2" => Strategy::coverage(0.2).ok()?,
        "coverage0.8" => Strategy::coverage(0.8).ok()?,
        "count1" => Strategy::counting(1, None).ok()?,
        "count1d" => Strategy::counting(1, Some(DEFAULT_DISCOUNT_BEYOND_M)).ok()?,
        "count50" => Strategy::counting(50, Some(DEFAULT_DISCOUNT_BEYOND_M)).ok()?,
        "count50u" => Strategy::counting(50, None).ok()?,
        "frontier" => Strategy::frontier(),
        _ => return None,
    })
}

fn main() -> ExitCode {
    let mut worlds = vec!["corridor".to_string()];
    let mut seeds = 1u64;
    let mut strategies: Vec<String> = ["coverage", "count1", "count50", "frontier"]
        .map(String::from)
        .to_vec();
    let (mut verbose, mut laser, mut clear_no_echo, mut no_multipath, mut digest) =
        (false, false, false, false, false);
    let mut where_uncertain = false;
    let mut scan_spacing_m = None;
    let mut resolution_m = None;
    let mut max_path_m = None;
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        let list = |v: Option<String>| -> Vec<String> {
            v.unwrap_or_default().split(',').map(String::from).collect()
        };
        match a.as_str() {
            "--worlds" => worlds = list(args.next()),
            "--strategies" => strategies = list(args.next()),
            "--seeds" => match args.next().and_then(|s| s.parse().ok()) {
                Some(n) => seeds = n,
                None => return usage("--seeds needs a count"),
            },
            "--scan-spacing" => match args.next().and_then(|s| s.parse().ok()) {
                Some(m) => scan_spacing_m = Some(m),
                None => return usage("--scan-spacing needs a distance in metres"),
            },
            "--resolution" => match args.next().and_then(|s| s.parse().ok()) {
                Some(m) => resolution_m = Some(m),
                None => return usage("--resolution needs a cell size in metres"),
            },
            "--max-path" => match args.next().and_then(|s| s.parse().ok()) {
                Some(m) => max_path_m = Some(m),
                None => return usage("--max-path needs a distance in metres"),
            },
            "--verbose" => verbose = true,
            "--laser" => laser = true,
            "--clear-no-echo" => clear_no_echo = true,
            "--no-multipath" => no_multipath = true,
            "--digest" => digest = true,
            "--where" => where_uncertain = true,
            _ => return usage(&format!("unexpected argument {a:?}")),
        }
    }
    println!(
        "{:<9} {:<8} {:>4} {:>8} {:>10} {:<10} {:>5} {:>6} {:>8} {:>8} {:>8} {:>8} {:>7}",
        "strategy",
        "world",
        "seed",
        "path m",
        "uncert. %",
        "end",
        "steps",
        "scans",
        "contacts",
        "mae cov",
        "mae occ",
        "seconds",
        "x real"
    );
    for world_name in &worlds {
        let world = match World::builtin(world_name) {
            Ok(w) => Arc::new(w),
            Err(e) => return usage(&e.to_string()),
        };
        for name in &strategies {
            let Some(s) = strategy(name) else {
                return usage(&format!("unknown strategy {name:?}"));
            };
            for seed in 0..seeds {
                let mut options = ExploreOptions {
                    seed,
                    sensor: if laser {
                        SimSensor::laser()
                    } else {
                        SimSensor::default()
                    },
                    ..ExploreOptions::default()
                };
                options.config.occlude_no_echo = !clear_no_echo;
                if let (true, SimSensor::Sonar(ring)) = (no_multipath, &mut options.sensor) {
                    ring.multipath_probability = 0.0;
                }
                if let Some(m) = scan_spacing_m {
                    options.config.scan_spacing_m = m;
                }
                if let Some(m) = resolution_m {
                    options.resolution_m = m;
                }
                if let Some(m) = max_path_m {
                    options.config.max_path_m = m;
                }
                match run(&world, s, &options, verbose, digest, where_uncertain) {
                    Ok(row) => println!("{:<9} {:<8} {:>4} {row}", name, world_name, seed),
                    Err(e) => {
                        eprintln!("table1: {e}");
                        return ExitCode::FAILURE;
                    }
                }
            }
        }
    }
    ExitCode::SUCCESS
}

fn run(
    world: &Arc<World>,
    strategy: Strategy,
    options: &ExploreOptions,
    verbose: bool,
    digest: bool,
    where_uncertain: bool,
) -> Result<String, Box<dyn std::error::Error>> {
    let mut sim = SimExploration::new(Arc::clone(world), strategy, options)?;
    while let Some(step) = sim.step()? {
        if verbose {
            let e = sim.exploration();
            eprintln!(
                "  step {:>4}: goal ({:6.2}, {:5.2}) reached {:5} contact {:?} pose ({:.3}, {:.3}) path {:7.2} m, uncertain {:5.2} %",
                step.index,
                step.goal.x_m,
                step.goal.y_m,
                step.reached,
                step.contact_m,
                step.pose.x_m,
                step.pose.y_m,
                e.path_length_m(),
                100.0 * e.uncertain_fraction()
            );
        }
    }
    let run = sim.into_result()?;
    let r = &run.result;
    let first = |f: f64| {
        r.trace
            .uncertain_fraction
            .iter()
            .position(|&u| u <= f)
            .map_or("-".to_string(), |k| {
                format!("{:.0}", r.trace.path_length_m[k])
            })
    };
    eprintln!(
        "    path at 10/5/2/1 % uncertain: {} {} {} {} m",
        first(0.1),
        first(0.05),
        first(0.02),
        first(0.01)
    );
    if where_uncertain {
        eprintln!("{}", uncertain_cells(&run, options.config.epsilon));
    }
    let real_s = r.path_length_m / 0.5;
    let digest = if digest {
        format!("   digest {:016x}", run_digest(r))
    } else {
        String::new()
    };
    Ok(format!(
        "{:>8.1} {:>10.2} {:<10} {:>5} {:>6} {:>8} {:>8.4} {:>8.4} {:>8.2} {:>7.0}   (plan {:.2} s, sense {:.2} s, integrate {:.2} s){digest}",
        r.path_length_m,
        100.0 * run.high_entropy_fraction,
        r.termination.map_or("-", |t| t.as_str()),
        r.steps,
        r.scans,
        r.contacts,
        run.errors.coverage_map,
        run.errors.occupancy,
        run.seconds,
        real_s / run.seconds,
        r.timing.planning_s,
        r.timing.sensing_s,
        r.timing.integration_s,
    ))
}

/// Where the evaluation cells left uncertain (entropy at least `epsilon`)
/// lie: by their distance (8-connected steps, in cells) from the nearest
/// surface cell (a cell the truth holds partly covered, or a free or
/// covered cell next to one of the other kind), and how many of them have
/// most of their mass on two neighbouring bins (a split that readings tip
/// back and forth) or have stagnated.
fn uncertain_cells(run: &covmap_sim::exploration::ExplorationRun, epsilon: f64) -> String {
    let grid = &run.grid;
    let (rows, cols) = (grid.rows(), grid.cols());
    let truth = &run.truth;
    let covered = |i: usize| truth[i] > 0.0;
    let neighbours = |i: usize| {
        let (r, c) = ((i / cols) as i64, (i % cols) as i64);
        [
            (-1, 0),
            (1, 0),
            (0, -1),
            (0, 1),
            (-1, -1),
            (-1, 1),
            (1, -1),
            (1, 1),
        ]
        .into_iter()
        .map(move |(dr, dc)| (r + dr, c + dc))
        .filter(|&(r, c)| r >= 0 && c >= 0 && (r as usize) < rows && (c as usize) < cols)
        .map(|(r, c)| r as usize * cols + c as usize)
    };
    let surface = |i: usize| {
        (truth[i] > 0.0 && truth[i] < 1.0) || neighbours(i).any(|j| covered(j) != covered(i))
    };
    // Breadth-first distances from the surface cells.
    let mut distance = vec![usize::MAX; truth.len()];
    let mut frontier: Vec<usize> = (0..truth.len()).filter(|&i| surface(i)).collect();
    for &i in &frontier {
        distance[i] = 0;
    }
    let mut d = 0;
    while !frontier.is_empty() {
        d += 1;
        let mut next = Vec::new();
        for &i in &frontier {
            for j in neighbours(i) {
                if distance[j] == usize::MAX {
                    distance[j] = d;
                    next.push(j);
                }
            }
        }
        frontier = next;
    }
    let map = &run.result.map;
    let entropy = map.entropy();
    let bins = map.bins();
    let histograms = map.histograms();
    let stagnation = map.stagnation();
    let mut by_distance = [0usize; 7];
    let (mut total, mut split, mut stagnated) = (0, 0, 0);
    for i in (0..truth.len()).filter(|&i| run.evaluation_cells[i]) {
        if f64::from(entropy[i]) < epsilon {
            continue;
        }
        total += 1;
        by_distance[distance[i].min(by_distance.len() - 1)] += 1;
        let h = &histograms[i * bins..(i + 1) * bins];
        let top = covmap_core::histogram::argmax(h);
        let pair = [top.checked_sub(1), Some(top + 1)]
            .into_iter()
            .flatten()
            .filter_map(|k| h.get(k).copied())
            .fold(0.0_f32, f32::max);
        if h[top] + pair > 0.9 {
            split += 1;
        }
        if stagnation[i] {
            stagnated += 1;
        }
    }
    let columns: Vec<String> = by_distance
        .iter()
        .enumerate()
        .map(|(d, n)| {
            let plus = if d + 1 == by_distance.len() { "+" } else { "" };
            format!("{d}{plus}: {n}")
        })
        .collect();
    format!(
        "    uncertain evaluation cells: {total}; by cells from the nearest surface {}; \
         {split} with 90 % of their mass on two neighbouring bins; {stagnated} stagnated",
        columns.join(", ")
    )
}

/// FNV-1a over the bits of everything `r` holds but its timing: equal
/// digests, runs equal bit for bit (but for a collision).
fn run_digest(r: &covmap_core::exploration::ExplorationResult) -> u64 {
    let mut hash = 0xcbf2_9ce4_8422_2325_u64;
    let mut add = |bits: u64| {
        for byte in bits.to_le_bytes() {
            hash = (hash ^ u64::from(byte)).wrapping_mul(0x0100_0000_01b3);
        }
    };
    add(r.path_length_m.to_bits());
    for byte in r.termination.map_or("-", |t| t.as_str()).bytes() {
        add(u64::from(byte));
    }
    for n in [r.scans, r.steps, r.contacts] {
        add(n as u64);
    }
    for (p, &scanned) in r.trajectory.poses.iter().zip(&r.trajectory.scanned) {
        for v in [p.x_m, p.y_m, p.theta_rad] {
            add(v.to_bits());
        }
        add(u64::from(scanned));
    }
    let t = &r.trace;
    for k in 0..t.path_length_m.len() {
        add(t.path_length_m[k].to_bits());
        add(t.scans[k] as u64);
        add(t.uncertain_fraction[k].to_bits());
        add(u64::from(t.contact[k]));
    }
    for v in r.map.histograms() {
        add(u64::from(v.to_bits()));
    }
    if let Some(history) = r.map.history_state() {
        for v in history.entropies {
            add(u64::from(v.to_bits()));
        }
        for n in history.count {
            add(u64::from(n));
        }
    }
    for v in r
        .occupancy
        .log_odds()
        .iter()
        .chain(r.occupancy.counts().counts())
    {
        add(u64::from(v.to_bits()));
    }
    for seen in r.occupancy.observed() {
        add(u64::from(seen));
    }
    hash
}

fn usage(problem: &str) -> ExitCode {
    eprintln!(
        "table1: {problem}\nusage: table1 [--worlds corridor,office] [--seeds N] [--strategies coverage,count1,count1d,count50,count50u,frontier] [--scan-spacing M] [--resolution M] [--max-path M] [--clear-no-echo] [--no-multipath] [--laser] [--verbose] [--digest] [--where]"
    );
    ExitCode::from(2)
}
