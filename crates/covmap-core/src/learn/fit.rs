//! The search: Nelder-Mead over the chosen parameters, restarted from
//! seeded points, the restarts in parallel.

use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};

use argmin::core::{CostFunction, Error as SearchError, Executor, State};
use argmin::solver::neldermead::NelderMead;

use super::point::Point;
use super::{Fittable, check_truth, log_likelihood};
use crate::coverage_map::CoverageMap;
use crate::error::{CovmapError, Result};
use crate::grid::Grid;
use crate::log::Log;
use crate::scan_map::ScanMap;
use crate::sensor::SensorModel;

/// The most evaluations a fit may be asked for (a day's work here at 70 ms
/// each is about a million; a fit of a dozen parameters converges in hundreds).
pub const MAX_EVALUATIONS: usize = 100_000;

/// The most restarts a fit runs (each from its own seeded start).
pub const MAX_RESTARTS: usize = 256;

/// What a fit scores models on: a recorded drive, the grid its maps are
/// built on, and the ground-truth coverage of that grid's cells (row-major),
/// scored over every cell or those where `cells` is true.
#[derive(Clone, Copy, Debug)]
pub struct FitData<'a> {
    /// The drive the maps are built from.
    pub log: &'a Log,
    /// The grid of the maps (and of `truth`).
    pub grid: Grid,
    /// The exact coverage of every cell, in `[0, 1]`.
    pub truth: &'a [f64],
    /// The cells scored (all if `None`).
    pub cells: Option<&'a [bool]>,
}

/// How a fit searches.
#[derive(Clone, Debug, PartialEq)]
pub struct FitOptions {
    /// The parameters fitted, by name ([`Fittable::parameters`]); `None`:
    /// all the model has.
    pub parameters: Option<Vec<String>>,
    /// Search bounds replacing the defaults of the named parameters.
    pub bounds: Vec<(String, [f64; 2])>,
    /// At most this many maps are built and scored, the starting model's
    /// included (default 300).
    pub max_evaluations: usize,
    /// Independent searches (default 2): the first from the starting model,
    /// the others from points drawn around it from `seed`. They run in
    /// parallel and share the evaluations.
    pub restarts: usize,
    /// Seed of the restarts' starting points.
    pub seed: u64,
    /// Bins of the maps built (default 16).
    pub bins: usize,
    /// A search stops when its simplex's scores spread by less than this
    /// (standard deviation, nats; default 0.5).
    pub tolerance: f64,
    /// Whether the maps are built with no-echo readings occluded by the map
    /// ([`CoverageMap::occluding`]) rather than clearing
    /// their whole footprint ([`CoverageMap::integrate_log`]; the default).
    pub occlude_no_echo: bool,
}

impl Default for FitOptions {
    fn default() -> Self {
        Self {
            parameters: None,
            bounds: Vec::new(),
            max_evaluations: 300,
            restarts: 2,
            seed: 0,
            bins: 16,
            tolerance: 0.5,
            occlude_no_echo: false,
        }
    }
}

/// One evaluated model: its fitted parameters (in the order of
/// [`SensorFit::parameters`]) and the log-likelihood of the truth under the
/// map it built.
#[derive(Clone, Debug, PartialEq)]
pub struct FitEvaluation {
    /// The fitted parameters' values.
    pub values: Vec<f64>,
    /// The score.
    pub log_likelihood: f64,
}

/// The result of [`fit_sensor_model`].
#[derive(Clone, Debug, PartialEq)]
pub struct SensorFit<M> {
    /// The best model found (the starting model if nothing scored higher).
    pub model: M,
    /// The names of the fitted parameters.
    pub parameters: Vec<&'static str>,
    /// The bounds they were searched within.
    pub bounds: Vec<[f64; 2]>,
    /// The best model's score.
    pub log_likelihood: f64,
    /// The starting model's score.
    pub initial_log_likelihood: f64,
    /// How many maps were built and scored.
    pub evaluations: usize,
    /// Every evaluation: the starting model's first, then each restart's in
    /// the order it made them.
    pub trace: Vec<FitEvaluation>,
}

