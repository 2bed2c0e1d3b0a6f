//! The exploration loop, from scan to decision to motion (the drive and its
//! contacts in `drive.rs`, the read-outs kept between steps in
//! `bookkeeping.rs`).
//!
//! The run starts with a scan where the robot stands; a sensor that does
//! not see all around (a 180-degree laser) turns on the spot and scans
//! again until it has faced every way once. Then, one step of
//! [`Exploration::step`]:
//!
//! 1. **Decide** on the maps: the strategy picks a goal and a path to it on
//!    what the robot has built (never on the world), or says it is done.
//! 2. **Drive** along the path (straight lines between cell centres) through
//!    the world, with the [`Motion`]: a scan every `scan_spacing_m` of
//!    travel, and one at the goal, after turning to the goal's heading.
//! 3. **Integrate** every scan into all three maps (coverage map, occupancy
//!    grid, scan counts: the very same beams).
//! 4. On **contact** (the map showed the way free, the world did not), the
//!    robot stops at its last free point and scans; the cells it ran into
//!    are pinned certainly covered in the coverage map (after every scan
//!    from then on: [`CoverageMap::pin_covered`]) and integrated as
//!    occupied into the occupancy grid (a bumper), it backs off a cell, and
//!    the step ends: the next one replans. A goal the robot could make no headway
//!    towards (less than a centimetre) is a *failed goal*: no strategy
//!    chooses it again, since the map may go on showing the way free.
//!
//! Poses are exact: the robot is where the motion says, with no
//! localisation error (the paper's runs assume a localised robot too).

use std::time::Instant;

use super::bookkeeping::Bookkeeping;
use super::config::ExplorationConfig;
use super::region;
use super::result::{ExplorationResult, StepReport, Termination, Timing, Trace, Trajectory};
use super::sensor::AnySensorModel;
use super::source::{Motion, ScanSource};
use super::strategy::{DecisionInputs, ExplorationStrategy, GoalOutcome, NextGoal, Strategy};
use crate::counting::ScanCounts;
use crate::coverage_map::CoverageMap;
use crate::error::{CovmapError, Result};
use crate::grid::{Cell, Grid};
use crate::histogram::DEFAULT_BINS;
use crate::occupancy::{OccupancyGrid, OccupancyModel};
use crate::planner::PlanningCache;
use crate::pose::{Pose, check_bearings, check_pose};
use crate::sensor::SensorModel;

/// Headway below which a drive to a goal made none, metres.
const NO_HEADWAY_M: f64 = 0.01;

/// How far short of `max_path_m` the path may end and count as at the
/// limit, metres (rounding in the sum of the legs' lengths).
const PATH_LIMIT_TOLERANCE_M: f64 = 1e-9;

/// Everything a run starts from, besides its scan source and motion.
#[derive(Clone, Debug, PartialEq)]
pub struct ExplorationSetup {
    /// The grid of the maps (it must hold the start and everything the
    /// robot will see: the world's bounds and a margin).
    pub grid: Grid,
    /// Histogram bins of the coverage map (2 to 256; default 16).
    pub bins: usize,
    /// Where the robot starts.
    pub start: Pose,
    /// How it chooses goals.
    pub strategy: Strategy,
    /// The inverse model of its sensor.
    pub model: AnySensorModel,
    /// The other settings.
    pub config: ExplorationConfig,
    /// The cells whose uncertain fraction the per-step trace records, one
    /// flag a cell (`None`: every cell of the grid). A simulation passes its
    /// evaluation cells.
    pub report_cells: Option<Vec<bool>>,
}

impl ExplorationSetup {
    /// A setup with the defaults: 16 bins, [`AnySensorModel::default`] (the
    /// sonar), [`ExplorationConfig::default`], every cell reported.
    pub fn new(grid: Grid, start: Pose, strategy: Strategy) -> Self {
        Self {
            grid,
            bins: DEFAULT_BINS,
            start,
            strategy,
            model: AnySensorModel::default(),
            config: ExplorationConfig::default(),
            report_cells: None,
        }
    }
}

/// What a run has done so far, in numbers.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Totals {
    pub path_length_m: f64,
    pub scans: usize,
    pub steps: usize,
    pub contacts: usize,
    pub termination: Option<Termination>,
    pub timing: Timing,
}

