//! The map's storage and what is read out of it: histograms, the ML, mean
//! and entropy maps.

use std::borrow::Cow;

use super::changes::ChangeStamps;
use super::history::History;
use crate::aligned::Aligned;
use crate::error::{CovmapError, Result};
use crate::grid::{Cell, Grid};
use crate::histogram::{self, DEFAULT_BINS};
use crate::memory;
use crate::sensor::{KernelTable, RangeModel};

/// A grid whose every cell holds a histogram over how much of it is covered.
///
/// Storage is one contiguous `f32` array, row-major over cells with the bins of
/// a cell adjacent: cell `i`'s histogram is `[i * bins, (i + 1) * bins)`. At the
/// default 16 bins that is one 64-byte cache line per cell. Beside it, laid out
/// the same way, the evidence the histograms come from: each cell's
/// log-likelihoods, to which an update adds its kernel's logarithms; a
/// histogram is a function of its cell's log-likelihoods alone
/// ([`CoverageMap::evidence`]), so the map after a set of scans is the same,
/// but for rounding, in whatever order they came (the model, section 2).
/// The two take `8 * bins` bytes a cell, 128 at 16 bins.
///
/// Invariants, after any sequence of updates: every histogram sums to 1 within
/// `1e-5`, every bin is finite and at least [`histogram::BIN_FLOOR`].
///
/// # Example
/// ```
/// use covmap_core::{CoverageMap, Grid, LaserModel, Pose, ScanMap};
/// let grid = Grid::new([0.0, 0.0], 0.05, 100, 100).unwrap();
/// let mut map = CoverageMap::new(grid);
/// let laser = LaserModel::default();
/// // One beam along +x from (1, 2.525) that ends at x = 3.04.
/// let updated = map.integrate(&Pose::new(1.0, 2.525, 0.0), &[2.04], &[0.0], &laser).unwrap();
/// assert!(updated > 40);
/// let ml = map.ml();
/// let cell = |x: f64| grid.index(grid.world_to_cell(x, 2.525).unwrap()).unwrap();
/// assert_eq!(ml[cell(2.0)], 0.0); // the beam passed: empty
/// assert_eq!(ml[cell(3.1)], 1.0); // just behind the end point: covered
/// assert!(map.entropy()[cell(2.0)] < map.entropy()[cell(0.5)]); // untouched cells keep the prior
/// ```
#[derive(Clone, Debug)]
pub struct CoverageMap {
    pub(super) grid: Grid,
    pub(super) bins: usize,
    /// The histograms, cell-major, starting on a cache line so that a 16-bin
    /// histogram is exactly one line.
    pub(super) data: Aligned<f32>,
    /// The evidence behind the histograms: each cell's log-likelihoods,
    /// laid out as `data`, shifted so that each cell's largest is 0. The
    /// update adds to them; each histogram is a function of its cell's
    /// ([`histogram::update_log`]).
    pub(super) log: Aligned<f32>,
    /// The last sensor model's kernels, rebuilt when the model changes.
    pub(super) table: Option<Box<KernelTable>>,
    /// Per-cell entropy history, when tracked.
    pub(super) history: Option<Box<History>>,
    /// Which cells changed when: the map's change feed.
    pub(super) changes: ChangeStamps,
}

impl CoverageMap {
    /// A copy of the map, or [`CovmapError::OutOfMemory`](crate::CovmapError::OutOfMemory)
    /// where `clone` would abort the process: the memory of its histograms
    /// is asked for first (twice that with the entropy history kept, more
    /// than the history takes).
    ///
    /// # Errors
    /// [`CovmapError::OutOfMemory`](crate::CovmapError::OutOfMemory) naming
    /// the copy.
    pub fn try_clone(&self) -> Result<Self> {
        // The history takes less than the histograms, the stamps a bin's worth a cell.
        let floats = self.data.len() * if self.history.is_some() { 3 } else { 2 } + self.grid.len();
        drop(crate::memory::try_with_capacity::<f32>(
            floats,
            "a copy of the coverage map",
        )?);
        Ok(self.clone())
    }

