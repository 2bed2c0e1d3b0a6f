//! The coverage map: one histogram over coverage values per cell.

use std::borrow::Cow;

use crate::aligned::Aligned;
use crate::error::{CovmapError, Result};
use crate::footprint::{CellVisitor, visit};
use crate::grid::{Cell, Grid};
use crate::histogram::{self, DEFAULT_BINS};
use crate::scan::{Pose, validate_scan};
use crate::sensor::{KernelTable, RangeModel, ReadingLookup, SensorModel};

/// A grid whose every cell holds a histogram over how much of it is covered.
///
/// Storage is one contiguous `f32` array, row-major over cells with the bins of
/// a cell adjacent: cell `i`'s histogram is `[i * bins, (i + 1) * bins)`. At the
/// default 16 bins that is one 64-byte cache line per cell.
///
/// Invariants, after any sequence of updates: every histogram sums to 1 within
/// `1e-5`, every bin is finite and at least [`histogram::bin_floor`].
///
/// # Example
/// ```
/// use covmap_core::{CoverageMap, Grid, LaserModel, Pose};
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
    grid: Grid,
    bins: usize,
    floor: f32,
    /// The histograms, cell-major, starting on a cache line so that a 16-bin
    /// histogram is exactly one line.
    data: Aligned<f32>,
    /// The last sensor model's kernels, rebuilt when the model changes.
    table: Option<Box<KernelTable>>,
    /// Per-cell entropy history, when tracked.
    history: Option<Box<History>>,
}

/// Measurements of a cell an entropy change is judged over.
pub const STAGNATION_MEASUREMENTS: usize = 5;
/// Entropy change (nats) below which a cell has stagnated.
pub const STAGNATION_NATS: f32 = 0.001;

/// The entropies of each cell after its last measurements, for the paper's
/// termination rule.
#[derive(Clone, Debug)]
struct History {
    /// A ring of the last `STAGNATION_MEASUREMENTS + 1` entropies of each cell.
    entropies: Vec<[f32; STAGNATION_MEASUREMENTS + 1]>,
    /// Measurements of each cell so far.
    count: Vec<u32>,
    /// The scan that last touched each cell.
    stamp: Vec<u32>,
    scan: u32,
}

/// The persistent part of a map's entropy history, to save a map with it and
/// load it again ([`CoverageMap::history_state`],
/// [`CoverageMap::restore_history`]).
///
/// Cell `i`'s last `STAGNATION_MEASUREMENTS + 1` entropies are a ring at
/// `entropies[i * (STAGNATION_MEASUREMENTS + 1)..][..STAGNATION_MEASUREMENTS + 1]`:
/// slot `k` holds the entropy (nats) after the cell's measurement `n`
/// (counting from 0) with `n % (STAGNATION_MEASUREMENTS + 1) == k`, and slots
/// not written yet hold 0. `count[i]` is the number of measurements of cell
/// `i`. Both are row-major over the cells.
///
/// # Example
/// ```
/// use covmap_core::{CoverageMap, Grid, LaserModel, Pose};
/// let grid = Grid::new([0.0, 0.0], 0.05, 4, 40).unwrap();
/// let mut map = CoverageMap::new(grid);
/// map.track_history(true);
/// map.integrate(&Pose::new(0.01, 0.1, 0.0), &[1.0], &[0.0], &LaserModel::default()).unwrap();
/// let state = map.history_state().unwrap();
/// // Saved and loaded: the histograms and the history.
/// let mut loaded = CoverageMap::from_histograms(grid, map.bins(), map.histograms().to_vec()).unwrap();
/// loaded.restore_history(state.clone()).unwrap();
/// assert!(loaded.tracks_history());
/// assert_eq!(loaded.measurement_counts(), map.measurement_counts());
/// assert_eq!(loaded.history_state(), Some(state));
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct HistoryState {
    /// Each cell's ring of its last `STAGNATION_MEASUREMENTS + 1` entropies,
    /// nats, `grid.len() * (STAGNATION_MEASUREMENTS + 1)` values.
    pub entropies: Vec<f32>,
    /// Measurements of each cell, `grid.len()` values.
    pub count: Vec<u32>,
}

