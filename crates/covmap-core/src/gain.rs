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
//! (to rounding) much faster, from these facts:
//! - a cell in front of the end point gets a kernel that depends on the cell's
//!   distance, not on the reading (see [`crate::sensor`]), so the readings that
//!   leave it in free space contribute `I_free * (sum of their p(d))`: a suffix
//!   sum of `p(d)`; only the few readings that end near the cell need a kernel
//!   of their own;
//! - readings of probability 0 contribute nothing and are skipped, and a
//!   beam's footprint is walked only out to the reach of its farthest
//!   possible reading: a cell the ML map holds as fully covered stops every
//!   predicted beam, so the cells behind it (out of reach of every reading
//!   that can occur) are not visited at all;
//! - every cell still at the uniform prior gains the same under a given
//!   kernel, so those gains are computed once per kernel of the table and
//!   looked up (in unexplored space a pair costs a table read);
//! - with `h ln h` of every bin computed once per evaluator, the entropy of an
//!   updated histogram costs three dot products and one logarithm:
//!   `H(h k / Z) = ln Z - A / Z`, `Z = sum h k`, `A = sum k (h ln h) + h (k ln k)`;
//! - the gains are computed in batches, the logarithms of a batch together as
//!   vector code; the whole walk of a beam is compiled for the widest
//!   arithmetic the processor has (detected at run time): AVX-512, where
//!   eight gains go through the sums, the logarithm and the weighting
//!   together (a 16-bin row in two registers), or AVX2 and FMA, or the
//!   target's baseline; every path agrees with the others to rounding and is
//!   tested against the exact evaluator; the cache lines a queued gain will
//!   read are requested when it is queued, so that they have arrived when the
//!   batch is computed;
//! - a cone is walked in blocks of a row's neighbouring cells, and a block
//!   that lies wholly in front of the nearest echo it could meet (most of
//!   them) queues its free-space gains at once, without testing echoes cell
//!   by cell.
//!
//! Candidates are evaluated in parallel (feature `parallel`), in groups of
//! neighbours whose beams are taken in the order of their direction, so that
//! consecutive beams find their cells in the cache. Every candidate's beams are
//! summed in the order of their direction whatever the other candidates are,
//! so a result depends neither on scheduling nor on the company a candidate
//! keeps.

use std::borrow::Cow;

use serde::{Deserialize, Serialize};

use crate::aligned::Aligned;
use crate::coverage_map::CoverageMap;
use crate::error::{CovmapError, Result};
use crate::footprint::{CellVisitor, ROW_BLOCK, visit};
use crate::grid::Grid;
#[cfg(target_arch = "x86_64")]
use crate::numeric::ln_normal_zmm;
use crate::numeric::{ln_normal, x_ln_x, x_ln_x_of_f32};
use crate::scan::{Pose, check_bearings, check_pose};
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
    /// resolution. Between [`MIN_STEP_FRACTION`] (1/1024) of the grid
    /// resolution and the resolution.
    pub range_step_m: Option<f64>,
    /// Which coverage value of a cell stops a predicted beam.
    pub stop_coverage: StopCoverage,
}

/// Entropy of a histogram in nats, in `f64`.
pub fn entropy(h: &[f32]) -> f64 {
    -h.iter().map(|&p| x_ln_x(f64::from(p))).sum::<f64>()
}

/// `I(h | k) = H(h) - H(h')`, `h'` the normalised product of `h` and kernel
/// `k`, straight from the definitions (eq. 11-12).
pub fn information_gain(h: &[f32], k: &[f32]) -> f64 {
    let z: f64 = h
        .iter()
        .zip(k)
        .map(|(&a, &b)| f64::from(a) * f64::from(b))
        .sum();
    let posterior_entropy = -h
        .iter()
        .zip(k)
        .map(|(&a, &b)| x_ln_x(f64::from(a) * f64::from(b) / z))
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
/// [module documentation](self). Readings past the map's far corner cannot
/// occur and get no slot.
///
/// Errors if `stop` does not hold one value per cell, the origin is not
/// finite or lies outside the grid, the angle is not finite, the range model
/// is invalid, or `step_m` is not a step between [`MIN_STEP_FRACTION`] of
/// the grid resolution and the resolution.
pub fn reading_distribution(
    grid: &Grid,
    stop: &[f32],
    origin: [f64; 2],
    angle_rad: f64,
    range: &RangeModel,
    step_m: f64,
) -> Result<ReadingDistribution> {
    if stop.len() != grid.len() {
        return Err(CovmapError::LengthMismatch {
            what: "stop coverage and grid cells",
            left: stop.len(),
            right: grid.len(),
        });
    }
    check_pose(grid, &Pose::new(origin[0], origin[1], angle_rad))?;
    range.validate()?;
    check_step(step_m, grid.resolution_m())?;
    Ok(trace_readings(grid, stop, origin, angle_rad, range, step_m))
}

/// The finest spacing of hypothetical readings, as a fraction of the grid
/// resolution (the kernels resolve a reading to 1/32 of a cell).
pub const MIN_STEP_FRACTION: f64 = 1.0 / 1024.0;

/// Errors unless `step_m` lies between [`MIN_STEP_FRACTION`] of
/// `resolution_m` and `resolution_m`.
fn check_step(step_m: f64, resolution_m: f64) -> Result<()> {
    if step_m >= MIN_STEP_FRACTION * resolution_m && step_m <= resolution_m {
        Ok(())
    } else {
        Err(CovmapError::InvalidParameter {
            name: "range_step_m",
            value: step_m,
            expected: "a step between 1/1024 of the grid resolution and the resolution",
        })
    }
}

/// [`reading_distribution`] of valid inputs.
fn trace_readings(
    grid: &Grid,
    stop: &[f32],
    origin: [f64; 2],
    angle_rad: f64,
    range: &RangeModel,
    step_m: f64,
) -> ReadingDistribution {
    let r = grid.resolution_m();
    // A reading ends at most half a cell past the centre of a cell the beam
    // crosses, so none lies beyond the map's farthest corner plus a cell.
    let [x0, y0, x1, y1] = grid.bounds_m();
    let far = (origin[0] - x0)
        .max(x1 - origin[0])
        .hypot((origin[1] - y0).max(y1 - origin[1]));
    let limit = ((far + r) / step_m).ceil() + 1.0;
    let wanted = (range.max_range_m / step_m).ceil();
    let slots = if wanted > limit {
        // Every one of these readings lies below the maximum range.
        limit as usize
    } else {
        // The readings `j * step_m` below the maximum range.
        let n = wanted as usize;
        (0..=n)
            .rev()
            .find(|&j| (j as f64) * step_m < range.max_range_m)
            .map_or(0, |j| j + 1)
    };
    let mut probabilities = vec![0.0; slots];
    let mut through = 1.0f64;
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
    visit(
        grid,
        origin,
        angle_rad,
        range.max_range_m,
        Footprint::Ray,
        &mut trace,
    );
    ReadingDistribution {
        step_m,
        probabilities,
        no_echo: through,
    }
}

/// `h ln h` of every bin of every histogram, in `f64` (through the
/// vectorisable logarithm, within two ulps of `x_ln_x`), and each histogram's
/// entropy summed from those same products (so that rounding cancels in the
/// gain's differences). `f64` because the gain of a nearly certain cell is a
/// small difference of such sums: rounded to `f32` they put the fast evaluator
/// 1e-4 (relative) off the exact one on some maps.
///
/// Cells still at the uniform prior (every bin `1 / bins`, bit for bit) all
/// gain the same under a kernel, so their gains are computed once per kernel
/// of the table and looked up: in unexplored space a pair then costs a table
/// read, not three dot products and a logarithm.
struct LogCache {
    /// Laid out as the histograms, from the start of a cache line.
    h_ln_h: Aligned<f64>,
    entropy: Vec<f64>,
    /// 1 for a cell at the uniform prior, else 0 (bytes, so that a row block
    /// reads its eight flags as one word).
    prior: Vec<u8>,
    /// The gain of the prior histogram under each kernel of the table, by
    /// kernel index (offset / bins). Empty if no cell is at the prior.
    prior_gain: Vec<f64>,
}

impl LogCache {
    fn new(map: &CoverageMap, table: &KernelTable) -> Self {
        let bins = map.bins();
        let h = map.histograms();
        let mut h_ln_h = Aligned::zeroed(h.len());
        let mut entropy = vec![0.0; h.len() / bins];
        let mut prior = vec![0u8; h.len() / bins];
        let prior_bits = (1.0 / bins as f32).to_bits();
        // One pass per piece of the map: its `h ln h`, then its entropies and
        // which of its cells are at the prior.
        const CELLS: usize = 4096;
        let fill = |(((u, e), p), h): Piece<'_>| {
            u.iter_mut()
                .zip(h)
                .for_each(|(u, &v)| *u = x_ln_x_of_f32(v));
            e.iter_mut()
                .zip(u.chunks_exact(bins))
                .for_each(|(e, u)| *e = -u.iter().sum::<f64>());
            p.iter_mut()
                .zip(h.chunks_exact(bins))
                .for_each(|(p, h)| *p = u8::from(h.iter().all(|v| v.to_bits() == prior_bits)));
        };
        let pieces: Vec<Piece<'_>> = h_ln_h
            .chunks_mut(CELLS * bins)
            .zip(entropy.chunks_mut(CELLS))
            .zip(prior.chunks_mut(CELLS))
            .zip(h.chunks(CELLS * bins))
            .collect();
        #[cfg(feature = "parallel")]
        {
            use rayon::prelude::*;
            pieces.into_par_iter().for_each(fill);
        }
        #[cfg(not(feature = "parallel"))]
        pieces.into_iter().for_each(fill);
        let prior_gain = if prior.contains(&1) {
            prior_gains(bins, table)
        } else {
            Vec::new()
        };
        Self {
            h_ln_h,
            entropy,
            prior,
            prior_gain,
        }
    }
}

