//! The evaluator of the expected gain: what every candidate needs, built once
//! per map state, and the evaluation of candidates.

use std::borrow::Cow;
use std::f64::consts::TAU;
use std::sync::OnceLock;

use super::fast::{Arith, CellTerms, Queue};
use super::map_terms::MapTerms;
use super::reads::{Marks, TileSet, Tiles};
use super::schedule::in_groups;
use super::{GainMethod, GainOptions};
use crate::coverage_map::CoverageMap;
use crate::error::Result;
use crate::footprint::visit;
use crate::grid::Grid;
use crate::parallel;
use crate::pose::{Pose, check_bearings, check_pose};
use crate::sensor::{
    Footprint, KernelTable, RangeModel, ReadingDistribution, SensorModel, StopCoverage,
    check_range_step, trace_readings_with,
};

/// Evaluates the expected information gain of candidate viewpoints on one map
/// with one sensor model. Build it once per map state; it caches what every
/// candidate needs.
///
/// # Example
/// ```
/// use covmap_core::gain::{GainEvaluator, GainMethod, GainOptions};
/// use covmap_core::{CoverageMap, Grid, Pose, SonarModel};
/// let map = CoverageMap::new(Grid::new([0.0, 0.0], 0.1, 60, 60).unwrap());
/// let sonar = SonarModel::default();
/// let eval = GainEvaluator::new(&map, &sonar, GainOptions::default()).unwrap();
/// let bearings = [0.0, std::f64::consts::FRAC_PI_2];
/// let poses = [Pose::new(3.0, 3.0, 0.0), Pose::new(0.5, 0.5, 3.14)];
/// let fast = eval.evaluate(&poses, &bearings, GainMethod::Fast).unwrap();
/// let exact = eval.evaluate(&poses, &bearings, GainMethod::Exact).unwrap();
/// assert!(fast[0] > 0.0); // nothing is known yet: every reading teaches something
/// assert!(fast[1] < fast[0]); // facing out of the map from a corner sees less
/// assert!((fast[0] - exact[0]).abs() <= 1e-6 * exact[0]);
/// ```
pub struct GainEvaluator<'a> {
    pub(super) map: &'a CoverageMap,
    pub(super) table: Cow<'a, KernelTable>,
    pub(super) range: RangeModel,
    pub(super) footprint: Footprint,
    /// The coverage of every cell that stops a predicted beam.
    pub(super) stop: Cow<'a, [f32]>,
    pub(super) step_m: f64,
    /// What the fast evaluator knows of every cell.
    pub(super) cell_terms: Terms<'a>,
    /// The widest arithmetic the processor offers (detected at run time).
    pub(super) arith: Arith,
}

impl<'a> GainEvaluator<'a> {
    /// An evaluator for `map` and `model`.
    ///
    /// # Errors
    /// [`CovmapError::InvalidParameter`](crate::CovmapError::InvalidParameter)
    /// if the model is invalid, or `options.range_step_m` is not between
    /// [`MIN_STEP_FRACTION`](super::MIN_STEP_FRACTION) of the grid resolution
    /// and the resolution.
    pub fn new<M: SensorModel + ?Sized>(
        map: &'a CoverageMap,
        model: &M,
        options: GainOptions,
    ) -> Result<Self> {
        let step_m = Self::check(map, model, options)?;
        let range = *model.range_model();
        let table = map.kernel_table(&range)?;
        Ok(Self {
            map,
            table,
            range,
            footprint: model.footprint(),
            stop: Cow::Owned(stop_coverage(map, options.stop_coverage)),
            step_m,
            cell_terms: Terms::Lazy(OnceLock::new()),
            arith: Arith::detect(),
        })
    }

    /// Errors as [`Self::new`] does, in the same order, for `model` and
    /// `options` on `map`; else the spacing of the predicted readings.
    pub(crate) fn check<M: SensorModel + ?Sized>(
        map: &CoverageMap,
        model: &M,
        options: GainOptions,
    ) -> Result<f64> {
        model.validate()?;
        let resolution = map.grid().resolution_m();
        let step_m = options.range_step_m.unwrap_or(resolution);
        check_range_step(step_m, Some(resolution))?;
        Ok(step_m)
    }