impl CoverageMap {
    /// A map at the uniform prior with [`DEFAULT_BINS`] bins.
    ///
    /// # Panics
    /// If the histograms (64 bytes a cell) cannot be allocated;
    /// [`Self::with_bins`] returns an error instead.
    pub fn new(grid: Grid) -> Self {
        Self::with_bins(grid, DEFAULT_BINS)
            .expect("the default bin count is valid and the map fits in memory")
    }

    /// A map at the uniform prior with `bins` bins per cell (2 to 256).
    ///
    /// Errors if the bin count is not supported, or the histograms
    /// (`4 * bins` bytes a cell) cannot be allocated.
    pub fn with_bins(grid: Grid, bins: usize) -> Result<Self> {
        histogram::check_bins(bins)?;
        let p = 1.0 / bins as f32;
        let data = Aligned::try_filled(p, grid.len() * bins).ok_or_else(|| {
            CovmapError::InvalidGrid(format!(
                "{} x {} cells of {bins} bins need {} bytes, more than can be allocated",
                grid.rows(),
                grid.cols(),
                grid.len() as u128 * bins as u128 * 4
            ))
        })?;
        Ok(Self {
            grid,
            bins,
            floor: histogram::bin_floor(bins),
            data,
            table: None,
            history: None,
        })
    }

    /// A map from stored histograms (`grid.len() * bins` values, cell-major).
    /// Each histogram must be finite, non-negative and sum to 1 within `1e-3`.
    /// Histograms that already satisfy the map's invariants (sum within `1e-5`
    /// of 1, no bin below the floor) are kept bit for bit, so a map saved and
    /// loaded is the same map; the others are renormalised and floored.
    pub fn from_histograms(grid: Grid, bins: usize, mut data: Vec<f32>) -> Result<Self> {
        histogram::check_bins(bins)?;
        if data.len() != grid.len() * bins {
            return Err(CovmapError::LengthMismatch {
                what: "histogram values and grid cells x bins",
                left: data.len(),
                right: grid.len() * bins,
            });
        }
        let floor = histogram::bin_floor(bins);
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
        Ok(Self {
            grid,
            bins,
            floor,
            data: Aligned::from_slice(&data),
            table: None,
            history: None,
        })
    }

    /// The kernel table of the last model integrated, if any.
    pub(crate) fn cached_table(&self) -> Option<&KernelTable> {
        self.table.as_deref()
    }

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

    /// The maximum-likelihood map: each cell's most probable coverage value.
    ///
    /// Ties go to the lower bin, so a cell still at the uniform prior reads 0:
    /// use [`CoverageMap::entropy`] (`ln(bins)` at the prior) to tell unknown
    /// cells from empty ones.
    pub fn ml(&self) -> Vec<f32> {
        let scale = 1.0 / (self.bins - 1) as f32;
        self.data
            .chunks_exact(self.bins)
            .map(|h| histogram::argmax(h) as f32 * scale)
            .collect()
    }
    /// The mean map: each cell's expected coverage.
    pub fn mean(&self) -> Vec<f32> {
        self.data
            .chunks_exact(self.bins)
            .map(histogram::mean)
            .collect()
    }
    /// The entropy map, nats: `ln(bins)` at the prior, 0 when certain.
    pub fn entropy(&self) -> Vec<f32> {
        self.data
            .chunks_exact(self.bins)
            .map(histogram::entropy)
            .collect()
    }