/// A piece of the map as [`LogCache::new`] fills it: its `h ln h`, its
/// entropies and prior flags (to be written), and its histograms.
type Piece<'p> = (((&'p mut [f64], &'p mut [f64]), &'p mut [u8]), &'p [f32]);

/// The gain `H(h) - H(h k / Z)` of the uniform prior `h` under every kernel
/// `k` of `table`, with the prior's `h ln h` and entropy computed as
/// [`LogCache`] computes every cell's.
fn prior_gains(bins: usize, table: &KernelTable) -> Vec<f64> {
    let p = 1.0 / bins as f32;
    let (h, u) = (f64::from(p), x_ln_x_of_f32(p));
    let entropy = -(0..bins).map(|_| u).sum::<f64>();
    table
        .values_f64()
        .chunks_exact(bins)
        .zip(table.k_ln_k().chunks_exact(bins))
        .map(|(k, m)| plain_gain(std::iter::repeat_n((h, u), bins), entropy, k, m))
        .collect()
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
    /// The widest arithmetic the processor offers (detected at run time).
    arith: Arith,
}

impl<'a> GainEvaluator<'a> {
    /// An evaluator for `map` and `model`.
    ///
    /// # Errors
    /// [`CovmapError::InvalidParameter`] if the model is invalid, or
    /// `options.range_step_m` is not between [`MIN_STEP_FRACTION`] of the
    /// grid resolution and the resolution.
    pub fn new<M: SensorModel + ?Sized>(
        map: &'a CoverageMap,
        model: &M,
        options: GainOptions,
    ) -> Result<Self> {
        model.validate()?;
        let resolution = map.grid().resolution_m();
        let step_m = options.range_step_m.unwrap_or(resolution);
        check_step(step_m, resolution)?;
        let range = *model.range_model();
        let table = map.kernel_table(&range)?;
        let stop = match options.stop_coverage {
            StopCoverage::MaximumLikelihood => map.ml(),
            StopCoverage::Mean => map.mean(),
        };
        Ok(Self {
            map,
            table,
            range,
            footprint: model.footprint(),
            stop,
            step_m,
            cache: std::sync::OnceLock::new(),
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
    /// [`CovmapError::InvalidPose`] if a pose is not finite,
    /// [`CovmapError::PoseOutsideMap`] if one lies in no cell of the map,
    /// [`CovmapError::InvalidBearing`] if a bearing, or its sum with a
    /// pose's heading, is not finite.
    pub fn evaluate(
        &self,
        poses: &[Pose],
        bearings: &[f64],
        method: GainMethod,
    ) -> Result<Vec<f64>> {
        self.validate(poses, bearings)?;
        if method == GainMethod::Fast {
            self.cache
                .get_or_init(|| LogCache::new(self.map, &self.table));
        }
        let beam = |pose: &Pose, b: f64, queue: &mut Queue| -> f64 {
            let origin = [pose.x_m, pose.y_m];
            let angle = pose.theta_rad + b;
            match method {
                GainMethod::Exact => self.exact_beam(origin, angle),
                GainMethod::Fast => self.fast_beam(origin, angle, queue),
            }
        };
        // Candidates are taken in groups of neighbours (in Z order over the
        // map), and a group's beams in the order of their direction: beams
        // that follow each other then cover much the same cells, which are
        // still in the processor's cache.
        let grid = self.map.grid();
        let mut order: Vec<(u64, usize)> = poses
            .iter()
            .enumerate()
            .map(|(k, p)| {
                let [gx, gy] = grid.world_to_grid(p.x_m, p.y_m);
                (z_order(gx as u32, gy as u32), k)
            })
            .collect();
        order.sort_unstable();
        let group = |members: &[(u64, usize)]| -> Vec<(usize, f64)> {
            let mut beams: Vec<(f64, usize, f64)> =
                Vec::with_capacity(members.len() * bearings.len());
            for (slot, &(_, k)) in members.iter().enumerate() {
                for &b in bearings {
                    beams.push((
                        (poses[k].theta_rad + b).rem_euclid(std::f64::consts::TAU),
                        slot,
                        b,
                    ));
                }
            }
            beams.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
            let mut totals: Vec<(usize, f64)> = members.iter().map(|&(_, k)| (k, 0.0)).collect();
            // One queue of gains for the group's beams (each beam leaves it empty).
            let mut queue = Queue::new();
            for (_, slot, b) in beams {
                totals[slot].1 += beam(&poses[totals[slot].0], b, &mut queue);
            }
            totals
        };
        #[cfg(feature = "parallel")]
        let parts: Vec<(usize, f64)> = {
            use rayon::prelude::*;
            order.par_chunks(GROUP).flat_map_iter(group).collect()
        };
        #[cfg(not(feature = "parallel"))]
        let parts: Vec<(usize, f64)> = order.chunks(GROUP).flat_map(group).collect();
        let mut gains = vec![0.0; poses.len()];
        for (k, g) in parts {
            gains[k] = g;
        }
        Ok(gains)
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
                visit(
                    self.map.grid(),
                    [pose.x_m, pose.y_m],
                    pose.theta_rad + b,
                    reach,
                    self.footprint,
                    &mut |_, _| n += 1,
                );
            }
        }
        Ok(n)
    }

    fn validate(&self, poses: &[Pose], bearings: &[f64]) -> Result<()> {
        if poses.is_empty() {
            // No direction to form: the bearings themselves.
            return check_bearings(0.0, bearings);
        }
        for pose in poses {
            check_pose(self.map.grid(), pose)?;
            check_bearings(pose.theta_rad, bearings)?;
        }
        Ok(())
    }

    fn distribution(&self, origin: [f64; 2], angle: f64) -> ReadingDistribution {
        trace_readings(
            self.map.grid(),
            &self.stop,
            origin,
            angle,
            &self.range,
            self.step_m,
        )
    }

    /// The widest reach of any hypothetical reading.
    fn widest_reach(&self) -> f64 {
        let last = (self.range.max_range_m / self.step_m).ceil() * self.step_m;
        self.range
            .reach(self.range.max_range_m)
            .0
            .max(last + self.range.band_m)
    }

    /// Sum of the gains of the cells a reading `d` would update.
    fn exact_reading(&self, origin: [f64; 2], angle: f64, d: f64) -> f64 {
        let (reach, echo) = self.range.reach(d);
        let lookup = self.table.reading(d.min(self.range.max_range_m), echo);
        let (data, bins) = (self.map.histograms(), self.map.bins());
        let mut sum = 0.0;
        visit(
            self.map.grid(),
            origin,
            angle,
            reach,
            self.footprint,
            &mut |i, d_l| {
                sum += information_gain(
                    &data[i * bins..(i + 1) * bins],
                    self.table.at(lookup.offset(d_l)),
                );
            },
        );
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

    fn fast_beam(&self, origin: [f64; 2], angle: f64, queue: &mut Queue) -> f64 {
        let Some(cache) = self.cache.get() else {
            return f64::NAN;
        };
        let dist = self.distribution(origin, angle);
        let (none_reach, _) = self.range.reach(self.range.max_range_m);
        let n = dist.probabilities.len();
        // Only echoes of non-zero probability matter.
        let possible: Vec<Hypothesis> = (0..n)
            .filter(|&j| dist.probabilities[j] > 0.0)
            .map(|j| {
                let d = j as f64 * dist.step_m;
                let (reach, echo) = self.range.reach(d);
                Hypothesis {
                    lookup: self.table.reading(d, echo),
                    reach,
                    p: dist.probabilities[j],
                }
            })
            .collect();
        // The footprint of the farthest reading that can occur: no cell
        // beyond it is updated by any (behind a wall the ML map marks as
        // covered, none), and footprints of growing reaches are nested.
        let echo_reach = possible.last().map_or(0.0, |h| h.reach);
        let reach = if dist.no_echo > 0.0 {
            echo_reach.max(none_reach)
        } else {
            echo_reach
        };
        let mut suffix = vec![0.0; possible.len() + 1];
        for j in (0..possible.len()).rev() {
            suffix[j] = suffix[j + 1] + possible[j].p;
        }
        let bucket_m = dist.step_m;
        let buckets = if possible.len() <= FEW_ECHOES {
            Vec::new()
        } else {
            echo_buckets(&possible, bucket_m, reach, self.map.grid().resolution_m())
        };
        let beam = Beam {
            origin,
            angle,
            reach,
            map: self.map,
            cache,
            table: &self.table,
            possible: &possible,
            suffix: &suffix,
            buckets: &buckets,
            inv_bucket_m: 1.0 / bucket_m,
            last_bucket: buckets.len().saturating_sub(1) as f64,
            no_echo: dist.no_echo,
            none_lookup: self.table.reading(self.range.max_range_m, false),
            none_reach,
        };
        // Fix the bin count at compile time for the common sizes, so that the
        // per-cell gain is straight vector code.
        match self.map.bins() {
            8 => self.run::<8>(&beam, queue),
            16 => self.run::<16>(&beam, queue),
            32 => self.run::<32>(&beam, queue),
            _ => self.run::<0>(&beam, queue),
        }
    }

    /// One beam's sum with `N` bins, the whole walk compiled for the widest
    /// arithmetic the processor has.
    fn run<const N: usize>(&self, beam: &Beam<'_>, queue: &mut Queue) -> f64 {
        #[cfg(target_arch = "x86_64")]
        match self.arith {
            // SAFETY: `arith` is `Avx512` or `Avx2` only where the processor
            // has those instructions (`Arith::detect`).
            Arith::Avx512 => return unsafe { self.run_avx512::<N>(beam, queue) },
            Arith::Avx2 => return unsafe { self.run_avx2::<N>(beam, queue) },
            Arith::Baseline => {}
        }
        #[cfg(not(target_arch = "x86_64"))]
        let _ = self.arith;
        self.run_with::<N, BASELINE>(Has::baseline(), beam, queue)
    }

    /// [`Self::run_with`] compiled for AVX-512 (F, DQ, VL), AVX2 and FMA.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx512f,avx512dq,avx512vl,avx2,fma")]
    fn run_avx512<const N: usize>(&self, beam: &Beam<'_>, queue: &mut Queue) -> f64 {
        // SAFETY: this function is compiled for AVX-512, so it may only be
        // called where the processor has it.
        let has = unsafe { Has::<AVX512>::new() };
        self.run_with::<N, AVX512>(has, beam, queue)
    }

    /// [`Self::run_with`] compiled for AVX2 and FMA.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,fma")]
    fn run_avx2<const N: usize>(&self, beam: &Beam<'_>, queue: &mut Queue) -> f64 {
        // SAFETY: this function is compiled for AVX2 and FMA, so it may only
        // be called where the processor has them.
        let has = unsafe { Has::<AVX2>::new() };
        self.run_with::<N, AVX2>(has, beam, queue)
    }

    /// One beam's sum with `N` bins and the arithmetic `A`, which `has`
    /// shows the processor to have.
    #[inline(always)]
    fn run_with<const N: usize, const A: u8>(
        &self,
        has: Has<A>,
        beam: &Beam<'_>,
        queue: &mut Queue,
    ) -> f64 {
        let rows = Rows::new(
            self.map.histograms(),
            &beam.cache.h_ln_h,
            &beam.cache.entropy,
            self.table.values_f64(),
            self.table.k_ln_k(),
        );
        debug_assert_eq!(queue.len, 0);
        let mut sweep = FastBeam::<N, A> {
            has,
            beam,
            rows,
            total: 0.0,
            queue,
        };
        visit(
            self.map.grid(),
            beam.origin,
            beam.angle,
            beam.reach,
            self.footprint,
            &mut sweep,
        );
        sweep.flush();
        sweep.total
    }
}

/// Up to this many echoes of non-zero probability, a cell tests each of them
/// rather than looking up its bucket.
const FEW_ECHOES: usize = 8;

/// For each distance bucket of `bucket_m` along a beam's footprint (out to
/// `reach`), the run `possible[lo..hi]` of echoes a cell reached in it must
/// test; see [`Beam::buckets`]. Reach and freeness grow with the echo's
/// distance, so the echoes before the run cannot reach the bucket's cells and
/// those after it leave them all in free space.
fn echo_buckets(
    possible: &[Hypothesis],
    bucket_m: f64,
    reach: f64,
    resolution_m: f64,
) -> Vec<(usize, usize)> {
    // A cell's centre distance lies within half a cell diagonal of where the
    // footprint reaches it (they are equal for a cone).
    let margin = resolution_m + 1e-6 * bucket_m;
    let count = (reach / bucket_m) as usize + 2;
    let (mut lo, mut hi) = (0, 0);
    let mut buckets = Vec::with_capacity(count);
    for b in 0..count {
        let enter_lo = b as f64 * bucket_m - 1e-6 * bucket_m;
        let d_l_hi = (b + 1) as f64 * bucket_m + margin;
        while lo < possible.len() && possible[lo].reach < enter_lo {
            lo += 1;
        }
        hi = hi.max(lo);
        while hi < possible.len() && !possible[hi].lookup.is_free(d_l_hi) {
            hi += 1;
        }
        buckets.push((lo, hi));
    }
    buckets
}

/// One hypothetical echo of a beam.
#[derive(Clone, Copy)]
struct Hypothesis {
    lookup: ReadingLookup,
    reach: f64,
    p: f64,
}

/// What every cell of one beam's widest footprint needs to know.
struct Beam<'a> {
    /// Where the beam starts, metres.
    origin: [f64; 2],
    /// Its direction, radians.
    angle: f64,
    /// How far its footprint is walked, metres.
    reach: f64,
    map: &'a CoverageMap,
    cache: &'a LogCache,
    table: &'a KernelTable,
    /// The echoes of non-zero probability, nearest first.
    possible: &'a [Hypothesis],
    /// `suffix[j]`: the probability of the echoes `possible[j..]`.
    suffix: &'a [f64],
    /// For cells reached at `enter` in bucket `b = enter / bucket`: the
    /// echoes `possible[..lo]` do not reach them, `possible[hi..]` leave them
    /// in free space, and `possible[lo..hi]` need a test. Empty when there
    /// are so few echoes that testing each beats the lookup.
    buckets: &'a [(usize, usize)],
    inv_bucket_m: f64,
    /// The index of the last bucket.
    last_bucket: f64,
    no_echo: f64,
    none_lookup: ReadingLookup,
    none_reach: f64,
}

impl Beam<'_> {
    /// The bucket of cells the footprint reaches at `enter` metres.
    #[inline(always)]
    fn bucket(&self, enter: f64) -> usize {
        // Clamped in floating point, so that the conversion is a plain truncation.
        (enter * self.inv_bucket_m).min(self.last_bucket) as i32 as usize
    }
}

