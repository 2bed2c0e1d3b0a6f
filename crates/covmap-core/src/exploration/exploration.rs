//! The exploration loop, from scan to decision to motion.
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
//!    are integrated as covered into the coverage map and as occupied into
//!    the occupancy grid (a bumper), it backs off a cell, and the step
//!    ends: the next one replans. A goal the robot could make no headway
//!    towards (less than a centimetre) is a *failed goal*: no strategy
//!    chooses it again, since the map may go on showing the way free.
//!
//! Poses are exact: the robot is where the motion says, with no
//! localisation error (the paper's runs assume a localised robot too).

use std::time::Instant;

use super::config::ExplorationConfig;
use super::region;
use super::result::{ExplorationResult, StepReport, Termination, Timing, Trace, Trajectory};
use super::sensor::AnySensorModel;
use super::source::{Motion, ScanSource, Travel};
use super::strategy::{
    Chooser, Decision, Outcome, Strategy, View, sees_all_around, widest_gap_rad,
};
use crate::counting::ScanCounts;
use crate::coverage_map::CoverageMap;
use crate::error::{CovmapError, Result};
use crate::grid::{Cell, Grid};
use crate::histogram::DEFAULT_BINS;
use crate::occupancy::{OccupancyGrid, OccupancyModel};
use crate::pose::{Pose, check_bearings, check_pose};
use crate::sensor::SensorModel;

/// How far a contact point is moved into the obstacle to find the cell it
/// lies in, metres (a point on a cell's edge belongs to one of two cells).
const INTO_CONTACT_M: f64 = 1e-3;

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

/// A robot exploring: its maps, its strategy, where it is and has been.
///
/// Drive it one step at a time ([`Exploration::step`]) or to the end
/// ([`Exploration::run`]). (It is no iterator of its steps on purpose: an
/// iterator's `map` would hide [`Exploration::map`].)
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
    /// The coverage map's entropy after the last scan, kept up to date from
    /// the map's entropy journal (see [`Exploration::refresh_entropy`]).
    entropy: Vec<f32>,
    /// How many entries of the map's entropy journal `entropy` has taken in.
    entropy_read: usize,
    report_cells: Option<Vec<bool>>,
    /// The report cells whose entropy is above epsilon, and all of them:
    /// counted at the start and kept as the entropy map changes.
    uncertain: (usize, usize),
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
    /// Goals (row-major cells) the robot could make no headway towards.
    failed_goals: Vec<usize>,
    /// Every cell the robot has run into, in the order it did.
    contact_cells: Vec<Cell>,
    /// The cells the robot's centre has driven through, row-major (the
    /// start's cell and every cell a straight leg crossed).
    driven: Vec<bool>,
    /// The coverage map with the contact cells pinned, for a strategy that
    /// plans on it (`None`: no contact yet, the map itself; or a strategy
    /// that reads its ML coverage alone), kept up to date from the map's
    /// entropy journal (see [`Exploration::update_planning_map`]).
    planning_map: Option<CoverageMap>,
    /// The ML coverage of the coverage map with the contact cells pinned,
    /// kept with it.
    planning_ml: Vec<f32>,
    /// The ML coverage of a pinned cell.
    pinned_ml: f32,
    /// How many entries of the map's entropy journal the planning map and
    /// its ML coverage have taken in.
    planning_read: usize,
    /// The cells the journal names, each once, for the planning map.
    changed: Distinct,
}

/// The distinct cells of a list that names some more than once, in the
/// order they first appear: a cell's stamp says which list last took it.
struct Distinct {
    stamp: Vec<u32>,
    list: u32,
    cells: Vec<usize>,
}

impl Distinct {
    /// For a grid of `cells` cells.
    fn new(cells: usize) -> Self {
        Self {
            stamp: vec![0; cells],
            list: 0,
            cells: Vec::new(),
        }
    }

    /// The distinct cells of `cells`, in the order they first appear.
    fn of(&mut self, cells: impl Iterator<Item = usize>) -> &[usize] {
        self.list = self.list.wrapping_add(1);
        if self.list == 0 {
            // Stamps of earlier lists would read as this one's.
            self.stamp.fill(0);
            self.list = 1;
        }
        self.cells.clear();
        for i in cells {
            if self.stamp[i] != self.list {
                self.stamp[i] = self.list;
                self.cells.push(i);
            }
        }
        &self.cells
    }
}

