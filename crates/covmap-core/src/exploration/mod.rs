//! Closed-loop exploration: a robot scans, chooses where to look next on
//! the maps it builds, drives there scanning on the way, and stops when its
//! strategy is done ([the model](crate::model), section 4; the paper's
//! Table I).
//!
//! The loop ([`Exploration`], in `exploration.rs`: one file to read from
//! scan to decision to motion; the drive and its contacts in `drive.rs`,
//! the read-outs it keeps from the map's change feed in `bookkeeping.rs`)
//! knows the robot through two small traits, a
//! [`ScanSource`] and a [`Motion`]; `covmap_sim` implements them with a
//! simulated sensor and a disc robot in a true world, and a log replay or a
//! real robot can be others. The strategies ([`Strategy`], one file each in
//! `strategy/`, each an [`ExplorationStrategy`]; a caller's own strategy
//! drives the loop through [`Exploration::with_strategy`]) choose on the
//! maps only.
//!
//! # The loop's model (covmap's choices where the paper is silent)
//! - **A step**: the strategy picks a goal and a path (cell centres) on the
//!   maps; the robot drives the path's straight runs through the world,
//!   scanning every `scan_spacing_m` of travel and at the goal (after
//!   turning to the goal's heading), and integrates every scan into the
//!   coverage map, the occupancy grid and the scan counts, the very same
//!   beams. Poses are exact: no localisation error.
//! - **No echo**: a reading at the maximum range clears only the cells
//!   its line of sight reaches: in each sector of its footprint (a cell wide
//!   at the maximum range), those nearer than the nearest obstacle the
//!   coverage map already holds there and is certain of (ML coverage above
//!   0.5 and entropy at most `epsilon`, or a contact;
//!   [`CoverageMap::occludes`](crate::CoverageMap::occludes),
//!   [`NoEchoSight`](crate::NoEchoSight)), the same in all three
//!   maps ([`ExplorationConfig::occlude_no_echo`], on by default). A sonar's specular miss of a known wall says nothing of what
//!   lies behind it; integrated to the maximum range, as the sensor model
//!   alone has it, oblique misses erase the walls the perpendicular echoes
//!   found (in the built-in corridor the robot then plans through walls on
//!   most steps). Every sector, not the axis alone: a cone grazing a
//!   wall along its flank, its axis clear of it, would otherwise clear the
//!   wall's face under its flank (on the corridor, stopping at the axis
//!   left the wall's face and inner cells of the north wall reading free
//!   on long stretches, and the robot touched it 50 times in one run). Nor
//!   the whole cone at its nearest obstacle, as until 2026-12-07: a cone
//!   aimed at a doorway then stopped at the jambs, the doorway's cells
//!   were never cleared by the readings through it, and the door stayed
//!   closed on the map (docs/experiments.md, "The line of sight").
//! - **Echoes explained**: where the end band of an echo holds a cell the
//!   coverage map holds covered and is certain of (as above), the echo
//!   marks only the cells at such a cell's bearing and the certain ones,
//!   not the rest of its arc at and past its range
//!   ([`EchoSources`](crate::EchoSources), [the model](crate::model),
//!   section 5), the same in all three maps (with
//!   [`ExplorationConfig::occlude_no_echo`]: both read the scan against
//!   what the map is certain of). A settled jamb's echoes then leave the
//!   doorway beside it as they found it.
//! - **Contacts**: where the world stops the robot short of its target (the
//!   map showed the way free), the robot stops at its last free point,
//!   scans, takes the contact into the coverage map (the cell it ran into
//!   and its neighbours along the surface) and the occupancy grid
//!   (occupied), backs off a cell and replans. The robot remembers its
//!   contacts: every contact cell is held certainly covered in the
//!   coverage map from then on, whatever the readings say
//!   ([`CoverageMap::pin_covered`](crate::CoverageMap::pin_covered), after
//!   every scan), so a wall the sensor misses cannot lure the robot back,
//!   and the map the strategy plans on is the map its termination rule and
//!   the run's measures read. A goal it could
//!   make no headway towards (less than a centimetre) is never chosen again.
//! - **Planning radius**: paths are planned for a disc a cell (at least 5 cm) wider than
//!   the robot, since a cell less than half covered reads free and a sonar
//!   map often holds the face row of a wall as free (see `region`).
//! - **The way back**: every strategy may always pass the cells the robot's
//!   centre has driven through, whatever its map says of them since (the
//!   robot fitted there, and the world does not change): the end arcs of
//!   readings that catch a door's jambs narrow the door on the map behind
//!   the robot, and it would end shut in the room it drove into (see
//!   `region`).
//! - **The reachable region**: the cells the robot can reach through known
//!   free space (of the coverage map; counting: of the occupancy grid, what
//!   the beams have seen), plus a shell of the planning radius and the
//!   sensor's end band (coverage) or one cell (counting) around them: an
//!   unexplored doorway is in it, the unknown outside a building is not
//!   ([`Exploration::region`]: coverage's).
//! - **Coverage** ([`Strategy::Coverage`]): eq. 14 through the
//!   [`Planner`](crate::planner::Planner), candidates on a lattice of
//!   `candidate_stride_m`, at least `min_travel_m` away, promising more than
//!   `ln bins - epsilon` nats (what making one unknown cell certain is
//!   worth). Ends [`Termination::Certain`] when every region cell is below
//!   epsilon, [`Termination::Stagnated`] when the rest have stagnated (the
//!   paper's rule), [`Termination::NoGoal`] when no candidate is worth
//!   visiting. A goal reached whose step gained less than that least
//!   gain is not chosen again, nor is one whose step gained less than the
//!   goal promised and whose scans lowered its promise by less than that
//!   least gain.
//! - **Counting** ([`Strategy::Counting`]): the nearest candidate from which
//!   the beams, traced on the ML map, would intercept a region cell counted
//!   fewer than `n` times (beams beyond `discount_beyond_m` count
//!   `discount_beyond_m / d`); a cell three visits failed to add a full
//!   interception to is given up. Ends [`Termination::NoGoal`].
//! - **Frontier** ([`Strategy::Frontier`]): the nearest reachable group of
//!   known-free cells of the occupancy grid next to unknown ones (groups of
//!   fewer cells than the robot's diameter spans dropped). Ends
//!   [`Termination::NoGoal`].
//!
//! # Example
//! A robot with a ring of 90 laser beams in an empty 4 m x 4 m room whose
//! walls its motion stops it at.
//! ```
//! use covmap_core::exploration::{
//!     AnySensorModel, Exploration, ExplorationSetup, Motion, ScanSource, Strategy, Travel,
//! };
//! use covmap_core::{Grid, Pose, Result};
//!
//! /// Distance from (x, y) along `angle` to the walls of the room [0, 4]^2.
//! fn to_wall(x: f64, y: f64, angle: f64) -> f64 {
//!     let (s, c) = angle.sin_cos();
//!     let tx = if c > 0.0 { (4.0 - x) / c } else if c < 0.0 { -x / c } else { f64::INFINITY };
//!     let ty = if s > 0.0 { (4.0 - y) / s } else if s < 0.0 { -y / s } else { f64::INFINITY };
//!     tx.min(ty)
//! }
//! struct Ring(Vec<f64>);
//! impl ScanSource for Ring {
//!     fn bearings(&self) -> &[f64] { &self.0 }
//!     fn scan(&mut self, p: &Pose) -> Result<Vec<f64>> {
//!         Ok(self.0.iter().map(|b| to_wall(p.x_m, p.y_m, p.theta_rad + b)).collect())
//!     }
//! }
//! struct Free;
//! impl Motion for Free {
//!     fn drive(&mut self, from: [f64; 2], to: [f64; 2]) -> Result<Travel> {
//!         Ok(Travel { travelled_m: (to[0] - from[0]).hypot(to[1] - from[1]), contact_m: None })
//!     }
//! }
//! let bearings = (0..90).map(|i| i as f64 * std::f64::consts::TAU / 90.0).collect();
//! let grid = Grid::covering(-0.5, -0.5, 4.5, 4.5, 0.05).unwrap();
//! let mut setup = ExplorationSetup::new(grid, Pose::new(1.0, 1.0, 0.0), Strategy::counting(1, None).unwrap());
//! setup.model = AnySensorModel::laser();
//! let mut run = Exploration::new(setup, Ring(bearings), Free).unwrap();
//! let termination = run.run().unwrap();
//! assert!(termination.by_rule(), "{termination}");
//! assert!(run.scans() > 1 && run.path_length_m() > 0.0);
//! ```

mod bookkeeping;
mod config;
mod dilation;
mod drive;
mod evaluation;
#[allow(clippy::module_inception)]
mod exploration;
mod region;
mod result;
mod sensor;
mod source;
mod steering;
mod strategy;
#[cfg(test)]
mod test_maps;

pub use config::ExplorationConfig;
pub use evaluation::{high_entropy_fraction, mean_absolute_error};
pub use exploration::{Exploration, ExplorationSetup};
pub use region::dilate;
pub use result::{ExplorationResult, StepReport, Termination, Timing, Trace, Trajectory};
pub use sensor::AnySensorModel;
pub use source::{Motion, ScanSource, Travel};
pub use strategy::{
    DEFAULT_DISCOUNT_BEYOND_M, DecisionInputs, ExplorationStrategy, GoalOutcome, NextGoal, Strategy,
};