/// A robot exploring: its maps, its strategy, where it is and has been.
///
/// Drive it one step at a time ([`Exploration::step`]) or to the end
/// ([`Exploration::run`]). (It is no iterator of its steps on purpose: an
/// iterator's `map` would hide [`Exploration::map`].)
pub struct Exploration<S, M> {
    pub(super) source: S,
    pub(super) motion: M,
    pub(super) bearings: Vec<f64>,
    pub(super) model: AnySensorModel,
    pub(super) config: ExplorationConfig,
    /// The strategy as described (what the result reports).
    strategy: Strategy,
    /// The strategy at work: its state between steps.
    chooser: Box<dyn ExplorationStrategy>,
    pub(super) map: CoverageMap,
    pub(super) occupancy: OccupancyGrid,
    /// The coverage map's read-outs, kept up to date from its change feed.
    pub(super) kept: Bookkeeping,
    pub(super) pose: Pose,
    pub(super) trajectory: Trajectory,
    pub(super) totals: Totals,
    /// Distance driven since the last scan.
    pub(super) since_scan_m: f64,
    trace: Trace,
    /// Goals (row-major cells) the robot could make no headway towards.
    pub(super) failed_goals: Vec<usize>,
    /// Every cell the robot has run into, in the order it did.
    pub(super) contact_cells: Vec<Cell>,
    /// The cells the robot's centre has driven through, row-major (the
    /// start's cell and every cell a straight leg crossed).
    pub(super) driven: Vec<bool>,
    /// What [`Exploration::viewpoints`] keeps from call to call (the
    /// candidates' gains where the map did not change under them).
    pub(super) viewpoint_cache: PlanningCache,
}

impl<S: ScanSource, M: Motion> Exploration<S, M> {
    /// A robot at `setup.start`, nothing scanned yet (the first step scans
    /// there first), choosing its goals by `setup.strategy`.
    ///
    /// # Errors
    /// Before anything runs: [`CovmapError::InvalidParameter`] naming a bad
    /// setting, strategy value, model parameter or bin count;
    /// [`CovmapError::InvalidPose`] or [`CovmapError::PoseOutsideMap`] for
    /// the start; [`CovmapError::InvalidBearing`] for a source without
    /// bearings or with one that is not finite;
    /// [`CovmapError::LengthMismatch`] for report cells that do not fit the
    /// grid.
    pub fn new(setup: ExplorationSetup, source: S, motion: M) -> Result<Self> {
        setup.strategy.validate()?;
        let chooser = setup
            .strategy
            .start(&setup.config, &setup.grid, setup.bins)?;
        Self::with_strategy(setup, chooser, source, motion)
    }

    /// [`Exploration::new`], the goals chosen by `chooser` (a strategy of
    /// the caller's; `setup.strategy` is what the result reports).
    ///
    /// # Errors
    /// As [`Exploration::new`].
    pub fn with_strategy(
        setup: ExplorationSetup,
        chooser: Box<dyn ExplorationStrategy>,
        source: S,
        motion: M,
    ) -> Result<Self> {
        let ExplorationSetup {
            grid,
            bins,
            start,
            strategy,
            model,
            config,
            report_cells,
        } = setup;
        config.validate()?;
        config.check_scan_spacing(grid.resolution_m())?;
        crate::histogram::check_bins(bins)?;
        config.check_epsilon(bins)?;
        strategy.validate()?;
        model.validate()?;
        let start_cell = grid.index(check_pose(&grid, &start)?)?;
        let bearings = source.bearings().to_vec();
        if bearings.is_empty() {
            return Err(CovmapError::InvalidBearing {
                index: 0,
                value: f64::NAN,
            });
        }
        check_bearings(start.theta_rad, &bearings)?;
        if let Some(cells) = &report_cells
            && cells.len() != grid.len()
        {
            return Err(CovmapError::LengthMismatch {
                what: "report cells and grid cells",
                left: cells.len(),
                right: grid.len(),
            });
        }
        let mut map = CoverageMap::with_bins(grid, bins)?;
        map.track_history(true);
        let counts = match strategy {
            Strategy::Counting {
                discount_beyond_m: Some(d),
                ..
            } => ScanCounts::with_discount(grid, d)?,
            _ => ScanCounts::new(grid),
        };
        let occupancy = OccupancyGrid::with_model(OccupancyModel::default(), counts)?;
        let kept = Bookkeeping::new(&map, report_cells, config.epsilon);
        Ok(Self {
            source,
            motion,
            bearings,
            model,
            config,
            strategy,
            chooser,
            map,
            occupancy,
            kept,
            pose: start,
            // The start is the first pose before anything runs; the first
            // scan, taken there, marks it scanned.
            trajectory: {
                let mut trajectory = Trajectory::default();
                trajectory.push(start, false);
                trajectory
            },
            totals: Totals::default(),
            since_scan_m: 0.0,
            trace: Trace::default(),
            failed_goals: Vec::new(),
            viewpoint_cache: PlanningCache::new(),
            contact_cells: Vec::new(),
            driven: (0..grid.len()).map(|i| i == start_cell).collect(),
        })
    }

