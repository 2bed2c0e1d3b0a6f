//! Expected information gain of a viewpoint (MODEL.md section 4, paper eq. 11-13).
//!
//! For a candidate pose `l` and a sensor (bearings and an inverse model),
//!
//! ```text
//! E[I(l)] = sum over beams  sum_d p(d | c) * sum_{c_i in C(l, d)} I(h(c_i) | d)
//! ```
//!
//! with `I(h | d) = H(h) - H(h'_d)` the entropy a cell loses when reading `d` is
//! integrated, and `C(l, d)` exactly the cells [`CoverageMap::integrate`] would
//! update for that reading, with exactly the kernels it would multiply in.
//!
//! # The model of `p(d | c)`
//! Beams are independent (as the map's cells are): each beam's readings are
//! predicted on their own and the gains add up. A beam's reading is predicted by
//! tracing its axis through the map cell by cell ([`StopCoverage`] picks the
//! coverage value of each cell: the ML map by default, as in the paper). A cell
//! of coverage `c` stops the beam with probability `c`; if it does, the beam is
//! taken to end where an obstacle filling the far `c` of the cell would stop it,
//! `d = d_l + r/2 - c r` (so that the reading reproduces the cell's coverage
//! under the sensor model). Readings are discretised on a grid of
//! `range_step_m` (the grid resolution by default); readings at or beyond the
//! maximum range, and beams that reach it or leave the map unstopped, are "no
//! echo". A cone sensor is traced along its axis. No extra noise blur is added:
//! the sensor's uncertainty enters through the kernels.
//!
//! # Two evaluators
//! [`GainMethod::Exact`] is the equation as written: for every discretised
//! reading, the gain of every cell it would update, each entropy from its
//! definition. It is the reference. [`GainMethod::Fast`] gives the same sums
//! (to rounding) much faster, from three facts:
//! - a cell in front of the end point gets a kernel that depends on the cell's
//!   distance, not on the reading (see [`crate::sensor`]), so the readings that
//!   leave it in free space contribute `I_free * (sum of their p(d))`: a suffix
//!   sum of `p(d)`; only the few readings that end near the cell need a kernel
//!   of their own;
//! - readings of probability 0 contribute nothing and are skipped;
//! - with `ln h` of every bin computed once per evaluator, the entropy of an
//!   updated histogram costs one logarithm: `H(h k / Z) = ln Z - sum h k (ln h +
//!   ln k) / Z`.
//!
//! Candidates are evaluated in parallel (feature `parallel`); every candidate's
//! sum is computed in a fixed order, so results do not depend on scheduling.

use std::borrow::Cow;

use serde::{Deserialize, Serialize};

use crate::coverage_map::CoverageMap;
use crate::error::{CovmapError, Result};
use crate::footprint::{CellVisitor, visit};
use crate::grid::Grid;
use crate::scan::Pose;
use crate::sensor::{Footprint, KernelTable, RangeModel, ReadingLookup, SensorModel};

/// Which evaluator computes the expected gain.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum GainMethod {
    /// The equation as written: the reference.
    Exact,
    /// The production evaluator: equal to `Exact` up to rounding.
    #[default]
    Fast,
}

/// Which coverage value of a cell stops a predicted beam.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum StopCoverage {
    /// The most probable coverage (the paper's choice). A cell still at the
    /// uniform prior reads 0: unknown space is predicted to let beams through,
    /// which makes looking into it worth a lot.
    #[default]
    MaximumLikelihood,
    /// The expected coverage: unknown space (0.5) stops beams quickly.
    Mean,
}

/// Settings of the expected-gain computation.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GainOptions {
    /// Spacing of the hypothetical readings, metres; `None`: the grid
    /// resolution. At most the grid resolution.
    pub range_step_m: Option<f64>,
    /// Which coverage value of a cell stops a predicted beam.
    pub stop_coverage: StopCoverage,
}

/// Entropy of a histogram in nats, in `f64`.
pub fn entropy(h: &[f32]) -> f64 {
    -h.iter().map(|&p| f64::from(p)).filter(|&p| p > 0.0).map(|p| p * p.ln()).sum::<f64>()
}

/// `I(h | k) = H(h) - H(h')`, `h'` the normalised product of `h` and kernel
/// `k`, straight from the definitions (eq. 11-12).
pub fn information_gain(h: &[f32], k: &[f32]) -> f64 {
    let z: f64 = h.iter().zip(k).map(|(&a, &b)| f64::from(a) * f64::from(b)).sum();
    let posterior_entropy = -h
        .iter()
        .zip(k)
        .map(|(&a, &b)| f64::from(a) * f64::from(b) / z)
        .filter(|&p| p > 0.0)
        .map(|p| p * p.ln())
        .sum::<f64>();
    entropy(h) - posterior_entropy
}

