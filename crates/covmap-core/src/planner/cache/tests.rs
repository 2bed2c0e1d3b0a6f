//! The cached plan against a fresh one, step after step of an exploration of
//! two walled rooms, and what the cache reuses.

use crate::scan_map::ScanMap;
use std::f64::consts::{FRAC_PI_2, PI, TAU};

use super::*;
use crate::grid::Cell;
use crate::planner::PlannerConfig;
use crate::planner::test_maps::ring;
use crate::sensor::{LaserModel, SonarModel};
use crate::test_rng::uniform;

/// Two rooms of a hall, [0.5, 12] and [12, 23.5] by [0.5, 5.5] m, joined by
/// a door at the north end of the wall between them (y from 4.3 to 5.5), as
/// segments.
const WALLS: [[f64; 4]; 6] = [
    [0.5, 0.5, 23.5, 0.5],
    [23.5, 0.5, 23.5, 5.5],
    [23.5, 5.5, 0.5, 5.5],
    [0.5, 5.5, 0.5, 0.5],
    [12.0, 0.5, 12.0, 4.3],
    // A pillar in the east room.
    [18.0, 2.0, 18.0, 2.6],
];

/// The distance from `origin` along `angle` to the nearest wall, if any.
fn cast(origin: [f64; 2], angle: f64) -> Option<f64> {
    let (s, c) = angle.sin_cos();
    WALLS
        .iter()
        .filter_map(|&[x0, y0, x1, y1]| {
            let (ex, ey) = (x1 - x0, y1 - y0);
            let det = ex * s - ey * c;
            if det.abs() < 1e-12 {
                return None;
            }
            let (wx, wy) = (x0 - origin[0], y0 - origin[1]);
            let t = (ex * wy - ey * wx) / det;
            let u = (c * wy - s * wx) / det;
            (t > 0.0 && (0.0..=1.0).contains(&u)).then_some(t)
        })
        .min_by(f64::total_cmp)
}

/// A simulated scan from `pose`: the distance to the nearest wall along
/// each beam, with seeded noise, or past the maximum range where none is
/// within it.
fn scan(
    pose: &Pose,
    bearings: &[f64],
    max_range_m: f64,
    next: &mut impl FnMut() -> f64,
) -> Vec<f64> {
    bearings
        .iter()
        .map(|b| match cast([pose.x_m, pose.y_m], pose.theta_rad + b) {
            Some(d) if d < max_range_m => (d + 0.03 * (next() - 0.5)).max(0.0),
            _ => max_range_m + 1.0,
        })
        .collect()
}

/// The bits of everything a plan holds.
fn bits(plan: &Plan) -> Vec<u64> {
    let pose = |p: &Pose| [p.x_m, p.y_m, p.theta_rad].map(f64::to_bits);
    let c = &plan.candidates;
    let mut out: Vec<u64> = plan.pose.iter().flat_map(pose).collect();
    out.push(plan.chosen.map_or(u64::MAX, |k| k as u64));
    out.extend(plan.path.iter().flatten().map(|v| v.to_bits()));
    out.push(c.poses.len() as u64);
    out.extend(c.poses.iter().flat_map(pose));
    for values in [&c.gains, &c.costs, &c.utilities] {
        out.push(values.len() as u64);
        out.extend(values.iter().map(|v| v.to_bits()));
    }
    out
}

/// A 24 m x 6 m map at 10 cm at the prior.
fn empty() -> CoverageMap {
    CoverageMap::new(Grid::new([0.0, 0.0], 0.1, 60, 240).unwrap())
}

/// The robot's way, a scan every 0.5 m: along the west room, through the
/// door, along the east room; heading east throughout.
fn way() -> Vec<Pose> {
    let along = |from: f64, to: f64, y: f64| {
        let n = ((to - from) / 0.5).round() as usize;
        (0..=n).map(move |k| Pose::new(from + 0.5 * k as f64, y, 0.0))
    };
    along(1.5, 11.0, 3.0)
        .chain(along(11.5, 12.5, 4.9))
        .chain(along(13.5, 22.5, 3.5))
        .collect()
}