    /// An evaluator for `map` and `model` that reads the per-map work from
    /// `terms` (brought up to date with `map` by [`MapTerms::update`]) and
    /// multiplies the kernels of `table`, instead of computing them: what
    /// [`Self::new`] would compute, so that every gain is the same, bit for
    /// bit.
    ///
    /// # Errors
    /// As [`Self::new`].
    ///
    /// # Panics
    /// If `terms` were not made for a map of `map`'s size with `options`'
    /// stop coverage, or `table` does not serve `model` on `map`.
    pub(crate) fn with_terms<M: SensorModel + ?Sized>(
        map: &'a CoverageMap,
        model: &M,
        options: GainOptions,
        table: &'a KernelTable,
        terms: &'a MapTerms,
    ) -> Result<Self> {
        let step_m = Self::check(map, model, options)?;
        let range = *model.range_model();
        assert!(
            table.serves(&range, map.grid().resolution_m(), map.bins()),
            "the kernel table is not the model's"
        );
        assert!(
            terms.fits(map, options.stop_coverage),
            "the terms are not this map's"
        );
        Ok(Self {
            map,
            table: Cow::Borrowed(table),
            range,
            footprint: model.footprint(),
            stop: Cow::Borrowed(&terms.stop),
            step_m,
            cell_terms: Terms::Given(&terms.cells),
            arith: Arith::detect(),
        })
    }

    /// The map evaluated.
    pub fn map(&self) -> &CoverageMap {
        self.map
    }

    /// The expected information gain (nats) of scanning from each pose with
    /// beams at `bearings` (relative to each pose's heading).
    ///
    /// # Errors
    /// [`CovmapError::InvalidPose`](crate::CovmapError::InvalidPose) if a pose
    /// is not finite,
    /// [`CovmapError::PoseOutsideMap`](crate::CovmapError::PoseOutsideMap) if
    /// one lies in no cell of the map,
    /// [`CovmapError::InvalidBearing`](crate::CovmapError::InvalidBearing) if
    /// a bearing, or its sum with a pose's heading, is not finite.
    pub fn evaluate(
        &self,
        poses: &[Pose],
        bearings: &[f64],
        method: GainMethod,
    ) -> Result<Vec<f64>> {
        self.validate(poses, bearings)?;
        let evaluator = match method {
            GainMethod::Exact => Evaluator::Exact,
            GainMethod::Fast => Evaluator::Fast(self.cell_terms()),
        };
        let beam = |pose: &Pose, bearing: f64, queue: &mut Queue| -> f64 {
            let origin = [pose.x_m, pose.y_m];
            let angle = pose.theta_rad + bearing;
            match evaluator {
                Evaluator::Exact => self.exact_beam(origin, angle),
                Evaluator::Fast(terms) => self.fast_beam(terms, origin, angle, queue, None),
            }
        };
        Ok(in_groups(self.map.grid(), poses, bearings, beam))
    }

    /// The fast evaluator's expected gain (nats) of each beam of `beams`, a
    /// pose and a bearing relative to its heading, with the tiles (of
    /// `tiles`, this map's) of every cell it read (see
    /// [`crate::gain::reads`]): the terms [`Self::evaluate`] sums into a
    /// candidate's gain ([`beam_sum`](super::schedule::beam_sum) sums them
    /// as it does), and what the planning cache needs to know when one has
    /// changed. A beam's gain and tiles depend on its pose and bearing
    /// alone, whatever beams it is evaluated with. In parallel with the
    /// feature `parallel`.
    ///
    /// # Errors
    /// As [`Self::evaluate`], for each beam's pose and bearing.
    pub(crate) fn beam_gains_and_reads(
        &self,
        beams: &[(Pose, f64)],
        tiles: &Tiles,
    ) -> Result<Vec<(f64, TileSet)>> {
        for (pose, bearing) in beams {
            self.validate(std::slice::from_ref(pose), std::slice::from_ref(bearing))?;
        }
        let terms = self.cell_terms();
        // Beams evaluated together, in the order of their directions, so
        // that consecutive ones find much of their data in the cache.
        const TOGETHER: usize = 64;
        let chunk = |beams: &[(Pose, f64)]| -> Vec<(f64, TileSet)> {
            let mut order: Vec<(f64, usize)> = beams
                .iter()
                .enumerate()
                .map(|(k, (pose, bearing))| ((pose.theta_rad + bearing).rem_euclid(TAU), k))
                .collect();
            order.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
            let mut queue = Queue::default();
            let mut marks = Marks::new(tiles);
            let mut out = vec![(0.0, TileSet::default()); beams.len()];
            for (_, k) in order {
                let (pose, bearing) = beams[k];
                let angle = pose.theta_rad + bearing;
                let origin = [pose.x_m, pose.y_m];
                let gain = self.fast_beam(terms, origin, angle, &mut queue, Some(&mut marks));
                out[k] = (gain, marks.take());
            }
            out
        };
        Ok(parallel::map(beams.chunks(TOGETHER).collect(), chunk).concat())
    }

