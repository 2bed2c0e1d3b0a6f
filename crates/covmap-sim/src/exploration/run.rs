//! A simulated exploration run: the core loop driving the simulated robot
//! in a true world, and what the run is measured by.

use std::sync::Arc;
use std::time::Instant;

use covmap_core::exploration::{
    Exploration, ExplorationResult, ExplorationSetup, ExplorationStrategy, StepReport, Strategy,
    Termination, high_entropy_fraction, mean_absolute_error,
};
use covmap_core::{Grid, Pose, SensorModel};

use super::cells::{check_start, choose_start, clearances, evaluation_cells};
use super::options::ExploreOptions;
use super::robot_io::{WorldMotion, WorldScans};
use crate::error::Result;
use crate::robot::Robot;
use crate::world::World;

/// The core loop with the simulated robot.
pub type WorldExploration = Exploration<WorldScans, WorldMotion>;

/// Mean absolute errors of the maps' estimates of coverage against the
/// exact truth, over the evaluation cells.
///
/// The scan counts have none: a count says how often a cell was seen, not
/// how much of it is covered, and no estimate of coverage follows from it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ExplorationErrors {
    /// The coverage map's mean map.
    pub coverage_map: f64,
    /// The occupancy grid's probability of occupancy.
    pub occupancy: f64,
}

/// Everything a simulated run reports.
#[derive(Clone, Debug)]
pub struct ExplorationRun {
    /// What the loop reports: termination, path, scans, steps, trajectory,
    /// trace, timing, the maps.
    pub result: ExplorationResult,
    /// The start (chosen from the seed when none was given).
    pub start: Pose,
    /// The seed.
    pub seed: u64,
    /// The grid of the maps.
    pub grid: Grid,
    /// The exact coverage of every cell ([`World::coverage`]).
    pub truth: Vec<f64>,
    /// The cells the run is judged on ([`super::cells`]).
    pub evaluation_cells: Vec<bool>,
    /// Table I's measure: the fraction of the evaluation cells whose entropy
    /// on the coverage map is above epsilon at the end.
    pub high_entropy_fraction: f64,
    /// The maps' errors on the evaluation cells.
    pub errors: ExplorationErrors,
    /// Wall time of the whole run, the setup (ground truth, evaluation
    /// cells) included, seconds.
    pub seconds: f64,
}

/// A simulated run under way: the core loop and what the true world says
/// about it.
pub struct SimExploration {
    exploration: WorldExploration,
    start: Pose,
    seed: u64,
    truth: Vec<f64>,
    evaluation_cells: Vec<bool>,
    started: Instant,
}

/// Bytes a run keeps for each cell of its grid besides the histograms' and
/// their evidence's `8 * bins`: the truth, the clearances, the entropy, history and
/// planning maps, the occupancy grid and counts, and the flags, rounded up.
const RUN_BYTES_PER_CELL: usize = 128;

/// [`covmap_core::CovmapError::OutOfMemory`] unless what a run on `grid`
/// with `bins` bins keeps could be allocated now: checked before the first
/// of its per-cell arrays is computed, so that a grid too fine for the
/// machine is an error, not an abort halfway through the set-up.
fn check_run_memory(grid: &Grid, bins: usize) -> Result<()> {
    let per_cell = RUN_BYTES_PER_CELL.saturating_add(bins.saturating_mul(8));
    let bytes = grid.len().saturating_mul(per_cell);
    let what = format!(
        "an exploration on {} x {} cells of {bins} bins",
        grid.rows(),
        grid.cols()
    );
    let probe = covmap_core::memory::try_with_capacity::<u8>(bytes, &what)?;
    std::hint::black_box(&probe);
    Ok(())
}

impl SimExploration {
    /// A robot at the start of `options` in `world`, exploring with
    /// `strategy`; nothing scanned yet.
    ///
    /// # Errors
    /// Before anything runs: an invalid option or strategy (naming the
    /// value), a start off the grid or in an obstacle, a world too small
    /// for the robot anywhere.
    pub fn new(world: Arc<World>, strategy: Strategy, options: &ExploreOptions) -> Result<Self> {
        Self::set_up(world, strategy, None, options)
    }

    /// [`SimExploration::new`], the goals chosen by `chooser`, a strategy
    /// of the caller's ([`ExplorationStrategy`]); the result reports it as
    /// [`Strategy::Custom`].
    ///
    /// # Errors
    /// As [`SimExploration::new`].
    pub fn with_strategy(
        world: Arc<World>,
        chooser: Box<dyn ExplorationStrategy>,
        options: &ExploreOptions,
    ) -> Result<Self> {
        Self::set_up(world, Strategy::Custom, Some(chooser), options)
    }

    fn set_up(
        world: Arc<World>,
        strategy: Strategy,
        chooser: Option<Box<dyn ExplorationStrategy>>,
        options: &ExploreOptions,
    ) -> Result<Self> {
        let started = Instant::now();
        options.validate()?;
        strategy.validate()?;
        let robot = Robot::new(options.config.robot_radius_m)?;
        let [x0, y0, x1, y1] = world.bounds_m();
        let m = options.margin_m.max(options.resolution_m);
        let grid = Grid::covering(x0 - m, y0 - m, x1 + m, y1 + m, options.resolution_m)?;
        check_run_memory(&grid, options.bins)?;
        if let Some(start) = &options.start {
            check_start(&world, &grid, &robot, start)?;
        }
        let clearance = clearances(&world, &grid, &robot);
        let start = match options.start {
            Some(start) => start,
            None => choose_start(&grid, &clearance, robot.radius_m(), options.seed)?,
        };
        let model = options.model();
        let band_m = model.range_model().band_m;
        let truth = world.coverage(&grid);
        let evaluation_cells =
            evaluation_cells(&grid, &clearance, &truth, &start, robot.radius_m(), band_m)?;
        let setup = ExplorationSetup {
            grid,
            bins: options.bins,
            start,
            strategy,
            model,
            config: options.config,
            report_cells: Some(evaluation_cells.clone()),
        };
        let source = WorldScans::new(Arc::clone(&world), options.sensor.clone(), options.seed);
        let motion = WorldMotion::new(world, robot);
        let exploration = match chooser {
            Some(chooser) => Exploration::with_strategy(setup, chooser, source, motion)?,
            None => Exploration::new(setup, source, motion)?,
        };
        Ok(Self {
            exploration,
            start,
            seed: options.seed,
            truth,
            evaluation_cells,
            started,
        })
    }