/// The cached plan and a fresh one for the same inputs, asserted equal in
/// every bit; the cache's stats.
fn plan_both<M: SensorModel + ?Sized>(
    planner: &Planner,
    cache: &mut PlanningCache,
    map: &CoverageMap,
    pose: &Pose,
    bearings: &[f64],
    model: &M,
) -> CacheStats {
    let fresh = planner.next_viewpoint(map, pose, bearings, model);
    let cached = planner.next_viewpoint_cached(cache, map, pose, bearings, model);
    match (&fresh, &cached) {
        (Ok(fresh), Ok(cached)) => assert_eq!(bits(fresh), bits(cached), "at {pose:?}"),
        // Errors holding NaN are not equal to themselves: compared as written.
        _ => assert_eq!(format!("{fresh:?}"), format!("{cached:?}"), "at {pose:?}"),
    }
    cache.stats()
}

/// A sonar exploration of the two rooms with planning after every scan:
/// the cached plan is the fresh one in every bit at every step, and once the
/// robot is in the east room, the west room's candidates keep their gains.
#[test]
fn the_cached_plan_is_the_fresh_plan_after_every_scan() {
    let sonar = SonarModel::default();
    let bearings = ring();
    let planner = Planner::new(PlannerConfig::default()).unwrap();
    let mut cache = PlanningCache::new();
    let mut map = empty();
    let mut next = uniform(41);
    let mut last = CacheStats::default();
    let mut reused_in_the_east = Vec::new();
    for (step, pose) in way().iter().enumerate() {
        let ranges = scan(pose, &bearings, sonar.range.max_range_m, &mut next);
        map.integrate(pose, &ranges, &bearings, &sonar).unwrap();
        last = plan_both(&planner, &mut cache, &map, pose, &bearings, &sonar);
        assert_eq!(last.rebuilt, step == 0);
        assert!(last.changed_cells > 0);
        if pose.x_m > 20.0 {
            reused_in_the_east.push(last);
        }
    }
    assert!(last.candidates > 300, "{last:?}");
    // After a scan at the east room's far end, the west room's candidates
    // (more than 10.4 m away, twice the reach of a sonar beam) kept their
    // gains. (The east room's are all within that distance: a sonar map's
    // walls hold few cells as covered with certainty, so most predicted
    // beams may get through them, and a gain depends on the cells beyond.)
    assert!(!reused_in_the_east.is_empty());
    for stats in &reused_in_the_east {
        assert!(10 * stats.recomputed < 6 * stats.candidates, "{stats:?}");
        assert!(20 * stats.recomputed_beams < 9 * stats.beams, "{stats:?}");
    }
    // Nothing changed: nothing recomputed, the same plan.
    let pose = way()[way().len() - 1];
    let again = plan_both(&planner, &mut cache, &map, &pose, &bearings, &sonar);
    assert_eq!((again.recomputed, again.changed_cells), (0, 0));
}

/// With a sonar of 2.5 m, a scan changes the cells within 2.7 m of the
/// robot. Only candidates whose beams reach them are computed again: none
/// farther than twice that (and a tile), well under half of all, nearly all
/// of them candidates whose gain did change (the tiles a gain reads are a
/// close bound), and of those only the beams that reach them.
#[test]
fn only_candidates_within_reach_of_a_scan_are_computed_again() {
    let mut sonar = SonarModel::default();
    sonar.range.max_range_m = 2.5;
    let reach_m = sonar.range.max_range_m + sonar.range.band_m;
    let bearings = ring();
    let planner = Planner::new(PlannerConfig::default()).unwrap();
    let mut cache = PlanningCache::new();
    let mut map = empty();
    let mut next = uniform(5);
    for pose in &way() {
        let ranges = scan(pose, &bearings, sonar.range.max_range_m, &mut next);
        map.integrate(pose, &ranges, &bearings, &sonar).unwrap();
    }
    plan_both(&planner, &mut cache, &map, &way()[0], &bearings, &sonar);
    for pose in [Pose::new(3.0, 2.0, 0.0), Pose::new(20.0, 3.0, 0.0)] {
        let before = planner
            .next_viewpoint(&map, &pose, &bearings, &sonar)
            .unwrap();
        let ranges = scan(&pose, &bearings, sonar.range.max_range_m, &mut next);
        map.integrate(&pose, &ranges, &bearings, &sonar).unwrap();
        let stats = plan_both(&planner, &mut cache, &map, &pose, &bearings, &sonar);
        let after = planner
            .next_viewpoint(&map, &pose, &bearings, &sonar)
            .unwrap();
        let (b, a) = (&before.candidates, &after.candidates);
        let gain_before: HashMap<[u64; 2], u64> = (b.poses.iter().zip(&b.gains))
            .map(|(p, g)| ([p.x_m.to_bits(), p.y_m.to_bits()], g.to_bits()))
            .collect();
        // Candidates new to the plan (free space grew) are computed too.
        let mut changed = 0;
        for (k, p) in a.poses.iter().enumerate() {
            let before = gain_before.get(&[p.x_m.to_bits(), p.y_m.to_bits()]);
            if before != Some(&a.gains[k].to_bits()) {
                changed += 1;
                // Two reaches, and the diagonals of a tile and a cell.
                let distance = (p.x_m - pose.x_m).hypot(p.y_m - pose.y_m);
                assert!(
                    before.is_none() || distance < 2.0 * reach_m + 0.8 * 1.5 + 0.15,
                    "{p:?}"
                );
            }
        }
        assert!(stats.candidates > 300, "{stats:?}");
        assert!(
            20 * stats.recomputed < 9 * stats.candidates,
            "{stats:?}: under 45 % computed again"
        );
        assert!(
            changed <= stats.recomputed && 10 * changed >= 8 * stats.recomputed,
            "{stats:?}: {changed} gains changed"
        );
        // Of a candidate computed again, only the beams towards the scan.
        assert!(
            10 * stats.recomputed_beams < 3 * stats.beams
                && stats.recomputed_beams < 20 * stats.recomputed,
            "{stats:?}: under 30 % of the beams, under 20 of 24 a candidate"
        );
    }
}

