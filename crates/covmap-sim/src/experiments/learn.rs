//! Learning the sensor model in simulation: a training drive in one world,
//! a test drive in another, and the learned model measured against the
//! default on both (`covmap learn`; paper section 5).

use covmap_core::exploration::AnySensorModel;
use covmap_core::histogram::DEFAULT_BINS;
use covmap_core::learn::{
    FitData, FitOptions, SensorFit, fit_sensor_model, log_likelihood, map_of_log,
};
use covmap_core::planner::{DEFAULT_EPSILON, shortest_paths};
use covmap_core::{CoverageMap, Grid, Log, OccupancyGrid, Pose};
use covmap_core::{ScanMap, integrate_log_occluded};
use rand::RngExt;

use crate::error::{Result, check_param};
use crate::exploration::{choose_start, clearances, evaluation_cells};
use crate::laser::Laser;
use crate::reached::reached_counts;
use crate::rng::sim_rng_stream;
use crate::robot::Robot;
use crate::simulate::record;
use crate::sonar::SonarRing;
use crate::world::World;

/// The stream of a drive's seed its waypoints are drawn from.
const DRIVE_STREAM: u64 = u64::MAX - 1;

/// A drive through `world` for a robot of `robot_radius_m`: from the start
/// a run seeded `seed` would take ([`choose_start`]), along shortest paths
/// through the true free space (cells whose centre keeps the robot's disc
/// clear by its radius again) to waypoints drawn uniformly among the cells
/// 1.5 m or more away, with a pose every `step_m` of path, heading along
/// the path, until there are `scans` poses.
///
/// # Errors
/// For a step not above 1 cm or no scans; as [`choose_start`] if the robot
/// fits nowhere.
pub fn survey_drive(
    world: &World,
    grid: &Grid,
    robot_radius_m: f64,
    seed: u64,
    step_m: f64,
    scans: usize,
) -> Result<Vec<Pose>> {
    check_param("step_m", step_m, step_m > 0.01, "a step longer than 1 cm")?;
    check_param(
        "scans",
        scans as f64,
        (1..=MAX_DRIVE_SCANS).contains(&scans),
        "1 to 100000 scans",
    )?;
    let robot = Robot::new(robot_radius_m)?;
    let clearance = clearances(world, grid, &robot);
    let start = choose_start(grid, &clearance, robot_radius_m, seed)?;
    let roomy: Vec<bool> = clearance.iter().map(|&c| c >= robot_radius_m).collect();
    let mut rng = sim_rng_stream(seed, DRIVE_STREAM);
    let mut poses = vec![start];
    let Some(mut at) = grid.world_to_cell(start.x_m, start.y_m) else {
        return Err(covmap_core::CovmapError::InvalidStart {
            x: start.x_m,
            y: start.y_m,
            reason: "off the grid".into(),
        }
        .into());
    };
    let mut since = 0.0;
    while poses.len() < scans {
        let mut passable = roomy.clone();
        passable[grid.index(at)?] = true;
        let reach = shortest_paths(grid, &passable, at)?;
        let targets: Vec<usize> = (0..grid.len())
            .filter(|&i| reach.cost(i).is_finite() && reach.cost(i) >= 1.5)
            .collect();
        if targets.is_empty() {
            break;
        }
        let target = targets[rng.random_range(0..targets.len())];
        let path = reach.path_to(target);
        for w in path.windows(2) {
            let (p, q) = (w[0], w[1]);
            let length = (q[0] - p[0]).hypot(q[1] - p[1]);
            since += length;
            if since >= step_m && poses.len() < scans {
                since = 0.0;
                poses.push(Pose::new(q[0], q[1], (q[1] - p[1]).atan2(q[0] - p[0])));
            }
        }
        at = grid.cell(target);
    }
    Ok(poses)
}