/// The fast evaluator's work for one beam, with `N` bins per histogram (0: any
/// number).
struct FastBeam<'a, const N: usize, const A: u8> {
    /// That the processor has the arithmetic `A` the gains are computed with.
    has: Has<A>,
    beam: &'a Beam<'a>,
    rows: Rows<'a, N>,
    total: f64,
    /// Gains waiting to be computed. Computing them in batches lets the
    /// processor overlap the independent cells instead of waiting on each
    /// one's logarithm. Fewer than [`BATCH`] wait between calls, so a row
    /// block always finds room for its [`ROW_BLOCK`]. Empty between beams.
    queue: &'a mut Queue,
}

/// Gains waiting to be computed, the first `len` of each array: cell
/// `cell[j]`'s gain under the kernel at table offset `offset[j]`, weighted by
/// `weight[j]`. Arrays side by side, not one of tuples, so that vector code
/// reads eight weights (or entropies) at once.
struct Queue {
    cell: [usize; SLOTS],
    offset: [usize; SLOTS],
    weight: [f64; SLOTS],
    /// `H(h)` of each job's cell, read when it is queued (neighbouring cells
    /// of a row block at once), so that a batch needs no gather.
    entropy: [f64; SLOTS],
    len: usize,
}

impl Queue {
    fn new() -> Self {
        Self {
            cell: [0; SLOTS],
            offset: [0; SLOTS],
            weight: [0.0; SLOTS],
            entropy: [0.0; SLOTS],
            len: 0,
        }
    }
}

