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
//! A goal the robot could not make any headway towards (a failed goal, see
//! [`Exploration`](crate::exploration::Exploration)) is not chosen again:
//! the best candidate left is taken instead.
//!
//! # Termination
//! Done when every cell of the reachable region is certain (entropy below
//! epsilon: [`Termination::Certain`]) or, some not being certain, has
//! stagnated ([`Termination::Stagnated`]: its entropy changed by less than
//! 0.001 nats over its last five measurements); before that, when no
//! candidate is worth visiting ([`Termination::NoGoal`]).
//!
//! The run as a whole has stagnated too ([`Termination::Stagnated`]) when
//! for [`STALL_STEPS`] (20) steps in a row the number of cells of the
//! region that are certain or stagnated has not risen above the most there
//! were before *and* the region's entropy has fallen by less than the
//! planner's `min_gain_nats` (1 nat) a step: the steps gain less than a goal
//! must promise to be chosen. covmap's choice where the paper is silent: a cell whose true
//! coverage lies between two bin values ends up split between them, with an
//! entropy near `ln 2 = 0.69` nats, above the paper's epsilon of 0.65; every
//! reading that ends in it tips the split one way or the other, so its
//! entropy never settles to within 0.001, and a few such cells along the
//! walls would keep the run going forever, the robot collecting fractions
//! of a nat from them.

use super::{Decision, Outcome, View};
use crate::error::Result;
use crate::exploration::ExplorationConfig;
use crate::exploration::region::{navigator, reachable_region};
use crate::exploration::result::Termination;
use crate::grid::Grid;
use crate::planner::{Plan, Planner, PlannerConfig};

/// Steps without a new settled cell after which the run has stagnated.
pub(crate) const STALL_STEPS: usize = 20;

/// The decision-theoretic strategy's state.
pub(crate) struct Coverage {
    planner: Planner,
    /// The planner with `alpha` irrelevant: reachability and free space.
    navigator: Planner,
    /// The most cells of the region certain or stagnated at once so far.
    most_settled: usize,
    /// The region's entropy (nats) at each decision since that number last
    /// grew.
    entropy_since_more_settled: Vec<f64>,
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
            most_settled: 0,
            entropy_since_more_settled: Vec::new(),
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
            Some(k) if index_of(k).is_some_and(|i| view.failed_goals.contains(&i)) => {
                best_not_failed(&plan, index_of, view.failed_goals)
            }
            other => other,
        };
        let Some(k) = chosen else {
            return Ok(Decision::Done(Termination::NoGoal));
        };
        let path = if Some(k) == plan.chosen {
            plan.path
        } else {
            let reach = self.planner.reachability(view.planning_map, &view.pose)?;
            index_of(k).map_or_else(Vec::new, |i| reach.path_to(i))
        };
        Ok(Decision::Goal {
            pose: plan.candidates.poses[k],
            path,
        })
    }

    /// The one call of the planner's choice (eq. 14).
    fn plan(&self, view: &View) -> Result<Plan> {
        self.planner
            .next_viewpoint(view.planning_map, &view.pose, view.bearings, view.model)
    }

    /// Whether every cell of the reachable region is certain or stagnated,
    /// or the run has stagnated (see the module documentation).
    fn termination(&mut self, view: &View) -> Result<Option<Termination>> {
        let band_m = view.model.as_dyn().range_model().band_m;
        let region = reachable_region(&self.navigator, view.planning_map, &view.pose, band_m)?;
        let epsilon = view.config.epsilon;
        let (mut certain, mut stagnated, mut open) = (0usize, 0usize, 0usize);
        let mut entropy = 0.0;
        for (i, _) in region.iter().enumerate().filter(|(_, r)| **r) {
            entropy += f64::from(view.entropy[i]);
            if f64::from(view.entropy[i]) < epsilon {
                certain += 1;
            } else if view.map.stagnated_at(i) {
                stagnated += 1;
            } else {
                open += 1;
            }
        }
        if open == 0 {
            return Ok(Some(if stagnated > 0 {
                Termination::Stagnated
            } else {
                Termination::Certain
            }));
        }
        let history = &mut self.entropy_since_more_settled;
        if certain + stagnated > self.most_settled {
            self.most_settled = certain + stagnated;
            history.clear();
        }
        history.push(entropy);
        // The region's entropy `STALL_STEPS` decisions ago, and now.
        let stalled = history.len() > STALL_STEPS
            && history[history.len() - 1 - STALL_STEPS] - entropy
                < STALL_STEPS as f64 * self.planner.config().min_gain_nats;
        Ok(stalled.then_some(Termination::Stagnated))
    }

    pub fn learn(&mut self, _view: &View, _outcome: &Outcome) {}
}

/// The candidate of greatest utility whose cell (`index_of`) is no failed
/// goal.
fn best_not_failed(
    plan: &Plan,
    index_of: impl Fn(usize) -> Option<usize>,
    failed: &[usize],
) -> Option<usize> {
    let utilities = &plan.candidates.utilities;
    (0..utilities.len())
        .filter(|&k| utilities[k] > f64::NEG_INFINITY)
        .filter(|&k| index_of(k).is_some_and(|i| !failed.contains(&i)))
        .max_by(|&a, &b| {
            utilities[a]
                .total_cmp(&utilities[b])
                .then_with(|| b.cmp(&a))
        })
}
