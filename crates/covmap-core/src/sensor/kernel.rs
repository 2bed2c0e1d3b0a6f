//! The precomputed kernel table: the update loop evaluates no `exp` or `log`.

use super::{RangeModel, kernel_values};
use crate::aligned::Aligned;
use crate::error::{Result, check_parameter};
use crate::grid::MIN_RESOLUTION_M;
use crate::histogram::MAX_BINS;
use crate::numeric::x_ln_x;

/// Slices the end band (one cell deep) is cut into: `mu` is resolved to 1/32.
pub const BAND_SLICES: usize = 32;
/// Steps the distance `s = min(d_l, d)` is cut into, from 0 to `max_range_m`.
pub const DISTANCE_STEPS: usize = 256;
/// Regions in a table.
const REGIONS: usize = BAND_SLICES + 2;

/// Errors unless `resolution_m` is a finite cell size a grid may have (at
/// least [`MIN_RESOLUTION_M`]).
pub(crate) fn check_resolution(resolution_m: f64) -> Result<()> {
    check_parameter(
        resolution_m.is_finite() && resolution_m >= MIN_RESOLUTION_M,
        "resolution_m",
        resolution_m,
        "a finite cell size of at least 1e-6 m",
    )
}

/// Kernels of one [`RangeModel`] for one grid resolution and bin count,
/// quantised on `(region, s)`.
///
/// Region 0 is free space (`mu = 0`), regions `1..=BAND_SLICES` are slices of
/// the end band (each evaluated at its centre), region `BAND_SLICES + 1` is the
/// band behind the end point (`mu = 1`; these mixed with the prior by the
/// model's `end_weight`). A no-echo reading's cells are free space, region 0
/// at `d = max_range_m`. The distance `s` is rounded
/// to the nearest of `DISTANCE_STEPS + 1` steps; `sigma` and `xi` are linear
/// in `s`, so the quantisation moves them by at most half a step's worth.
///
/// Memory: `(BAND_SLICES + 2) * (DISTANCE_STEPS + 1) * bins` kernel values,
/// 139 808 at 16 bins: 546 KiB in `f32` and as much for their logarithms
/// for the update (of which the free-space row it reads most is 16 KiB),
/// and twice 1.1 MiB in `f64` (the values and their `k ln k`) for the
/// expected gain, 3.2 MiB in all.
#[derive(Clone, Debug)]
pub struct KernelTable {
    model: RangeModel,
    resolution_m: f64,
    bins: usize,
    /// Inverse of the `s` step, 1/m.
    inv_step_s: f64,
    /// Inverse of a band slice's depth, 1/m.
    inv_slice: f64,
    /// `[region][s][bin]`, each kernel normalised to sum 1.
    values: Vec<f32>,
    /// The logarithm of every value of `values`, as laid out there: what
    /// the update adds to a cell's log-likelihoods.
    ln_values: Vec<f32>,
    /// Every value `k` in `f64`, and `k ln k`, for the entropies of updated
    /// histograms ([`crate::gain`]), from the start of a cache line (so that
    /// a 16-bin kernel's eight-value halves never straddle two).
    values_f64: Aligned<f64>,
    k_ln_k: Aligned<f64>,
}

impl KernelTable {
    /// Tabulate `model` for a grid of `resolution_m` with `bins` bins.
    pub fn new(model: &RangeModel, resolution_m: f64, bins: usize) -> Result<Self> {
        model.validate()?;
        check_resolution(resolution_m)?;
        crate::histogram::check_bins(bins)?;
        debug_assert!(bins <= MAX_BINS);
        let step_s = model.max_range_m / DISTANCE_STEPS as f64;
        let slice = resolution_m / BAND_SLICES as f64;
        let mut values = Vec::with_capacity(REGIONS * (DISTANCE_STEPS + 1) * bins);
        for region in 0..REGIONS {
            for step in 0..=DISTANCE_STEPS {
                let s = step as f64 * step_s;
                let (mu, sigma) = match region {
                    0 => (0.0, model.sigma(s)),
                    r if r <= BAND_SLICES => {
                        let o = -0.5 * resolution_m + (r as f64 - 0.5) * slice;
                        (0.5 + o / resolution_m, model.sigma_end)
                    }
                    _ => (1.0, model.sigma(s)),
                };
                let mut k = kernel_values(mu, sigma, model.xi(s), bins);
                if region > 0 {
                    k = model.end_mixture(k);
                }
                values.extend(k.into_iter().map(|v| v as f32));
            }
        }
        let (mut values_f64, mut k_ln_k) =
            (Aligned::zeroed(values.len()), Aligned::zeroed(values.len()));
        for ((k, m), &v) in values_f64.iter_mut().zip(k_ln_k.iter_mut()).zip(&values) {
            *k = f64::from(v);
            *m = x_ln_x(*k);
        }
        let ln_values = values.iter().map(|v| v.ln()).collect();
        Ok(Self {
            model: *model,
            resolution_m,
            bins,
            inv_step_s: 1.0 / step_s,
            inv_slice: 1.0 / slice,
            values,
            ln_values,
            values_f64,
            k_ln_k,
        })
    }

