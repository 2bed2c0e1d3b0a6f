//! The paper's decision-theoretic strategy (the model, section 4, eq. 14),
//! through the [`Planner`].
//!
//! # Choice
//! The planner's candidates are the reachable free cells on a lattice of
//! `candidate_stride_m`, at least `min_travel_m` away along the path, with
//! an expected gain above its `min_gain_nats` (1 nat); of those it takes
//! the one maximising `alpha * gain / max gain - (1 - alpha) * cost / max
//! cost`. Paths and costs are for the planning radius (the robot's and one
//! cell, see [`region`](crate::exploration)), with unknown cells blocking.
//!
//! A goal the robot could not make any headway towards (a contact within a
//! centimetre of where it stood) is never chosen again: the map may keep
//! showing the way free (a wall no reading has seen), and the same goal
//! would win again and again. The best candidate left is taken instead.
//!
//! # Termination
//! Done when every cell of the reachable region is certain (entropy below
//! epsilon: [`Termination::Certain`]) or, some not being certain, has
//! stagnated ([`Termination::Stagnated`]); before that, when no candidate
//! is worth visiting ([`Termination::NoGoal`]).

use super::{Decision, Outcome, View};
use crate::error::Result;
use crate::exploration::ExplorationConfig;
use crate::exploration::region::{navigator, reachable_region};
use crate::exploration::result::Termination;
use crate::grid::Grid;
use crate::planner::{Plan, Planner, PlannerConfig};

/// Headway below which a drive made none, metres.
const NO_HEADWAY_M: f64 = 0.01;

/// The decision-theoretic strategy's state.
pub(crate) struct Coverage {
    planner: Planner,
    /// The planner with `alpha` irrelevant: reachability and free space.
    navigator: Planner,
    /// Goals (row-major cell indices) the robot made no headway towards.
    failed: Vec<usize>,
    /// The cell of the last goal.
    last_goal: Option<usize>,
}

impl Coverage {
    pub fn new(alpha: f64, config: &ExplorationConfig, grid: &Grid) -> Result<Self> {
        let navigator = navigator(config.robot_radius_m, grid, alpha)?;
        let planner = Planner::new(PlannerConfig {
            candidate_stride_m: config.candidate_stride_m,
            min_travel_m: config.min_travel_m,
            epsilon: config.epsilon,
            ..*navigator.config()
        })?;
        Ok(Self {
            planner,
            navigator,
            failed: Vec::new(),
            last_goal: None,
        })
    }

    pub fn decide(&mut self, view: &View) -> Result<Decision> {
        if let Some(done) = self.termination(view)? {
            return Ok(Decision::Done(done));
        }
        let plan = self.plan(view)?;
        let grid = view.grid();
        let index_of = |k: usize| {
            let p = &plan.candidates.poses[k];
            grid.world_to_cell(p.x_m, p.y_m)
                .and_then(|c| grid.index(c).ok())
        };
        let chosen = match plan.chosen {
            Some(k) if index_of(k).is_some_and(|i| self.failed.contains(&i)) => {
                self.best_not_failed(&plan, index_of)
            }
            other => other,
        };
        let Some(k) = chosen else {
            return Ok(Decision::Done(Termination::NoGoal));
        };
        let path = if Some(k) == plan.chosen {
            plan.path
        } else {
            let reach = self.planner.reachability(view.map, &view.pose)?;
            index_of(k).map_or_else(Vec::new, |i| reach.path_to(i))
        };
        self.last_goal = index_of(k);
        Ok(Decision::Goal {
            pose: plan.candidates.poses[k],
            path,
        })
    }

    /// The one call of the planner's choice (eq. 14).
    fn plan(&self, view: &View) -> Result<Plan> {
        self.planner
            .next_viewpoint(view.map, &view.pose, view.bearings, view.model)
    }

    /// The candidate of greatest utility whose cell is no failed goal.
    fn best_not_failed(
        &self,
        plan: &Plan,
        index_of: impl Fn(usize) -> Option<usize>,
    ) -> Option<usize> {
        let utilities = &plan.candidates.utilities;
        (0..utilities.len())
            .filter(|&k| utilities[k] > f64::NEG_INFINITY)
            .filter(|&k| index_of(k).is_some_and(|i| !self.failed.contains(&i)))
            .max_by(|&a, &b| {
                utilities[a]
                    .total_cmp(&utilities[b])
                    .then_with(|| b.cmp(&a))
            })
    }

    /// Whether every cell of the reachable region is certain or stagnated.
    fn termination(&self, view: &View) -> Result<Option<Termination>> {
        let band_m = view.model.as_dyn().range_model().band_m;
        let region = reachable_region(&self.navigator, view.map, &view.pose, band_m)?;
        let epsilon = view.config.epsilon;
        let mut stagnated = false;
        for (i, _) in region.iter().enumerate().filter(|(_, r)| **r) {
            if f64::from(view.entropy[i]) < epsilon {
                continue;
            }
            if !view.map.stagnated_at(i) {
                return Ok(None);
            }
            stagnated = true;
        }
        Ok(Some(if stagnated {
            Termination::Stagnated
        } else {
            Termination::Certain
        }))
    }

    pub fn learn(&mut self, _view: &View, outcome: &Outcome) {
        if !outcome.reached
            && outcome.travelled_m < NO_HEADWAY_M
            && let Some(goal) = self.last_goal
        {
            self.failed.push(goal);
        }
    }
}