    /// Integrate one scan taken from `pose`: reading `ranges[i]` (metres) along
    /// `pose.theta_rad + bearings[i]`. Returns the number of cell updates.
    ///
    /// Everything is validated before anything changes: a non-finite pose, a
    /// pose outside the map, a NaN, infinite or negative range, a non-finite
    /// bearing, mismatched lengths or an invalid model is an error and leaves
    /// the map exactly as it was. Beams leaving the map update the part inside.
    pub fn integrate<M: SensorModel + ?Sized>(
        &mut self,
        pose: &Pose,
        ranges: &[f64],
        bearings: &[f64],
        model: &M,
    ) -> Result<usize> {
        model.validate()?;
        validate_scan(&self.grid, pose, ranges, bearings)?;
        let range = model.range_model();
        let resolution = self.grid.resolution_m();
        if !self
            .table
            .as_ref()
            .is_some_and(|t| t.serves(range, resolution, self.bins))
        {
            self.table = Some(Box::new(KernelTable::new(range, resolution, self.bins)?));
        }
        // Pick the update once per scan, so the per-cell loop is straight code.
        let updates = match self.bins {
            8 => self.apply::<8, M>(pose, ranges, bearings, model),
            16 => self.apply::<16, M>(pose, ranges, bearings, model),
            32 => self.apply::<32, M>(pose, ranges, bearings, model),
            _ => self.apply::<0, M>(pose, ranges, bearings, model),
        };
        if self.history.is_some() {
            self.record_history(pose, ranges, bearings, model);
        }
        Ok(updates)
    }

    /// Keep (or stop keeping) each cell's entropy after its last measurements,
    /// for [`CoverageMap::stagnated`]. A scan that updates a cell counts as one
    /// measurement of it, however many of its beams do. Off by default: it
    /// costs an entropy per touched cell per scan. Turning it on starts an
    /// empty history.
    pub fn track_history(&mut self, on: bool) {
        self.history = on.then(|| {
            Box::new(History {
                entropies: vec![[0.0; STAGNATION_MEASUREMENTS + 1]; self.grid.len()],
                count: vec![0; self.grid.len()],
                stamp: vec![0; self.grid.len()],
                scan: 0,
            })
        });
    }

    /// Whether the history is kept.
    pub fn tracks_history(&self) -> bool {
        self.history.is_some()
    }

    /// Measurements of `cell` since the history was turned on (0 while it is
    /// off).
    pub fn measurements(&self, cell: Cell) -> Result<u32> {
        let i = self.grid.index(cell)?;
        Ok(self.history.as_ref().map_or(0, |h| h.count[i]))
    }

    /// Measurements of every cell since the history was turned on, row-major.
    pub fn measurement_counts(&self) -> Vec<u32> {
        self.history
            .as_ref()
            .map_or_else(|| vec![0; self.grid.len()], |h| h.count.clone())
    }

    /// The entropy history (`None` while it is off), to be handed to
    /// [`CoverageMap::restore_history`] of a map loaded from this one's
    /// histograms.
    pub fn history_state(&self) -> Option<HistoryState> {
        self.history.as_ref().map(|h| HistoryState {
            entropies: h.entropies.as_flattened().to_vec(),
            count: h.count.clone(),
        })
    }

    /// Track the history and make it `state` (from
    /// [`CoverageMap::history_state`] of a map with the same grid), so that
    /// further scans continue it as they would have continued the original.
    ///
    /// A state whose lengths do not fit the grid, or with an entropy that is
    /// not finite and non-negative, is an error and leaves the map exactly as
    /// it was.
    pub fn restore_history(&mut self, state: HistoryState) -> Result<()> {
        const LEN: usize = STAGNATION_MEASUREMENTS + 1;
        let cells = self.grid.len();
        if state.count.len() != cells {
            return Err(CovmapError::LengthMismatch {
                what: "history measurement counts and grid cells",
                left: state.count.len(),
                right: cells,
            });
        }
        if state.entropies.len() != cells * LEN {
            return Err(CovmapError::LengthMismatch {
                what: "history entropies and grid cells x (STAGNATION_MEASUREMENTS + 1)",
                left: state.entropies.len(),
                right: cells * LEN,
            });
        }
        // No histogram's entropy exceeds the prior's, `ln bins` (with room
        // for the rounding of an `f32` entropy).
        let most = (self.bins as f32).ln() * (1.0 + 1e-5) + 1e-6;
        let impossible = |v: &f32| !(v.is_finite() && *v >= 0.0 && *v <= most);
        if let Some((i, &value)) = state
            .entropies
            .iter()
            .enumerate()
            .find(|(_, v)| impossible(v))
        {
            return Err(CovmapError::InvalidHistory {
                cell: i / LEN,
                value: f64::from(value),
            });
        }
        let entropies = state
            .entropies
            .chunks_exact(LEN)
            .map(|ring| std::array::from_fn(|k| ring[k]))
            .collect();
        // No scan of this map has stamped a cell yet: the per-scan bookkeeping starts afresh.
        self.history = Some(Box::new(History {
            entropies,
            count: state.count,
            stamp: vec![0; cells],
            scan: 0,
        }));
        Ok(())
    }