    /// One step of the loop ([`Exploration::step`]).
    ///
    /// # Errors
    /// As [`Exploration::step`].
    pub fn step(&mut self) -> Result<Option<StepReport>> {
        Ok(self.exploration.step()?)
    }

    /// Steps until the run is over; how it ended.
    ///
    /// # Errors
    /// As [`Exploration::step`].
    pub fn run(&mut self) -> Result<Termination> {
        Ok(self.exploration.run()?)
    }

    /// The first scans, if none were taken; whether the run may step
    /// ([`Exploration::begin`]).
    ///
    /// # Errors
    /// As [`Exploration::begin`].
    pub fn begin(&mut self) -> Result<bool> {
        Ok(self.exploration.begin()?)
    }

    /// One step to a goal of the caller's ([`Exploration::step_to`]).
    ///
    /// # Errors
    /// As [`Exploration::step_to`].
    pub fn step_to(&mut self, goal: Pose) -> Result<Option<StepReport>> {
        Ok(self.exploration.step_to(goal)?)
    }

    /// End the run on the caller's word ([`Exploration::finish`]).
    ///
    /// # Errors
    /// As [`Exploration::finish`].
    pub fn finish(&mut self) -> Result<Termination> {
        Ok(self.exploration.finish()?)
    }

    /// The candidate viewpoints the coverage strategy weighs now
    /// ([`Exploration::viewpoints`]).
    ///
    /// # Errors
    /// As [`Exploration::viewpoints`].
    pub fn viewpoints(&mut self, alpha: f64) -> Result<covmap_core::planner::Plan> {
        Ok(self.exploration.viewpoints(alpha)?)
    }

    /// The loop: its maps, pose, trajectory, state.
    pub fn exploration(&self) -> &WorldExploration {
        &self.exploration
    }
    /// The exact coverage of every cell.
    pub fn truth(&self) -> &[f64] {
        &self.truth
    }
    /// The cells the run is judged on.
    pub fn evaluation_cells(&self) -> &[bool] {
        &self.evaluation_cells
    }
    /// The start.
    pub fn start(&self) -> Pose {
        self.start
    }

    /// Everything the run has reported so far, measured against the truth.
    ///
    /// # Errors
    /// None in practice: the maps, the truth and the cells share the grid.
    pub fn result(&self) -> Result<ExplorationRun> {
        self.parts().measure(
            self.exploration.result(),
            self.truth.clone(),
            self.evaluation_cells.clone(),
        )
    }

    /// [`SimExploration::result`], the maps moved out.
    ///
    /// # Errors
    /// As [`SimExploration::result`].
    pub fn into_result(self) -> Result<ExplorationRun> {
        let parts = self.parts();
        parts.measure(
            self.exploration.into_result(),
            self.truth,
            self.evaluation_cells,
        )
    }

    fn parts(&self) -> Measure {
        Measure {
            start: self.start,
            seed: self.seed,
            epsilon: self.exploration.config().epsilon,
            started: self.started,
        }
    }
}

/// What measuring a run needs besides its maps, truth and cells.
struct Measure {
    start: Pose,
    seed: u64,
    epsilon: f64,
    started: Instant,
}

impl Measure {
    fn measure(
        self,
        result: ExplorationResult,
        truth: Vec<f64>,
        evaluation_cells: Vec<bool>,
    ) -> Result<ExplorationRun> {
        let cells = &evaluation_cells;
        let high_entropy_fraction =
            high_entropy_fraction(&result.map.entropy(), cells, self.epsilon)?;
        let errors = ExplorationErrors {
            coverage_map: mean_absolute_error(&result.map.mean(), &truth, cells)?,
            occupancy: mean_absolute_error(&result.occupancy.probabilities(), &truth, cells)?,
        };
        Ok(ExplorationRun {
            grid: *result.map.grid(),
            result,
            start: self.start,
            seed: self.seed,
            truth,
            evaluation_cells,
            high_entropy_fraction,
            errors,
            seconds: self.started.elapsed().as_secs_f64(),
        })
    }
}

/// Explore `world` with `strategy` to the end of the run.
///
/// # Errors
/// As [`SimExploration::new`] and [`Exploration::step`].
///
/// # Example
/// ```no_run
/// use covmap_core::exploration::Strategy;
/// use covmap_sim::World;
/// use covmap_sim::exploration::{ExploreOptions, explore};
/// let world = World::builtin("corridor").unwrap();
/// let run = explore(&world, Strategy::coverage(0.5).unwrap(), &ExploreOptions::default()).unwrap();
/// assert!(run.result.termination.unwrap().by_rule());
/// println!("{:.1} m, {:.1} % uncertain", run.result.path_length_m, 100.0 * run.high_entropy_fraction);
/// ```
pub fn explore(
    world: &World,
    strategy: Strategy,
    options: &ExploreOptions,
) -> Result<ExplorationRun> {
    let mut run = SimExploration::new(Arc::new(world.clone()), strategy, options)?;
    run.run()?;
    run.into_result()
}