/// What one gain reads, cut into rows of `N` bins (empty for `N = 0`), so
/// that a row costs one bounds check.
struct Rows<'a, const N: usize> {
    /// Histograms, per cell.
    h: &'a [[f32; N]],
    /// `h ln h`, per cell.
    h_ln_h: &'a [[f64; N]],
    /// Entropies, per cell.
    entropy: &'a [f64],
    /// Kernels, per table entry.
    k: &'a [[f64; N]],
    /// `k ln k`, per table entry.
    k_ln_k: &'a [[f64; N]],
}

impl<'a, const N: usize> Rows<'a, N> {
    /// The rows of histograms `h` and their `h ln h`, and of kernels `k` and
    /// their `k ln k`.
    ///
    /// # Panics
    /// If `h_ln_h` is not as long as `h` or `k_ln_k` not as long as `k` (the
    /// unchecked reads of [`row_sums_zmm`] rely on both), or `entropy` does
    /// not hold one value per histogram.
    fn new(
        h: &'a [f32],
        h_ln_h: &'a [f64],
        entropy: &'a [f64],
        k: &'a [f64],
        k_ln_k: &'a [f64],
    ) -> Self {
        assert!(
            h.len() == h_ln_h.len() && k.len() == k_ln_k.len(),
            "rows of unequal lengths"
        );
        let rows = Self {
            h: rows(h),
            h_ln_h: rows(h_ln_h),
            entropy,
            k: rows(k),
            k_ln_k: rows(k_ln_k),
        };
        assert!(
            N == 0 || rows.h.len() == entropy.len(),
            "one entropy per histogram"
        );
        rows
    }
}

/// `values` cut into rows of `N` (none for `N = 0`).
fn rows<T, const N: usize>(values: &[T]) -> &[[T; N]] {
    if N == 0 {
        &[]
    } else {
        values.as_chunks::<N>().0
    }
}

/// Candidates evaluated together.
const GROUP: usize = 16;

/// Interleave the bits of two cell coordinates (Z order).
fn z_order(x: u32, y: u32) -> u64 {
    let spread = |v: u32| {
        let mut v = u64::from(v);
        v = (v | (v << 16)) & 0x0000_ffff_0000_ffff;
        v = (v | (v << 8)) & 0x00ff_00ff_00ff_00ff;
        v = (v | (v << 4)) & 0x0f0f_0f0f_0f0f_0f0f;
        v = (v | (v << 2)) & 0x3333_3333_3333_3333;
        (v | (v << 1)) & 0x5555_5555_5555_5555
    };
    spread(x) | (spread(y) << 1)
}

/// Gains queued before a batch is computed.
const BATCH: usize = 64;
/// Room for the jobs of a batch: one row block may overfill it.
const SLOTS: usize = BATCH + ROW_BLOCK;
const _: () = assert!(SLOTS.is_multiple_of(8));

impl<const N: usize, const A: u8> FastBeam<'_, N, A> {
    /// Compute the waiting gains, in the order they were queued.
    fn flush(&mut self) {
        if self.queue.len == 0 {
            return;
        }
        let q = &self.queue;
        self.total += if N == 0 {
            weighted_gains_any(self.beam, q)
        } else {
            weighted_gains::<N, A>(self.has, &self.rows, q)
        };
        self.queue.len = 0;
    }
}

/// The arithmetic the fast evaluator is compiled for: what [`Arith::detect`]
/// finds decides which one runs. Each wider one includes the narrower.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u8)]
enum Arith {
    /// The target's baseline (SSE2 on x86-64).
    Baseline = BASELINE,
    /// AVX2 and FMA.
    Avx2 = AVX2,
    /// AVX-512 (F, DQ, VL) with AVX2 and FMA: a 16-bin row in two registers.
    Avx512 = AVX512,
}

/// [`Arith`] as the const parameter of the compiled paths.
const BASELINE: u8 = 0;
const AVX2: u8 = 1;
const AVX512: u8 = 2;

mod evidence {
    /// Evidence that the processor has the instructions the arithmetic `A`
    /// ([`super::Arith`]) names: the paths compiled for them run only with
    /// one in hand. Only the baseline's is made without `unsafe`.
    #[derive(Clone, Copy)]
    pub(super) struct Has<const A: u8>(());

    impl<const A: u8> Has<A> {
        /// # Safety
        /// The processor must have the instructions `A` names.
        pub(super) unsafe fn new() -> Self {
            Self(())
        }
    }

    impl Has<{ super::BASELINE }> {
        /// Every processor has the target's baseline.
        pub(super) fn baseline() -> Self {
            Self(())
        }
    }
}
use evidence::Has;

impl Arith {
    /// The widest arithmetic this processor has.
    fn detect() -> Self {
        #[cfg(target_arch = "x86_64")]
        {
            use std::arch::is_x86_feature_detected as has;
            let avx2 = has!("avx2") && has!("fma");
            if avx2 && has!("avx512f") && has!("avx512dq") && has!("avx512vl") {
                return Self::Avx512;
            }
            if avx2 {
                return Self::Avx2;
            }
        }
        Self::Baseline
    }

    /// Every arithmetic this processor can run, widest first (for tests).
    #[cfg(test)]
    fn available() -> Vec<Self> {
        let widest = Self::detect() as u8;
        [Self::Avx512, Self::Avx2, Self::Baseline]
            .into_iter()
            .filter(|&a| a as u8 <= widest)
            .collect()
    }
}

/// [`weighted_gains_with`] compiled for the arithmetic `A` (`N > 0`), which
/// `has` shows the processor to have.
fn weighted_gains<const N: usize, const A: u8>(
    has: Has<A>,
    rows: &Rows<'_, N>,
    jobs: &Queue,
) -> f64 {
    #[cfg(target_arch = "x86_64")]
    {
        // SAFETY: `has` shows that the processor has the instructions `A`
        // names.
        if A == AVX512 {
            return unsafe { weighted_gains_avx512::<N>(rows, jobs) };
        }
        if A == AVX2 {
            return unsafe { weighted_gains_avx2::<N>(rows, jobs) };
        }
    }
    let _ = has;
    weighted_gains_with::<N, BASELINE>(Has::baseline(), rows, jobs)
}

/// [`weighted_gains_zmm`], compiled for AVX-512.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f,avx512dq,avx512vl,avx2,fma")]
fn weighted_gains_avx512<const N: usize>(rows: &Rows<'_, N>, jobs: &Queue) -> f64 {
    weighted_gains_zmm::<N>(rows, jobs)
}

/// [`weighted_gains_with`] compiled for AVX2 and FMA.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
fn weighted_gains_avx2<const N: usize>(rows: &Rows<'_, N>, jobs: &Queue) -> f64 {
    // SAFETY: this function is compiled for AVX2 and FMA, so it may only be
    // called where the processor has them.
    weighted_gains_with::<N, AVX2>(unsafe { Has::new() }, rows, jobs)
}

/// `sum w I(h_i | k)` over the queued jobs, each gain
/// `I = H(h) - H(h k / Z) = H(h) - ln Z + A / Z` with `Z = sum h k` and
/// `A = sum h k ln(h k) = sum k (h ln h) + h (k ln k)`: three dot products and
/// one logarithm. The logarithms of the batch are taken together, as vector
/// code. `A` names the arithmetic the caller is compiled for, which `has`
/// shows the processor to have: with [`AVX2`] (or wider) the sums are formed
/// in AVX2 registers ([`sums_avx2`]), else in plain code ([`sums`]).
#[inline(always)]
fn weighted_gains_with<const N: usize, const A: u8>(
    has: Has<A>,
    rows: &Rows<'_, N>,
    q: &Queue,
) -> f64 {
    let _ = has;
    let n = q.len.min(SLOTS);
    // Unused slots hold Z = 1, A = 0.
    let mut z = [1.0f64; SLOTS];
    let mut a = [0.0f64; SLOTS];
    for j in 0..n {
        let (i, e) = (q.cell[j], q.offset[j] / N);
        #[cfg(target_arch = "x86_64")]
        if A >= AVX2 {
            // SAFETY: `has` shows that the processor has AVX2 and FMA.
            (z[j], a[j]) =
                unsafe { sums_avx2::<N>(&rows.h[i], &rows.h_ln_h[i], &rows.k[e], &rows.k_ln_k[e]) };
            continue;
        }
        (z[j], a[j]) = sums::<N>(&rows.h[i], &rows.h_ln_h[i], &rows.k[e], &rows.k_ln_k[e]);
    }
    // `ln Z - A / Z` for the whole batch.
    let mut posterior = [0.0f64; SLOTS];
    for j in 0..SLOTS {
        posterior[j] = ln_normal(z[j]) - a[j] / z[j];
    }
    let mut total = 0.0;
    for j in 0..n {
        // The fast logarithm holds for normal numbers only.
        let h_post = if z[j].is_normal() {
            posterior[j]
        } else {
            z[j].ln() - a[j] / z[j]
        };
        total += q.weight[j] * (q.entropy[j] - h_post);
    }
    total
}