/// Planning from random poses with random headings, a map changed without
/// a scan, and bearings, models and gain options that change between steps:
/// the same plans as fresh ones, bit for bit.
#[test]
fn the_cached_plan_is_the_fresh_plan_whatever_changes_between_steps() {
    let sonar = SonarModel::default();
    let narrow = SonarModel {
        opening_angle_rad: 10f64.to_radians(),
        range: RangeModel {
            band_m: 0.1,
            ..SonarModel::default().range
        },
    };
    let laser = LaserModel {
        range: RangeModel {
            max_range_m: 6.0,
            ..LaserModel::default().range
        },
    };
    let half: Vec<f64> = (0..19).map(|i| -FRAC_PI_2 + i as f64 * PI / 18.0).collect();
    let ring = ring();
    let mut next = uniform(7);
    let mut map = empty();
    for pose in way().iter().take(10) {
        let ranges = scan(pose, &ring, sonar.range.max_range_m, &mut next);
        map.integrate(pose, &ranges, &ring, &sonar).unwrap();
    }
    let mut cache = PlanningCache::new();
    let mut rebuilt = 0;
    for step in 0..14 {
        // A random pose in the west room, heading east or random.
        let (x, y, heading) = (1.0 + 4.5 * next(), 1.0 + 4.0 * next(), TAU * next());
        let pose = Pose::new(x, y, if step % 2 == 0 { 0.0 } else { heading });
        let (config, bearings, model): (_, &[f64], &dyn SensorModel) = match step % 7 {
            0..=2 => (PlannerConfig::default(), &ring, &sonar),
            3 => (PlannerConfig::default(), &ring[..12], &sonar),
            4 => (PlannerConfig::default(), &ring, &narrow),
            5 => (
                PlannerConfig {
                    candidate_headings: Some(4),
                    candidate_stride_m: 0.75,
                    ..PlannerConfig::default()
                },
                &half,
                &laser,
            ),
            _ => (
                PlannerConfig {
                    gain: GainOptions {
                        stop_coverage: StopCoverage::Mean,
                        range_step_m: Some(0.025),
                    },
                    ..PlannerConfig::default()
                },
                &ring,
                &sonar,
            ),
        };
        let planner = Planner::new(config).unwrap();
        if step % 3 == 1 {
            // A scan by the model planned with.
            let ranges = scan(&pose, bearings, model.range_model().max_range_m, &mut next);
            map.integrate(&pose, &ranges, bearings, model).unwrap();
        } else if step % 3 == 2 {
            // A few cells changed by hand, as a map loaded in its place.
            let mut data = map.histograms().to_vec();
            for _ in 0..5 {
                let cell = Cell {
                    row: 5 + (50.0 * next()) as usize,
                    col: 10 + (100.0 * next()) as usize,
                };
                let i = map.grid().index(cell).unwrap();
                data[i * 16..(i + 1) * 16].fill(0.0);
                data[i * 16 + 15] = 1.0;
            }
            map = CoverageMap::from_histograms(*map.grid(), 16, data).unwrap();
        }
        let stats = plan_both(&planner, &mut cache, &map, &pose, bearings, model);
        rebuilt += usize::from(stats.rebuilt);
    }
    assert!(rebuilt >= 4, "the settings changed, the cache started over");
}