/// Fit `start`'s parameters to `data` by maximum likelihood: the model
/// whose map of `data.log` gives the truth the highest [`log_likelihood`].
///
/// Each search is Nelder-Mead over the parameters scaled to `[0, 1]`
/// between their bounds (a point outside them, or a model that does not
/// validate, scores minus infinity and builds no map); the first starts
/// from `start`, every other from a point drawn around it. `progress` is
/// called with the number of evaluations so far after each (from the
/// threads the searches run on). The result depends on the inputs alone,
/// not on the thread count: every search is sequential and their results
/// are combined in order. The fit never returns a model scoring lower than
/// `start`.
///
/// # Errors
/// Before any evaluation: [`CovmapError::InvalidSetting`] for an empty log,
/// an unknown or repeated parameter name, bounds of a parameter not fitted,
/// bounds that are not finite and increasing, bounds excluding the starting
/// value, no evaluations, more than [`MAX_EVALUATIONS`], or no restarts; [`CovmapError::LengthMismatch`]
/// and [`CovmapError::InvalidParameter`] for a truth or mask of the wrong
/// size or a truth value outside `[0, 1]`; the model's and the bin count's
/// own errors. Then the errors of building the starting model's map (a scan
/// outside the grid, say).
pub fn fit_sensor_model<M: Fittable>(
    data: &FitData<'_>,
    start: &M,
    options: &FitOptions,
    progress: &(dyn Fn(usize) + Sync),
) -> Result<SensorFit<M>> {
    let search = Search::new(data, start, options)?;
    let initial = search.score(start)?;
    let done = AtomicUsize::new(1);
    progress(1);
    let u0 = search.point_of(start);
    let rest = options.max_evaluations - 1;
    let restarts: Vec<usize> = (0..options.restarts).collect();
    let results = crate::parallel::map(restarts, |k| {
        let budget = rest / options.restarts + usize::from(k < rest % options.restarts);
        let from = if k == 0 {
            u0.clone()
        } else {
            search.drawn_around(&u0, options.seed, k)
        };
        search.run(from, (&u0, initial), budget, &done, progress)
    });
    let mut trace = vec![FitEvaluation {
        values: search
            .names
            .iter()
            .map(|n| start.get(n).unwrap_or(f64::NAN))
            .collect(),
        log_likelihood: initial,
    }];
    for result in results {
        trace.extend(result?);
    }
    // The best, the earliest of equals (the starting model first).
    let best = trace.iter().enumerate().fold(0, |best, (i, e)| {
        if e.log_likelihood > trace[best].log_likelihood {
            i
        } else {
            best
        }
    });
    let mut model = start.clone();
    for (name, &value) in search.names.iter().zip(&trace[best].values) {
        model.set(name, value);
    }
    Ok(SensorFit {
        model,
        parameters: search.names.clone(),
        bounds: search.bounds.clone(),
        log_likelihood: trace[best].log_likelihood,
        initial_log_likelihood: initial,
        evaluations: trace.len(),
        trace,
    })
}

/// The coverage map of `data.log` on `data.grid` with `bins` bins, built
/// with `model` as a fit builds it: every scan, no-echo readings occluded
/// by the map of the log's echoes if `occlude_no_echo`
/// ([`CoverageMap::occluding`], [`crate::integrate_log_occluded`]).
///
/// # Errors
/// As [`CoverageMap::with_bins`] and [`CoverageMap::integrate_log`].
pub fn map_of_log<M: SensorModel + ?Sized>(
    data: &FitData<'_>,
    bins: usize,
    model: &M,
    occlude_no_echo: bool,
) -> Result<CoverageMap> {
    let mut map = CoverageMap::with_bins(data.grid, bins)?;
    if occlude_no_echo {
        map.occluding().integrate_log(data.log, model)?;
    } else {
        map.integrate_log(data.log, model)?;
    }
    Ok(map)
}

/// `u` in `[0, 1]` to a value within `bounds`.
fn unscale(u: f64, [lo, hi]: [f64; 2]) -> f64 {
    lo + u * (hi - lo)
}

