//! Goals from outside the loop: a strategy the caller runs (a Python
//! function, a learned policy) steers the run one goal at a time
//! ([`Strategy::Custom`](super::Strategy::Custom), or any strategy the
//! caller overrides for a step).
//!
//! - [`Exploration::step_to`] takes one step to the caller's goal: the path
//!   to it as the coverage strategy plans its paths ([`Exploration::paths`]:
//!   for the planning radius, through the space the coverage map knows to
//!   be free, unknown cells blocking), then the drive, its scans and the
//!   scan at the goal, as [`Exploration::step`] does. A goal that is not
//!   finite, lies off the map or cannot be reached on it is refused before
//!   anything moves.
//! - [`Exploration::viewpoints`] shows what the coverage strategy weighs:
//!   every candidate viewpoint with its expected gain and path cost.
//! - [`Exploration::rule`] says whether the paper's rule holds now, and
//!   [`Exploration::finish`] ends the run on the caller's word.

use std::time::Instant;

use super::exploration::Exploration;
use super::region;
use super::result::{StepReport, Termination};
use super::source::{Motion, ScanSource};
use crate::error::{CovmapError, Result};
use crate::planner::{Plan, Planner, PlannerConfig, Reachability};
use crate::pose::{Pose, check_pose};

impl<S: ScanSource, M: Motion> Exploration<S, M> {
    /// One step to `goal`, chosen by the caller (see the documentation of
    /// the module `exploration::steering`): a report of the step, or `None`
    /// once the run is over (a limit reached, or ended). At the first step the
    /// robot scans where it stands first, as [`Exploration::step`] does.
    ///
    /// # Errors
    /// [`CovmapError::InvalidGoal`] for a goal that is not finite, lies off
    /// the map or that the robot cannot reach on its map: the run is as it
    /// was (but for the first scans, when it had taken none); an error of
    /// the scan source or the motion, passed on, as [`Exploration::step`].
    pub fn step_to(&mut self, goal: Pose) -> Result<Option<StepReport>> {
        let invalid = |reason: String| CovmapError::InvalidGoal {
            x: goal.x_m,
            y: goal.y_m,
            reason,
        };
        let cell = check_pose(self.map.grid(), &goal).map_err(|e| invalid(e.to_string()))?;
        if !self.begin()? {
            return Ok(None);
        }
        let started = Instant::now();
        let index = self.map.grid().index(cell)?;
        let paths = self.paths()?;
        if !paths.reachable(index) {
            return Err(invalid(format!(
                "the robot cannot reach it on its map (a disc of {} m through cells the coverage map \
                 knows to be free); choose a reachable cell, such as a candidate viewpoint",
                self.config.robot_radius_m
            )));
        }
        let path = paths.path_to(index);
        let planning_s = started.elapsed().as_secs_f64();
        self.go(goal, path, planning_s).map(Some)
    }

    /// The shortest paths from the robot on its coverage map, as the
    /// coverage strategy plans them: for the planning radius, through cells
    /// the map knows to be free (unknown cells blocking).
    ///
    /// # Errors
    /// None in practice (the robot's pose lies on the map).
    pub fn paths(&self) -> Result<Reachability> {
        let navigator = region::navigator(self.config.robot_radius_m, 0.0)?;
        Ok(navigator
            .free_and_reachable_driven(&self.map, &self.pose, Some(&self.driven))?
            .1)
    }

    /// The candidate viewpoints the coverage strategy weighs now, each with
    /// its expected gain, path cost and eq. 14's utility for `alpha`, and
    /// the one the planner would choose (without the loop's memory of
    /// goals that failed or gained too little). Planned as the loop plans,
    /// keeping the candidates' gains from call to call where the map did
    /// not change under them ([`Planner::next_viewpoint_cached`]): the plan
    /// a full computation gives, bit for bit.
    ///
    /// # Errors
    /// [`CovmapError::InvalidParameter`] for an `alpha` outside `[0, 1]`.
    pub fn viewpoints(&mut self, alpha: f64) -> Result<Plan> {
        let planner = Planner::new(PlannerConfig {
            alpha,
            robot_radius_m: self.config.robot_radius_m,
            candidate_stride_m: self.config.candidate_stride_m,
            min_travel_m: self.config.min_travel_m,
            epsilon: self.config.epsilon,
            ..PlannerConfig::default()
        })?;
        planner.next_viewpoint_cached(
            &mut self.viewpoint_cache,
            &self.map,
            &self.pose,
            &self.bearings,
            self.model.as_dyn(),
        )
    }

    /// Whether the paper's rule holds now: every cell of the region the
    /// robot can reach ([`Exploration::region`]) certain
    /// ([`Termination::Certain`]), or certain or stagnated, some stagnated
    /// ([`Termination::Stagnated`]); `None` while a cell of it is neither.
    ///
    /// # Errors
    /// None in practice (the robot's pose lies on the map).
    pub fn rule(&self) -> Result<Option<Termination>> {
        let region = self.region()?;
        let (mut stagnated, mut open) = (0usize, 0usize);
        for (i, _) in region.iter().enumerate().filter(|(_, r)| **r) {
            if f64::from(self.kept.entropy[i]) < self.config.epsilon {
                continue;
            }
            if self.map.stagnated_at(i) {
                stagnated += 1;
            } else {
                open += 1;
            }
        }
        Ok(match (open, stagnated) {
            (0, 0) => Some(Termination::Certain),
            (0, _) => Some(Termination::Stagnated),
            _ => None,
        })
    }

    /// End the run on the caller's word (its strategy has no goal it would
    /// go to): by the paper's rule where it holds ([`Exploration::rule`]),
    /// else [`Termination::NoGoal`]. How the run ended (as it was, for a
    /// run already over).
    ///
    /// # Errors
    /// None in practice (the robot's pose lies on the map).
    pub fn finish(&mut self) -> Result<Termination> {
        if let Some(done) = self.totals.termination {
            return Ok(done);
        }
        let done = self.rule()?.unwrap_or(Termination::NoGoal);
        self.totals.termination = Some(done);
        Ok(done)
    }
}
