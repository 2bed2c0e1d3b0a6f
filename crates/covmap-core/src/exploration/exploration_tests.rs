//! The loop's tests: runs in a room that scan, drive and touch.

use super::*;
use crate::exploration::Travel;
use crate::planner::{Planner, PlannerConfig};
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

/// After every step, the read-outs the loop keeps from the map's change
/// feed are the map's, bit for bit, the uncertain cells counted anew,
/// and every cell the robot ran into is held certainly covered, for
/// every strategy, in runs that scan, drive and run into the pane.
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
            let step = run.steps();
            let (entropy, ml) = (run.map.entropy(), run.map.ml());
            let bits = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(
                bits(&run.kept.entropy),
                bits(&entropy),
                "{strategy:?}, step {step}"
            );
            assert_eq!(bits(&run.kept.ml), bits(&ml), "{strategy:?}, step {step}");
            let uncertain = entropy.iter().filter(|&&e| f64::from(e) > 0.65).count();
            let fraction = uncertain as f64 / entropy.len() as f64;
            assert_eq!(
                run.uncertain_fraction(),
                fraction,
                "{strategy:?}, step {step}"
            );
            assert!(uncertain > 0 && uncertain < entropy.len());
            for &cell in &run.contact_cells {
                let i = grid.index(cell).unwrap();
                assert!(
                    ml[i] == 1.0 && entropy[i] < 1e-6,
                    "{strategy:?}, step {step}"
                );
            }
        }
        assert!(
            run.totals.contacts > 0 && run.steps() > 3,
            "{strategy:?}: {} contacts, {} steps",
            run.totals.contacts,
            run.steps()
        );
    }
}

fn room_run(strategy: Strategy) -> Exploration<RoomRing, Bumper> {
    let bearings: Vec<f64> = (0..90)
        .map(|i| i as f64 * std::f64::consts::TAU / 90.0)
        .collect();
    let grid = Grid::covering(-0.5, -0.5, 4.5, 3.5, 0.05).unwrap();
    let mut setup = ExplorationSetup::new(grid, Pose::new(1.0, 1.5, 0.0), strategy);
    setup.model = AnySensorModel::Laser(LaserModel::default());
    setup.config.max_path_m = 40.0;
    Exploration::new(setup, RoomRing(bearings), Bumper).unwrap()
}

/// A run steered from outside with the goals the coverage strategy chose
/// is the coverage strategy's run, step by step, bit for bit.
#[test]
fn the_goals_of_a_strategy_given_from_outside_make_its_run() {
    let mut own = room_run(Strategy::coverage(0.5).unwrap());
    let mut steered = room_run(Strategy::Custom);
    while let Some(step) = own.step().unwrap() {
        let again = steered.step_to(step.goal).unwrap().unwrap();
        assert_eq!(again, step);
        let bits = |m: &CoverageMap| {
            m.histograms()
                .iter()
                .map(|v| v.to_bits())
                .collect::<Vec<_>>()
        };
        assert_eq!(bits(&own.map), bits(&steered.map), "step {}", step.index);
    }
    assert!(own.steps() > 3, "{} steps", own.steps());
    // Ended on the caller's word: by the paper's rule where it holds.
    let rule = steered.rule().unwrap();
    assert_eq!(
        steered.finish().unwrap(),
        rule.unwrap_or(Termination::NoGoal)
    );
    if matches!(
        own.termination(),
        Some(Termination::Certain | Termination::Stagnated)
    ) {
        assert_eq!(rule, own.termination());
    }
    assert_eq!(steered.step_to(Pose::new(1.0, 1.5, 0.0)).unwrap(), None);
}

/// Goals the robot cannot go to are refused with the run as it was; the
/// loop does not choose for a custom strategy; a run ended on the caller's
/// word with cells left open has no goal.
#[test]
fn a_goal_the_robot_cannot_go_to_leaves_the_run_as_it_was() {
    let mut run = room_run(Strategy::Custom);
    // The loop does not choose for it (the first scans are taken).
    assert!(matches!(
        run.step(),
        Err(CovmapError::InvalidSetting {
            name: "strategy",
            ..
        })
    ));
    // The planner's choice is a goal the robot can reach.
    let plan = run.viewpoints(0.5).unwrap();
    assert!(!plan.candidates.poses.is_empty());
    let first = run.step_to(plan.pose.unwrap()).unwrap().unwrap();
    assert!(first.reached && first.path == plan.path);
    let before = (
        run.steps(),
        run.scans(),
        run.pose(),
        run.map.histograms().to_vec(),
    );
    for goal in [
        Pose::new(f64::NAN, 1.0, 0.0),
        Pose::new(40.0, 1.0, 0.0),
        Pose::new(3.0, 1.5, 0.0), // the pane is in the way, the cell behind unknown
        Pose::new(4.3, 1.5, 0.0), // behind the wall
    ] {
        match run.step_to(goal) {
            Err(CovmapError::InvalidGoal { .. }) => {}
            other => panic!("{goal:?}: {other:?}"),
        }
        let now = (
            run.steps(),
            run.scans(),
            run.pose(),
            run.map.histograms().to_vec(),
        );
        assert!(now == before, "{goal:?}");
    }
    assert_eq!(run.rule().unwrap(), None);
    assert_eq!(run.finish().unwrap(), Termination::NoGoal);
    assert_eq!(run.step_to(Pose::new(1.5, 1.5, 0.0)).unwrap(), None);
}

/// The candidates a steered run weighs, kept from call to call, are a
/// fresh plan's, bit for bit, after every step.
#[test]
fn viewpoints_kept_from_call_to_call_are_a_fresh_plan() {
    let mut run = room_run(Strategy::Custom);
    run.begin().unwrap();
    for _ in 0..4 {
        let kept = run.viewpoints(0.5).unwrap();
        let fresh = Planner::new(PlannerConfig {
            alpha: 0.5,
            robot_radius_m: run.config.robot_radius_m,
            candidate_stride_m: run.config.candidate_stride_m,
            min_travel_m: run.config.min_travel_m,
            epsilon: run.config.epsilon,
            ..PlannerConfig::default()
        })
        .unwrap()
        .next_viewpoint(&run.map, &run.pose, &run.bearings, run.model.as_dyn())
        .unwrap();
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&kept.candidates.gains), bits(&fresh.candidates.gains));
        assert_eq!(
            bits(&kept.candidates.utilities),
            bits(&fresh.candidates.utilities)
        );
        assert_eq!(kept.pose, fresh.pose);
        let Some(goal) = kept.pose else { break };
        run.step_to(goal).unwrap();
    }
}