/// The predicted readings of one beam: `probabilities[j]` is the probability of
/// reading `j * step_m` (all below the maximum range), `no_echo` that of no echo.
#[derive(Clone, Debug, PartialEq)]
pub struct ReadingDistribution {
    /// Spacing of the readings, metres.
    pub step_m: f64,
    /// Probability of each reading.
    pub probabilities: Vec<f64>,
    /// Probability of no echo.
    pub no_echo: f64,
}

/// Predict the readings of a beam from `origin` along `angle_rad` by tracing
/// its axis through `stop` (one coverage value per cell); see the
/// [module documentation](self).
pub fn reading_distribution(
    grid: &Grid,
    stop: &[f32],
    origin: [f64; 2],
    angle_rad: f64,
    range: &RangeModel,
    step_m: f64,
) -> ReadingDistribution {
    let slots = (range.max_range_m / step_m).ceil() as usize;
    let slots = (0..=slots).rev().find(|&j| (j as f64) * step_m < range.max_range_m).map_or(0, |j| j + 1);
    let mut probabilities = vec![0.0; slots];
    let mut through = 1.0f64;
    let r = grid.resolution_m();
    let mut trace = |i: usize, d_l: f64| {
        let c = f64::from(stop[i]);
        if c <= 0.0 || through <= 0.0 {
            return;
        }
        let d = (d_l + 0.5 * r - c * r).max(0.0);
        let j = (d / step_m).round() as usize;
        if j < slots {
            probabilities[j] += through * c;
            through *= 1.0 - c;
        }
    };
    visit(grid, origin, angle_rad, range.max_range_m, Footprint::Ray, &mut trace);
    ReadingDistribution { step_m, probabilities, no_echo: through }
}

/// `ln` of every bin of every histogram, and each histogram's entropy computed
/// from those same logarithms (so that rounding cancels in differences).
struct LogCache {
    log_h: Vec<f64>,
    entropy: Vec<f64>,
}

impl LogCache {
    fn new(map: &CoverageMap) -> Self {
        let bins = map.bins();
        let data = map.histograms();
        // In f64: the update's logarithms must be exact enough that the entropy
        // differences of nearly unchanged cells keep their digits.
        let log_h: Vec<f64> = par_map_chunks(data, 4096, |chunk| chunk.iter().map(|&v| f64::from(v).ln()).collect());
        let entropy = par_map_chunks(data, 4096 * bins, |chunk| chunk.chunks_exact(bins).map(entropy).collect());
        Self { log_h, entropy }
    }
}

/// Map `f` over `chunk`-sized pieces of `data` (in parallel with the
/// `parallel` feature) and concatenate the results in order.
fn par_map_chunks<T: Sync, U: Send>(data: &[T], chunk: usize, f: impl Fn(&[T]) -> Vec<U> + Sync + Send) -> Vec<U> {
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        data.par_chunks(chunk).flat_map_iter(f).collect()
    }
    #[cfg(not(feature = "parallel"))]
    {
        data.chunks(chunk).flat_map(f).collect()
    }
}

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
    map: &'a CoverageMap,
    table: Cow<'a, KernelTable>,
    range: RangeModel,
    footprint: Footprint,
    stop: Vec<f32>,
    step_m: f64,
    cache: std::sync::OnceLock<LogCache>,
}

impl<'a> GainEvaluator<'a> {
    /// An evaluator for `map` and `model`.
    pub fn new<M: SensorModel + ?Sized>(map: &'a CoverageMap, model: &M, options: GainOptions) -> Result<Self> {
        model.validate()?;
        let resolution = map.grid().resolution_m();
        let step_m = options.range_step_m.unwrap_or(resolution);
        if !(step_m > 0.0 && step_m <= resolution) {
            return Err(CovmapError::InvalidParameter {
                name: "range_step_m",
                value: step_m,
                expected: "a positive step no larger than the grid resolution",
            });
        }
        let range = *model.range_model();
        let table = map.kernel_table(&range)?;
        let stop = match options.stop_coverage {
            StopCoverage::MaximumLikelihood => map.ml(),
            StopCoverage::Mean => map.mean(),
        };
        Ok(Self { map, table, range, footprint: model.footprint(), stop, step_m, cache: std::sync::OnceLock::new() })
    }