    /// Whether `cell`'s entropy changed by less than [`STAGNATION_NATS`] over
    /// its last [`STAGNATION_MEASUREMENTS`] measurements (false while the
    /// history is off or too short).
    pub fn stagnated(&self, cell: Cell) -> Result<bool> {
        Ok(self.stagnated_at(self.grid.index(cell)?))
    }

    /// [`CoverageMap::stagnated`] for every cell, row-major.
    pub fn stagnation(&self) -> Vec<bool> {
        (0..self.grid.len()).map(|i| self.stagnated_at(i)).collect()
    }

    /// [`CoverageMap::stagnated`] by row-major index (below `grid.len()`).
    pub(crate) fn stagnated_at(&self, index: usize) -> bool {
        let Some(h) = &self.history else { return false };
        let n = h.count[index] as usize;
        if n <= STAGNATION_MEASUREMENTS {
            return false;
        }
        let ring = &h.entropies[index];
        let len = STAGNATION_MEASUREMENTS + 1;
        (ring[(n - 1) % len] - ring[(n - 1 - STAGNATION_MEASUREMENTS) % len]).abs()
            < STAGNATION_NATS
    }

    fn record_history<M: SensorModel + ?Sized>(
        &mut self,
        pose: &Pose,
        ranges: &[f64],
        bearings: &[f64],
        model: &M,
    ) {
        let Self {
            grid,
            bins,
            data,
            history,
            ..
        } = self;
        let Some(h) = history.as_deref_mut() else {
            return;
        };
        h.scan = h.scan.wrapping_add(1).max(1);
        let scan = h.scan;
        let range = model.range_model();
        let mut touched = Vec::new();
        for (&r, &bearing) in ranges.iter().zip(bearings) {
            let (reach, _) = range.reach(r);
            visit(
                grid,
                [pose.x_m, pose.y_m],
                pose.theta_rad + bearing,
                reach,
                model.footprint(),
                &mut |i, _| {
                    if h.stamp[i] != scan {
                        h.stamp[i] = scan;
                        touched.push(i);
                    }
                },
            );
        }
        let len = STAGNATION_MEASUREMENTS + 1;
        for i in touched {
            let n = h.count[i] as usize;
            h.entropies[i][n % len] = histogram::entropy(&data[i * *bins..(i + 1) * *bins]);
            h.count[i] = h.count[i].saturating_add(1);
        }
    }

    /// Multiply the kernels of a validated scan into the map, `N` bins per
    /// cell (`N = 0`: any number).
    fn apply<const N: usize, M: SensorModel + ?Sized>(
        &mut self,
        pose: &Pose,
        ranges: &[f64],
        bearings: &[f64],
        model: &M,
    ) -> usize {
        let Self {
            grid,
            bins,
            floor,
            data,
            table,
            ..
        } = self;
        let Some(table) = table.as_deref() else {
            return 0;
        };
        let range = model.range_model();
        let footprint = model.footprint();
        let mut updates = 0;
        for (&r, &bearing) in ranges.iter().zip(bearings) {
            let (reach, echo) = range.reach(r);
            let mut beam = BeamUpdate::<N> {
                data,
                table,
                bins: *bins,
                floor: *floor,
                lookup: table.reading(r.min(range.max_range_m), echo),
                updates: 0,
            };
            visit(
                grid,
                [pose.x_m, pose.y_m],
                pose.theta_rad + bearing,
                reach,
                footprint,
                &mut beam,
            );
            updates += beam.updates;
        }
        updates
    }
}