/// A fit's validated setting.
struct Search<'a, M> {
    data: &'a FitData<'a>,
    start: &'a M,
    names: Vec<&'static str>,
    bounds: Vec<[f64; 2]>,
    bins: usize,
    tolerance: f64,
    occlude_no_echo: bool,
}

impl<'a, M: Fittable> Search<'a, M> {
    /// Check everything a fit takes before any map is built.
    fn new(data: &'a FitData<'a>, start: &'a M, options: &FitOptions) -> Result<Self> {
        let setting =
            |name: &'static str, reason: String| CovmapError::InvalidSetting { name, reason };
        start.validate()?;
        crate::histogram::check_bins(options.bins)?;
        check_truth(&data.grid, data.truth, data.cells)?;
        if data.log.is_empty() {
            return Err(setting("log", "the log holds no scans".into()));
        }
        if !(1..=MAX_EVALUATIONS).contains(&options.max_evaluations) {
            return Err(setting(
                "max_evaluations",
                format!(
                    "{}: expected 1 to {MAX_EVALUATIONS}",
                    options.max_evaluations
                ),
            ));
        }
        if !(1..=MAX_RESTARTS).contains(&options.restarts) {
            return Err(setting(
                "restarts",
                format!("{}: expected 1 to {MAX_RESTARTS}", options.restarts),
            ));
        }
        if !(options.tolerance >= 0.0 && options.tolerance.is_finite()) {
            return Err(setting(
                "tolerance",
                format!(
                    "{}: expected a finite, non-negative spread",
                    options.tolerance
                ),
            ));
        }
        let known = start.parameters();
        let known_names = || known.iter().map(|p| p.name).collect::<Vec<_>>().join(", ");
        let names: Vec<&'static str> = match &options.parameters {
            None => known.iter().map(|p| p.name).collect(),
            Some(wanted) => {
                let mut names = Vec::with_capacity(wanted.len());
                for w in wanted {
                    let Some(p) = known.iter().find(|p| p.name == w.as_str()) else {
                        return Err(setting(
                            "parameters",
                            format!(
                                "unknown parameter {}: expected one of {}",
                                crate::quoted(w),
                                known_names()
                            ),
                        ));
                    };
                    if names.contains(&p.name) {
                        return Err(setting(
                            "parameters",
                            format!("{} is named twice", crate::quoted(w)),
                        ));
                    }
                    names.push(p.name);
                }
                if names.is_empty() {
                    return Err(setting("parameters", "no parameter to fit".into()));
                }
                names
            }
        };
        let mut bounds: Vec<[f64; 2]> = names
            .iter()
            .map(|n| {
                known
                    .iter()
                    .find(|p| p.name == *n)
                    .and_then(|p| p.fit_bounds)
                    .unwrap_or([0.0, 1.0])
            })
            .collect();
        for (name, b) in &options.bounds {
            let Some(i) = names.iter().position(|n| *n == name.as_str()) else {
                return Err(setting(
                    "bounds",
                    format!(
                        "bounds for {}, which is not fitted (fitted: {})",
                        crate::quoted(name),
                        names.join(", ")
                    ),
                ));
            };
            if !(b[0].is_finite() && b[1].is_finite() && b[0] < b[1]) {
                return Err(setting(
                    "bounds",
                    format!(
                        "`{name}`: [{}, {}] is not a finite, increasing interval",
                        b[0], b[1]
                    ),
                ));
            }
            bounds[i] = *b;
        }
        for (name, b) in names.iter().zip(&bounds) {
            let v = start.get(name).unwrap_or(f64::NAN);
            if !(b[0] <= v && v <= b[1]) {
                return Err(setting(
                    "bounds",
                    format!(
                        "`{name}`: [{}, {}] excludes the starting value {v}",
                        b[0], b[1]
                    ),
                ));
            }
        }
        Ok(Self {
            data,
            start,
            names,
            bounds,
            bins: options.bins,
            tolerance: options.tolerance,
            occlude_no_echo: options.occlude_no_echo,
        })
    }

    /// The log-likelihood of the truth under the map `model` builds.
    fn score(&self, model: &M) -> Result<f64> {
        let map = map_of_log(self.data, self.bins, model, self.occlude_no_echo)?;
        log_likelihood(&map, self.data.truth, self.data.cells)
    }

    /// `model`'s fitted parameters scaled to `[0, 1]`.
    fn point_of(&self, model: &M) -> Vec<f64> {
        self.names
            .iter()
            .zip(&self.bounds)
            .map(|(n, [lo, hi])| (model.get(n).unwrap_or(*lo) - lo) / (hi - lo))
            .collect()
    }

    /// The model at `u`, if `u` lies within the bounds and the model
    /// validates.
    fn model_at(&self, u: &[f64]) -> Option<M> {
        if !u.iter().all(|x| (0.0..=1.0).contains(x)) {
            return None;
        }
        let mut model = self.start.clone();
        for ((name, &x), &b) in self.names.iter().zip(u).zip(&self.bounds) {
            model.set(name, unscale(x, b));
        }
        model.validate().is_ok().then_some(model)
    }

    /// A valid point drawn around `u0` for restart `k`: each coordinate
    /// moved by up to 0.25 of its range, from a generator seeded with
    /// `seed` and `k` (`u0` itself if no draw of 100 validates).
    fn drawn_around(&self, u0: &[f64], seed: u64, k: usize) -> Vec<f64> {
        let mut state = seed ^ (k as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15);
        for _ in 0..100 {
            let u: Vec<f64> = u0
                .iter()
                .map(|x| (x + 0.5 * (unit(&mut state) - 0.5)).clamp(0.0, 1.0))
                .collect();
            if self.model_at(&u).is_some() {
                return u;
            }
        }
        u0.to_vec()
    }

    /// One Nelder-Mead search from `from` with at most `budget`
    /// evaluations; `known` is a point already scored (the starting model),
    /// which is not scored again. Returns the search's evaluations.
    fn run(
        &self,
        from: Vec<f64>,
        known: (&[f64], f64),
        budget: usize,
        done: &AtomicUsize,
        progress: &(dyn Fn(usize) + Sync),
    ) -> Result<Vec<FitEvaluation>> {
        let trace = Mutex::new(Vec::new());
        let failure = Mutex::new(None);
        if budget > 0 {
            let problem = Restart {
                search: self,
                known,
                budget,
                done,
                progress,
                trace: &trace,
                failure: &failure,
            };
            let simplex = simplex(&from);
            // What the search found is in the trace, however it ended.
            let _ = NelderMead::new(simplex)
                .with_sd_tolerance(self.tolerance)
                .map(|solver| {
                    Executor::new(problem, solver)
                        .configure(|state| state.max_iters(4 * budget as u64 + 16))
                        .run()
                        .map(|r| r.state().get_iter())
                });
        }
        if let Some(e) = failure.into_inner().unwrap_or_else(|e| e.into_inner()) {
            return Err(e);
        }
        Ok(trace.into_inner().unwrap_or_else(|e| e.into_inner()))
    }
}