/// [`weighted_gains_with`] in AVX-512 registers, eight gains at a time from
/// the sums to the weighted total (`N` a multiple of 8): each job's products
/// fill eight lanes ([`row_sums_zmm`]), the eight jobs' lanes are summed
/// together by a transposing tree ([`sum_pairs`], [`sum_quads`]), and the
/// logarithm ([`ln_normal_zmm`], the same operations as [`ln_normal`]), the
/// two divisions and the weighting take the same instructions for all eight
/// as for one. The weighted gains go into eight running sums, added pairwise
/// at the end. Each job's gain is formed in the same order whatever its
/// neighbours, and each beam's total in an order fixed by its own queue.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f,avx512dq,avx512vl,avx2,fma")]
fn weighted_gains_zmm<const N: usize>(rows: &Rows<'_, N>, q: &Queue) -> f64 {
    use std::arch::x86_64::*;
    // The bin counts with a path of their own (8, 16, 32) fill whole registers.
    const { assert!(N.is_multiple_of(8)) };
    const GROUPS: usize = SLOTS.div_ceil(8);
    let n = q.len.min(SLOTS);
    let groups = n.div_ceil(8);
    // Three passes over the groups of eight: the sums, the logarithms, the
    // weighted total.
    let mut z = [_mm512_set1_pd(1.0); GROUPS];
    let mut a = [_mm512_setzero_pd(); GROUPS];
    for g in 0..groups {
        let lanes = (n - 8 * g).min(8);
        // Lanes past the last job repeat it; they weigh 0. The jobs' sums
        // are folded in as they come (see `sum_pairs`), so that few vectors
        // wait at a time. (Written out: with closures, a scratch build of this
        // loop called them out of line.)
        let mut j = [0usize; 8];
        for (l, j) in j.iter_mut().enumerate() {
            *j = 8 * g + l.min(lanes - 1);
        }
        let (za, aa) = row_sums_zmm::<N>(rows, q.cell[j[0]], q.offset[j[0]] / N);
        let (zb, ab) = row_sums_zmm::<N>(rows, q.cell[j[1]], q.offset[j[1]] / N);
        let (z01, a01) = (sum_pairs(za, zb), sum_pairs(aa, ab));
        let (za, aa) = row_sums_zmm::<N>(rows, q.cell[j[2]], q.offset[j[2]] / N);
        let (zb, ab) = row_sums_zmm::<N>(rows, q.cell[j[3]], q.offset[j[3]] / N);
        let (z23, a23) = (sum_pairs(za, zb), sum_pairs(aa, ab));
        let (z0, a0) = (sum_quads(z01, z23), sum_quads(a01, a23));
        let (za, aa) = row_sums_zmm::<N>(rows, q.cell[j[4]], q.offset[j[4]] / N);
        let (zb, ab) = row_sums_zmm::<N>(rows, q.cell[j[5]], q.offset[j[5]] / N);
        let (z45, a45) = (sum_pairs(za, zb), sum_pairs(aa, ab));
        let (za, aa) = row_sums_zmm::<N>(rows, q.cell[j[6]], q.offset[j[6]] / N);
        let (zb, ab) = row_sums_zmm::<N>(rows, q.cell[j[7]], q.offset[j[7]] / N);
        let (z67, a67) = (sum_pairs(za, zb), sum_pairs(aa, ab));
        let (z1, a1) = (sum_quads(z45, z67), sum_quads(a45, a67));
        (z[g], a[g]) = (sum_quads(z0, z1), sum_quads(a0, a1));
    }
    let mut posterior = [_mm512_setzero_pd(); GROUPS];
    let mut normal = 0xffu8;
    for g in 0..groups {
        posterior[g] = _mm512_sub_pd(ln_normal_zmm(z[g]), _mm512_div_pd(a[g], z[g]));
        // The fast logarithm holds for normal (positive) numbers only.
        normal &= _mm512_cmp_pd_mask::<_CMP_GE_OQ>(z[g], _mm512_set1_pd(f64::MIN_POSITIVE))
            & _mm512_cmp_pd_mask::<_CMP_LE_OQ>(z[g], _mm512_set1_pd(f64::MAX));
    }
    if normal != 0xff {
        // Rare: the library's logarithm for the lanes that need it.
        for g in 0..groups {
            let (mut zs, mut ps, mut as_) = ([0.0f64; 8], [0.0f64; 8], [0.0f64; 8]);
            // SAFETY: each array holds eight values.
            unsafe {
                _mm512_storeu_pd(zs.as_mut_ptr(), z[g]);
                _mm512_storeu_pd(as_.as_mut_ptr(), a[g]);
                _mm512_storeu_pd(ps.as_mut_ptr(), posterior[g]);
            }
            for l in 0..8 {
                if !zs[l].is_normal() {
                    ps[l] = zs[l].ln() - as_[l] / zs[l];
                }
            }
            // SAFETY: `ps` holds eight values.
            posterior[g] = unsafe { _mm512_loadu_pd(ps.as_ptr()) };
        }
    }
    let mut acc = _mm512_setzero_pd();
    for (g, &posterior) in posterior.iter().enumerate().take(groups) {
        let lanes = (n - 8 * g).min(8);
        let used: __mmask8 = if lanes == 8 { 0xff } else { (1u8 << lanes) - 1 };
        // SAFETY: `8 g + 8 <= SLOTS` (`SLOTS` is a multiple of 8), so eight
        // weights and entropies lie in the queue.
        let (w, entropy) = unsafe {
            (
                _mm512_maskz_loadu_pd(used, q.weight.as_ptr().add(8 * g)),
                _mm512_maskz_loadu_pd(used, q.entropy.as_ptr().add(8 * g)),
            )
        };
        // Unused lanes keep `acc` as it is (whatever their posterior).
        acc = _mm512_mask3_fmadd_pd(w, _mm512_sub_pd(entropy, posterior), acc, used);
    }
    let mut lanes = [0.0f64; 8];
    // SAFETY: `lanes` holds eight values.
    unsafe { _mm512_storeu_pd(lanes.as_mut_ptr(), acc) };
    pairwise_sum(&lanes)
}

/// `Z` and `A` of cell `i` under kernel `e`, each as eight lane sums (`N` a
/// multiple of 8).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
#[inline]
fn row_sums_zmm<const N: usize>(
    rows: &Rows<'_, N>,
    i: usize,
    e: usize,
) -> (std::arch::x86_64::__m512d, std::arch::x86_64::__m512d) {
    use std::arch::x86_64::*;
    assert!(
        i < rows.h.len() && e < rows.k.len(),
        "cell or kernel out of range"
    );
    // SAFETY: `Rows::new` made `h_ln_h` as long as `h` and `k_ln_k` as long
    // as `k`, and the two indices were checked against those.
    let (h, u, k, m) = unsafe {
        (
            rows.h.get_unchecked(i),
            rows.h_ln_h.get_unchecked(i),
            rows.k.get_unchecked(e),
            rows.k_ln_k.get_unchecked(e),
        )
    };
    // Each chunk of eight bins on its own, then the chunks added pairwise.
    let mut z = [_mm512_setzero_pd(); 4];
    let mut a = [_mm512_setzero_pd(); 4];
    for c in 0..N / 8 {
        // SAFETY: `8 c + 7 < N`, the length of every row.
        let (hv, uv, kv, mv) = unsafe {
            (
                _mm512_cvtps_pd(_mm256_loadu_ps(h.as_ptr().add(8 * c))),
                _mm512_loadu_pd(u.as_ptr().add(8 * c)),
                _mm512_loadu_pd(k.as_ptr().add(8 * c)),
                _mm512_loadu_pd(m.as_ptr().add(8 * c)),
            )
        };
        let (zc, ac) = (
            _mm512_mul_pd(hv, kv),
            _mm512_fmadd_pd(uv, kv, _mm512_mul_pd(hv, mv)),
        );
        if c < 4 {
            (z[c], a[c]) = (zc, ac);
        } else {
            (z[c % 4], a[c % 4]) = (_mm512_add_pd(z[c % 4], zc), _mm512_add_pd(a[c % 4], ac));
        }
    }
    (fold4::<N>(z), fold4::<N>(a))
}