    /// The model this table was made from.
    pub fn model(&self) -> &RangeModel {
        &self.model
    }
    /// The grid resolution it was made for, metres.
    pub fn resolution_m(&self) -> f64 {
        self.resolution_m
    }
    /// Bins per kernel.
    pub fn bins(&self) -> usize {
        self.bins
    }
    /// Whether this table serves `model` on a grid of `resolution_m` with `bins`.
    pub fn serves(&self, model: &RangeModel, resolution_m: f64, bins: usize) -> bool {
        self.model == *model && self.resolution_m == resolution_m && self.bins == bins
    }

    /// The lookup for one reading `d` (clamped to the maximum range), `echo`
    /// false for a no-echo reading.
    #[inline(always)]
    pub(crate) fn reading(&self, d: f64, echo: bool) -> ReadingLookup {
        let half = 0.5 * self.resolution_m;
        ReadingLookup {
            // step(d_l) = min(d_l, d) / step_s, rounded.
            inv_step_s: self.inv_step_s,
            d,
            // slice(d_l) = (d_l - d + r/2) / slice depth; negative: free.
            slice_per_m: if echo { self.inv_slice } else { 0.0 },
            slice_at_zero: if echo {
                (half - d) * self.inv_slice
            } else {
                -1.0
            },
            bins: self.bins,
        }
    }

    /// The kernel at a table offset from [`ReadingLookup::offset`].
    #[inline(always)]
    pub(crate) fn at(&self, offset: usize) -> &[f32] {
        &self.values[offset..offset + self.bins]
    }

    /// The logarithms of the kernel at a table offset from
    /// [`ReadingLookup::offset`].
    #[inline(always)]
    pub(crate) fn ln_at(&self, offset: usize) -> &[f32] {
        &self.ln_values[offset..offset + self.bins]
    }

    /// Every kernel in `f64`, one after the other (a kernel's offset is
    /// [`ReadingLookup::offset`]).
    pub(crate) fn values_f64(&self) -> &[f64] {
        &self.values_f64
    }

    /// `k ln k` of every bin of every kernel, laid out as [`Self::values_f64`].
    pub(crate) fn k_ln_k(&self) -> &[f64] {
        &self.k_ln_k
    }

    /// The kernel the update multiplies in for a cell at `cell_distance_m` and a
    /// reading of `measured_distance_m`, or `None` where the cell is not updated.
    pub fn kernel_at(&self, cell_distance_m: f64, measured_distance_m: f64) -> Option<Vec<f32>> {
        let (reach, echo) = self.model.reach(measured_distance_m);
        if !(cell_distance_m <= reach) {
            return None;
        }
        let d = measured_distance_m.min(self.model.max_range_m);
        Some(
            self.at(self.reading(d, echo).offset(cell_distance_m))
                .to_vec(),
        )
    }
}

/// The kernel lookup for one reading, with everything that depends only on it
/// computed once per beam.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ReadingLookup {
    inv_step_s: f64,
    d: f64,
    slice_per_m: f64,
    slice_at_zero: f64,
    bins: usize,
}

impl ReadingLookup {
    /// Whether a cell at `d_l` lies in front of the end point's cell (free
    /// space) for this reading: the test [`ReadingLookup::offset`] makes.
    #[inline(always)]
    pub(crate) fn is_free(&self, d_l: f64) -> bool {
        d_l * self.slice_per_m + self.slice_at_zero < 0.0
    }

    /// Offset in the table of the kernel for a cell at `d_l` metres.
    #[inline(always)]
    pub(crate) fn offset(&self, d_l: f64) -> usize {
        // Clamped in floating point first, so that each conversion is a plain
        // truncation of a value known to fit.
        let slice = d_l * self.slice_per_m + self.slice_at_zero;
        if slice < 0.0 {
            return self.free_offset(d_l);
        }
        let region = if slice <= BAND_SLICES as f64 {
            1 + (slice as i32 as usize).min(BAND_SLICES - 1)
        } else {
            BAND_SLICES + 1
        };
        region * (DISTANCE_STEPS + 1) * self.bins + self.free_step(d_l) * self.bins
    }