/// The starting simplex around `u`: `u` and, for each parameter, `u` moved
/// by 0.2 of its range (back toward the middle where that would leave it).
fn simplex(u: &[f64]) -> Vec<Point> {
    let mut simplex = vec![Point(u.to_vec())];
    for i in 0..u.len() {
        let mut v = u.to_vec();
        v[i] += if v[i] + 0.2 <= 1.0 { 0.2 } else { -0.2 };
        simplex.push(Point(v));
    }
    simplex
}

/// A uniform draw in `[0, 1)` from a SplitMix64 state.
fn unit(state: &mut u64) -> f64 {
    *state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    (z ^ (z >> 31)) as f64 / 2f64.powi(64)
}

/// One search's cost function: minus the score, counted and traced.
struct Restart<'a, M> {
    search: &'a Search<'a, M>,
    known: (&'a [f64], f64),
    budget: usize,
    done: &'a AtomicUsize,
    progress: &'a (dyn Fn(usize) + Sync),
    trace: &'a Mutex<Vec<FitEvaluation>>,
    failure: &'a Mutex<Option<CovmapError>>,
}

impl<M: Fittable> CostFunction for Restart<'_, M> {
    type Param = Point;
    type Output = f64;

    fn cost(&self, u: &Point) -> std::result::Result<f64, SearchError> {
        if u.0 == self.known.0 {
            return Ok(-self.known.1);
        }
        let Some(model) = self.search.model_at(&u.0) else {
            return Ok(f64::INFINITY);
        };
        let mut trace = self.trace.lock().unwrap_or_else(|e| e.into_inner());
        // argmin's Nelder-Mead unwraps some of its cost calls, so this one
        // never fails: a spent budget or a failure scores minus infinity
        // (builds no map) and the search runs out its iterations at once.
        let mut failure = self.failure.lock().unwrap_or_else(|e| e.into_inner());
        if trace.len() >= self.budget || failure.is_some() {
            return Ok(f64::INFINITY);
        }
        let score = match self.search.score(&model) {
            Ok(score) => score,
            Err(e) => {
                *failure = Some(e);
                return Ok(f64::INFINITY);
            }
        };
        drop(failure);
        let values =
            u.0.iter()
                .zip(&self.search.bounds)
                .map(|(x, b)| unscale(*x, *b))
                .collect();
        trace.push(FitEvaluation {
            values,
            log_likelihood: score,
        });
        drop(trace);
        (self.progress)(self.done.fetch_add(1, Ordering::Relaxed) + 1);
        Ok(-score)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::log::Bearings;
    use crate::pose::Pose;
    use crate::sensor::LaserModel;

    /// A wall at x = 2 m seen by a two-beam laser from a few poses.
    fn wall() -> (Log, Grid, Vec<f64>) {
        let grid = Grid::new([0.0, 0.0], 0.1, 20, 30).unwrap();
        let mut truth = vec![0.0; grid.len()];
        for row in 0..20 {
            truth[row * 30 + 20] = 1.0;
        }
        let poses: Vec<Pose> = (0..4)
            .map(|i| Pose::new(0.5, 0.4 + 0.3 * i as f64, 0.0))
            .collect();
        let ranges = (0..4).flat_map(|_| [1.5, 1.5]).collect();
        let times = (0..4).map(f64::from).collect();
        let log = Log::new(poses, times, ranges, Bearings::Fixed(vec![0.0, 0.05]), 30.0).unwrap();
        (log, grid, truth)
    }

    /// However small the budget, the search stops within it (argmin's
    /// solver must never see a failing cost), and the result is the same
    /// at every run.
    #[test]
    fn every_budget_is_kept_and_the_fit_repeats_exactly() {
        let (log, grid, truth) = wall();
        let data = FitData {
            log: &log,
            grid,
            truth: &truth,
            cells: None,
        };
        for budget in 1..12 {
            for restarts in [1, 2, 3] {
                let options = FitOptions {
                    max_evaluations: budget,
                    restarts,
                    ..FitOptions::default()
                };
                let fit =
                    fit_sensor_model(&data, &LaserModel::default(), &options, &|_| {}).unwrap();
                assert!(fit.evaluations <= budget && fit.evaluations == fit.trace.len());
                assert!(fit.log_likelihood >= fit.initial_log_likelihood);
                let again =
                    fit_sensor_model(&data, &LaserModel::default(), &options, &|_| {}).unwrap();
                assert_eq!(fit, again);
            }
        }
    }

    /// A log that leaves the grid fails on the starting model, before any
    /// search.
    #[test]
    fn a_log_off_the_grid_is_an_error_naming_the_scan() {
        let (_, grid, truth) = wall();
        let far = Log::new(
            vec![Pose::new(9.0, 1.0, 0.0)],
            vec![0.0],
            vec![1.0],
            Bearings::Fixed(vec![0.0]),
            30.0,
        )
        .unwrap();
        let data = FitData {
            log: &far,
            grid,
            truth: &truth,
            cells: None,
        };
        let calls = AtomicUsize::new(0);
        let err = fit_sensor_model(
            &data,
            &LaserModel::default(),
            &FitOptions::default(),
            &|_| {
                calls.fetch_add(1, Ordering::Relaxed);
            },
        )
        .unwrap_err();
        assert!(matches!(err, CovmapError::InScan { scan: 0, .. }), "{err}");
        assert_eq!(calls.load(Ordering::Relaxed), 0);
    }
}