/// The per-cell work of one beam: look the kernel up, multiply it in.
struct BeamUpdate<'a, const N: usize> {
    data: &'a mut [f32],
    table: &'a KernelTable,
    bins: usize,
    floor: f32,
    lookup: ReadingLookup,
    updates: usize,
}

impl<const N: usize> CellVisitor for BeamUpdate<'_, N> {
    #[inline(always)]
    fn cell(&mut self, index: usize, d_l: f64, _enter_m: f64) {
        let h = &mut self.data[index * self.bins..(index + 1) * self.bins];
        let k = self.table.at(self.lookup.offset(d_l));
        if N == 0 {
            histogram::update_any(h, k, self.floor)
        } else {
            histogram::update_fixed::<N>(h, k, self.floor)
        }
        self.updates += 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sensor::{LaserModel, SonarModel};

    fn grid() -> Grid {
        Grid::new([0.0, 0.0], 0.05, 60, 80).unwrap()
    }

    #[test]
    fn bad_input_leaves_map_unchanged() {
        let mut map = CoverageMap::new(grid());
        let sonar = SonarModel::default();
        map.integrate(&Pose::new(2.0, 1.5, 0.3), &[1.0, 2.0], &[0.0, 1.0], &sonar)
            .unwrap();
        let before = map.histograms().to_vec();
        let p = Pose::new(2.0, 1.5, 0.0);
        let cases: Vec<(Pose, Vec<f64>, Vec<f64>)> = vec![
            (p, vec![1.0, f64::NAN], vec![0.0, 1.0]),
            (p, vec![1.0, -0.1], vec![0.0, 1.0]),
            (p, vec![f64::INFINITY], vec![0.0]),
            (p, vec![1.0], vec![f64::NAN]),
            (p, vec![1.0, 2.0], vec![0.0]),
            (Pose::new(f64::NAN, 1.0, 0.0), vec![1.0], vec![0.0]),
            (Pose::new(1.0, 1.0, f64::INFINITY), vec![1.0], vec![0.0]),
            (Pose::new(-0.01, 1.0, 0.0), vec![1.0], vec![0.0]),
            (Pose::new(4.0, 1.0, 0.0), vec![1.0], vec![0.0]),
            // Heading plus bearing overflows.
            (Pose::new(2.0, 1.5, 1e308), vec![1.0], vec![1e308]),
        ];
        for (pose, r, b) in cases {
            assert!(
                map.integrate(&pose, &r, &b, &sonar).is_err(),
                "{pose:?} {r:?} {b:?}"
            );
            assert_eq!(map.histograms(), &before[..]);
        }
        // Parameters of the right sign whose kernels cannot be computed: a
        // subnormal sigma overflows the density's scale, a huge uniform
        // weight the normalising sum.
        // Each error names the parameter at fault.
        type Break = (fn(&mut SonarModel), &'static str);
        let breaks: [Break; 5] = [
            (|m| m.range.sigma_min = -1.0, "sigma_min"),
            (
                |m| (m.range.sigma_min, m.range.sigma_per_m) = (1e-310, 0.0),
                "sigma_min",
            ),
            (
                |m| (m.range.xi_min, m.range.xi_per_m) = (2e6, 0.0),
                "xi_min",
            ),
            (|m| m.range.xi_min = 1e308, "xi_min"),
            (|m| m.range.xi_per_m = 1e306, "xi_per_m"),
        ];
        for (brk, at_fault) in breaks {
            let mut bad = sonar;
            brk(&mut bad);
            let err = map.integrate(&p, &[1.0], &[0.0], &bad).unwrap_err();
            assert!(
                matches!(err, CovmapError::InvalidParameter { name, .. } if name == at_fault),
                "{err}"
            );
            assert_eq!(map.histograms(), &before[..]);
        }
    }

    #[test]
    fn a_million_identical_readings_leave_no_zero_bin() {
        let g = Grid::new([0.0, 0.0], 0.05, 4, 40).unwrap();
        let mut map = CoverageMap::new(g);
        let laser = LaserModel::default();
        let pose = Pose::new(0.01, 0.1, 0.0);
        let ranges = vec![1.0; 1000];
        let bearings = vec![0.0; 1000];
        for _ in 0..1000 {
            map.integrate(&pose, &ranges, &bearings, &laser).unwrap();
        }
        for h in map.histograms().chunks_exact(16) {
            assert!(h.iter().all(|&v| v > 0.0 && v.is_finite()));
            assert!((h.iter().sum::<f32>() - 1.0).abs() < 1e-5);
        }
        // And a cell that has seen a million "empty" readings still changes its
        // mind when the world changes.
        let cell = g.world_to_cell(0.5, 0.1).unwrap();
        assert_eq!(map.ml()[g.index(cell).unwrap()], 0.0);
        let short = vec![0.49; 100];
        map.integrate(&pose, &short, &bearings[..100], &laser)
            .unwrap();
        assert!(map.mean()[g.index(cell).unwrap()] > 0.5);
    }

    #[test]
    fn model_change_rebuilds_kernels() {
        let mut a = CoverageMap::new(grid());
        let mut b = CoverageMap::new(grid());
        let p = Pose::new(2.0, 1.5, 0.0);
        let sonar = SonarModel::default();
        let mut wide = sonar;
        wide.range.xi_min = 0.5;
        a.integrate(&p, &[1.0], &[0.0], &sonar).unwrap();
        a.integrate(&p, &[1.0], &[0.0], &wide).unwrap();
        b.integrate(&p, &[1.0], &[0.0], &wide).unwrap();
        b.integrate(&p, &[1.0], &[0.0], &sonar).unwrap();
        for (x, y) in a.histograms().iter().zip(b.histograms()) {
            assert!((x - y).abs() < 1e-6);
        }
    }

    #[test]
    fn stagnation_needs_five_measurements_of_little_change() {
        let g = Grid::new([0.0, 0.0], 0.05, 4, 40).unwrap();
        let mut map = CoverageMap::new(g);
        map.track_history(true);
        let laser = LaserModel::default();
        let pose = Pose::new(0.01, 0.1, 0.0);
        let cell = g.world_to_cell(0.5, 0.1).unwrap();
        for k in 0..5 {
            map.integrate(&pose, &[1.0], &[0.0], &laser).unwrap();
            assert_eq!(map.measurements(cell).unwrap(), k + 1);
            assert!(
                !map.stagnated(cell).unwrap(),
                "not after {} measurements",
                k + 1
            );
        }
        // Many readings per scan: the cell's entropy has settled.
        for _ in 0..40 {
            map.integrate(&pose, &vec![1.0; 50], &[0.0; 50], &laser)
                .unwrap();
        }
        assert!(map.stagnated(cell).unwrap());
        let all = map.stagnation();
        for (i, &stagnated) in all.iter().enumerate() {
            assert_eq!(stagnated, map.stagnated(g.cell(i)).unwrap());
        }
        assert!(
            all.iter().any(|&s| !s),
            "cells the beam never reached have no history"
        );
        let untouched = g.world_to_cell(1.9, 0.1).unwrap();
        assert_eq!(map.measurements(untouched).unwrap(), 0);
        assert!(!map.stagnated(untouched).unwrap());
        assert!(map.stagnated(Cell { row: 4, col: 0 }).is_err());
    }

    /// The scans of the history tests: one beam, then many beams per scan, so
    /// that the cells along the beam settle and stagnate.
    fn settling_scans(map: &mut CoverageMap, scans: std::ops::Range<usize>) {
        let laser = LaserModel::default();
        let sonar = SonarModel::default();
        for k in scans {
            let pose = Pose::new(0.01 + 0.002 * (k % 3) as f64, 0.1, 0.0);
            let beams = if k < 5 { 1 } else { 50 };
            if k % 4 == 3 {
                map.integrate(&pose, &vec![1.2; beams], &vec![0.1; beams], &sonar)
                    .unwrap();
            } else {
                map.integrate(&pose, &vec![1.0; beams], &vec![0.0; beams], &laser)
                    .unwrap();
            }
        }
    }

    #[test]
    fn restored_history_continues_like_the_original() {
        let g = Grid::new([0.0, 0.0], 0.05, 4, 40).unwrap();
        let total = 45;
        // Before any cell has five measurements, and after the rings have wrapped.
        for split in [3, 20] {
            let mut original = CoverageMap::new(g);
            original.track_history(true);
            settling_scans(&mut original, 0..split);
            let state = original.history_state().unwrap();
            assert!(
                state.count.iter().any(|&n| n as usize == split),
                "a cell measured by every scan"
            );

            let mut loaded =
                CoverageMap::from_histograms(g, original.bins(), original.histograms().to_vec())
                    .unwrap();
            assert!(!loaded.tracks_history());
            loaded.restore_history(state.clone()).unwrap();
            assert!(loaded.tracks_history());
            assert_eq!(loaded.history_state().as_ref(), Some(&state));
            assert_eq!(loaded.stagnation(), original.stagnation());
            assert_eq!(loaded.measurement_counts(), original.measurement_counts());

            settling_scans(&mut original, split..total);
            settling_scans(&mut loaded, split..total);
            assert_eq!(loaded.histograms(), original.histograms());
            assert_eq!(loaded.measurement_counts(), original.measurement_counts());
            assert_eq!(loaded.history_state(), original.history_state());
            let stagnation = original.stagnation();
            assert_eq!(loaded.stagnation(), stagnation);
            assert!(
                stagnation.iter().any(|&s| s) && stagnation.iter().any(|&s| !s),
                "split {split}"
            );
        }
    }

    #[test]
    fn restore_history_rejects_bad_state_and_leaves_map_unchanged() {
        let g = Grid::new([0.0, 0.0], 0.05, 4, 40).unwrap();
        let mut tracked = CoverageMap::new(g);
        tracked.track_history(true);
        settling_scans(&mut tracked, 0..8);
        let good = tracked.history_state().unwrap();
        let mut untracked = CoverageMap::new(g);
        assert_eq!(untracked.history_state(), None);

        let len = STAGNATION_MEASUREMENTS + 1;
        let with = |edit: &dyn Fn(&mut HistoryState)| {
            let mut s = good.clone();
            edit(&mut s);
            s
        };
        let cases = [
            with(&|s| s.count.truncate(g.len() - 1)),
            with(&|s| s.count.push(0)),
            with(&|s| s.entropies.truncate(g.len() * len - 1)),
            with(&|s| s.entropies.truncate(g.len() * (len - 1))),
            with(&|s| s.entropies[7 * len + 2] = f32::NAN),
            with(&|s| s.entropies[7 * len + 2] = f32::INFINITY),
            with(&|s| s.entropies[7 * len + 2] = -0.5),
            // More than the prior's ln 16 = 2.77 nats.
            with(&|s| s.entropies[7 * len + 2] = 2.8),
        ];
        for map in [&mut tracked, &mut untracked] {
            let (histograms, history) = (map.histograms().to_vec(), map.history_state());
            for bad in &cases {
                let err = map.restore_history(bad.clone()).unwrap_err();
                if bad.count.len() != g.len() || bad.entropies.len() != g.len() * len {
                    assert!(matches!(err, CovmapError::LengthMismatch { .. }), "{err}");
                } else {
                    assert!(
                        matches!(err, CovmapError::InvalidHistory { cell: 7, .. }),
                        "{err}"
                    );
                }
                assert_eq!(map.histograms(), &histograms[..]);
                assert_eq!(map.history_state(), history);
                assert_eq!(map.tracks_history(), history.is_some());
            }
        }
    }

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
