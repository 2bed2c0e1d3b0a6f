//! The exploration loop, from scan to decision to motion.
//!
//! One step of [`Exploration::step`]:
//!
//! 1. **Decide** on the maps: the strategy picks a goal and a path to it on
//!    what the robot has built (never on the world), or says it is done.
//! 2. **Drive** along the path (straight lines between cell centres) through
//!    the world, with the [`Motion`]: a scan every `scan_spacing_m` of
//!    travel, and one at the goal, after turning to the goal's heading.
//! 3. **Integrate** every scan into all three maps (coverage map, occupancy
//!    grid, scan counts: the very same beams).
//! 4. On **contact** (the map showed the way free, the world did not), the
//!    robot stops at its last free point and scans; the cell it ran into is
//!    integrated as covered into the coverage map and as occupied into the
//!    occupancy grid (a bumper), and the step ends: the next one replans.
//!
//! Poses are exact: the robot is where the motion says, with no
//! localisation error (the paper's runs assume a localised robot too).

use std::time::Instant;

use super::config::ExplorationConfig;
use super::result::{ExplorationResult, StepReport, Termination, Timing, Trace, Trajectory};
use super::sensor::AnySensorModel;
use super::source::{Motion, ScanSource};
use super::strategy::{Chooser, Decision, Outcome, Strategy, View};
use crate::counting::ScanCounts;
use crate::coverage_map::CoverageMap;
use crate::error::{CovmapError, Result};
use crate::grid::Grid;
use crate::histogram::DEFAULT_BINS;
use crate::occupancy::{OccupancyGrid, OccupancyModel};
use crate::pose::{Pose, check_bearings, check_pose};
use crate::sensor::SensorModel;

/// How far a contact point is moved into the obstacle to find the cell it
/// lies in, metres (a point on a cell's edge belongs to one of two cells).
const INTO_CONTACT_M: f64 = 1e-3;

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

/// A robot exploring: its maps, its strategy, where it is and has been.
///
/// Drive it one step at a time ([`Exploration::step`], or as an iterator of
/// steps) or to the end ([`Exploration::run`]).
pub struct Exploration<S, M> {
    source: S,
    motion: M,
    bearings: Vec<f64>,
    model: AnySensorModel,
    config: ExplorationConfig,
    strategy: Strategy,
    chooser: Chooser,
    map: CoverageMap,
    occupancy: OccupancyGrid,
    /// The coverage map's entropy after the last scan.
    entropy: Vec<f32>,
    report_cells: Option<Vec<bool>>,
    pose: Pose,
    trajectory: Trajectory,
    path_length_m: f64,
    /// Distance driven since the last scan.
    since_scan_m: f64,
    scans: usize,
    steps: usize,
    contacts: usize,
    trace: Trace,
    timing: Timing,
    termination: Option<Termination>,
}

/// How one drive along a path went.
struct Drive {
    reached: bool,
    travelled_m: f64,
    scans: usize,
    contact_m: Option<[f64; 2]>,
}