    /// The map evaluated.
    pub fn map(&self) -> &CoverageMap {
        self.map
    }

    /// The expected information gain (nats) of scanning from each pose with
    /// beams at `bearings` (relative to each pose's heading).
    ///
    /// Errors if a pose is not finite or lies outside the map, or a bearing is
    /// not finite.
    pub fn evaluate(&self, poses: &[Pose], bearings: &[f64], method: GainMethod) -> Result<Vec<f64>> {
        self.validate(poses, bearings)?;
        if method == GainMethod::Fast {
            self.cache.get_or_init(|| LogCache::new(self.map));
        }
        let one = |pose: &Pose| -> f64 {
            bearings
                .iter()
                .map(|&b| {
                    let origin = [pose.x_m, pose.y_m];
                    let angle = pose.theta_rad + b;
                    match method {
                        GainMethod::Exact => self.exact_beam(origin, angle),
                        GainMethod::Fast => self.fast_beam(origin, angle),
                    }
                })
                .sum()
        };
        #[cfg(feature = "parallel")]
        {
            use rayon::prelude::*;
            Ok(poses.par_iter().with_min_len(4).map(one).collect())
        }
        #[cfg(not(feature = "parallel"))]
        {
            Ok(poses.iter().map(one).collect())
        }
    }

    /// How many (beam, cell) pairs the fast evaluator visits for these
    /// candidates: the cells of each beam's widest footprint. The unit of the
    /// benchmarks' cost per pair.
    pub fn pairs(&self, poses: &[Pose], bearings: &[f64]) -> Result<u64> {
        self.validate(poses, bearings)?;
        let reach = self.widest_reach();
        let mut n = 0u64;
        for pose in poses {
            for &b in bearings {
                visit(self.map.grid(), [pose.x_m, pose.y_m], pose.theta_rad + b, reach, self.footprint, &mut |_, _| {
                    n += 1
                });
            }
        }
        Ok(n)
    }

    fn validate(&self, poses: &[Pose], bearings: &[f64]) -> Result<()> {
        for pose in poses {
            if !(pose.x_m.is_finite() && pose.y_m.is_finite() && pose.theta_rad.is_finite()) {
                return Err(CovmapError::InvalidPose { x: pose.x_m, y: pose.y_m, theta: pose.theta_rad });
            }
            self.map.grid().check_inside(pose.x_m, pose.y_m)?;
        }
        if let Some((index, &value)) = bearings.iter().enumerate().find(|(_, b)| !b.is_finite()) {
            return Err(CovmapError::InvalidBearing { index, value });
        }
        Ok(())
    }

    fn distribution(&self, origin: [f64; 2], angle: f64) -> ReadingDistribution {
        reading_distribution(self.map.grid(), &self.stop, origin, angle, &self.range, self.step_m)
    }

    /// The widest reach of any hypothetical reading.
    fn widest_reach(&self) -> f64 {
        let last = (self.range.max_range_m / self.step_m).ceil() * self.step_m;
        self.range.reach(self.range.max_range_m).0.max(last + self.range.band_m)
    }

    /// Sum of the gains of the cells a reading `d` would update.
    fn exact_reading(&self, origin: [f64; 2], angle: f64, d: f64) -> f64 {
        let (reach, echo) = self.range.reach(d);
        let lookup = self.table.reading(d.min(self.range.max_range_m), echo);
        let (data, bins) = (self.map.histograms(), self.map.bins());
        let mut sum = 0.0;
        visit(self.map.grid(), origin, angle, reach, self.footprint, &mut |i, d_l| {
            sum += information_gain(&data[i * bins..(i + 1) * bins], self.table.at(lookup.offset(d_l)));
        });
        sum
    }

    fn exact_beam(&self, origin: [f64; 2], angle: f64) -> f64 {
        let dist = self.distribution(origin, angle);
        let mut total = 0.0;
        for (j, &p) in dist.probabilities.iter().enumerate() {
            total += p * self.exact_reading(origin, angle, j as f64 * dist.step_m);
        }
        total + dist.no_echo * self.exact_reading(origin, angle, self.range.max_range_m)
    }

