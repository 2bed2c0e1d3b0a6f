//! The paper's Fig. 3: a coverage map of the corridor built from ultrasound,
//! measured against the exact ground truth.

use covmap_core::ScanMap;
use std::f64::consts::TAU;

use covmap_core::{CoverageMap, Grid, OccupancyGrid, Pose, SonarModel};
use rand::RngExt;

use crate::error::{Result, SimError, check_param};
use crate::rng::sim_rng_stream;
use crate::robot::Robot;
use crate::simulate::simulate;
use crate::sonar::SonarRing;
use crate::world::World;

/// The setting of [`fig3_with`].
#[derive(Clone, Debug, PartialEq)]
pub struct Fig3Config {
    /// Seed of the path and of every sensor draw.
    pub seed: u64,
    /// Grid resolution, metres (the paper's 5 cm).
    pub resolution_m: f64,
    /// Distance between consecutive poses along the path, metres.
    pub step_m: f64,
    /// The simulated sensors (default: 24 sonars; the cone and maximum range
    /// of `model`).
    pub sonar: SonarRing,
    /// The inverse model both maps integrate with.
    pub model: SonarModel,
    /// Radius of the robot, metres: every pose of the path keeps this clear.
    pub robot_radius_m: f64,
}

impl Default for Fig3Config {
    fn default() -> Self {
        let model = SonarModel::default();
        Self {
            seed: 0,
            resolution_m: 0.05,
            step_m: 0.2,
            sonar: SonarRing::default().with_model(&model),
            model,
            robot_radius_m: 0.26,
        }
    }
}

/// Mean absolute errors of a map against the ground truth, over the cells the
/// sensors reached, and over the subset whose true coverage is strictly
/// between 0 and 1 (the cells a wall face cuts).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MapErrors {
    /// Over all reached cells.
    pub all: f64,
    /// Over reached cells with `0 < truth < 1`.
    pub partial: f64,
}

/// What [`fig3_with`] measured.
#[derive(Clone, Debug)]
pub struct Fig3Report {
    /// The map grid: the corridor and its walls, cell boundaries off the wall
    /// faces so that the faces cut cells (as in the paper's Fig. 1).
    pub grid: Grid,
    /// The path, one pose every `step_m`.
    pub poses: Vec<Pose>,
    /// Number of sonar readings integrated.
    pub readings: usize,
    /// Cells some reading intercepted (scan count above zero).
    pub reached: Vec<bool>,
    /// Number of reached cells.
    pub cells_reached: usize,
    /// Exact coverage of every cell.
    pub truth: Vec<f64>,
    /// The coverage map's maximum-likelihood map.
    pub ml: Vec<f32>,
    /// The coverage map's mean map.
    pub mean: Vec<f32>,
    /// The coverage map's entropy, nats.
    pub entropy: Vec<f32>,
    /// The occupancy grid's probabilities.
    pub occupancy: Vec<f32>,
    /// Errors of the ML map.
    pub mae_ml: MapErrors,
    /// Errors of the mean map.
    pub mae_mean: MapErrors,
    /// Errors of the occupancy probabilities read as coverage.
    pub mae_occupancy: MapErrors,
    /// Log-likelihood of the ground truth under the coverage map: the sum over
    /// reached cells of the log of the mass of the bin nearest the truth.
    pub log_likelihood: f64,
    /// The same under the uniform prior, for scale (`cells_reached * ln(1 / bins)`).
    pub log_likelihood_prior: f64,
}

/// [`fig3_with`] with the default setting and `seed`.
///
/// # Example
/// ```
/// let r = covmap_sim::experiments::fig3(1).unwrap();
/// assert!(r.mae_ml.all < r.mae_occupancy.all);
/// assert!(r.log_likelihood.is_finite());
/// ```
pub fn fig3(seed: u64) -> Result<Fig3Report> {
    fig3_with(&Fig3Config {
        seed,
        ..Fig3Config::default()
    })
}