impl<S: ScanSource, M: Motion> Exploration<S, M> {
    /// A robot at `setup.start`, nothing scanned yet (the first step scans
    /// there first).
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
        strategy.validate()?;
        model.validate()?;
        check_pose(&grid, &start)?;
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
        let chooser = Chooser::new(&strategy, &config, &grid)?;
        let entropy = map.entropy();
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
            entropy,
            report_cells,
            pose: start,
            trajectory: Trajectory::default(),
            path_length_m: 0.0,
            since_scan_m: 0.0,
            scans: 0,
            steps: 0,
            contacts: 0,
            trace: Trace::default(),
            timing: Timing::default(),
            termination: None,
        })
    }

    /// One step: decide, drive, scan, integrate (see the
    /// [module documentation](self)). Returns what the step did, or `None`
    /// once the run is over (the strategy is done or a limit is reached:
    /// [`Exploration::termination`] says which).
    ///
    /// # Errors
    /// An error of the scan source or the motion, passed on. The run can go
    /// on after it; the scan that failed was not integrated.
    pub fn step(&mut self) -> Result<Option<StepReport>> {
        if self.termination.is_some() {
            return Ok(None);
        }
        if self.scans == 0 {
            self.scan_here()?;
            self.refresh_entropy();
        }
        if self.path_length_m >= self.config.max_path_m || self.steps >= self.config.max_steps {
            self.termination = Some(Termination::Limit);
            return Ok(None);
        }

        // 1. Decide on the maps.
        let started = Instant::now();
        let decision = {
            let (chooser, view) = self.chooser_and_view();
            chooser.decide(&view)?
        };
        let planning_s = started.elapsed().as_secs_f64();
        self.timing.planning_s += planning_s;
        let (goal, path) = match decision {
            Decision::Done(termination) => {
                self.termination = Some(termination);
                return Ok(None);
            }
            Decision::Goal { pose, path } => (pose, path),
        };

        // 2.-4. Drive through the world, scanning and integrating on the way.
        let drive = self.follow(&path, &goal)?;
        self.refresh_entropy();
        let outcome = Outcome {
            reached: drive.reached,
            travelled_m: drive.travelled_m,
        };
        let (chooser, view) = self.chooser_and_view();
        chooser.learn(&view, &outcome);

        let report = StepReport {
            index: self.steps,
            goal,
            path,
            reached: drive.reached,
            contact_m: drive.contact_m,
            travelled_m: drive.travelled_m,
            scans: drive.scans,
            pose: self.pose,
        };
        self.steps += 1;
        self.trace.path_length_m.push(self.path_length_m);
        self.trace.scans.push(self.scans);
        self.trace
            .uncertain_fraction
            .push(self.uncertain_fraction());
        self.trace.contact.push(drive.contact_m.is_some());
        self.trace.planning_s.push(planning_s);
        Ok(Some(report))
    }

    /// Steps until the run is over; how it ended.
    ///
    /// # Errors
    /// As [`Exploration::step`].
    pub fn run(&mut self) -> Result<Termination> {
        while self.step()?.is_some() {}
        Ok(self.termination.unwrap_or(Termination::Limit))
    }

    /// Drive along `path` (cell centres, from the robot's cell) to `goal`:
    /// straight legs, a scan every `scan_spacing_m`, a stop at a contact or
    /// at the path limit, a turn to the goal's heading and a scan at the goal.
    fn follow(&mut self, path: &[[f64; 2]], goal: &Pose) -> Result<Drive> {
        let resolution_m = self.map.grid().resolution_m();
        let mut drive = Drive {
            reached: false,
            travelled_m: 0.0,
            scans: self.scans,
            contact_m: None,
        };
        for waypoint in straight_runs(path, resolution_m) {
            loop {
                let here = [self.pose.x_m, self.pose.y_m];
                let left_m = (waypoint[0] - here[0]).hypot(waypoint[1] - here[1]);
                if left_m <= 1e-9 {
                    break;
                }
                let budget_m = self.config.max_path_m - self.path_length_m;
                let leg_m = left_m
                    .min(self.config.scan_spacing_m - self.since_scan_m)
                    .min(budget_m);
                let direction = [
                    (waypoint[0] - here[0]) / left_m,
                    (waypoint[1] - here[1]) / left_m,
                ];
                let to = if leg_m >= left_m {
                    waypoint
                } else {
                    [
                        here[0] + direction[0] * leg_m,
                        here[1] + direction[1] * leg_m,
                    ]
                };
                let started = Instant::now();
                let travel = self.motion.drive(here, to)?;
                self.timing.sensing_s += started.elapsed().as_secs_f64();

                let travelled_m = travel.travelled_m.clamp(0.0, leg_m);
                self.pose = Pose::new(
                    here[0] + direction[0] * travelled_m,
                    here[1] + direction[1] * travelled_m,
                    direction[1].atan2(direction[0]),
                );
                self.trajectory.push(self.pose, false);
                self.path_length_m += travelled_m;
                self.since_scan_m += travelled_m;
                drive.travelled_m += travelled_m;

                if let Some(contact_m) = travel.contact_m {
                    self.scan_here()?;
                    self.integrate_contact(contact_m)?;
                    drive.contact_m = Some(contact_m);
                    drive.scans = self.scans - drive.scans;
                    return Ok(drive);
                }
                if self.since_scan_m >= self.config.scan_spacing_m - 1e-9 {
                    self.scan_here()?;
                }
                if self.path_length_m >= self.config.max_path_m - 1e-9 {
                    if self.since_scan_m > 0.0 {
                        self.scan_here()?;
                    }
                    drive.scans = self.scans - drive.scans;
                    return Ok(drive);
                }
            }
        }
        // At the goal: face the goal's heading and scan.
        let turned = self.pose.theta_rad != goal.theta_rad;
        if turned {
            self.pose.theta_rad = goal.theta_rad;
            self.trajectory.push(self.pose, false);
        }
        if turned || self.since_scan_m > 0.0 || drive.travelled_m == 0.0 {
            self.scan_here()?;
        }
        drive.reached = true;
        drive.scans = self.scans - drive.scans;
        Ok(drive)
    }

    /// Scan from the robot's pose and integrate the scan into every map.
    fn scan_here(&mut self) -> Result<()> {
        let started = Instant::now();
        let ranges = self.source.scan(&self.pose)?;
        let integrating = Instant::now();
        self.timing.sensing_s += (integrating - started).as_secs_f64();
        let (pose, bearings, model) = (&self.pose, &self.bearings[..], self.model.as_dyn());
        // The coverage map validates the scan first: an invalid one changes no map.
        self.map.integrate(pose, &ranges, bearings, model)?;
        self.occupancy.integrate(pose, &ranges, bearings, model)?;
        self.timing.integration_s += integrating.elapsed().as_secs_f64();
        self.scans += 1;
        self.since_scan_m = 0.0;
        match (
            self.trajectory.poses.last(),
            self.trajectory.scanned.last_mut(),
        ) {
            (Some(last), Some(scanned)) if *last == self.pose && !*scanned => *scanned = true,
            _ => self.trajectory.push(self.pose, true),
        }
        Ok(())
    }

    /// Integrate a contact at `contact_m` (world metres) into the coverage
    /// map and the occupancy grid: the cell the robot ran into.
    fn integrate_contact(&mut self, contact_m: [f64; 2]) -> Result<()> {
        let started = Instant::now();
        let (dx, dy) = (contact_m[0] - self.pose.x_m, contact_m[1] - self.pose.y_m);
        let length = dx.hypot(dy).max(f64::MIN_POSITIVE);
        let inside = [
            contact_m[0] + INTO_CONTACT_M * dx / length,
            contact_m[1] + INTO_CONTACT_M * dy / length,
        ];
        let cell = self.map.grid().check_inside(inside[0], inside[1])?;
        self.map.integrate_contact(cell)?;
        self.occupancy.integrate_contact(cell)?;
        self.contacts += 1;
        self.timing.integration_s += started.elapsed().as_secs_f64();
        Ok(())
    }

    /// Recompute the entropy map after the scans of a step.
    fn refresh_entropy(&mut self) {
        let started = Instant::now();
        self.entropy = self.map.entropy();
        self.timing.integration_s += started.elapsed().as_secs_f64();
    }

    /// The strategy, and what it sees.
    fn chooser_and_view(&mut self) -> (&mut Chooser, View<'_>) {
        let view = View {
            map: &self.map,
            occupancy: &self.occupancy,
            entropy: &self.entropy,
            pose: self.pose,
            bearings: &self.bearings,
            model: &self.model,
            config: &self.config,
        };
        (&mut self.chooser, view)
    }
}