    fn fast_beam(&self, origin: [f64; 2], angle: f64) -> f64 {
        let Some(cache) = self.cache.get() else { return f64::NAN };
        let dist = self.distribution(origin, angle);
        let n = dist.probabilities.len();
        let mut hypotheses = Vec::with_capacity(n);
        for j in 0..n {
            let d = j as f64 * dist.step_m;
            let (reach, echo) = self.range.reach(d);
            hypotheses.push(Hypothesis { lookup: self.table.reading(d, echo), reach, p: dist.probabilities[j] });
        }
        let mut suffix = vec![0.0; n + 1];
        for j in (0..n).rev() {
            suffix[j] = suffix[j + 1] + dist.probabilities[j];
        }
        let (none_reach, _) = self.range.reach(self.range.max_range_m);
        let possible: Vec<Hypothesis> = hypotheses.iter().filter(|h| h.p > 0.0).copied().collect();
        let beam = Beam {
            map: self.map,
            cache,
            table: &self.table,
            hypotheses: &hypotheses,
            sparse: (possible.len() <= SPARSE_ECHOES).then_some(&possible[..]),
            suffix: &suffix,
            inv_step_m: 1.0 / dist.step_m,
            band_m: self.range.band_m,
            half_cell_m: 0.5 * self.map.grid().resolution_m(),
            no_echo: dist.no_echo,
            none_lookup: self.table.reading(self.range.max_range_m, false),
            none_reach,
        };
        let reach = hypotheses.last().map_or(none_reach, |h| h.reach.max(none_reach));
        // Fix the bin count at compile time for the common sizes, so that the
        // per-cell gain is straight vector code.
        match self.map.bins() {
            8 => self.run::<8>(&beam, origin, angle, reach),
            16 => self.run::<16>(&beam, origin, angle, reach),
            32 => self.run::<32>(&beam, origin, angle, reach),
            _ => self.run::<0>(&beam, origin, angle, reach),
        }
    }

    fn run<const N: usize>(&self, beam: &Beam<'_>, origin: [f64; 2], angle: f64, reach: f64) -> f64 {
        let mut sweep = FastBeam::<N> { beam, total: 0.0, jobs: Vec::with_capacity(BATCH + 64) };
        visit(self.map.grid(), origin, angle, reach, self.footprint, &mut sweep);
        sweep.flush();
        sweep.total
    }
}

/// Up to this many echoes of non-zero probability, a cell tests each of them;
/// beyond, it finds the ones that matter by suffix sums.
const SPARSE_ECHOES: usize = 12;

/// One hypothetical echo of a beam.
#[derive(Clone, Copy)]
struct Hypothesis {
    lookup: ReadingLookup,
    reach: f64,
    p: f64,
}

/// What every cell of one beam's widest footprint needs to know.
struct Beam<'a> {
    map: &'a CoverageMap,
    cache: &'a LogCache,
    table: &'a KernelTable,
    hypotheses: &'a [Hypothesis],
    /// The echoes of non-zero probability, when there are few.
    sparse: Option<&'a [Hypothesis]>,
    /// `suffix[j]`: the probability of the echoes `j..`.
    suffix: &'a [f64],
    inv_step_m: f64,
    band_m: f64,
    half_cell_m: f64,
    no_echo: f64,
    none_lookup: ReadingLookup,
    none_reach: f64,
}

/// The fast evaluator's work for one beam, with `N` bins per histogram (0: any
/// number).
struct FastBeam<'a, const N: usize> {
    beam: &'a Beam<'a>,
    total: f64,
    /// Gains waiting to be computed: `(cell, kernel offset, weight)`.
    /// Computing them in batches lets the processor overlap the
    /// independent cells instead of waiting on each one's logarithm.
    jobs: Vec<(usize, usize, f64)>,
}

/// Gains computed per batch.
const BATCH: usize = 64;

impl<const N: usize> FastBeam<'_, N> {
    /// The first index in `0..=n` where the monotone predicate `pred` holds,
    /// starting the search from the estimate `guess`.
    #[inline(always)]
    fn first(n: usize, guess: f64, pred: impl Fn(usize) -> bool) -> usize {
        let mut j = guess.clamp(0.0, n as f64) as usize;
        while j > 0 && pred(j - 1) {
            j -= 1;
        }
        while j < n && !pred(j) {
            j += 1;
        }
        j
    }

    /// Compute the waiting gains, in the order they were queued.
    fn flush(&mut self) {
        self.total += self.batch();
        self.jobs.clear();
    }

    /// The weighted gains of the waiting jobs, summed in order.
    #[inline(always)]
    fn batch(&self) -> f64 {
        let mut total = 0.0;
        for &(i, offset, w) in &self.jobs {
            total += w * self.gain(i, offset);
        }
        total
    }

    /// `I(h_i | k)` for the kernel at `offset`, with one logarithm.
    #[inline(always)]
    fn gain(&self, i: usize, offset: usize) -> f64 {
        let bins = if N == 0 { self.beam.map.bins() } else { N };
        let h = &self.beam.map.histograms()[i * bins..(i + 1) * bins];
        let log_h = &self.beam.cache.log_h[i * bins..(i + 1) * bins];
        let (z, a) = if N == 0 {
            sums_any(h, log_h, self.beam.table.at_f64(offset), self.beam.table.log_at(offset))
        } else {
            sums_fixed::<N>(h, log_h, self.beam.table.at_f64(offset), self.beam.table.log_at(offset))
        };
        self.beam.cache.entropy[i] - (z.ln() - a / z)
    }
}