    /// One step: decide, drive, scan, integrate (see the
    /// [module documentation](crate::exploration)). Returns what the step did, or `None`
    /// once the run is over (the strategy is done or a limit is reached:
    /// [`Exploration::termination`] says which).
    ///
    /// # Errors
    /// An error of the scan source, the motion or the strategy, passed on.
    /// The run can go on after it; the scan that failed was not integrated.
    pub fn step(&mut self) -> Result<Option<StepReport>> {
        if !self.begin()? {
            return Ok(None);
        }

        // 1. Decide on the maps.
        let started = Instant::now();
        let decision = {
            let (chooser, inputs) = self.chooser_and_inputs();
            chooser.decide(&inputs)?
        };
        let planning_s = started.elapsed().as_secs_f64();
        match decision {
            NextGoal::Done(termination) => {
                self.totals.timing.planning_s += planning_s;
                self.totals.termination = Some(termination);
                Ok(None)
            }
            NextGoal::Goal { pose, path } => self.go(pose, path, planning_s).map(Some),
        }
    }

    /// Before a step: the first scans where the robot stands (if it has
    /// taken none), then whether the run may take a step (`false` once it
    /// is over; reaching a limit ends it). A strategy outside the loop
    /// calls it before it looks at the maps.
    ///
    /// # Errors
    /// An error of the scan source, passed on.
    pub fn begin(&mut self) -> Result<bool> {
        if self.totals.termination.is_some() {
            return Ok(false);
        }
        if self.totals.scans == 0 {
            self.look_around()?;
            self.take_in_changes();
        }
        if self.at_path_limit() || self.totals.steps >= self.config.max_steps {
            self.totals.termination = Some(Termination::Limit);
            return Ok(false);
        }
        Ok(true)
    }

    /// Steps 2 to 4 of a step to `goal` along `path`, chosen in
    /// `planning_s` seconds: drive, scan and integrate, learn, record.
    ///
    /// # Errors
    /// An error of the scan source or the motion, passed on.
    pub(super) fn go(
        &mut self,
        goal: Pose,
        path: Vec<[f64; 2]>,
        planning_s: f64,
    ) -> Result<StepReport> {
        self.totals.timing.planning_s += planning_s;
        // 2.-4. Drive through the world, scanning and integrating on the way.
        let drive = self.follow(&path, &goal)?;
        self.take_in_changes();
        if !drive.reached
            && drive.headway_m < NO_HEADWAY_M
            && let Some(cell) = self.map.grid().world_to_cell(goal.x_m, goal.y_m)
        {
            self.failed_goals.push(self.map.grid().index(cell)?);
        }
        let outcome = GoalOutcome {
            reached: drive.reached,
        };
        let (chooser, inputs) = self.chooser_and_inputs();
        chooser.learn(&inputs, &outcome);

        let report = StepReport {
            index: self.totals.steps,
            goal,
            path,
            reached: drive.reached,
            contact_m: drive.contact_m,
            travelled_m: drive.travelled_m,
            scans: drive.scans,
            pose: self.pose,
        };
        self.totals.steps += 1;
        self.trace.path_length_m.push(self.totals.path_length_m);
        self.trace.scans.push(self.totals.scans);
        self.trace
            .uncertain_fraction
            .push(self.kept.uncertain_fraction());
        self.trace.contact.push(drive.contact_m.is_some());
        self.trace.planning_s.push(planning_s);
        Ok(report)
    }

    /// Steps until the run is over; how it ended.
    ///
    /// # Errors
    /// As [`Exploration::step`].
    pub fn run(&mut self) -> Result<Termination> {
        while self.step()?.is_some() {}
        Ok(self.totals.termination.unwrap_or(Termination::Limit))
    }

    /// Bring the read-outs up to date with what the scans of a step changed.
    fn take_in_changes(&mut self) {
        let started = Instant::now();
        self.kept.take_in(&self.map);
        self.totals.timing.integration_s += started.elapsed().as_secs_f64();
    }

