//! The paper's decision-theoretic strategy (the model, section 4, eq. 14),
//! through the [`Planner`].
//!
//! # Choice
//! The planner's candidates are the reachable free cells on a lattice of
//! `candidate_stride_m`, at least `min_travel_m` away along the path, with
//! an expected gain above `min_gain_nats`: what making one cell at the
//! prior certain is worth, `ln bins - epsilon` (2.12 nats for 16 bins and
//! epsilon 0.65; at least the planner's default of 1 nat); of those it takes
//! the one maximising `alpha * gain / max gain - (1 - alpha) * cost / max
//! cost`. Paths and costs are for the planning radius (the robot's and a cell, at
//! least 5 cm, see [`region`](crate::exploration)), with unknown cells blocking.
//!
//! A goal the robot could not make any headway towards (a failed goal, see
//! [`Exploration`](crate::exploration::Exploration)) is not chosen again,
//! nor is a goal the robot reached whose step (the drive, its scans and
//! the scan at the goal) lowered the map's entropy by less than the
//! same `min_gain_nats`, the least a candidate must promise to be a goal at
//! all: the prediction, made on the ML map, can keep promising
//! what the readings do not deliver (through a pane the sensor sees
//! through, or cells split between two bins), and eq. 14 would send the
//! robot back and forth between two such goals for ever. Nor is a goal
//! whose step delivered less than it promised and whose scans did not
//! lower what it promises by that least gain: its expected gain, evaluated
//! again on the first plan after the robot got there, fell by less than
//! `min_gain_nats` from what it was when the goal was chosen, and the
//! map's entropy fell by less than that promise. The readings gathered
//! there did not confirm the prediction (a beam predicted to pass a gap in
//! a thin wall that its cone cleared at grazing incidence, say, and that
//! echoes every time), and the same pose would read the same again; the
//! drive between two such goals lowers the map's entropy by a few nats a
//! step and evades the first rule. A goal whose step delivered at least
//! its promise stays a candidate whatever it promises now (at a frontier
//! the scan makes new space visible, and the promise can stay as high).
//! The best candidate left is taken instead.
//!
//! A sensor that sees all around (no two neighbouring bearings more than 45
//! degrees apart, as the 24-sonar ring) is planned with the fixed heading 0
//! at every candidate, and the robot turns to it at the goal; one that does
//! not (a 180-degree laser) considers every candidate with eight headings,
//! 45 degrees apart, and the robot turns to the chosen one. Fixed headings
//! let the planning cache keep every candidate's gain across steps where
//! the scans did not change what its beams read
//! ([`Planner::next_viewpoint_cached`]: the same plan as a full
//! recomputation, bit for bit).
//!
//! # Termination
//! Done when every cell of the reachable region is certain (entropy below
//! epsilon: [`Termination::Certain`]) or, some not being certain, has
//! stagnated ([`Termination::Stagnated`]: its entropy changed by less than
//! 0.001 nats over its last five measurements); before that, when no
//! candidate is worth visiting ([`Termination::NoGoal`]).
//!
//! No rule of the run as a whole stops it: the goals' exhaustion (above)
//! ends a run whose goals no longer deliver what they promise, by
//! [`Termination::NoGoal`] once no candidate is left. Until 2026-12-06 a
//! window of 60 steps without a newly settled cell ended the run as
//! stagnated, a length chosen on the built-in corridor;
//! docs/experiments.md has what left it without a cause.

use super::{DecisionInputs, ExplorationStrategy, GoalOutcome, NextGoal};
use crate::error::Result;
use crate::exploration::ExplorationConfig;
use crate::exploration::region::{navigator, reachable_region, region_of};
use crate::exploration::result::Termination;
use crate::planner::{Plan, Planner, PlannerConfig, PlanningCache, Reachability};
use crate::pose::Pose;

/// The decision-theoretic strategy's state.
pub(crate) struct DecisionTheoretic {
    /// The planner with the loop's settings: its paths and free space are
    /// the strategies' navigator's ([`navigator`]).
    planner: Planner,
    /// The least gain a goal must promise, nats ([`Planner::min_gain_nats`]
    /// on the map's bins).
    min_gain_nats: f64,
    /// Goals (row-major cells) the robot reached without learning what a
    /// goal must promise: not chosen again.
    exhausted: Vec<usize>,
    /// The last goal, while the robot is on its way.
    last: Option<LastGoal>,
    /// The last goal, reached, and how much its step (the drive, its scans
    /// and the scan at the goal) lowered the map's entropy (nats): its
    /// promise is checked on the next plan.
    reached: Option<(LastGoal, f64)>,
    /// What planning after the next scan can keep of this one's work.
    cache: PlanningCache,
}