/// `Z = sum h k` and `A = sum h k (ln h + ln k)` for `N` bins (a multiple of
/// 4), in four lanes added in a fixed order.
#[inline(always)]
fn sums_fixed<const N: usize>(h: &[f32], log_h: &[f64], k: &[f64], log_k: &[f64]) -> (f64, f64) {
    let (Ok(h), Ok(log_h), Ok(k), Ok(log_k)) = (
        <&[f32; N]>::try_from(h),
        <&[f64; N]>::try_from(log_h),
        <&[f64; N]>::try_from(k),
        <&[f64; N]>::try_from(log_k),
    ) else {
        unreachable!("the caller passes slices of N bins")
    };
    let mut z = [0.0f64; 4];
    let mut a = [0.0f64; 4];
    for c in 0..N / 4 {
        for l in 0..4 {
            let b = 4 * c + l;
            let hk = f64::from(h[b]) * k[b];
            z[l] += hk;
            a[l] += hk * (log_h[b] + log_k[b]);
        }
    }
    ((z[0] + z[2]) + (z[1] + z[3]), (a[0] + a[2]) + (a[1] + a[3]))
}

/// [`sums_fixed`] for any bin count.
fn sums_any(h: &[f32], log_h: &[f64], k: &[f64], log_k: &[f64]) -> (f64, f64) {
    let (mut z, mut a) = (0.0, 0.0);
    for b in 0..h.len() {
        let hk = f64::from(h[b]) * k[b];
        z += hk;
        a += hk * (log_h[b] + log_k[b]);
    }
    (z, a)
}

impl<const N: usize> CellVisitor for FastBeam<'_, N> {
    #[inline(always)]
    fn cell(&mut self, i: usize, d_l: f64, enter: f64) {
        // Every echo that leaves the cell in free space gives it the same
        // kernel as no echo does: region 0 at distance min(d_l, d) = d_l.
        let mut free_weight = 0.0;
        if let Some(sparse) = self.beam.sparse {
            // Few echoes have any probability: test each.
            for h in sparse {
                if enter <= h.reach {
                    if h.lookup.is_free(d_l) {
                        free_weight += h.p;
                    } else {
                        self.jobs.push((i, h.lookup.offset(d_l), h.p));
                    }
                }
            }
        } else {
            // Echoes whose footprint holds the cell: `j >= reach_from`; echoes
            // that leave it in free space: `j >= free_from`, a suffix sum.
            let hyps = self.beam.hypotheses;
            let n = hyps.len();
            let reach_from =
                Self::first(n, (enter - self.beam.band_m) * self.beam.inv_step_m, |j| enter <= hyps[j].reach);
            let free_from =
                Self::first(n, (d_l + self.beam.half_cell_m) * self.beam.inv_step_m, |j| hyps[j].lookup.is_free(d_l))
                    .max(reach_from);
            for h in &hyps[reach_from..free_from] {
                if h.p > 0.0 {
                    self.jobs.push((i, h.lookup.offset(d_l), h.p));
                }
            }
            free_weight = self.beam.suffix[free_from];
        }
        if enter <= self.beam.none_reach {
            free_weight += self.beam.no_echo;
        }
        if free_weight > 0.0 {
            self.jobs.push((i, self.beam.none_lookup.offset(d_l), free_weight));
        }
        if self.jobs.len() >= BATCH {
            self.flush();
        }
    }
}