    /// A map at the uniform prior with [`DEFAULT_BINS`] bins.
    ///
    /// # Panics
    /// If the histograms and their evidence (128 bytes a cell) cannot be
    /// allocated;
    /// [`Self::with_bins`] returns an error instead.
    #[allow(
        clippy::expect_used,
        reason = "documented under Panics; with_bins is the fallible form"
    )]
    pub fn new(grid: Grid) -> Self {
        Self::with_bins(grid, DEFAULT_BINS)
            .expect("the default bin count is valid and the map fits in memory")
    }

    /// A map at the uniform prior with `bins` bins per cell (2 to 256).
    ///
    /// Errors if the bin count is not supported, or the histograms and
    /// their evidence (`8 * bins` bytes a cell) cannot be allocated.
    pub fn with_bins(grid: Grid, bins: usize) -> Result<Self> {
        histogram::check_bins(bins)?;
        let p = 1.0 / bins as f32;
        let data = Aligned::try_filled(p, grid.len() * bins).ok_or_else(|| {
            memory::out_of_memory::<f32>(
                &format!(
                    "a coverage map of {} x {} cells of {bins} bins",
                    grid.rows(),
                    grid.cols()
                ),
                grid.len() * bins,
            )
        })?;
        let log = Aligned::try_filled(0.0, grid.len() * bins).ok_or_else(|| {
            memory::out_of_memory::<f32>(
                &format!(
                    "the evidence of a coverage map of {} x {} cells of {bins} bins",
                    grid.rows(),
                    grid.cols()
                ),
                grid.len() * bins,
            )
        })?;
        Ok(Self {
            grid,
            bins,
            data,
            log,
            table: None,
            history: None,
            changes: ChangeStamps::new(grid.len())?,
        })
    }

    /// A map from stored histograms (`grid.len() * bins` values, cell-major).
    /// Each histogram must be finite, non-negative and sum to 1 within `1e-3`.
    /// Histograms that already satisfy the map's invariants (sum within `1e-5`
    /// of 1, no bin below the floor) are kept bit for bit, so a map saved and
    /// loaded is the same map; the others are renormalised and floored.
    /// The evidence behind each histogram is taken to be its logarithm: a
    /// bin at the floor holds no more than the floor's 69 nats against it
    /// (a map in memory may hold more), so a loaded map can be revised by
    /// fewer contrary readings than the map that was saved.
    pub fn from_histograms(grid: Grid, bins: usize, mut data: Vec<f32>) -> Result<Self> {
        histogram::check_bins(bins)?;
        if data.len() != grid.len() * bins {
            return Err(CovmapError::LengthMismatch {
                what: "histogram values and grid cells x bins",
                left: data.len(),
                right: grid.len() * bins,
            });
        }
        let floor = histogram::BIN_FLOOR;
        for (i, h) in data.chunks_exact(bins).enumerate() {
            let sum: f32 = h.iter().sum();
            if h.iter().any(|v| !(v.is_finite() && *v >= 0.0)) || (sum - 1.0).abs() > 1e-3 {
                return Err(CovmapError::InvalidHistogram(format!(
                    "cell {i}: bins must be finite, non-negative and sum to 1 (sum {sum})"
                )));
            }
        }
        let uniform = vec![1.0; bins];
        for h in data.chunks_exact_mut(bins) {
            let sum: f32 = h.iter().sum();
            if (sum - 1.0).abs() > 1e-5 || h.iter().any(|&v| v < floor) {
                histogram::update(h, &uniform, floor);
            }
        }
        let mut log = vec![0.0f32; data.len()];
        for (h, l) in data.chunks_exact(bins).zip(log.chunks_exact_mut(bins)) {
            histogram::log_of(h, l);
        }
        Ok(Self {
            grid,
            bins,
            data: Aligned::from_slice(&data),
            log: Aligned::from_slice(&log),
            table: None,
            history: None,
            changes: ChangeStamps::new(grid.len())?,
        })
    }

    /// The kernel table for `range` on this map: the one of the last model
    /// integrated when it serves, else a new one.
    pub(crate) fn kernel_table(&self, range: &RangeModel) -> Result<Cow<'_, KernelTable>> {
        cached_or_new(self.table.as_deref(), range, &self.grid, self.bins)
    }

    /// The grid.
    pub fn grid(&self) -> &Grid {
        &self.grid
    }
    /// Bins per cell.
    pub fn bins(&self) -> usize {
        self.bins
    }
    /// The coverage value of each bin, `b / (bins - 1)`.
    pub fn bin_values(&self) -> Vec<f64> {
        (0..self.bins)
            .map(|b| histogram::bin_value(b, self.bins))
            .collect()
    }
    /// All histograms, cell-major (`grid.len() * bins` values).
    pub fn histograms(&self) -> &[f32] {
        &self.data
    }
    /// One cell's histogram.
    pub fn histogram(&self, cell: Cell) -> Result<&[f32]> {
        let i = self.grid.index(cell)?;
        Ok(&self.data[i * self.bins..(i + 1) * self.bins])
    }

    /// The entropy of the cell at row-major `index`, nats, as
    /// [`CoverageMap::entropy`] computes it.
    ///
    /// # Panics
    /// If `index` is not a cell of the grid.
    pub(crate) fn entropy_at(&self, index: usize) -> f32 {
        histogram::entropy(&self.data[index * self.bins..(index + 1) * self.bins])
    }

    /// The ML coverage of the cell at row-major `index`, as
    /// [`CoverageMap::ml`] computes it.
    ///
    /// # Panics
    /// If `index` is not a cell of the grid.
    pub(crate) fn ml_at(&self, index: usize) -> f32 {
        ml_value(self.bins)(&self.data[index * self.bins..(index + 1) * self.bins])
    }

    /// The maximum-likelihood map: each cell's most probable coverage value.
    ///
    /// Ties go to the lower bin, so a cell still at the uniform prior reads 0:
    /// use [`CoverageMap::entropy`] (`ln(bins)` at the prior) to tell unknown
    /// cells from empty ones.
    pub fn ml(&self) -> Vec<f32> {
        self.cells().map(ml_value(self.bins)).collect()
    }
    /// The mean map: each cell's expected coverage.
    pub fn mean(&self) -> Vec<f32> {
        self.cells().map(histogram::mean).collect()
    }
    /// The entropy map, nats: `ln(bins)` at the prior, 0 when certain.
    pub fn entropy(&self) -> Vec<f32> {
        self.cells().map(histogram::entropy).collect()
    }

    /// [`CoverageMap::ml`], or [`CovmapError::OutOfMemory`] where the
    /// result (4 bytes a cell) cannot be allocated.
    pub fn try_ml(&self) -> Result<Vec<f32>> {
        memory::try_collect(self.cells().map(ml_value(self.bins)), "the ML map")
    }
    /// [`CoverageMap::mean`], or [`CovmapError::OutOfMemory`] where the
    /// result cannot be allocated.
    pub fn try_mean(&self) -> Result<Vec<f32>> {
        memory::try_collect(self.cells().map(histogram::mean), "the mean map")
    }
    /// [`CoverageMap::entropy`], or [`CovmapError::OutOfMemory`] where the
    /// result cannot be allocated.
    pub fn try_entropy(&self) -> Result<Vec<f32>> {
        memory::try_collect(self.cells().map(histogram::entropy), "the entropy map")
    }
    /// A copy of [`CoverageMap::histograms`], or
    /// [`CovmapError::OutOfMemory`] where it cannot be allocated.
    pub fn try_histograms_vec(&self) -> Result<Vec<f32>> {
        memory::try_collect(self.data.iter().copied(), "the histograms")
    }

    /// Each cell's histogram, row-major.
    pub(super) fn cells(&self) -> std::slice::ChunksExact<'_, f32> {
        self.data.chunks_exact(self.bins)
    }
}