    /// The strategy, and what it sees.
    fn chooser_and_inputs(&mut self) -> (&mut dyn ExplorationStrategy, DecisionInputs<'_>) {
        let inputs = DecisionInputs {
            map: &self.map,
            ml: &self.kept.ml,
            entropy: &self.kept.entropy,
            changed: &self.kept.changed,
            occupancy: &self.occupancy,
            contact_cells: &self.contact_cells,
            driven: &self.driven,
            pose: self.pose,
            bearings: &self.bearings,
            model: &self.model,
            config: &self.config,
            failed_goals: &self.failed_goals,
        };
        (self.chooser.as_mut(), inputs)
    }
}

impl<S, M> Exploration<S, M> {
    /// Whether the robot has driven as far as the run may (within
    /// [`PATH_LIMIT_TOLERANCE_M`]: the legs' lengths, added up, can fall
    /// short of the limit by a rounding error, and a run would then go on
    /// with steps that drive nothing).
    pub(super) fn at_path_limit(&self) -> bool {
        self.totals.path_length_m >= self.config.max_path_m - PATH_LIMIT_TOLERANCE_M
    }

    /// The region the robot can reach on its coverage map now, one flag a
    /// cell: the cells the coverage strategy's termination rule and the
    /// counting strategy's unexplored cells are taken from (see
    /// [`Strategy`]'s documentation).
    ///
    /// # Errors
    /// None in practice (the robot's pose lies on the map).
    pub fn region(&self) -> Result<Vec<bool>> {
        let navigator = region::navigator(self.config.robot_radius_m, 0.0)?;
        region::reachable_region(
            &navigator,
            &self.map,
            &self.pose,
            self.model.as_dyn().range_model().band_m,
            &self.driven,
        )
    }

    /// The fraction of the report cells whose entropy is above epsilon now.
    pub fn uncertain_fraction(&self) -> f64 {
        self.kept.uncertain_fraction()
    }

    /// The coverage map being built.
    pub fn map(&self) -> &CoverageMap {
        &self.map
    }
    /// The occupancy grid being built from the same beams.
    pub fn occupancy(&self) -> &OccupancyGrid {
        &self.occupancy
    }
    /// The scan counts of the same beams.
    pub fn counts(&self) -> &ScanCounts {
        self.occupancy.counts()
    }
    /// Where the robot is.
    pub fn pose(&self) -> Pose {
        self.pose
    }
    /// Every pose so far, scans marked.
    pub fn trajectory(&self) -> &Trajectory {
        &self.trajectory
    }
    /// Distance driven so far, metres.
    pub fn path_length_m(&self) -> f64 {
        self.totals.path_length_m
    }
    /// Steps taken so far.
    pub fn steps(&self) -> usize {
        self.totals.steps
    }
    /// Scans taken so far.
    pub fn scans(&self) -> usize {
        self.totals.scans
    }
    /// The strategy.
    pub fn strategy(&self) -> &Strategy {
        &self.strategy
    }
    /// The settings.
    pub fn config(&self) -> &ExplorationConfig {
        &self.config
    }
    /// The inverse sensor model.
    pub fn model(&self) -> &AnySensorModel {
        &self.model
    }
    /// How the run ended, `None` while it goes on.
    pub fn termination(&self) -> Option<Termination> {
        self.totals.termination
    }
    /// Whether the run is over.
    pub fn done(&self) -> bool {
        self.totals.termination.is_some()
    }
    /// The scan source.
    pub fn source(&self) -> &S {
        &self.source
    }
    /// The motion.
    pub fn motion(&self) -> &M {
        &self.motion
    }

    /// Everything the run has reported so far (the maps copied).
    pub fn result(&self) -> ExplorationResult {
        let maps = (self.map.clone(), self.occupancy.clone());
        let path = (self.trajectory.clone(), self.trace.clone());
        assemble(self.strategy, self.totals, path, maps)
    }

    /// [`Exploration::result`], the maps moved out.
    pub fn into_result(self) -> ExplorationResult {
        let (maps, path) = ((self.map, self.occupancy), (self.trajectory, self.trace));
        assemble(self.strategy, self.totals, path, maps)
    }
}

/// A run's result from its parts.
fn assemble(
    strategy: Strategy,
    totals: Totals,
    (trajectory, trace): (Trajectory, Trace),
    (map, occupancy): (CoverageMap, OccupancyGrid),
) -> ExplorationResult {
    ExplorationResult {
        strategy,
        termination: totals.termination,
        path_length_m: totals.path_length_m,
        scans: totals.scans,
        steps: totals.steps,
        contacts: totals.contacts,
        trajectory,
        trace,
        timing: totals.timing,
        map,
        occupancy,
    }
}

#[cfg(test)]
#[path = "exploration_tests.rs"]
mod tests;