/// How one drive along a path went.
struct Drive {
    reached: bool,
    travelled_m: f64,
    /// Distance driven towards the goal (without backing off a contact).
    headway_m: f64,
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
        map.keep_entropy_journal(true);
        let counts = match strategy {
            Strategy::Counting {
                discount_beyond_m: Some(d),
                ..
            } => ScanCounts::with_discount(grid, d)?,
            _ => ScanCounts::new(grid),
        };
        let occupancy = OccupancyGrid::with_model(OccupancyModel::default(), counts)?;
        let chooser = Chooser::new(&strategy, &config, &grid, bins, &bearings)?;
        let entropy = map.entropy();
        let uncertain = uncertain_cells(&entropy, report_cells.as_deref(), config.epsilon);
        let planning_ml = map.ml();
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
            entropy_read: 0,
            report_cells,
            uncertain,
            pose: start,
            // The start is the first pose before anything runs; the first
            // scan, taken there, marks it scanned.
            trajectory: {
                let mut trajectory = Trajectory::default();
                trajectory.push(start, false);
                trajectory
            },
            path_length_m: 0.0,
            since_scan_m: 0.0,
            scans: 0,
            steps: 0,
            contacts: 0,
            trace: Trace::default(),
            timing: Timing::default(),
            termination: None,
            failed_goals: Vec::new(),
            contact_cells: Vec::new(),
            driven: (0..grid.len()).map(|i| i == start_cell).collect(),
            planning_map: None,
            planning_ml,
            pinned_ml: CoverageMap::pinned_ml(bins),
            planning_read: 0,
            changed: Distinct::new(grid.len()),
        })
    }

    /// One step: decide, drive, scan, integrate (see the
    /// [module documentation](crate::exploration)). Returns what the step did, or `None`
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
            self.look_around()?;
            self.refresh_entropy();
        }
        if self.at_path_limit() || self.steps >= self.config.max_steps {
            self.termination = Some(Termination::Limit);
            return Ok(None);
        }

        // 1. Decide on the maps (the cells the robot ran into pinned: see
        //    `CoverageMap::with_contacts`).
        let started = Instant::now();
        self.update_planning_map()?;
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
        };
        if !drive.reached
            && drive.headway_m < NO_HEADWAY_M
            && let Some(cell) = self.map.grid().world_to_cell(goal.x_m, goal.y_m)
        {
            self.failed_goals.push(self.map.grid().index(cell)?);
        }
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

    /// Whether the robot has driven as far as the run may (within
    /// [`PATH_LIMIT_TOLERANCE_M`]: the legs' lengths, added up, can fall
    /// short of the limit by a rounding error, and a run would then go on
    /// with steps that drive nothing).
    fn at_path_limit(&self) -> bool {
        self.path_length_m >= self.config.max_path_m - PATH_LIMIT_TOLERANCE_M
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
            headway_m: 0.0,
            scans: self.scans,
            contact_m: None,
        };
        // The path starts at the centre of the robot's cell: the robot heads
        // for the next corner straight away (a detour to its own cell's
        // centre could run into what it has just touched).
        let corners = straight_runs(path, resolution_m);
        for waypoint in corners.into_iter().skip(usize::from(path.len() > 1)) {
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
                let heading = direction[1].atan2(direction[0]);
                let travel = self.drive_straight(to, direction, leg_m, heading)?;
                drive.travelled_m += travel.travelled_m;

                if let Some(contact_m) = travel.contact_m {
                    self.scan_here()?;
                    self.integrate_contact(contact_m)?;
                    drive.headway_m = drive.travelled_m;
                    drive.travelled_m += self.back_off(contact_m)?;
                    drive.contact_m = Some(contact_m);
                    drive.scans = self.scans - drive.scans;
                    return Ok(drive);
                }
                if self.since_scan_m >= self.config.scan_spacing_m - 1e-9 {
                    self.scan_here()?;
                }
                if self.at_path_limit() {
                    if self.since_scan_m > 0.0 {
                        self.scan_here()?;
                    }
                    drive.headway_m = drive.travelled_m;
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
        drive.headway_m = drive.travelled_m;
        drive.scans = self.scans - drive.scans;
        Ok(drive)
    }

    /// The first scans: one at the start and, for a sensor that does not see
    /// all around, one after each turn on the spot by the arc its bearings
    /// span, until the turns have come full circle (a 180-degree laser scans
    /// twice, facing both ways): a robot knows nothing of what lies behind
    /// it, and planning on cells still unknown around its own disc would
    /// find no way out.
    fn look_around(&mut self) -> Result<()> {
        use std::f64::consts::TAU;
        self.scan_here()?;
        if sees_all_around(&self.bearings) {
            return Ok(());
        }
        // The arc the bearings span (at least one beam's worth: a single
        // bearing turns by 45 degrees).
        let arc_rad = (TAU - widest_gap_rad(&self.bearings)).max(TAU / 8.0);
        let turns = (TAU / arc_rad).ceil() as usize - 1;
        let start = self.pose.theta_rad;
        for k in 1..=turns {
            let theta = (start + k as f64 * arc_rad + std::f64::consts::PI).rem_euclid(TAU)
                - std::f64::consts::PI;
            self.pose = Pose::new(self.pose.x_m, self.pose.y_m, theta);
            self.scan_here()?;
        }
        Ok(())
    }

    /// Scan from the robot's pose and integrate the scan into every map.
    fn scan_here(&mut self) -> Result<()> {
        let started = Instant::now();
        let ranges = self.source.scan(&self.pose)?;
        let integrating = Instant::now();
        self.timing.sensing_s += (integrating - started).as_secs_f64();
        let (pose, bearings, model) = (&self.pose, &self.bearings[..], self.model.as_dyn());
        // The coverage map validates the scan first: an invalid one changes no map.
        if self.config.occlude_no_echo {
            let reaches =
                self.map
                    .no_echo_reaches(&self.contact_cells, pose, &ranges, bearings, model);
            self.map
                .integrate_clipped(pose, &ranges, bearings, model, &reaches)?;
            self.occupancy
                .integrate_clipped(pose, &ranges, bearings, model, &reaches)?;
        } else {
            self.map.integrate(pose, &ranges, bearings, model)?;
            self.occupancy.integrate(pose, &ranges, bearings, model)?;
        }
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
    /// map and the occupancy grid: the cell the robot ran into, and its
    /// neighbours along the surface there, one cell either side (the
    /// surface is taken to go on that far: a wall, a pane, a column's
    /// flank; a flat bumper learns no more).
    fn integrate_contact(&mut self, contact_m: [f64; 2]) -> Result<()> {
        let started = Instant::now();
        let resolution_m = self.map.grid().resolution_m();
        let (dx, dy) = (contact_m[0] - self.pose.x_m, contact_m[1] - self.pose.y_m);
        let length = dx.hypot(dy).max(f64::MIN_POSITIVE);
        let (normal, tangent) = ([dx / length, dy / length], [-dy / length, dx / length]);
        let mut cells = Vec::new();
        for along in [-1.0, 0.0, 1.0] {
            let x = contact_m[0] + INTO_CONTACT_M * normal[0] + along * resolution_m * tangent[0];
            let y = contact_m[1] + INTO_CONTACT_M * normal[1] + along * resolution_m * tangent[1];
            if let Some(cell) = self.map.grid().world_to_cell(x, y)
                && !cells.contains(&cell)
            {
                cells.push(cell);
            }
        }
        if cells.is_empty() {
            // The contact lies off the map: the map's error, named.
            self.map.grid().check_inside(contact_m[0], contact_m[1])?;
        }
        for cell in cells {
            self.map.integrate_contact(cell)?;
            self.occupancy.integrate_contact(cell)?;
            if !self.contact_cells.contains(&cell) {
                self.contact_cells.push(cell);
            }
        }
        self.contacts += 1;
        self.timing.integration_s += started.elapsed().as_secs_f64();
        Ok(())
    }

    /// Back off a cell straight away from the contact at `contact_m`, as
    /// far as the motion lets the robot (and the path limit); the distance
    /// driven. A robot left touching a wall could not start along it.
    fn back_off(&mut self, contact_m: [f64; 2]) -> Result<f64> {
        let (dx, dy) = (self.pose.x_m - contact_m[0], self.pose.y_m - contact_m[1]);
        let length = dx.hypot(dy);
        let distance_m = self
            .map
            .grid()
            .resolution_m()
            .min(self.config.max_path_m - self.path_length_m);
        if !(length > 0.0 && distance_m > 0.0) {
            return Ok(0.0);
        }
        let away = [dx / length, dy / length];
        let to = [
            self.pose.x_m + away[0] * distance_m,
            self.pose.y_m + away[1] * distance_m,
        ];
        // Backing up: the robot keeps facing the way it came.
        let travel = self.drive_straight(to, away, distance_m, self.pose.theta_rad)?;
        Ok(travel.travelled_m)
    }

    /// Drive straight towards `to`, `distance_m` away along the unit vector
    /// `direction`, facing `theta_rad`, with the motion: the robot ends where
    /// the motion stopped it, the pose on the trajectory, the distance on
    /// the path. Returns the distance driven and the contact, if any.
    fn drive_straight(
        &mut self,
        to: [f64; 2],
        direction: [f64; 2],
        distance_m: f64,
        theta_rad: f64,
    ) -> Result<Travel> {
        let here = [self.pose.x_m, self.pose.y_m];
        let started = Instant::now();
        let travel = self.motion.drive(here, to)?;
        self.timing.sensing_s += started.elapsed().as_secs_f64();
        let travelled_m = travel.travelled_m.clamp(0.0, distance_m);
        self.pose = Pose::new(
            here[0] + direction[0] * travelled_m,
            here[1] + direction[1] * travelled_m,
            theta_rad,
        );
        self.trajectory.push(self.pose, false);
        if travelled_m > 0.0 {
            let driven = &mut self.driven;
            crate::footprint::visit(
                self.map.grid(),
                here,
                direction[1].atan2(direction[0]),
                travelled_m,
                crate::sensor::Footprint::Ray,
                &mut |i: usize, _| driven[i] = true,
            );
        }
        self.path_length_m += travelled_m;
        self.since_scan_m += travelled_m;
        Ok(Travel {
            travelled_m,
            contact_m: travel.contact_m,
        })
    }

    /// Bring the entropy map up to date after the scans of a step: the
    /// entropy of every cell measured since, as the map's entropy history
    /// computed it after its last measurement (its journal). Every change of
    /// the map is a measurement (a scan's cells, a contact's cell, with the
    /// history kept), so that entropy is the one [`CoverageMap::entropy`]
    /// computes now, the same bits, with no histogram compared or entropy
    /// computed again (a step's scans touch a small part of a large map,
    /// and the history has just computed their entropies).
    fn refresh_entropy(&mut self) {
        let started = Instant::now();
        let epsilon = self.config.epsilon;
        let reported = |i: usize| self.report_cells.as_ref().is_none_or(|cells| cells[i]);
        for &(i, e) in &self.map.entropy_journal()[self.entropy_read..] {
            if reported(i) {
                let (was, now) = (f64::from(self.entropy[i]) > epsilon, f64::from(e) > epsilon);
                self.uncertain.0 = self.uncertain.0 + usize::from(now) - usize::from(was);
            }
            self.entropy[i] = e;
        }
        self.entropy_read = self.map.entropy_journal().len();
        self.done_with_journal();
        debug_assert_eq!(self.entropy, self.map.entropy());
        self.timing.integration_s += started.elapsed().as_secs_f64();
    }

    /// Bring what the strategies plan on up to date before they decide:
    /// the ML coverage of the coverage map with every contact cell pinned,
    /// of the cells the journal names since (the map's) and of the contact
    /// cells (a pinned cell's); and, for a strategy that plans on the
    /// histograms, the map with the contacts pinned
    /// ([`CoverageMap::with_contacts`]), made at the first contact and then
    /// kept, the cells the journal names copied and the contacts pinned
    /// again. The same histograms and ML coverage as a copy made anew,
    /// without copying the whole map at every step; the copy keeps the
    /// map's kernel table, so that planning does not compute the kernels
    /// again every time.
    fn update_planning_map(&mut self) -> Result<()> {
        // The journal names a cell once a scan that measured it: each
        // changed cell is taken once.
        let fresh = &self.map.entropy_journal()[self.planning_read..];
        let changed = self.changed.of(fresh.iter().map(|&(i, _)| i));
        for &i in changed {
            self.planning_ml[i] = self.map.ml_at(i);
        }
        let grid = *self.map.grid();
        for &cell in &self.contact_cells {
            self.planning_ml[grid.index(cell)?] = self.pinned_ml;
        }
        if self.strategy.plans_on_histograms() && !self.contact_cells.is_empty() {
            match &mut self.planning_map {
                Some(planned) => {
                    let cells = changed.iter().copied();
                    planned.update_with_contacts(&self.map, cells, &self.contact_cells)?;
                }
                None => {
                    let mut planned = self.map.with_contacts(&self.contact_cells)?;
                    planned.share_kernel_table(&self.map);
                    self.planning_map = Some(planned);
                }
            }
        }
        self.planning_read = self.map.entropy_journal().len();
        self.done_with_journal();
        Ok(())
    }

    /// Clear the map's entropy journal once both the entropy map and the
    /// planning map have taken it in.
    fn done_with_journal(&mut self) {
        let len = self.map.entropy_journal().len();
        if self.entropy_read == len && self.planning_read == len {
            self.map.clear_entropy_journal();
            (self.entropy_read, self.planning_read) = (0, 0);
        }
    }

    /// The strategy, and what it sees.
    fn chooser_and_view(&mut self) -> (&mut Chooser, View<'_>) {
        let view = View {
            map: &self.map,
            planning_map: self
                .strategy
                .plans_on_histograms()
                .then(|| self.planning_map.as_ref().unwrap_or(&self.map)),
            planning_ml: &self.planning_ml,
            contact_cells: &self.contact_cells,
            driven: &self.driven,
            occupancy: &self.occupancy,
            entropy: &self.entropy,
            pose: self.pose,
            bearings: &self.bearings,
            model: &self.model,
            config: &self.config,
            failed_goals: &self.failed_goals,
        };
        (&mut self.chooser, view)
    }
}

impl<S, M> Exploration<S, M> {
    /// The region the robot can reach on its coverage map now, one flag a
    /// cell: the cells the coverage strategy's termination rule and the
    /// counting strategy's unexplored cells are taken from (see
    /// [`Strategy`]'s documentation).
    ///
    /// # Errors
    /// None in practice (the robot's pose lies on the map).
    pub fn region(&self) -> Result<Vec<bool>> {
        let navigator = region::navigator(self.config.robot_radius_m, self.map.grid(), 0.0)?;
        region::reachable_region(
            &navigator,
            &self.map,
            &self.pose,
            self.model.as_dyn().range_model().band_m,
        )
    }

    /// The fraction of the report cells whose entropy is above epsilon now.
    pub fn uncertain_fraction(&self) -> f64 {
        match self.uncertain {
            (_, 0) => 0.0,
            (count, total) => count as f64 / total as f64,
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
            map: without_journal(self.map.clone()),
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
            map: without_journal(self.map),
            occupancy: self.occupancy,
        }
    }
}

/// How many of the report cells (`None`: every cell) have an entropy above
/// `epsilon` (nats), and how many report cells there are.
fn uncertain_cells(entropy: &[f32], report_cells: Option<&[bool]>, epsilon: f64) -> (usize, usize) {
    let uncertain = |i: usize| f64::from(entropy[i]) > epsilon;
    match report_cells {
        Some(cells) => (0..cells.len())
            .filter(|&i| cells[i])
            .fold((0, 0), |(u, t), i| (u + usize::from(uncertain(i)), t + 1)),
        None => (
            (0..entropy.len()).filter(|&i| uncertain(i)).count(),
            entropy.len(),
        ),
    }
}

/// `map` without the loop's entropy journal: a map handed out may be
/// integrated into further, and nothing would read or clear its journal.
fn without_journal(mut map: CoverageMap) -> CoverageMap {
    map.keep_entropy_journal(false);
    map
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
    use crate::sensor::LaserModel;

    /// A room `[0, 4] x [0, 3]` m with a pane `[2.2, 2.6] x [0.9, 2.1]` the
    /// sensor sees through and the robot runs into: the runs of
    /// [`every_step_keeps_the_loops_read_outs`] scan, drive and touch.
    const PANE: [f64; 4] = [2.2, 0.9, 2.6, 2.1];

    /// Exact laser ranges to the room's walls.
    struct RoomRing(Vec<f64>);
    impl ScanSource for RoomRing {
        fn bearings(&self) -> &[f64] {
            &self.0
        }
        fn scan(&mut self, p: &Pose) -> Result<Vec<f64>> {
            let to = |v: f64, high: f64, at: f64| match v {
                v if v > 1e-12 => (high - at) / v,
                v if v < -1e-12 => -at / v,
                _ => f64::INFINITY,
            };
            Ok(self
                .0
                .iter()
                .map(|b| {
                    let (s, c) = (p.theta_rad + b).sin_cos();
                    to(c, 4.0, p.x_m).min(to(s, 3.0, p.y_m))
                })
                .collect())
        }
    }

    /// A disc of 0.25 m stopped by the walls and the pane, in steps of a
    /// millimetre; the contact is the nearest point of what stopped it.
    struct Bumper;
    impl Motion for Bumper {
        fn drive(&mut self, from: [f64; 2], to: [f64; 2]) -> Result<Travel> {
            const R: f64 = 0.25;
            let nearest = |[x, y]: [f64; 2]| -> ([f64; 2], f64) {
                let [x0, y0, x1, y1] = PANE;
                let pane = [x.clamp(x0, x1), y.clamp(y0, y1)];
                [pane, [0.0, y], [4.0, y], [x, 0.0], [x, 3.0]]
                    .into_iter()
                    .map(|q| (q, (q[0] - x).hypot(q[1] - y)))
                    .fold(
                        ([0.0; 2], f64::INFINITY),
                        |a, b| if b.1 < a.1 { b } else { a },
                    )
            };
            let length = (to[0] - from[0]).hypot(to[1] - from[1]);
            let steps = (length / 1e-3).ceil() as usize;
            for k in 1..=steps {
                let t = k as f64 / steps as f64;
                let at = [
                    from[0] + t * (to[0] - from[0]),
                    from[1] + t * (to[1] - from[1]),
                ];
                let (contact, gap) = nearest(at);
                if gap < R {
                    return Ok(Travel {
                        travelled_m: (k - 1) as f64 / steps as f64 * length,
                        contact_m: Some(contact),
                    });
                }
            }
            Ok(Travel {
                travelled_m: length,
                contact_m: None,
            })
        }
    }

    /// After every step, the entropy map the loop keeps from the map's
    /// journal is the map's entropy, and the map it plans on and its ML
    /// coverage are the ones made anew from the map and the contacts, bit
    /// for bit, for every strategy, in runs that scan, drive and run into
    /// the pane.
    #[test]
    fn every_step_keeps_the_loops_read_outs() {
        let bearings: Vec<f64> = (0..90)
            .map(|i| i as f64 * std::f64::consts::TAU / 90.0)
            .collect();
        let grid = Grid::covering(-0.5, -0.5, 4.5, 3.5, 0.05).unwrap();
        for strategy in [
            Strategy::coverage(0.5).unwrap(),
            Strategy::counting(3, Some(2.0)).unwrap(),
            Strategy::frontier(),
        ] {
            let mut setup = ExplorationSetup::new(grid, Pose::new(1.0, 1.5, 0.0), strategy);
            setup.model = AnySensorModel::Laser(LaserModel::default());
            setup.config.max_path_m = 40.0;
            let mut run = Exploration::new(setup, RoomRing(bearings.clone()), Bumper).unwrap();
            while run.step().unwrap().is_some() {
                let entropy = run.map.entropy();
                let differs =
                    (0..entropy.len()).find(|&i| run.entropy[i].to_bits() != entropy[i].to_bits());
                assert_eq!(differs, None, "{strategy:?}, step {}: cell", run.steps);
                let epsilon = run.config.epsilon;
                let counted = uncertain_cells(&entropy, run.report_cells.as_deref(), epsilon);
                assert_eq!(run.uncertain, counted, "{strategy:?}, step {}", run.steps);
                assert!(counted.0 > 0 && counted.0 < counted.1);
                // What the next step plans on, made anew.
                run.update_planning_map().unwrap();
                let made = run.map.with_contacts(&run.contact_cells).unwrap();
                if let Some(planned) = run.chooser_and_view().1.planning_map {
                    let differs = (0..made.histograms().len()).find(|&i| {
                        made.histograms()[i].to_bits() != planned.histograms()[i].to_bits()
                    });
                    assert_eq!(differs, None, "{strategy:?}, step {}: value", run.steps);
                }
                assert_eq!(
                    run.planning_ml,
                    made.ml(),
                    "{strategy:?}, step {}",
                    run.steps
                );
                assert!(run.map.entropy_journal().len() < 20_000);
            }
            assert_eq!(
                run.planning_map.is_some(),
                strategy.plans_on_histograms(),
                "{strategy:?}"
            );
            assert!(
                run.contacts > 0 && run.steps > 3,
                "{strategy:?}: {} contacts, {} steps",
                run.contacts,
                run.steps
            );
        }
    }

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