/// The sum of the first `N / 8` (at most four) vectors of `v`, pairwise.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
#[inline]
fn fold4<const N: usize>(v: [std::arch::x86_64::__m512d; 4]) -> std::arch::x86_64::__m512d {
    use std::arch::x86_64::*;
    match N / 8 {
        1 => v[0],
        2 => _mm512_add_pd(v[0], v[1]),
        3 => _mm512_add_pd(_mm512_add_pd(v[0], v[1]), v[2]),
        _ => _mm512_add_pd(_mm512_add_pd(v[0], v[1]), _mm512_add_pd(v[2], v[3])),
    }
}

/// The first step of summing eight vectors' lanes into one vector (lane `j`
/// the sum of vector `j`'s lanes), for two of them:
/// `[x(0+1), y(0+1), x(2+3), y(2+3), x(4+5), y(4+5), x(6+7), y(6+7)]`.
/// [`sum_quads`] of two such gives four vectors' sums by halves, and of two
/// of those the eight sums in order: lane `j` adds vector `j`'s lanes in
/// neighbouring pairs, then pairs of pairs, then halves.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
#[inline]
fn sum_pairs(
    x: std::arch::x86_64::__m512d,
    y: std::arch::x86_64::__m512d,
) -> std::arch::x86_64::__m512d {
    use std::arch::x86_64::*;
    _mm512_add_pd(_mm512_unpacklo_pd(x, y), _mm512_unpackhi_pd(x, y))
}

/// 128-bit chunks 0 and 2 of each argument plus chunks 1 and 3 (see
/// [`sum_pairs`]).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
#[inline]
fn sum_quads(
    x: std::arch::x86_64::__m512d,
    y: std::arch::x86_64::__m512d,
) -> std::arch::x86_64::__m512d {
    use std::arch::x86_64::*;
    _mm512_add_pd(
        _mm512_shuffle_f64x2::<0b10_00_10_00>(x, y),
        _mm512_shuffle_f64x2::<0b11_01_11_01>(x, y),
    )
}

/// `Z = sum h k` and `A = sum k (h ln h) + h (k ln k)` for `N` bins (a
/// multiple of 4), in four lanes added in a fixed order.
#[inline(always)]
fn sums<const N: usize>(h: &[f32; N], u: &[f64; N], k: &[f64; N], m: &[f64; N]) -> (f64, f64) {
    let mut z = [0.0f64; 4];
    let mut a = [0.0f64; 4];
    for c in 0..N / 4 {
        for l in 0..4 {
            let b = 4 * c + l;
            let hb = f64::from(h[b]);
            z[l] += hb * k[b];
            a[l] += u[b] * k[b] + hb * m[b];
        }
    }
    ((z[0] + z[2]) + (z[1] + z[3]), (a[0] + a[2]) + (a[1] + a[3]))
}

/// [`sums`] in AVX2 registers with fused multiply-adds: the same four lanes,
/// added in the same order (the fused roundings make the last bits differ).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
#[inline]
fn sums_avx2<const N: usize>(h: &[f32; N], u: &[f64; N], k: &[f64; N], m: &[f64; N]) -> (f64, f64) {
    use std::arch::x86_64::*;
    let (mut z, mut a) = (_mm256_setzero_pd(), _mm256_setzero_pd());
    for c in 0..N / 4 {
        // SAFETY: `4 c + 3 < N`, the length of every array.
        let (hv, uv, kv, mv) = unsafe {
            (
                _mm256_cvtps_pd(_mm_loadu_ps(h.as_ptr().add(4 * c))),
                _mm256_loadu_pd(u.as_ptr().add(4 * c)),
                _mm256_loadu_pd(k.as_ptr().add(4 * c)),
                _mm256_loadu_pd(m.as_ptr().add(4 * c)),
            )
        };
        z = _mm256_fmadd_pd(hv, kv, z);
        a = _mm256_fmadd_pd(uv, kv, _mm256_fmadd_pd(hv, mv, a));
    }
    // (lane 0 + lane 2) + (lane 1 + lane 3), as `sums` adds them, for both
    // sums at once: [z0 + z2, z1 + z3, a0 + a2, a1 + a3], then pairwise.
    let halves = _mm256_add_pd(
        _mm256_permute2f128_pd::<0x20>(z, a),
        _mm256_permute2f128_pd::<0x31>(z, a),
    );
    let both = _mm256_hadd_pd(halves, halves);
    (
        _mm256_cvtsd_f64(both),
        _mm_cvtsd_f64(_mm256_extractf128_pd::<1>(both)),
    )
}

/// [`weighted_gains`] for any bin count, plainly.
fn weighted_gains_any(beam: &Beam<'_>, q: &Queue) -> f64 {
    let bins = beam.map.bins();
    let (k, m) = (beam.table.values_f64(), beam.table.k_ln_k());
    let mut total = 0.0;
    for (((&i, &offset), &w), &entropy) in q
        .cell
        .iter()
        .zip(&q.offset)
        .zip(&q.weight)
        .zip(&q.entropy)
        .take(q.len)
    {
        let cell = i * bins..(i + 1) * bins;
        let (h, u) = (
            &beam.map.histograms()[cell.clone()],
            &beam.cache.h_ln_h[cell],
        );
        let kernel = offset..offset + bins;
        let h_u = h.iter().map(|&v| f64::from(v)).zip(u.iter().copied());
        total += w * plain_gain(h_u, entropy, &k[kernel.clone()], &m[kernel]);
    }
    total
}

/// `H(h) - H(h k / Z) = H(h) - ln Z + A / Z` (see [`weighted_gains_with`]),
/// plainly, for any bin count: `h_u` gives each bin's `(h, h ln h)`,
/// `entropy` is `H(h)`, `k` the kernel and `m` its `k ln k`.
fn plain_gain(h_u: impl Iterator<Item = (f64, f64)>, entropy: f64, k: &[f64], m: &[f64]) -> f64 {
    let (mut z, mut a) = (0.0, 0.0);
    for ((h, u), (&k, &m)) in h_u.zip(k.iter().zip(m)) {
        z += h * k;
        a += u * k + h * m;
    }
    entropy - (z.ln() - a / z)
}

impl<const N: usize, const A: u8> FastBeam<'_, N, A> {
    /// Ask for the cache lines of cell `i`'s histogram and `h ln h`: its gains
    /// are computed at the next flush, by when they have arrived.
    #[inline(always)]
    fn prefetch(&self, i: usize) {
        #[cfg(target_arch = "x86_64")]
        if N > 0 {
            use std::arch::x86_64::{_MM_HINT_T0, _mm_prefetch};
            // Addresses only (`wrapping_add` never reads), so no bounds
            // check: a prefetch of any address is harmless.
            let h = self.rows.h.as_ptr().wrapping_add(i).cast::<i8>();
            let u = self.rows.h_ln_h.as_ptr().wrapping_add(i).cast::<i8>();
            // SAFETY: SSE is part of every x86-64 processor, and a prefetch
            // only hints at an address: it never reads or faults.
            unsafe {
                _mm_prefetch::<_MM_HINT_T0>(h);
                _mm_prefetch::<_MM_HINT_T0>(u);
                _mm_prefetch::<_MM_HINT_T0>(u.wrapping_add(64));
            }
        }
        #[cfg(not(target_arch = "x86_64"))]
        let _ = i;
    }

    /// The weight of the free kernel, if it is the only one every cell of a
    /// cone's row block (at distances from `near` to `far`) gets: every cell
    /// within `reach_m`, the echoes that end before the block reaching none
    /// of it, the next leaving all of it in free space, and either every cell
    /// or none within the reach of no echo. The same weight
    /// [`CellVisitor::cell`] gives each.
    #[inline(always)]
    fn block_weight(&self, [near, far]: [f64; 2], reach_m: f64) -> Option<f64> {
        let beam = self.beam;
        if !(far <= reach_m) {
            return None;
        }
        let mut j = if beam.buckets.is_empty() {
            0
        } else {
            beam.buckets[beam.bucket(near)].0
        };
        while j < beam.possible.len() && beam.possible[j].reach < near {
            j += 1;
        }
        if beam.possible.get(j).is_some_and(|h| !h.lookup.is_free(far)) {
            return None;
        }
        if far <= beam.none_reach {
            Some(beam.suffix[j] + beam.no_echo)
        } else if near > beam.none_reach {
            Some(beam.suffix[j])
        } else {
            None
        }
    }

    /// The index of the kernel at table `offset`.
    #[inline(always)]
    fn kernel_index(&self, offset: usize) -> usize {
        let bins = if N > 0 { N } else { self.beam.map.bins() };
        offset / bins
    }

    /// Cell `i`'s gain under the kernel at `offset`, weighted by `w`: added at
    /// once from the prior's gains if the cell is at the prior, else queued.
    #[inline(always)]
    fn gain(&mut self, i: usize, offset: usize, w: f64, prior: bool) {
        if prior {
            self.total += w * self.beam.cache.prior_gain[self.kernel_index(offset)];
        } else {
            self.push(i, offset, w);
        }
    }

    /// Queue one gain; compute the batch when it is full.
    #[inline(always)]
    fn push(&mut self, i: usize, offset: usize, w: f64) {
        debug_assert!(self.queue.len < BATCH);
        let j = self.queue.len.min(BATCH);
        let q = &mut self.queue;
        (q.cell[j], q.offset[j], q.weight[j], q.entropy[j]) = (i, offset, w, self.rows.entropy[i]);
        self.queue.len = j + 1;
        if self.queue.len >= BATCH {
            self.flush();
        }
    }
}