/// A histogram's most probable coverage value with `bins` bins (ties to the
/// lower bin).
pub(super) fn ml_value(bins: usize) -> impl Fn(&[f32]) -> f32 {
    let scale = 1.0 / (bins - 1) as f32;
    move |h| histogram::argmax(h) as f32 * scale
}

/// The kernel table for `range` on `grid` with `bins` bins: `cached` when it
/// serves, else a new one.
pub(super) fn cached_or_new<'t>(
    cached: Option<&'t KernelTable>,
    range: &RangeModel,
    grid: &Grid,
    bins: usize,
) -> Result<Cow<'t, KernelTable>> {
    let resolution = grid.resolution_m();
    match cached {
        Some(table) if table.serves(range, resolution, bins) => Ok(Cow::Borrowed(table)),
        _ => KernelTable::new(range, resolution, bins).map(Cow::Owned),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn from_histograms_validates() {
        let g = Grid::new([0.0, 0.0], 0.1, 2, 2).unwrap();
        assert!(CoverageMap::from_histograms(g, 4, vec![0.25; 15]).is_err());
        let mut d = vec![0.25; 16];
        d[3] = f32::NAN;
        assert!(CoverageMap::from_histograms(g, 4, d).is_err());
        let m = CoverageMap::from_histograms(g, 4, vec![0.25; 16]).unwrap();
        assert_eq!(m.entropy()[0], 4f32.ln());
    }

    /// A 16-bin histogram is one cache line, not two halves of neighbours.
    #[test]
    fn histograms_start_on_a_cache_line() {
        let g = Grid::new([0.0, 0.0], 0.1, 7, 9).unwrap();
        let fresh = CoverageMap::new(g);
        let loaded = CoverageMap::from_histograms(g, 16, fresh.histograms().to_vec()).unwrap();
        for map in [&fresh, &loaded, &loaded.clone()] {
            assert_eq!(map.histograms().as_ptr() as usize % 64, 0);
            assert_eq!(map.histograms().len(), 63 * 16);
        }
    }
}