impl<S, M> Exploration<S, M> {
    /// The fraction of the report cells whose entropy is above epsilon now.
    pub fn uncertain_fraction(&self) -> f64 {
        let epsilon = self.config.epsilon;
        let uncertain = |i: usize| f64::from(self.entropy[i]) > epsilon;
        let (count, total) = match &self.report_cells {
            Some(cells) => (0..cells.len())
                .filter(|&i| cells[i])
                .fold((0, 0), |(u, t), i| (u + usize::from(uncertain(i)), t + 1)),
            None => (
                (0..self.entropy.len()).filter(|&i| uncertain(i)).count(),
                self.entropy.len(),
            ),
        };
        if total == 0 {
            0.0
        } else {
            count as f64 / total as f64
        }
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
        self.path_length_m
    }
    /// Steps taken so far.
    pub fn steps(&self) -> usize {
        self.steps
    }
    /// Scans taken so far.
    pub fn scans(&self) -> usize {
        self.scans
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
        self.termination
    }
    /// Whether the run is over.
    pub fn done(&self) -> bool {
        self.termination.is_some()
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
        ExplorationResult {
            strategy: self.strategy,
            termination: self.termination,
            path_length_m: self.path_length_m,
            scans: self.scans,
            steps: self.steps,
            contacts: self.contacts,
            trajectory: self.trajectory.clone(),
            trace: self.trace.clone(),
            timing: self.timing,
            map: self.map.clone(),
            occupancy: self.occupancy.clone(),
        }
    }

    /// [`Exploration::result`], the maps moved out.
    pub fn into_result(self) -> ExplorationResult {
        ExplorationResult {
            strategy: self.strategy,
            termination: self.termination,
            path_length_m: self.path_length_m,
            scans: self.scans,
            steps: self.steps,
            contacts: self.contacts,
            trajectory: self.trajectory,
            trace: self.trace,
            timing: self.timing,
            map: self.map,
            occupancy: self.occupancy,
        }
    }
}

/// The steps of a run, until it is over.
impl<S: ScanSource, M: Motion> Iterator for Exploration<S, M> {
    type Item = Result<StepReport>;
    fn next(&mut self) -> Option<Self::Item> {
        self.step().transpose()
    }
}

/// The corners of `path` (cell centres, 8-connected steps): its first and
/// last points and every point where the step direction changes.
fn straight_runs(path: &[[f64; 2]], resolution_m: f64) -> Vec<[f64; 2]> {
    let step = |a: [f64; 2], b: [f64; 2]| {
        (
            ((b[0] - a[0]) / resolution_m).round() as i64,
            ((b[1] - a[1]) / resolution_m).round() as i64,
        )
    };
    let mut corners: Vec<[f64; 2]> = path.first().copied().into_iter().collect();
    for k in 1..path.len() {
        let last = k + 1 == path.len();
        if last || step(path[k - 1], path[k]) != step(path[k], path[k + 1]) {
            corners.push(path[k]);
        }
    }
    corners
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn straight_runs_keep_the_corners() {
        let p = |x: f64, y: f64| [x * 0.05, y * 0.05];
        let path = [
            p(0., 0.),
            p(1., 0.),
            p(2., 0.),
            p(3., 1.),
            p(4., 2.),
            p(4., 3.),
        ];
        assert_eq!(
            straight_runs(&path, 0.05),
            vec![p(0., 0.), p(2., 0.), p(4., 2.), p(4., 3.)]
        );
        assert_eq!(straight_runs(&path[..1], 0.05), vec![p(0., 0.)]);
        assert!(straight_runs(&[], 0.05).is_empty());
    }
}