/// The setting of [`learn`].
#[derive(Clone, Debug, PartialEq)]
pub struct LearnConfig {
    /// The built-in world of the training drive.
    pub train_world: String,
    /// The built-in world of the test drive.
    pub test_world: String,
    /// The model the fit starts from; its kind picks the simulated sensor
    /// (the 24-sonar ring, or a 180-degree laser of 181 beams).
    pub model: AnySensorModel,
    /// Scans of each drive.
    pub scans: usize,
    /// Path between scans, metres.
    pub step_m: f64,
    /// Grid resolution, metres.
    pub resolution_m: f64,
    /// Seed of the training drive (path and readings).
    pub train_seed: u64,
    /// Seed of the test drive.
    pub test_seed: u64,
    /// How the fit searches, and how its maps take no-echo readings: by
    /// default occluded by the map ([`FitOptions::occlude_no_echo`] on), as
    /// the exploration loop builds its maps
    /// ([`covmap_core::exploration::ExplorationConfig::occlude_no_echo`]),
    /// so the model is fitted to the maps it serves. The drives' scores
    /// (and their occupancy grids) take the readings the same way.
    pub fit: FitOptions,
    /// Whether the fit scores the training drive's judged cells only
    /// ([`Drive::judged`]) rather than every cell of its grid.
    pub judged_only: bool,
}

/// The most scans a drive of [`learn`] may have.
pub const MAX_DRIVE_SCANS: usize = 100_000;

impl LearnConfig {
    /// Errors, naming the value, unless the drives' setting is usable:
    /// 1 to [`MAX_DRIVE_SCANS`] scans, a step of more than 1 cm and at most
    /// 10 m, cells of 1 cm to 1 m.
    pub fn validate(&self) -> Result<()> {
        check_param(
            "scans",
            self.scans as f64,
            (1..=MAX_DRIVE_SCANS).contains(&self.scans),
            "1 to 100000 scans",
        )?;
        check_param(
            "step_m",
            self.step_m,
            self.step_m > 0.01 && self.step_m <= 10.0,
            "a step of more than 1 cm and at most 10 m",
        )?;
        check_param(
            "resolution_m",
            self.resolution_m,
            (0.01..=1.0).contains(&self.resolution_m),
            "a cell size from 0.01 to 1 m",
        )
    }
}

impl Default for LearnConfig {
    fn default() -> Self {
        Self {
            train_world: "corridor".into(),
            test_world: "office".into(),
            model: AnySensorModel::default(),
            scans: 300,
            step_m: 0.15,
            resolution_m: 0.05,
            train_seed: 0,
            test_seed: 1,
            fit: FitOptions {
                occlude_no_echo: true,
                ..FitOptions::default()
            },
            judged_only: false,
        }
    }
}

/// One drive, its map's grid and ground truth.
#[derive(Clone, Debug)]
pub struct Drive {
    /// The drive's world's name.
    pub world: String,
    /// The recorded drive.
    pub log: Log,
    /// The grid maps of it are built on: the world's bounds and 0.5 m.
    pub grid: Grid,
    /// The exact coverage of every cell.
    pub truth: Vec<f64>,
    /// How many of the drive's scans reached each cell: the sound (or
    /// light) travelled there in the true world ([`reached_counts`]).
    pub reached: Vec<u32>,
    /// The cells the drive is judged on: those its readings reached (the
    /// sound travelled there: [`Drive::reached`] above 0) that a robot
    /// driving from the drive's start could observe ([`evaluation_cells`]
    /// with a 0.25 m robot and a 0.2 m end band: the free space it can
    /// reach and the obstacle cells that bound it). Not the free space
    /// behind walls nor the insides of thick walls: no reading reaches
    /// them, though no-echo footprints run through them.
    pub judged: Vec<bool>,
    /// The occupancy grid's probabilities of the drive (the baseline, built
    /// with the model the drive was simulated with, fed the same beams as
    /// that model's coverage map: with its no-echo readings occluded by
    /// that map if the drive is, see [`Drive::simulate`]).
    pub occupancy: Vec<f32>,
}

