//! A strategy of one's own driving covmap's exploration loop.
//!
//! `GainPerMetre` implements the core's [`ExplorationStrategy`]: each step
//! it weighs the planner's candidate viewpoints (their expected gains and
//! path costs on the coverage map) and goes to the one that promises the
//! most information per metre of travel, rather than eq. 14's normalised
//! trade-off; it is done when no candidate is worth a goal. The simulator
//! runs it ([`SimExploration::with_strategy`]) beside the built-in coverage
//! strategy on the same world and seed, and both are judged alike.
//!
//! Run: `cargo run --release --example custom_strategy -- [WORLD] [SEED]`
//! (default: the built-in `corridor`, seed 0).

use std::sync::Arc;

use covmap::exploration::{DecisionInputs, ExplorationStrategy, NextGoal, Strategy, Termination};
use covmap::planner::{Planner, PlannerConfig};
use covmap::sim::World;
use covmap::sim::exploration::{ExplorationRun, ExploreOptions, SimExploration};

/// Go where the expected gain per metre is highest.
struct GainPerMetre {
    planner: Planner,
}

impl GainPerMetre {
    /// Travel added to every path so that a candidate next to the robot
    /// does not win by a near-zero cost alone, metres.
    const LOOK_AHEAD_M: f64 = 1.0;
}

impl ExplorationStrategy for GainPerMetre {
    fn decide(&mut self, inputs: &DecisionInputs<'_>) -> covmap::Result<NextGoal> {
        let model = inputs.model.as_dyn();
        let plan = self
            .planner
            .next_viewpoint(inputs.map, &inputs.pose, inputs.bearings, model)?;
        let c = &plan.candidates;
        let grid = inputs.grid();
        let index = |k: usize| {
            grid.world_to_cell(c.poses[k].x_m, c.poses[k].y_m)
                .and_then(|cell| grid.index(cell).ok())
        };
        // Candidates worth a goal (eq. 14 gives the others -inf), not a
        // goal the robot could make no headway towards before.
        let best = (0..c.poses.len())
            .filter(|&k| c.utilities[k].is_finite())
            .filter(|&k| index(k).is_some_and(|i| !inputs.failed_goals.contains(&i)))
            .max_by(|&a, &b| {
                let rate = |k: usize| c.gains[k] / (c.costs[k] + Self::LOOK_AHEAD_M);
                rate(a).total_cmp(&rate(b))
            });
        let Some(k) = best else {
            return Ok(NextGoal::Done(Termination::NoGoal));
        };
        let paths = self.planner.reachability(inputs.map, &inputs.pose)?;
        Ok(NextGoal::Goal {
            pose: c.poses[k],
            path: paths.path_to(index(k).expect("a candidate lies on the map")),
        })
    }
}

fn report(name: &str, run: &ExplorationRun) {
    let r = &run.result;
    println!(
        "{name:<16} {:>8.1} m {:>6} scans {:>5} steps  {:>6.2} % uncertain  ends {}",
        r.path_length_m,
        r.scans,
        r.steps,
        100.0 * run.high_entropy_fraction,
        r.termination.map_or("-", |t| t.as_str())
    );
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let world_name = args.next().unwrap_or_else(|| "corridor".into());
    let seed: u64 = args.next().map(|s| s.parse()).transpose()?.unwrap_or(0);
    let world = Arc::new(World::builtin(&world_name)?);
    let options = ExploreOptions {
        seed,
        ..ExploreOptions::default()
    };

    let mut own = SimExploration::new(Arc::clone(&world), Strategy::coverage(0.5)?, &options)?;
    own.run()?;
    report("coverage (eq. 14)", &own.into_result()?);

    let chooser = GainPerMetre {
        planner: Planner::new(PlannerConfig {
            robot_radius_m: options.config.robot_radius_m,
            candidate_stride_m: options.config.candidate_stride_m,
            min_travel_m: options.config.min_travel_m,
            epsilon: options.config.epsilon,
            ..PlannerConfig::default()
        })?,
    };
    let mut custom = SimExploration::with_strategy(world, Box::new(chooser), &options)?;
    custom.run()?;
    let run = custom.into_result()?;
    assert_eq!(run.result.strategy, Strategy::Custom);
    report("gain per metre", &run);
    Ok(())
}