/// Drive the sonar ring along [`corridor_path`] through the built-in
/// `corridor`, integrate every scan into a [`CoverageMap`] and into the
/// [`OccupancyGrid`] baseline (both with `config.model`), and measure both
/// against the exact ground truth on the cells the readings reached.
pub fn fig3_with(config: &Fig3Config) -> Result<Fig3Report> {
    check_param(
        "resolution_m",
        config.resolution_m,
        config.resolution_m > 0.0,
        "a positive cell size",
    )?;
    let world = World::builtin("corridor")?;
    // Off the 5 cm lattice by 0.02 m and 0.03 m: every wall face cuts cells.
    let r = config.resolution_m;
    let origin = [-0.52, -0.53];
    let cols = ((17.6 - origin[0]) / r).ceil() as usize;
    let rows = ((3.35 - origin[1]) / r).ceil() as usize;
    let grid = Grid::new(origin, r, rows, cols)?;

    let poses = corridor_path(config.seed, config.step_m)?;
    let robot = Robot::new(config.robot_radius_m)?;
    if poses.iter().any(|p| robot.collides(&world, p)) {
        return Err(SimError::InvalidParameter {
            name: "robot_radius_m",
            value: config.robot_radius_m,
            expected: "a robot that fits along the corridor path",
        });
    }
    let scans = simulate(&config.sonar, &world, &poses, config.seed)?;

    let mut map = CoverageMap::new(grid);
    let mut occ = OccupancyGrid::new(grid);
    let mut readings = 0;
    for s in &scans {
        map.integrate(&s.pose, &s.ranges_m, &s.bearings_rad, &config.model)?;
        occ.integrate(&s.pose, &s.ranges_m, &s.bearings_rad, &config.model)?;
        readings += s.ranges_m.len();
    }

    let truth = world.coverage(&grid);
    let reached: Vec<bool> = occ.counts().counts().iter().map(|&c| c > 0.0).collect();
    let ml = map.ml();
    let mean = map.mean();
    let occupancy = occ.probabilities();
    let errors = |m: &[f32]| {
        let (mut all, mut n_all, mut part, mut n_part) = (0.0, 0usize, 0.0, 0usize);
        for i in (0..grid.len()).filter(|&i| reached[i]) {
            let e = (m[i] as f64 - truth[i]).abs();
            all += e;
            n_all += 1;
            if truth[i] > 0.0 && truth[i] < 1.0 {
                part += e;
                n_part += 1;
            }
        }
        MapErrors {
            all: all / n_all.max(1) as f64,
            partial: part / n_part.max(1) as f64,
        }
    };
    let bins = map.bins();
    let hist = map.histograms();
    let mut log_likelihood = 0.0;
    for i in (0..grid.len()).filter(|&i| reached[i]) {
        let b = (truth[i] * (bins - 1) as f64).round() as usize;
        log_likelihood += (hist[i * bins + b] as f64).ln();
    }
    let cells_reached = reached.iter().filter(|&&x| x).count();
    Ok(Fig3Report {
        grid,
        readings,
        cells_reached,
        mae_ml: errors(&ml),
        mae_mean: errors(&mean),
        mae_occupancy: errors(&occupancy),
        log_likelihood,
        log_likelihood_prior: cells_reached as f64 * (1.0 / bins as f64).ln(),
        entropy: map.entropy(),
        reached,
        truth,
        ml,
        mean,
        occupancy,
        poses,
    })
}

/// The seeded path of Fig. 3 through the built-in `corridor`: east along the
/// corridor from `x = 0.6` to `x = 16.3`, then back west, each leg weaving
/// gently about the centre line `y = 1.3` (a sine of seeded amplitude 0.15 to
/// 0.35 m, wavelength 3 to 6 m and phase), with a pose every `step_m` of arc
/// length, heading along the path.
pub fn corridor_path(seed: u64, step_m: f64) -> Result<Vec<Pose>> {
    check_param("step_m", step_m, step_m > 0.01, "a step longer than 1 cm")?;
    let mut rng = sim_rng_stream(seed, u64::MAX);
    let mut legs = Vec::new();
    for _ in 0..2 {
        let amplitude = 0.15 + 0.2 * rng.random::<f64>();
        let wavelength = 3.0 + 3.0 * rng.random::<f64>();
        let phase = TAU * rng.random::<f64>();
        legs.push((amplitude, wavelength, phase));
    }
    let (x0, x1) = (0.6f64, 16.3f64);
    // Each leg as a fine polyline, resampled every step_m of arc length from
    // its start; between the legs the robot turns on the spot.
    let fine = 0.01f64;
    let n = ((x1 - x0) / fine).ceil() as usize;
    let mut poses = Vec::new();
    for (k, &(a, l, ph)) in legs.iter().enumerate() {
        let points: Vec<[f64; 2]> = (0..=n)
            .map(|i| {
                let t = i as f64 / n as f64;
                let x = if k == 0 {
                    x0 + t * (x1 - x0)
                } else {
                    x1 - t * (x1 - x0)
                };
                // The weave fades in and out at the ends of each leg.
                let fade = (std::f64::consts::PI * t).sin();
                [x, 1.3 + fade * a * (TAU * x / l + ph).sin()]
            })
            .collect();
        let mut since = step_m;
        for w in points.windows(2) {
            let (p, q) = (w[0], w[1]);
            if since >= step_m {
                since = 0.0;
                poses.push(Pose::new(p[0], p[1], (q[1] - p[1]).atan2(q[0] - p[0])));
            }
            since += (q[0] - p[0]).hypot(q[1] - p[1]);
        }
    }
    Ok(poses)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn path_is_seeded_spaced_and_free() {
        let a = corridor_path(3, 0.2).unwrap();
        assert_eq!(a, corridor_path(3, 0.2).unwrap());
        assert_ne!(a, corridor_path(4, 0.2).unwrap());
        // Two legs of about 15.7 m each (a little longer for the weave).
        assert!(a.len() > 150 && a.len() < 190, "{}", a.len());
        // Poses 0.2 m apart (0.01 m resampling slack), except at the turn
        // between the legs, where the robot turns on the spot.
        let gaps: Vec<f64> = a
            .windows(2)
            .map(|w| (w[1].x_m - w[0].x_m).hypot(w[1].y_m - w[0].y_m))
            .collect();
        let off = gaps
            .iter()
            .filter(|&&d| !(0.19..0.215).contains(&d))
            .count();
        assert_eq!(off, 1, "{gaps:?}");
        assert!(gaps.iter().all(|&d| d < 0.215));
        let world = World::builtin("corridor").unwrap();
        let robot = Robot::new(0.26).unwrap();
        assert!(a.iter().all(|p| !robot.collides(&world, p)));
        assert!(corridor_path(3, 0.0).is_err());
    }
}