impl DecisionTheoretic {
    pub fn new(alpha: f64, config: &ExplorationConfig, bins: usize) -> Result<Self> {
        // The planner's own defaults choose the headings (by the bearings)
        // and the least gain (by the bins and epsilon).
        let planner = Planner::new(PlannerConfig {
            candidate_stride_m: config.candidate_stride_m,
            min_travel_m: config.min_travel_m,
            epsilon: config.epsilon,
            ..*navigator(config.robot_radius_m, alpha)?.config()
        })?;
        Ok(Self {
            min_gain_nats: planner.min_gain_nats(bins),
            planner,
            exhausted: Vec::new(),
            last: None,
            reached: None,
            cache: PlanningCache::new(),
        })
    }

    /// The next goal by eq. 14 (see the module documentation).
    fn choose(&mut self, view: &DecisionInputs<'_>) -> Result<NextGoal> {
        // The free space and the paths, found once for the termination
        // rule, the plan and the path to a goal other than the plan's (the
        // planner's cache keeps the map's read-outs they need).
        let (free, reach) = self.planner.free_and_reachable_cached(
            &mut self.cache,
            view.map,
            &view.pose,
            Some(view.driven),
        )?;
        if let Some(done) = self.termination(view, &reach)? {
            return Ok(NextGoal::Done(done));
        }
        let plan = self.plan(view, (&free, &reach))?;
        if let Some((goal, realised_nats)) = self.reached.take() {
            let now = self.cache.gain_at(
                view.map,
                view.model,
                self.planner.config().gain,
                &goal.pose,
                view.bearings,
            )?;
            if realised_nats < goal.promised_nats && goal.promised_nats - now < self.min_gain_nats {
                self.exhausted.push(goal.cell);
            }
        }
        let grid = view.grid();
        let index_of = |k: usize| {
            let p = &plan.candidates.poses[k];
            grid.world_to_cell(p.x_m, p.y_m)
                .and_then(|c| grid.index(c).ok())
        };
        let excluded = |i: usize| view.failed_goals.contains(&i) || self.exhausted.contains(&i);
        let chosen = match plan.chosen {
            Some(k) if index_of(k).is_some_and(excluded) => best_allowed(&plan, index_of, excluded),
            other => other,
        };
        let Some(k) = chosen else {
            return Ok(NextGoal::Done(Termination::NoGoal));
        };
        let path = if Some(k) == plan.chosen {
            plan.path
        } else {
            index_of(k).map_or_else(Vec::new, |i| reach.path_to(i))
        };
        self.last = index_of(k).map(|cell| LastGoal {
            cell,
            pose: plan.candidates.poses[k],
            promised_nats: plan.candidates.gains[k],
            entropy_nats: total_entropy(view.entropy),
        });
        Ok(NextGoal::Goal {
            pose: plan.candidates.poses[k],
            path,
        })
    }

    /// The one call of the planner's choice (eq. 14), keeping in the cache
    /// every candidate's gain for the next call, on the free space and
    /// paths `space` found for the robot's pose. The candidates' headings
    /// are fixed ([`Planner::headings`]: 0 for a sensor that sees all
    /// around, eight for the others), so that the gains of the candidates
    /// the scan did not reach are kept whichever way the robot faces.
    fn plan(&mut self, view: &DecisionInputs<'_>, space: (&[bool], &Reachability)) -> Result<Plan> {
        self.planner.next_viewpoint_on(
            &mut self.cache,
            view.map,
            &view.pose,
            view.bearings,
            view.model,
            space,
        )
    }

    /// Whether every cell of the reachable region is certain or stagnated
    /// (see the module documentation).
    fn termination(
        &self,
        view: &DecisionInputs<'_>,
        reach: &Reachability,
    ) -> Result<Option<Termination>> {
        let band_m = view.model.as_dyn().range_model().band_m;
        let region = region_of(reach, view.map.grid(), &self.planner, band_m);
        debug_assert_eq!(
            region,
            reachable_region(&self.planner, view.map, &view.pose, band_m, view.driven)?
        );
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
}

impl ExplorationStrategy for DecisionTheoretic {
    fn decide(&mut self, inputs: &DecisionInputs<'_>) -> Result<NextGoal> {
        self.choose(inputs)
    }