impl CoverageMap {
    /// The kernel table for `range` on this map: the cached one when it
    /// serves, else a new one.
    pub(crate) fn kernel_table(&self, range: &RangeModel) -> Result<Cow<'_, KernelTable>> {
        let resolution = self.grid().resolution_m();
        match self.cached_table() {
            Some(t) if t.serves(range, resolution, self.bins()) => Ok(Cow::Borrowed(t)),
            _ => Ok(Cow::Owned(KernelTable::new(range, resolution, self.bins())?)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sensor::{LaserModel, SonarModel};

    #[test]
    fn information_gain_of_uniform_kernel_is_zero() {
        let h = [0.1, 0.2, 0.3, 0.4];
        assert!(information_gain(&h, &[0.25; 4]).abs() < 1e-7);
        // From the prior, any informative kernel gains.
        assert!(information_gain(&[0.25; 4], &[0.7, 0.1, 0.1, 0.1]) > 0.0);
    }

    #[test]
    fn readings_sum_to_one() {
        let grid = Grid::new([0.0, 0.0], 0.05, 100, 100).unwrap();
        let mut stop = vec![0.0; grid.len()];
        for row in 0..100 {
            stop[grid.index(crate::Cell { row, col: 60 }).unwrap()] = 0.4;
            stop[grid.index(crate::Cell { row, col: 80 }).unwrap()] = 1.0;
        }
        let range = SonarModel::default().range;
        let d = reading_distribution(&grid, &stop, [1.025, 2.525], 0.0, &range, 0.05);
        let total: f64 = d.probabilities.iter().sum::<f64>() + d.no_echo;
        assert!((total - 1.0).abs() < 1e-12);
        assert_eq!(d.no_echo, 0.0, "the full wall stops every beam");
        // The partial cell at x in [3.0, 3.05) reflects 40 %, at 3.05 - 0.4 * 0.05 = 3.03.
        let j = ((3.03 - 1.025) / 0.05f64).round() as usize;
        assert!((d.probabilities[j] - 0.4).abs() < 1e-7, "{:?}", &d.probabilities[35..45]);
        let open = reading_distribution(&grid, &vec![0.0; grid.len()], [1.0, 1.0], 0.3, &range, 0.05);
        assert_eq!(open.no_echo, 1.0);
    }

    #[test]
    fn fast_equals_exact_on_a_partly_known_map() {
        let grid = Grid::new([0.0, 0.0], 0.1, 50, 70).unwrap();
        let mut map = CoverageMap::new(grid);
        let sonar = SonarModel::default();
        let bearings: Vec<f64> = (0..8).map(|i| i as f64 * 0.785).collect();
        map.integrate(&Pose::new(3.0, 2.5, 0.1), &[1.2, 2.0, 6.0, 0.7, 1.5, 2.2, 3.0, 0.4], &bearings, &sonar).unwrap();
        map.integrate(&Pose::new(5.0, 2.0, -0.3), &[2.5, 1.0, 1.7, 0.9, 5.5, 2.2, 1.0, 0.8], &bearings, &sonar)
            .unwrap();
        for model in [&sonar as &dyn SensorModel, &LaserModel::default()] {
            for stop_coverage in [StopCoverage::MaximumLikelihood, StopCoverage::Mean] {
                let options = GainOptions { range_step_m: None, stop_coverage };
                let eval = GainEvaluator::new(&map, model, options).unwrap();
                let poses: Vec<Pose> =
                    (0..6).map(|k| Pose::new(0.4 + 1.1 * k as f64, 1.0 + 0.6 * k as f64, k as f64)).collect();
                let fast = eval.evaluate(&poses, &bearings, GainMethod::Fast).unwrap();
                let exact = eval.evaluate(&poses, &bearings, GainMethod::Exact).unwrap();
                for (f, e) in fast.iter().zip(&exact) {
                    assert!(*e > 0.0);
                    assert!((f - e).abs() <= 1e-6 * e.abs(), "{stop_coverage:?}: fast {f} exact {e}");
                }
            }
        }
    }

    #[test]
    fn rejects_bad_input() {
        let map = CoverageMap::new(Grid::new([0.0, 0.0], 0.1, 10, 10).unwrap());
        let sonar = SonarModel::default();
        let eval = GainEvaluator::new(&map, &sonar, GainOptions::default()).unwrap();
        assert!(eval.evaluate(&[Pose::new(-1.0, 0.5, 0.0)], &[0.0], GainMethod::Fast).is_err());
        assert!(eval.evaluate(&[Pose::new(0.5, 0.5, f64::NAN)], &[0.0], GainMethod::Fast).is_err());
        assert!(eval.evaluate(&[Pose::new(0.5, 0.5, 0.0)], &[f64::INFINITY], GainMethod::Exact).is_err());
        let bad = GainOptions { range_step_m: Some(0.2), ..GainOptions::default() };
        assert!(GainEvaluator::new(&map, &sonar, bad).is_err());
    }
}