    /// How many (beam, cell) pairs the fast evaluator visits for these
    /// candidates: the cells of each beam's widest footprint. The unit of the
    /// benchmarks' cost per pair.
    pub fn pairs(&self, poses: &[Pose], bearings: &[f64]) -> Result<u64> {
        self.validate(poses, bearings)?;
        let reach = self.widest_reach();
        let mut pairs = 0u64;
        for pose in poses {
            for &bearing in bearings {
                visit(
                    self.map.grid(),
                    [pose.x_m, pose.y_m],
                    pose.theta_rad + bearing,
                    reach,
                    self.footprint,
                    &mut |_, _| pairs += 1,
                );
            }
        }
        Ok(pairs)
    }

    /// Errors unless every pose is finite and inside the map, and every
    /// bearing gives a finite direction from each.
    fn validate(&self, poses: &[Pose], bearings: &[f64]) -> Result<()> {
        validate_candidates(self.map.grid(), poses, bearings)
    }

    /// What the fast evaluator knows of every cell: given, or computed on
    /// first use.
    pub(super) fn cell_terms(&self) -> &CellTerms {
        match &self.cell_terms {
            Terms::Lazy(terms) => terms.get_or_init(|| CellTerms::new(self.map, &self.table)),
            Terms::Given(terms) => terms,
        }
    }

    /// The predicted readings of the beam from `origin` along `angle`.
    pub(super) fn distribution(&self, origin: [f64; 2], angle: f64) -> ReadingDistribution {
        self.distribution_with(origin, angle, |_| {})
    }

    /// [`Self::distribution`], calling `read` with every cell whose stop
    /// coverage it depends on (see `trace_readings_with`).
    pub(super) fn distribution_with(
        &self,
        origin: [f64; 2],
        angle: f64,
        read: impl FnMut(usize),
    ) -> ReadingDistribution {
        trace_readings_with(
            self.map.grid(),
            &self.stop,
            origin,
            angle,
            &self.range,
            self.step_m,
            read,
        )
    }

    /// The widest reach of any hypothetical reading.
    pub(super) fn widest_reach(&self) -> f64 {
        let last = (self.range.max_range_m / self.step_m).ceil() * self.step_m;
        self.range
            .reach(self.range.max_range_m)
            .0
            .max(last + self.range.band_m)
    }
}

/// Errors as [`GainEvaluator::evaluate`] does, in the same order, for
/// `poses` on `grid` and `bearings`: unless every pose is finite and inside
/// the grid, and every bearing gives a finite direction from each.
pub(crate) fn validate_candidates(grid: &Grid, poses: &[Pose], bearings: &[f64]) -> Result<()> {
    if poses.is_empty() {
        // No direction to form: the bearings themselves.
        return check_bearings(0.0, bearings);
    }
    for pose in poses {
        check_pose(grid, pose)?;
        check_bearings(pose.theta_rad, bearings)?;
    }
    Ok(())
}

/// The coverage of every cell of `map` that stops a predicted beam.
pub(super) fn stop_coverage(map: &CoverageMap, stop: StopCoverage) -> Vec<f32> {
    match stop {
        StopCoverage::MaximumLikelihood => map.ml(),
        StopCoverage::Mean => map.mean(),
    }
}

/// Where an evaluator's [`CellTerms`] come from.
pub(super) enum Terms<'a> {
    /// Computed from the map on first use ([`GainEvaluator::new`]).
    Lazy(OnceLock<CellTerms>),
    /// Kept up to date by the caller ([`GainEvaluator::with_terms`]).
    Given(&'a CellTerms),
}