    /// A goal reached whose drive and scans lowered the map's entropy by
    /// less than the planner's `min_gain_nats` is exhausted; any other goal
    /// reached has its promise checked on the next plan (see the module
    /// documentation).
    fn learn(&mut self, view: &DecisionInputs<'_>, outcome: &GoalOutcome) {
        if let Some(goal) = self.last.take()
            && outcome.reached
        {
            let realised_nats = goal.entropy_nats - total_entropy(view.entropy);
            if realised_nats < self.min_gain_nats {
                self.exhausted.push(goal.cell);
            } else {
                self.reached = Some((goal, realised_nats));
            }
        }
    }
}

/// A goal chosen.
struct LastGoal {
    /// Its cell, row-major.
    cell: usize,
    pose: Pose,
    /// Its expected gain when it was chosen, nats.
    promised_nats: f64,
    /// The map's entropy when it was chosen, nats.
    entropy_nats: f64,
}

/// The sum of a map's entropies, nats.
fn total_entropy(entropy: &[f32]) -> f64 {
    entropy.iter().map(|&e| f64::from(e)).sum()
}

/// The candidate of greatest utility whose cell (`index_of`) is not
/// `excluded`.
fn best_allowed(
    plan: &Plan,
    index_of: impl Fn(usize) -> Option<usize>,
    excluded: impl Fn(usize) -> bool,
) -> Option<usize> {
    let utilities = &plan.candidates.utilities;
    (0..utilities.len())
        .filter(|&k| utilities[k] > f64::NEG_INFINITY)
        .filter(|&k| index_of(k).is_some_and(|i| !excluded(i)))
        .max_by(|&a, &b| {
            utilities[a]
                .total_cmp(&utilities[b])
                .then_with(|| b.cmp(&a))
        })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::coverage_map::CoverageMap;
    use crate::exploration::AnySensorModel;
    use crate::exploration::test_maps::{scan_room, scanned_room};
    use crate::occupancy::OccupancyGrid;

    /// Eq. 14 through the strategy: with alpha = 0 the goal is the nearest
    /// candidate worth visiting, with alpha = 1 the most informative one.
    #[test]
    fn alpha_zero_goes_nearest_alpha_one_goes_for_the_most_gain() {
        let (map, occupancy, pose) = scanned_room(true, 2);
        let config = ExplorationConfig::default();
        let model = AnySensorModel::laser();
        let bearings: Vec<f64> = (0..180)
            .map(|i| i as f64 * std::f64::consts::TAU / 180.0)
            .collect();
        let (entropy, ml) = (map.entropy(), map.ml());
        let driven = vec![false; map.grid().len()];
        let changed: Vec<usize> = (0..map.grid().len()).collect();
        let view = DecisionInputs {
            map: &map,
            ml: &ml,
            entropy: &entropy,
            changed: &changed,
            contact_cells: &[],
            driven: &driven,
            occupancy: &occupancy,
            pose,
            bearings: &bearings,
            model: &model,
            config: &config,
            failed_goals: &[],
        };
        let mut goals = Vec::new();
        for alpha in [0.0, 1.0] {
            let mut strategy = DecisionTheoretic::new(alpha, &config, map.bins()).unwrap();
            let NextGoal::Goal { pose: goal, path } = strategy.decide(&view).unwrap() else {
                panic!("alpha {alpha}: no goal in a room not yet explored");
            };
            let (free, reach) = strategy
                .planner
                .free_and_reachable_cached(&mut strategy.cache, &map, &pose, Some(&driven))
                .unwrap();
            let plan = strategy.plan(&view, (&free, &reach)).unwrap();
            assert_eq!(
                plan,
                strategy
                    .planner
                    .next_viewpoint_cached(&mut strategy.cache, &map, &pose, &bearings, &model)
                    .unwrap()
            );
            let c = &plan.candidates;
            let worth: Vec<usize> = (0..c.gains.len())
                .filter(|&k| c.gains[k] > strategy.min_gain_nats)
                .collect();
            let k = c.poses.iter().position(|p| *p == goal).unwrap();
            if alpha == 0.0 {
                let nearest = worth
                    .iter()
                    .map(|&j| c.costs[j])
                    .fold(f64::INFINITY, f64::min);
                assert_eq!(c.costs[k], nearest);
            } else {
                let best = worth.iter().map(|&j| c.gains[j]).fold(0.0, f64::max);
                assert_eq!(c.gains[k], best);
            }
            assert_eq!(path.last(), Some(&[goal.x_m, goal.y_m]));
            // A planner with its defaults (the loop's) makes the same choice.
            let planner = Planner::new(PlannerConfig {
                alpha,
                ..PlannerConfig::default()
            })
            .unwrap();
            let fresh = planner
                .next_viewpoint(&map, &pose, &bearings, &model)
                .unwrap();
            assert_eq!((fresh.pose, &fresh.path), (Some(goal), &path));
            goals.push((c.costs[k], c.gains[k]));
        }
        assert!(
            goals[0].0 < goals[1].0 && goals[0].1 < goals[1].1,
            "{goals:?}"
        );
    }

    /// A goal reached whose step delivered less than it promised and whose
    /// scans did not lower what it promises by the least gain a goal must
    /// promise is not chosen again, though the map's entropy fell by more
    /// than that least gain on the way; one whose step delivered its
    /// promise, or whose scans settled it, is kept.
    #[test]
    fn a_goal_whose_promise_its_scans_did_not_lower_is_exhausted() {
        /// What the decisions share, but for the maps and the pose.
        struct Scene {
            occupancy: OccupancyGrid,
            config: ExplorationConfig,
            model: AnySensorModel,
            bearings: Vec<f64>,
            driven: Vec<bool>,
            changed: Vec<usize>,
        }
        fn view<'a>(
            scene: &'a Scene,
            map: &'a CoverageMap,
            ml: &'a [f32],
            entropy: &'a [f32],
            pose: Pose,
        ) -> DecisionInputs<'a> {
            DecisionInputs {
                map,
                ml,
                entropy,
                changed: &scene.changed,
                contact_cells: &[],
                driven: &scene.driven,
                occupancy: &scene.occupancy,
                pose,
                bearings: &scene.bearings,
                model: &scene.model,
                config: &scene.config,
                failed_goals: &[],
            }
        }
        let (map, occupancy, start) = scanned_room(true, 2);
        let scene = Scene {
            occupancy,
            config: ExplorationConfig::default(),
            model: AnySensorModel::laser(),
            bearings: (0..180)
                .map(|i| i as f64 * std::f64::consts::TAU / 180.0)
                .collect(),
            driven: vec![false; map.grid().len()],
            changed: (0..map.grid().len()).collect(),
        };
        // The goal from the start, and the strategy on its way there.
        let on_the_way = || {
            let mut strategy = DecisionTheoretic::new(0.5, &scene.config, map.bins()).unwrap();
            let (ml, entropy) = (map.ml(), map.entropy());
            let NextGoal::Goal { pose: goal, .. } = strategy
                .decide(&view(&scene, &map, &ml, &entropy, start))
                .unwrap()
            else {
                panic!("no goal in a room not yet explored");
            };
            let cell = map.grid().world_to_cell(goal.x_m, goal.y_m).unwrap();
            (strategy, goal, map.grid().index(cell).unwrap())
        };
        let reached = GoalOutcome { reached: true };