impl<const N: usize, const A: u8> CellVisitor for FastBeam<'_, N, A> {
    #[inline(always)]
    fn cell(&mut self, i: usize, d_l: f64, enter: f64) {
        let beam = self.beam;
        let prior = beam.cache.prior[i] != 0;
        if !prior {
            self.prefetch(i);
        }
        let (lo, hi) = if beam.buckets.is_empty() {
            (0, beam.possible.len())
        } else {
            beam.buckets[beam.bucket(enter)]
        };
        // Echoes that end near the cell need kernels of their own. From the
        // first echo that reaches the cell and leaves it in free space on,
        // every farther one does both (reach and freeness grow with the
        // echo's distance) and gives it the kernel no echo gives: region 0 at
        // distance min(d_l, d) = d_l.
        let mut j = lo;
        while j < hi {
            let h = &beam.possible[j];
            if enter <= h.reach {
                if h.lookup.is_free(d_l) {
                    break;
                }
                self.gain(i, h.lookup.offset(d_l), h.p, prior);
            }
            j += 1;
        }
        let mut free_weight = beam.suffix[j];
        if enter <= beam.none_reach {
            free_weight += beam.no_echo;
        }
        if free_weight > 0.0 {
            self.gain(i, beam.none_lookup.free_offset(d_l), free_weight, prior);
        }
    }

    #[inline(always)]
    fn row_block(
        &mut self,
        first: usize,
        d: &[f64; ROW_BLOCK],
        n: usize,
        bounds: [f64; 2],
        reach_m: f64,
    ) {
        if let Some(w) = self.block_weight(bounds, reach_m) {
            // Every cell of the block gets the free kernel with weight `w`:
            // what `cell` would do for each, done for the block at once.
            if w <= 0.0 {
                return;
            }
            let free = self.beam.none_lookup;
            let prior = &self.beam.cache.prior[first..first + n];
            let flags = match prior.first_chunk::<ROW_BLOCK>() {
                Some(all) => u64::from_ne_bytes(*all),
                None => u64::from(prior.iter().any(|&p| p != 0)),
            };
            if flags == u64::from_ne_bytes([1; ROW_BLOCK]) {
                // The whole block is at the prior (common in unexplored
                // space): free-space kernels are the table's first, so the
                // distance step is the kernel's index.
                let gains = &self.beam.cache.prior_gain;
                let g: [f64; ROW_BLOCK] = std::array::from_fn(|k| gains[free.free_step(d[k])]);
                self.total += w * pairwise_sum(&g);
                return;
            }
            if flags != 0 {
                // Cells at the prior take their gains from the table, summed
                // pairwise over the block; the others are queued.
                let mut g = [0.0f64; ROW_BLOCK];
                for k in 0..n {
                    if prior[k] != 0 {
                        g[k] = self.beam.cache.prior_gain[free.free_step(d[k])];
                    } else {
                        self.prefetch(first + k);
                        self.push(first + k, free.free_offset(d[k]), w);
                    }
                }
                self.total += w * pairwise_sum(&g);
                return;
            }
            // Fewer than `BATCH` wait, so the block fits; the `min` only
            // tells the compiler so.
            let q = &mut self.queue;
            let at = q.len.min(BATCH);
            let slots = at..at + ROW_BLOCK;
            for (k, ((cell, offset), weight)) in q.cell[slots.clone()]
                .iter_mut()
                .zip(&mut q.offset[slots.clone()])
                .zip(&mut q.weight[slots])
                .enumerate()
            {
                (*cell, *offset, *weight) = (first + k, free.free_offset(d[k]), w);
            }
            match self.rows.entropy.get(first..first + ROW_BLOCK) {
                Some(e) => q.entropy[at..at + ROW_BLOCK].copy_from_slice(e),
                None => q.entropy[at..at + n].copy_from_slice(&self.rows.entropy[first..first + n]),
            }
            q.len = at + n;
            for k in 0..n {
                self.prefetch(first + k);
            }
            if self.queue.len >= BATCH {
                self.flush();
            }
            return;
        }
        for (k, &d) in d[..n].iter().enumerate() {
            if d <= reach_m {
                self.cell(first + k, d, d);
            }
        }
    }
}

/// `sum g`, added in pairs, then pairs of pairs (a short chain of additions).
#[inline(always)]
fn pairwise_sum(g: &[f64; ROW_BLOCK]) -> f64 {
    const { assert!(ROW_BLOCK == 8) };
    ((g[0] + g[1]) + (g[2] + g[3])) + ((g[4] + g[5]) + (g[6] + g[7]))
}

impl CoverageMap {
    /// The kernel table for `range` on this map: the cached one when it
    /// serves, else a new one.
    pub(crate) fn kernel_table(&self, range: &RangeModel) -> Result<Cow<'_, KernelTable>> {
        let resolution = self.grid().resolution_m();
        match self.cached_table() {
            Some(t) if t.serves(range, resolution, self.bins()) => Ok(Cow::Borrowed(t)),
            _ => Ok(Cow::Owned(KernelTable::new(
                range,
                resolution,
                self.bins(),
            )?)),
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
        let d = reading_distribution(&grid, &stop, [1.025, 2.525], 0.0, &range, 0.05).unwrap();
        let total: f64 = d.probabilities.iter().sum::<f64>() + d.no_echo;
        assert!((total - 1.0).abs() < 1e-12);
        assert_eq!(d.no_echo, 0.0, "the full wall stops every beam");
        // The partial cell at x in [3.0, 3.05) reflects 40 %, at 3.05 - 0.4 * 0.05 = 3.03.
        let j = ((3.03 - 1.025) / 0.05f64).round() as usize;
        assert!(
            (d.probabilities[j] - 0.4).abs() < 1e-7,
            "{:?}",
            &d.probabilities[35..45]
        );
        let open =
            reading_distribution(&grid, &vec![0.0; grid.len()], [1.0, 1.0], 0.3, &range, 0.05)
                .unwrap();
        assert_eq!(open.no_echo, 1.0);
    }

    #[test]
    fn fast_equals_exact_on_a_partly_known_map() {
        let grid = Grid::new([0.0, 0.0], 0.1, 50, 70).unwrap();
        let mut map = CoverageMap::new(grid);
        let sonar = SonarModel::default();
        let bearings: Vec<f64> = (0..8).map(|i| i as f64 * 0.785).collect();
        map.integrate(
            &Pose::new(3.0, 2.5, 0.1),
            &[1.2, 2.0, 6.0, 0.7, 1.5, 2.2, 3.0, 0.4],
            &bearings,
            &sonar,
        )
        .unwrap();
        map.integrate(
            &Pose::new(5.0, 2.0, -0.3),
            &[2.5, 1.0, 1.7, 0.9, 5.5, 2.2, 1.0, 0.8],
            &bearings,
            &sonar,
        )
        .unwrap();
        // No band behind the end point: an echo's reach then ends where its
        // free space does, give or take the end band.
        let mut laser_no_band = LaserModel::default();
        laser_no_band.range.band_m = 0.0;
        let mut sonar_no_band = sonar;
        sonar_no_band.range.band_m = 0.0;
        let models: [&dyn SensorModel; 4] = [
            &sonar,
            &LaserModel::default(),
            &laser_no_band,
            &sonar_no_band,
        ];
        for model in models {
            for stop_coverage in [StopCoverage::MaximumLikelihood, StopCoverage::Mean] {
                let options = GainOptions {
                    range_step_m: None,
                    stop_coverage,
                };
                let mut eval = GainEvaluator::new(&map, model, options).unwrap();
                let poses: Vec<Pose> = (0..6)
                    .map(|k| Pose::new(0.4 + 1.1 * k as f64, 1.0 + 0.6 * k as f64, k as f64))
                    .collect();
                let exact = eval.evaluate(&poses, &bearings, GainMethod::Exact).unwrap();
                // Every arithmetic the processor can run.
                for arith in Arith::available() {
                    eval.arith = arith;
                    let fast = eval.evaluate(&poses, &bearings, GainMethod::Fast).unwrap();
                    for (f, e) in fast.iter().zip(&exact) {
                        assert!(*e > 0.0);
                        assert!(
                            (f - e).abs() <= 1e-6 * e.abs(),
                            "{stop_coverage:?}, {arith:?}: fast {f} exact {e}"
                        );
                    }
                }
            }
        }
    }