/// The evaluator a beam's gain is computed by, with what it needs.
#[derive(Clone, Copy)]
enum Evaluator<'c> {
    /// [`GainMethod::Exact`].
    Exact,
    /// [`GainMethod::Fast`], with the terms of every cell.
    Fast(&'c CellTerms),
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::CovmapError;
    use crate::gain::reading_distribution;
    use crate::gain::test_maps::scanned;
    use crate::grid::Grid;
    use crate::sensor::{LaserModel, SonarModel};

    #[test]
    fn rejects_bad_input() {
        let map = CoverageMap::new(Grid::new([0.0, 0.0], 0.1, 10, 10).unwrap());
        let sonar = SonarModel::default();
        let eval = GainEvaluator::new(&map, &sonar, GainOptions::default()).unwrap();
        assert!(
            eval.evaluate(&[Pose::new(-1.0, 0.5, 0.0)], &[0.0], GainMethod::Fast)
                .is_err()
        );
        assert!(
            eval.evaluate(&[Pose::new(0.5, 0.5, f64::NAN)], &[0.0], GainMethod::Fast)
                .is_err()
        );
        assert!(
            eval.evaluate(
                &[Pose::new(0.5, 0.5, 0.0)],
                &[f64::INFINITY],
                GainMethod::Exact
            )
            .is_err()
        );
        // The direction overflows although heading and bearing are finite.
        let err = eval
            .evaluate(&[Pose::new(0.5, 0.5, 1e308)], &[1e308], GainMethod::Fast)
            .unwrap_err();
        assert!(
            matches!(err, CovmapError::InvalidBearing { index: 0, .. }),
            "{err}"
        );
        for step in [0.2, 0.0, 5e-324, 0.05 / 1024.0, f64::NAN] {
            let bad = GainOptions {
                range_step_m: Some(step),
                ..GainOptions::default()
            };
            assert!(GainEvaluator::new(&map, &sonar, bad).is_err(), "{step}");
        }
        let finest = GainOptions {
            range_step_m: Some(0.1 / 1024.0),
            ..GainOptions::default()
        };
        assert!(GainEvaluator::new(&map, &sonar, finest).is_ok());
        // The public trace validates what the evaluator validates once.
        let (grid, range, stop) = (map.grid(), sonar.range, map.ml());
        assert!(reading_distribution(grid, &stop[1..], [0.5, 0.5], 0.0, &range, 0.1).is_err());
        assert!(reading_distribution(grid, &stop, [1.5, 0.5], 0.0, &range, 0.1).is_err());
        assert!(reading_distribution(grid, &stop, [0.5, 0.5], f64::NAN, &range, 0.1).is_err());
        assert!(reading_distribution(grid, &stop, [0.5, 0.5], 0.0, &range, 0.0).is_err());
    }

    /// A maximum range far beyond the map gives readings only as far as the
    /// map reaches: no slot is allocated past it, and the gains are those of
    /// the same sensor on the map.
    #[test]
    fn a_range_far_beyond_the_map_is_traced_to_the_map_edge() {
        let grid = Grid::new([0.0, 0.0], 0.1, 30, 40).unwrap();
        let mut laser = LaserModel::default();
        laser.range.max_range_m = 1e4;
        laser.range.sigma_per_m = 0.0;
        laser.range.xi_per_m = 0.0;
        let bearings: Vec<f64> = (0..8).map(|k| f64::from(k) * 0.8).collect();
        let scan: (Pose, &[f64]) = (
            Pose::new(2.0, 1.5, 0.1),
            &[1.0, 0.7, 3.0, 0.4, 2.0, 0.9, 1e13, 1.2],
        );
        let map = scanned(grid, &[scan], &bearings, &laser);
        let d = reading_distribution(map.grid(), &map.ml(), [2.0, 1.5], 0.3, &laser.range, 0.1)
            .unwrap();
        assert!(
            d.probabilities.len() <= 60,
            "{} slots",
            d.probabilities.len()
        );
        let total: f64 = d.probabilities.iter().sum::<f64>() + d.no_echo;
        assert!((total - 1.0).abs() < 1e-12);
        let eval = GainEvaluator::new(&map, &laser, GainOptions::default()).unwrap();
        let poses = [Pose::new(1.0, 1.0, 0.0), Pose::new(3.5, 2.5, 2.0)];
        let fast = eval.evaluate(&poses, &bearings, GainMethod::Fast).unwrap();
        let exact = eval.evaluate(&poses, &bearings, GainMethod::Exact).unwrap();
        for (f, e) in fast.iter().zip(&exact) {
            assert!(*e > 0.0 && (f - e).abs() <= 1e-6 * e, "{f} {e}");
        }
    }
}