        // The map's entropy as the loop reports it after a step that lowered
        // it by more than `nats` elsewhere (nothing changed where the goal
        // looks): the first cells above half a nat made certain.
        let fallen_by = |nats: f64| {
            let mut entropy = map.entropy();
            let mut fallen = 0.0;
            for e in entropy.iter_mut().filter(|e| **e > 0.5) {
                fallen += f64::from(*e);
                *e = 0.0;
                if fallen > nats {
                    break;
                }
            }
            assert!(fallen > nats);
            entropy
        };
        let ml = map.ml();

        // The step lowered the map's entropy by more than a goal must
        // promise but less than this goal promised.
        let (mut strategy, goal, cell) = on_the_way();
        let promised = strategy.last.as_ref().unwrap().promised_nats;
        assert!(promised > 4.0 * strategy.min_gain_nats, "{promised}");
        let entropy = fallen_by(2.0 * strategy.min_gain_nats);
        let at_goal = view(&scene, &map, &ml, &entropy, goal);
        strategy.learn(&at_goal, &reached);
        assert!(strategy.exhausted.is_empty(), "the entropy fell enough");
        assert!(strategy.reached.is_some());
        let next = strategy.decide(&at_goal).unwrap();
        assert_eq!(strategy.exhausted, [cell], "promised {promised}");
        assert!(!matches!(next, NextGoal::Goal { pose, .. } if pose == goal));

        // The step delivered all the goal promised (new space seen, say),
        // though the goal promises as much now: it stays a candidate.
        let (mut strategy, goal, _) = on_the_way();
        let entropy = fallen_by(promised);
        let at_goal = view(&scene, &map, &ml, &entropy, goal);
        strategy.learn(&at_goal, &reached);
        strategy.decide(&at_goal).unwrap();
        assert!(strategy.reached.is_none(), "the promise was checked");
        assert!(strategy.exhausted.is_empty());

        // The goal's scans settled what it promised: it stays a candidate.
        let (mut strategy, goal, _) = on_the_way();
        let promised = strategy.last.as_ref().unwrap().promised_nats;
        let mut scanned = map.clone();
        for _ in 0..4 {
            scan_room(true, &goal, &mut scanned);
        }
        let (ml, entropy) = (scanned.ml(), scanned.entropy());
        let at_goal = view(&scene, &scanned, &ml, &entropy, goal);
        strategy.learn(&at_goal, &reached);
        assert!(strategy.reached.is_some());
        strategy.decide(&at_goal).unwrap();
        assert!(strategy.reached.is_none(), "the promise was checked");
        let now = strategy
            .cache
            .gain_at(
                &scanned,
                &scene.model,
                strategy.planner.config().gain,
                &goal,
                &scene.bearings,
            )
            .unwrap();
        assert!(
            promised - now >= strategy.min_gain_nats,
            "{promised} -> {now}"
        );
        assert!(strategy.exhausted.is_empty());
    }
}