    /// Every arithmetic the processor can run, for every bin count with a
    /// path of its own (8, 16, 32) and one without (12), equals the exact
    /// evaluator on seeded random maps: cells from nearly uniform to nearly
    /// certain, some at the prior, some with bins far below the rest (which
    /// the map raises to its floor, 1e-30).
    #[test]
    fn every_arithmetic_equals_exact_on_random_maps() {
        let mut state = 0x243f_6a88_85a3_08d3u64;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let grid = Grid::new([0.0, 0.0], 0.1, 24, 28).unwrap();
        for case in 0..24 {
            let bins = [8, 16, 32, 12][case % 4];
            let mut data = Vec::with_capacity(grid.len() * bins);
            for _ in 0..grid.len() {
                let kind = next();
                if kind < 0.2 {
                    data.extend(std::iter::repeat_n(1.0 / bins as f32, bins));
                    continue;
                }
                let sharpness = (1.0 + 40.0 * next()) as i32;
                let mut h: Vec<f32> = (0..bins).map(|_| next().powi(sharpness) as f32).collect();
                if kind > 0.9 {
                    // Bins far below the rest (raised to the map's floor).
                    h.iter_mut().step_by(3).for_each(|v| *v *= 1e-40);
                }
                h[case % bins] += 1e-3;
                let sum: f32 = h.iter().sum();
                data.extend(h.iter().map(|v| v / sum));
            }
            let map = CoverageMap::from_histograms(grid, bins, data).unwrap();
            let mut sonar = SonarModel::default();
            sonar.range.max_range_m = 1.0 + 1.5 * next();
            sonar.opening_angle_rad = 0.1 + 0.8 * next();
            let mut laser = LaserModel::default();
            laser.range.max_range_m = 1.0 + 1.5 * next();
            let models: [&dyn SensorModel; 2] = [&sonar, &laser];
            let poses: Vec<Pose> = (0..3)
                .map(|_| Pose::new(0.05 + 2.7 * next(), 0.05 + 2.3 * next(), 6.0 * next() - 3.0))
                .collect();
            let bearings: Vec<f64> = (0..4).map(|_| 6.4 * next() - 3.2).collect();
            let stop_coverage = if case % 3 == 0 {
                StopCoverage::Mean
            } else {
                StopCoverage::MaximumLikelihood
            };
            for model in models {
                let options = GainOptions {
                    range_step_m: None,
                    stop_coverage,
                };
                let mut eval = GainEvaluator::new(&map, model, options).unwrap();
                let exact = eval.evaluate(&poses, &bearings, GainMethod::Exact).unwrap();
                for arith in Arith::available() {
                    eval.arith = arith;
                    let fast = eval.evaluate(&poses, &bearings, GainMethod::Fast).unwrap();
                    for (f, e) in fast.iter().zip(&exact) {
                        assert!(
                            (f - e).abs() <= 1e-6 * e.abs().max(1e-12),
                            "case {case}, {arith:?}: {f} vs {e}"
                        );
                    }
                }
            }
        }
    }

    /// The AVX-512 batch gives the plain batch's sum, for every bin count it
    /// serves and every queue length, with cells whose normaliser `Z` is
    /// subnormal (which the fast logarithm cannot take) among them.
    #[cfg(target_arch = "x86_64")]
    #[test]
    fn the_avx512_batch_is_the_plain_one() {
        if Arith::detect() != Arith::Avx512 {
            return;
        }
        fn check<const N: usize>() {
            let mut state = 0x9e37_79b9_7f4a_7c15u64;
            let mut next = move || {
                state ^= state << 13;
                state ^= state >> 7;
                state ^= state << 17;
                (state >> 11) as f64 / (1u64 << 53) as f64
            };
            // 40 cells; the last one's mass lies in the last bin.
            let cells = 40;
            let mut h = vec![0.0f32; cells * N];
            for c in 0..cells {
                let row = &mut h[c * N..(c + 1) * N];
                if c == cells - 1 {
                    row[N - 1] = 1.0;
                    continue;
                }
                row.iter_mut()
                    .for_each(|v| *v = (next() as f32).powi(3) + 1e-6);
                let sum: f32 = row.iter().sum();
                row.iter_mut().for_each(|v| *v /= sum);
            }
            let u: Vec<f64> = h.iter().map(|&v| x_ln_x(f64::from(v))).collect();
            let entropy: Vec<f64> = u.chunks(N).map(|r| -r.iter().sum::<f64>()).collect();
            let kernels = 6;
            let mut k = vec![0.0f64; kernels * N];
            for (e, row) in k.chunks_mut(N).enumerate() {
                row.iter_mut().for_each(|v| *v = next() + 0.01);
                let sum: f64 = row.iter().sum();
                row.iter_mut().for_each(|v| *v /= sum);
                // Kernel 0's last bin is subnormal: the last cell's `Z`.
                if e == 0 {
                    row[N - 1] = 1e-310;
                }
            }
            let m: Vec<f64> = k.iter().map(|&v| x_ln_x(v)).collect();
            let (h, u, k, m) = (
                Aligned::from_slice(&h),
                Aligned::from_slice(&u),
                Aligned::from_slice(&k),
                Aligned::from_slice(&m),
            );
            let rows = Rows::<N>::new(&h, &u, &entropy, &k, &m);
            for len in 1..=SLOTS {
                for with_empty in [false, true] {
                    let mut q = Queue::new();
                    for j in 0..len {
                        let i = if with_empty && j % 5 == 2 {
                            cells - 1
                        } else {
                            (j * 7) % (cells - 1)
                        };
                        let e = if with_empty {
                            j % kernels
                        } else {
                            1 + j % (kernels - 1)
                        };
                        (q.cell[j], q.offset[j], q.weight[j], q.entropy[j]) =
                            (i, e * N, next(), entropy[i]);
                    }
                    q.len = len;
                    let plain = weighted_gains_with::<N, BASELINE>(Has::baseline(), &rows, &q);
                    // SAFETY: AVX-512 was detected above.
                    let wide = weighted_gains::<N, AVX512>(unsafe { Has::new() }, &rows, &q);
                    assert!(plain.is_finite(), "{N} bins, {len}: {plain}");
                    assert!(
                        (wide - plain).abs() <= 1e-12 * plain.abs().max(1.0),
                        "{N} bins, {len}: {wide} {plain}"
                    );
                }
            }
        }
        check::<8>();
        check::<16>();
        check::<32>();
    }

    #[test]
    fn a_candidate_gains_the_same_alone_and_in_company() {
        let mut map = CoverageMap::new(Grid::new([0.0, 0.0], 0.1, 40, 50).unwrap());
        let sonar = SonarModel::default();
        let bearings: Vec<f64> = (0..8).map(|i| i as f64 * 0.785).collect();
        map.integrate(
            &Pose::new(2.0, 2.0, 0.3),
            &[1.2, 2.0, 6.0, 0.7, 1.5, 2.2, 3.0, 0.4],
            &bearings,
            &sonar,
        )
        .unwrap();
        let eval = GainEvaluator::new(&map, &sonar, GainOptions::default()).unwrap();
        let poses: Vec<Pose> = (0..40)
            .map(|k| Pose::new(0.3 + 0.12 * k as f64, 0.4 + 0.09 * k as f64, 0.7 * k as f64))
            .collect();
        let together = eval.evaluate(&poses, &bearings, GainMethod::Fast).unwrap();
        for (pose, g) in poses.iter().zip(&together) {
            let alone = eval
                .evaluate(std::slice::from_ref(pose), &bearings, GainMethod::Fast)
                .unwrap();
            assert_eq!(alone[0].to_bits(), g.to_bits());
        }
    }

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
        let mut map = CoverageMap::new(grid);
        let mut laser = LaserModel::default();
        laser.range.max_range_m = 1e12;
        laser.range.sigma_per_m = 0.0;
        laser.range.xi_per_m = 0.0;
        let bearings: Vec<f64> = (0..8).map(|k| f64::from(k) * 0.8).collect();
        map.integrate(
            &Pose::new(2.0, 1.5, 0.1),
            &[1.0, 0.7, 3.0, 0.4, 2.0, 0.9, 1e13, 1.2],
            &bearings,
            &laser,
        )
        .unwrap();
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