    /// [`ReadingLookup::offset`] for a cell in free space (`is_free`, or any
    /// cell of a no-echo reading): region 0.
    #[inline(always)]
    pub(crate) fn free_offset(&self, d_l: f64) -> usize {
        self.free_step(d_l) * self.bins
    }

    /// The distance step of [`ReadingLookup::free_offset`]: the index of the
    /// kernel among its region's `DISTANCE_STEPS + 1`, and so among all the
    /// table's kernels (region 0's come first).
    #[inline(always)]
    pub(crate) fn free_step(&self, d_l: f64) -> usize {
        // Clamped by comparisons (which become plain vector min and max; a
        // NaN distance, which valid input never gives, reads as `self.d`).
        let s = if d_l < self.d { d_l } else { self.d };
        let s = if s > 0.0 { s } else { 0.0 };
        let step = s * self.inv_step_s + 0.5;
        let steps = DISTANCE_STEPS as f64;
        (if step < steps { step } else { steps }) as i32 as usize
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sensor::{LaserModel, SonarModel};

    /// The table agrees with the exact model to within its quantisation.
    #[test]
    fn table_matches_exact_kernel() {
        let mut weak_end = SonarModel::default().range;
        weak_end.end_weight = 0.3;
        for model in [
            SonarModel::default().range,
            LaserModel::default().range,
            weak_end,
        ] {
            for bins in [8, 16, 33] {
                let r = 0.05;
                let table = KernelTable::new(&model, r, bins).unwrap();
                let mut worst = 0.0f64;
                for i in 0..400 {
                    let d = model.max_range_m * (i as f64 * 0.618_034).fract() * 1.05;
                    for j in 0..60 {
                        let d_l = (d + model.band_m) * j as f64 / 59.0;
                        let exact = model.kernel_exact(d_l, d, r, bins).unwrap();
                        let table = table.kernel_at(d_l, d);
                        assert_eq!(exact.is_some(), table.is_some(), "d_l {d_l} d {d}");
                        let (Some(e), Some(t)) = (exact, table) else {
                            continue;
                        };
                        for (a, b) in e.iter().zip(&t) {
                            worst = worst.max((a - *b as f64).abs());
                        }
                    }
                }
                // A band slice moves mu by 1/64 at most; a distance step moves
                // sigma and xi by half a step. Kernels sum to 1.
                assert!(worst < 0.02, "bins {bins}: worst kernel difference {worst}");
            }
        }
    }

    #[test]
    fn kernels_are_positive_and_normalised() {
        let table = KernelTable::new(&SonarModel::default().range, 0.05, 16).unwrap();
        for k in table.values.chunks(16) {
            assert!(k.iter().all(|&v| v > 0.0 && v.is_finite()));
            let sum: f32 = k.iter().sum();
            assert!((sum - 1.0).abs() < 1e-5);
        }
    }

    /// Both kernel queries validate what the table validates, and the
    /// distances.
    #[test]
    fn kernel_queries_reject_bad_input() {
        let model = SonarModel::default().range;
        assert!(model.kernel_exact(1.0, 2.0, 0.05, 16).unwrap().is_some());
        for (d_l, d, r, bins) in [
            (f64::NAN, 2.0, 0.05, 16),
            (1.0, f64::NAN, 0.05, 16),
            (-0.1, 2.0, 0.05, 16),
            (1.0, 2.0, 0.0, 16),
            (1.0, 2.0, 0.05, 1),
        ] {
            assert!(
                model.kernel_exact(d_l, d, r, bins).is_err(),
                "{d_l} {d} {r} {bins}"
            );
            assert!(
                model.kernel(d_l, d, r, bins).is_err(),
                "{d_l} {d} {r} {bins}"
            );
        }
    }

    #[test]
    fn far_region_is_not_updated() {
        let table = KernelTable::new(&SonarModel::default().range, 0.05, 16).unwrap();
        assert!(table.kernel_at(2.21, 2.0).is_none());
        assert!(table.kernel_at(2.19, 2.0).is_some());
        // No echo: clear up to the maximum range, never beyond.
        assert!(table.kernel_at(4.99, 7.0).is_some());
        assert!(table.kernel_at(5.01, 7.0).is_none());
    }
}