impl Drive {
    /// Simulate a drive of `scans` scans through built-in world `name` with
    /// the sensor `model` stands for; its baseline occupancy grid is fed
    /// the beams as `model`'s coverage map takes them, with no-echo readings
    /// occluded by the map of the log's echoes if `occlude_no_echo`
    /// ([`integrate_log_occluded`]).
    pub fn simulate(
        name: &str,
        model: &AnySensorModel,
        (scans, step_m, resolution_m): (usize, f64, f64),
        seed: u64,
        occlude_no_echo: bool,
    ) -> Result<Self> {
        let world = World::builtin(name)?;
        let [x0, y0, x1, y1] = world.bounds_m();
        let grid = Grid::covering(x0 - 0.5, y0 - 0.5, x1 + 0.5, y1 + 0.5, resolution_m)?;
        let poses = survey_drive(&world, &grid, 0.25, seed, step_m, scans)?;
        let truth = world.coverage(&grid);
        let clearance = clearances(&world, &grid, &Robot::new(0.25)?);
        let observable = evaluation_cells(&grid, &clearance, &truth, &poses[0], 0.25, 0.2)?;
        let log = match model {
            AnySensorModel::Sonar(m) => {
                record(&SonarRing::default().with_model(m), &world, &poses, seed)?
            }
            AnySensorModel::Laser(m) => {
                let mut laser = Laser::sick_180();
                laser.max_range_m = m.range.max_range_m;
                record(&laser, &world, &poses, seed)?
            }
        };
        // The baseline comes from the drive's own sensor (the model it was
        // simulated with), the same for every model scored.
        let mut occupancy = OccupancyGrid::new(grid);
        if occlude_no_echo {
            let mut map = CoverageMap::with_bins(grid, DEFAULT_BINS)?;
            integrate_log_occluded(
                &mut map,
                &log,
                model.as_dyn(),
                DEFAULT_EPSILON,
                &mut |_| {},
                |scan| occupancy.integrate_checked(scan, model.as_dyn()),
            )?;
        } else {
            occupancy.integrate_log(&log, model)?;
        }
        let reached = reached_counts(&world, &grid, &log, model.as_dyn().footprint());
        let judged = reached
            .iter()
            .zip(&observable)
            .map(|(&c, &observable)| c > 0 && observable)
            .collect();
        Ok(Self {
            world: name.into(),
            truth,
            reached,
            judged,
            occupancy: occupancy.probabilities(),
            log,
            grid,
        })
    }

    /// The mean absolute error of `values` against the truth over the
    /// judged cells whose truth `keep` accepts.
    pub fn error_where(&self, values: &[f32], keep: impl Fn(f64) -> bool) -> f64 {
        let (sum, n) = (0..self.grid.len())
            .filter(|&i| self.judged[i] && keep(self.truth[i]))
            .fold((0.0, 0usize), |(s, n), i| {
                (s + (f64::from(values[i]) - self.truth[i]).abs(), n + 1)
            });
        sum / n.max(1) as f64
    }

    /// How well maps of this drive built with `model` match the truth (its
    /// no-echo readings occluded by the map if `occlude_no_echo`, see
    /// [`covmap_core::CoverageMap::occluding`]).
    pub fn score(&self, model: &AnySensorModel, occlude_no_echo: bool) -> Result<DriveScore> {
        let map = map_of_log(&self.fit_data(None), DEFAULT_BINS, model, occlude_no_echo)?;
        let mean = map.mean();
        let walls = self.faced_walls();
        Ok(DriveScore {
            log_likelihood: log_likelihood(&map, &self.truth, None)?,
            judged_log_likelihood: log_likelihood(&map, &self.truth, Some(&self.judged))?,
            mean_error: self.error_where(&mean, |_| true),
            free_error: self.error_where(&mean, |t| t == 0.0),
            obstacle_error: self.error_where(&mean, |t| t > 0.0),
            occupancy_error: self.error_where(&self.occupancy, |_| true),
            cells_reached: self.judged.iter().filter(|&&r| r).count(),
            wall_coverage: mean_over(&mean, &walls),
            occupancy_wall: mean_over(&self.occupancy, &walls),
        })
    }

    /// The wall cells whose face the drive's sound reached repeatedly: the
    /// fully covered cells (true coverage at least 0.99) within the end
    /// band ([`WALL_BAND_M`]) of a cell that at least [`FACED_SCANS`] scans
    /// reached. A face cell itself is most often cut by the face and only
    /// partly covered; the cells behind it are the wall.
    pub fn faced_walls(&self) -> Vec<bool> {
        let faced: Vec<bool> = self.reached.iter().map(|&c| c >= FACED_SCANS).collect();
        let near = covmap_core::exploration::dilate(&self.grid, &faced, WALL_BAND_M);
        (0..self.grid.len())
            .map(|i| near[i] && self.truth[i] >= 0.99)
            .collect()
    }
}