/// A 180° laser with candidates in eight headings: the cached plan is the
/// fresh one, the headings are the fixed ones, and the gains of a position
/// differ between headings.
#[test]
fn candidates_in_several_headings() {
    let laser = LaserModel {
        range: RangeModel {
            max_range_m: 6.0,
            ..LaserModel::default().range
        },
    };
    let half: Vec<f64> = (0..37).map(|i| -FRAC_PI_2 + i as f64 * PI / 36.0).collect();
    let config = PlannerConfig {
        candidate_headings: Some(8),
        ..PlannerConfig::default()
    };
    let planner = Planner::new(config).unwrap();
    let mut cache = PlanningCache::new();
    let mut map = empty();
    let mut next = uniform(99);
    let mut last = None;
    for pose in way().iter().step_by(3) {
        let ranges = scan(pose, &half, laser.range.max_range_m, &mut next);
        map.integrate(pose, &ranges, &half, &laser).unwrap();
        plan_both(&planner, &mut cache, &map, pose, &half, &laser);
        last = Some(*pose);
    }
    let plan = planner
        .next_viewpoint(&map, &last.unwrap(), &half, &laser)
        .unwrap();
    let c = &plan.candidates;
    assert_eq!(c.poses.len() % 8, 0);
    for (k, pose) in c.poses.iter().enumerate() {
        assert_eq!(pose.theta_rad, (k % 8) as f64 * std::f64::consts::TAU / 8.0);
        assert_eq!(c.costs[k], c.costs[k - k % 8], "one position, one cost");
    }
    let differ = c
        .gains
        .chunks_exact(8)
        .filter(|g| g.iter().any(|&x| x != g[0]))
        .count();
    assert!(
        2 * differ > c.gains.len() / 8,
        "a half view depends on the heading"
    );
    let one = Planner::new(PlannerConfig {
        candidate_headings: Some(1),
        ..PlannerConfig::default()
    })
    .unwrap()
    .next_viewpoint(&map, &last.unwrap(), &half, &laser)
    .unwrap();
    assert_eq!(8 * one.candidates.poses.len(), c.poses.len());
    // By default, a sensor that does not see all around plans eight headings.
    let default = Planner::new(PlannerConfig::default())
        .unwrap()
        .next_viewpoint(&map, &last.unwrap(), &half, &laser)
        .unwrap();
    assert_eq!(bits(&default), bits(&plan));
}

/// Bad input: the same error as the fresh plan's, and the cache as it was.
#[test]
fn errors_are_the_fresh_plans_and_change_nothing() {
    let sonar = SonarModel::default();
    let bearings = ring();
    let planner = Planner::new(PlannerConfig::default()).unwrap();
    let mut cache = PlanningCache::new();
    let mut map = empty();
    let pose = Pose::new(2.0, 3.0, 0.0);
    let mut next = uniform(3);
    map.integrate(
        &pose,
        &scan(&pose, &bearings, 5.0, &mut next),
        &bearings,
        &sonar,
    )
    .unwrap();
    plan_both(&planner, &mut cache, &map, &pose, &bearings, &sonar);
    let before = cache.stats();
    let mut bad_model = sonar;
    bad_model.range.max_range_m = -1.0;
    let mut bad_bearings = bearings.clone();
    bad_bearings[3] = f64::NAN;
    for (pose, bearings, model) in [
        (Pose::new(-1.0, 3.0, 0.0), &bearings, &sonar),
        (Pose::new(2.0, 3.0, f64::INFINITY), &bearings, &sonar),
        (pose, &bad_bearings, &sonar),
        (pose, &bearings, &bad_model),
    ] {
        let fresh = planner
            .next_viewpoint(&map, &pose, bearings, model)
            .unwrap_err();
        let cached = planner
            .next_viewpoint_cached(&mut cache, &map, &pose, bearings, model)
            .unwrap_err();
        assert_eq!(format!("{fresh:?}"), format!("{cached:?}"));
        assert_eq!(cache.stats(), before);
    }
    let again = plan_both(&planner, &mut cache, &map, &pose, &bearings, &sonar);
    assert!(!again.rebuilt && again.recomputed == 0, "{again:?}");
}