/// Scans that must have reached a wall's face for the wall to count as
/// faced repeatedly ([`Drive::faced_walls`]).
pub const FACED_SCANS: u32 = 20;

/// How deep behind a face the cells of a faced wall are taken, metres:
/// the default sonar model's end band.
pub const WALL_BAND_M: f64 = 0.2;

/// The mean of `values` over the flagged cells (NaN if none is).
fn mean_over(values: &[f32], flagged: &[bool]) -> f64 {
    let (sum, n) = values
        .iter()
        .zip(flagged)
        .filter(|(_, f)| **f)
        .fold((0.0, 0usize), |(s, n), (&v, _)| (s + f64::from(v), n + 1));
    if n == 0 { f64::NAN } else { sum / n as f64 }
}

impl Drive {
    /// The drive as a fit takes it, scored over `cells` (all if `None`).
    pub fn fit_data<'a>(&'a self, cells: Option<&'a [bool]>) -> FitData<'a> {
        FitData {
            log: &self.log,
            grid: self.grid,
            truth: &self.truth,
            cells,
        }
    }
}

/// How well the maps of one drive, built with one model, match the truth.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DriveScore {
    /// Log-likelihood of the truth under the coverage map, over every cell.
    pub log_likelihood: f64,
    /// The same over the judged cells ([`Drive::judged`]).
    pub judged_log_likelihood: f64,
    /// Mean absolute error of the coverage map's mean over the judged cells
    /// ([`Drive::judged`]).
    pub mean_error: f64,
    /// The same over the reached cells that are free (truth 0).
    pub free_error: f64,
    /// The same over the reached cells that hold some obstacle (truth above 0).
    pub obstacle_error: f64,
    /// The same of the occupancy grid's probabilities (the drive's baseline,
    /// whatever the model scored).
    pub occupancy_error: f64,
    /// The judged cells.
    pub cells_reached: usize,
    /// The mean coverage of the coverage map's mean over the faced walls
    /// ([`Drive::faced_walls`]): above 0.5, walls survived the no-echo
    /// readings that crossed them.
    pub wall_coverage: f64,
    /// The occupancy grid's mean probability over the same cells.
    pub occupancy_wall: f64,
}

/// What [`learn`] found.
#[derive(Clone, Debug)]
pub struct LearnReport {
    /// The fit on the training drive.
    pub fit: SensorFit<AnySensorModel>,
    /// The starting model on the training drive, then on the test drive.
    pub default_scores: [DriveScore; 2],
    /// The learned model on both.
    pub learned_scores: [DriveScore; 2],
    /// The two drives.
    pub drives: [Drive; 2],
}

/// Simulate a training and a test drive, fit the model on the training
/// drive and score the starting and the learned model on both; `progress`
/// gets the fit's evaluations so far.
///
/// # Errors
/// For an unknown world, an invalid drive setting, and as
/// [`fit_sensor_model`].
pub fn learn(config: &LearnConfig, progress: &(dyn Fn(usize) + Sync)) -> Result<LearnReport> {
    config.validate()?;
    let drive = (config.scans, config.step_m, config.resolution_m);
    let occlude = config.fit.occlude_no_echo;
    let train = Drive::simulate(
        &config.train_world,
        &config.model,
        drive,
        config.train_seed,
        occlude,
    )?;
    let test = Drive::simulate(
        &config.test_world,
        &config.model,
        drive,
        config.test_seed,
        occlude,
    )?;
    let data = train.fit_data(config.judged_only.then_some(&train.judged[..]));
    let fit = fit_sensor_model(&data, &config.model, &config.fit, progress)?;
    let scores = |m: &AnySensorModel| -> Result<[DriveScore; 2]> {
        let occlude = config.fit.occlude_no_echo;
        Ok([train.score(m, occlude)?, test.score(m, occlude)?])
    };
    Ok(LearnReport {
        default_scores: scores(&config.model)?,
        learned_scores: scores(&fit.model)?,
        fit,
        drives: [train, test],
    })
}