/// Every parameter of the sensor model changed in turn between two cached
/// plans on the same map: each plan is the fresh plan, bit for bit (a
/// cache that compared only some of the parameters kept the gains of the
/// model before: 911 nats where a fresh evaluation gave 383 for a changed
/// no-echo weight, a parameter since removed).
#[test]
fn a_change_of_any_sensor_parameter_recomputes_the_gains() {
    let sonar = SonarModel::default();
    let ring = ring();
    let mut next = uniform(11);
    let mut map = empty();
    for pose in way().iter().take(6) {
        let ranges = scan(pose, &ring, sonar.range.max_range_m, &mut next);
        map.integrate(pose, &ranges, &ring, &sonar).unwrap();
    }
    let planner = Planner::new(PlannerConfig::default()).unwrap();
    let pose = Pose::new(3.0, 3.0, 0.0);
    let mut cache = PlanningCache::new();
    planner
        .next_viewpoint_cached(&mut cache, &map, &pose, &ring, &sonar)
        .unwrap();
    for (i, parameter) in crate::sensor::SONAR_MODEL_PARAMETERS.iter().enumerate() {
        let mut changed = sonar;
        let before = crate::learn::Fittable::get(&sonar, parameter.name).unwrap();
        // A valid value a little way off the default.
        let middle = parameter
            .fit_bounds
            .map_or(0.5, |[low, high]| 0.5 * (low + high));
        let value = [before * 0.8, before * 1.2 + 0.01, middle]
            .into_iter()
            .find(|&v| {
                let mut m = sonar;
                crate::learn::Fittable::set(&mut m, parameter.name, v);
                v != before && m.validate().is_ok()
            })
            .unwrap_or_else(|| panic!("no valid change of {}", parameter.name));
        assert!(crate::learn::Fittable::set(
            &mut changed,
            parameter.name,
            value
        ));
        assert_ne!(changed, sonar, "{}", parameter.name);
        for model in [&changed, &sonar] {
            let cached = planner
                .next_viewpoint_cached(&mut cache, &map, &pose, &ring, model)
                .unwrap();
            let fresh = planner.next_viewpoint(&map, &pose, &ring, model).unwrap();
            assert_eq!(
                bits(&cached),
                bits(&fresh),
                "parameter {i}, {}",
                parameter.name
            );
            assert!(cache.stats().rebuilt, "{}", parameter.name);
        }
    }
}

/// The gain at one pose read through the cache is the fresh evaluation's,
/// bit for bit: after a plan on the map (the cache's per-map work) and
/// after a scan the cache has not seen (computed anew).
#[test]
fn the_gain_at_a_pose_is_the_fresh_gain() {
    let sonar = SonarModel::default();
    let bearings = ring();
    let planner = Planner::new(PlannerConfig::default()).unwrap();
    let options = planner.config().gain;
    let mut cache = PlanningCache::new();
    let mut map = empty();
    let mut next = uniform(43);
    let fresh = |map: &CoverageMap, pose: &Pose| {
        GainEvaluator::new(map, &sonar, options)
            .unwrap()
            .evaluate(std::slice::from_ref(pose), &bearings, GainMethod::Fast)
            .unwrap()[0]
    };
    let poses = way();
    for (step, pose) in poses.iter().enumerate().step_by(4) {
        let ranges = scan(pose, &bearings, sonar.range.max_range_m, &mut next);
        map.integrate(pose, &ranges, &bearings, &sonar).unwrap();
        let ahead = &poses[(step + 3).min(poses.len() - 1)];
        for at in [pose, ahead] {
            let unseen = cache.gain_at(&map, &sonar, options, at, &bearings).unwrap();
            assert_eq!(unseen.to_bits(), fresh(&map, at).to_bits(), "at {at:?}");
        }
        planner
            .next_viewpoint_cached(&mut cache, &map, pose, &bearings, &sonar)
            .unwrap();
        for at in [pose, ahead] {
            let kept = cache.gain_at(&map, &sonar, options, at, &bearings).unwrap();
            assert_eq!(kept.to_bits(), fresh(&map, at).to_bits(), "at {at:?}");
        }
    }
    assert!(fresh(&map, &poses[0]) > 0.0);
}
