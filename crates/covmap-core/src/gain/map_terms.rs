//! The evaluator's per-map work kept across changes of the map: what every
//! candidate's gain reads of every cell (the coverage that stops a predicted
//! beam, and the fast evaluator's [`CellTerms`]), brought up to date cell by
//! cell where the map changed, for the planning cache.
//!
//! Every term of a cell is a function of its histogram alone, so
//! recomputing the changed cells' terms gives the same bits as computing
//! every cell's anew. Which cells changed is the caller's to find (the
//! planning cache compares every histogram with the one it saw last).

use super::fast::{CellTerms, Piece};
use crate::coverage_map::CoverageMap;
use crate::histogram;
use crate::parallel;
use crate::sensor::{KernelTable, StopCoverage};

/// Cells refreshed by one job of [`MapTerms::update`].
const CELLS: usize = 4096;

/// The per-map work of the gain evaluator, owned (the map is not borrowed,
/// so that it can be changed between uses).
#[derive(Clone)]
pub(crate) struct MapTerms {
    /// Bins per cell.
    bins: usize,
    /// Which coverage stops a predicted beam.
    stop_coverage: StopCoverage,
    /// The coverage of every cell that stops a predicted beam.
    pub(super) stop: Vec<f32>,
    /// What the fast evaluator knows of every cell.
    pub(super) cells: CellTerms,
}

impl MapTerms {
    /// The terms of every cell of `map`, for kernels of `table` (which must
    /// serve the map's resolution and bins) and beams stopped by
    /// `stop_coverage`.
    pub(crate) fn new(map: &CoverageMap, table: &KernelTable, stop_coverage: StopCoverage) -> Self {
        Self {
            bins: map.bins(),
            stop_coverage,
            stop: super::evaluator::stop_coverage(map, stop_coverage),
            cells: CellTerms::new(map, table),
        }
    }

    /// Whether these are terms of a map of `map`'s size and bins, with beams
    /// stopped by `stop_coverage`.
    pub(crate) fn fits(&self, map: &CoverageMap, stop_coverage: StopCoverage) -> bool {
        self.bins == map.bins()
            && self.stop.len() == map.grid().len()
            && self.cells.h_ln_h.len() == map.histograms().len()
            && self.stop_coverage == stop_coverage
    }

    /// Bring the terms up to date with `map` (a map these terms
    /// [fit](Self::fits)), for kernels of `table`: the cells `changed`
    /// (ascending row-major indices) get their terms anew from their
    /// histograms. The terms are `map`'s if every cell whose histogram
    /// changed since they were made is in `changed`.
    ///
    /// # Panics
    /// If the terms do not fit `map`, or a cell is not on it.
    pub(crate) fn update(&mut self, map: &CoverageMap, table: &KernelTable, changed: &[usize]) {
        assert!(
            self.fits(map, self.stop_coverage),
            "the terms are not this map's"
        );
        let (bins, stop_coverage) = (self.bins, self.stop_coverage);
        let cells = &mut self.cells;
        let mut rest = changed;
        let pieces: Vec<UpdatePiece<'_>> = self
            .stop
            .chunks_mut(CELLS)
            .zip(cells.h_ln_h.chunks_mut(CELLS * bins))
            .zip(cells.entropy.chunks_mut(CELLS))
            .zip(cells.prior.chunks_mut(CELLS))
            .enumerate()
            .filter_map(|(k, (((stop, h_ln_h), entropy), prior))| {
                let end = (k + 1) * CELLS;
                let mine = rest.partition_point(|&i| i < end);
                let (here, later) = rest.split_at(mine);
                rest = later;
                (!here.is_empty()).then_some(UpdatePiece {
                    first: k * CELLS,
                    changed: here,
                    stop,
                    h_ln_h,
                    entropy,
                    prior,
                })
            })
            .collect();
        assert!(rest.is_empty(), "a changed cell lies off the map");
        let histograms = map.histograms();
        parallel::map(pieces, |piece| {
            piece.update(histograms, bins, stop_coverage)
        });
        cells.add_prior_gains(bins, table);
    }
}

/// A piece of the terms, cells `first ..`, and which of its cells changed.
struct UpdatePiece<'p> {
    first: usize,
    changed: &'p [usize],
    stop: &'p mut [f32],
    h_ln_h: &'p mut [f64],
    entropy: &'p mut [f64],
    prior: &'p mut [u8],
}

impl UpdatePiece<'_> {
    /// Refresh the changed cells' terms from the map's `histograms`.
    fn update(self, histograms: &[f32], bins: usize, stop_coverage: StopCoverage) {
        for &i in self.changed {
            let k = i - self.first;
            let histogram = &histograms[i * bins..(i + 1) * bins];
            Piece {
                h_ln_h: &mut self.h_ln_h[k * bins..(k + 1) * bins],
                entropy: &mut self.entropy[k..k + 1],
                prior: &mut self.prior[k..k + 1],
                histograms: histogram,
                bins,
            }
            .fill();
            self.stop[k] = stop_coverage_of(histogram, stop_coverage);
        }
    }
}

/// The coverage of a cell with histogram `h` that stops a predicted beam:
/// the cell's value in [`CoverageMap::ml`] or [`CoverageMap::mean`].
pub(crate) fn stop_coverage_of(h: &[f32], stop_coverage: StopCoverage) -> f32 {
    match stop_coverage {
        StopCoverage::MaximumLikelihood => {
            histogram::argmax(h) as f32 * (1.0 / (h.len() - 1) as f32)
        }
        StopCoverage::Mean => histogram::mean(h),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grid::Grid;
    use crate::pose::Pose;
    use crate::scan_map::ScanMap;
    use crate::sensor::{LaserModel, SonarModel};
    use crate::test_rng::uniform;

    /// After any sequence of scans, the terms updated where the map changed
    /// are those computed anew, bit for bit.
    #[test]
    fn updated_terms_are_the_terms_computed_anew() {
        let grid = Grid::new([0.0, 0.0], 0.05, 90, 130).unwrap();
        let sonar = SonarModel::default();
        let laser = LaserModel::default();
        let bearings: Vec<f64> = (0..8).map(|i| f64::from(i) * 0.785).collect();
        let mut next = uniform(17);
        for stop_coverage in [StopCoverage::MaximumLikelihood, StopCoverage::Mean] {
            let mut map = CoverageMap::new(grid);
            let table = map.kernel_table(&sonar.range).unwrap().into_owned();
            let mut terms = MapTerms::new(&map, &table, stop_coverage);
            assert!(
                !terms.cells.prior_gain.is_empty(),
                "every cell at the prior"
            );
            for scan in 0..6 {
                let before = map.histograms().to_vec();
                let pose = Pose::new(0.5 + 5.5 * next(), 0.5 + 3.5 * next(), 6.0 * next());
                let ranges: Vec<f64> = bearings.iter().map(|_| 0.3 + 5.0 * next()).collect();
                if scan % 3 == 2 {
                    map.integrate(&pose, &ranges[..1], &[0.3], &laser).unwrap();
                } else {
                    map.integrate(&pose, &ranges, &bearings, &sonar).unwrap();
                }
                let changed: Vec<usize> = (0..grid.len())
                    .filter(|&i| {
                        let cell = i * 16..(i + 1) * 16;
                        map.histograms()[cell.clone()] != before[cell]
                    })
                    .collect();
                assert!(!changed.is_empty());
                terms.update(&map, &table, &changed);
                let fresh = MapTerms::new(&map, &table, stop_coverage);
                let bits = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                let bits64 = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                assert_eq!(bits(&terms.stop), bits(&fresh.stop));
                assert_eq!(bits64(&terms.cells.h_ln_h), bits64(&fresh.cells.h_ln_h));
                assert_eq!(bits64(&terms.cells.entropy), bits64(&fresh.cells.entropy));
                assert_eq!(terms.cells.prior, fresh.cells.prior);
                assert_eq!(
                    bits64(&terms.cells.prior_gain),
                    bits64(&fresh.cells.prior_gain)
                );
            }
        }
    }

    /// A map that returns to the prior in some cell (loaded, say) gets the
    /// prior's gains it did not need before.
    #[test]
    fn a_cell_back_at_the_prior_brings_the_prior_gains() {
        let grid = Grid::new([0.0, 0.0], 0.1, 4, 4).unwrap();
        let bins = 8;
        let certain: Vec<f32> = (0..grid.len() * bins)
            .map(|i| if i % bins == 0 { 1.0 } else { 0.0 })
            .collect();
        let map = CoverageMap::from_histograms(grid, bins, certain.clone()).unwrap();
        let table = KernelTable::new(&SonarModel::default().range, 0.1, bins).unwrap();
        let mut terms = MapTerms::new(&map, &table, StopCoverage::MaximumLikelihood);
        assert!(terms.cells.prior_gain.is_empty());
        let mut data = map.histograms().to_vec();
        data[5 * bins..6 * bins].fill(1.0 / bins as f32);
        let map = CoverageMap::from_histograms(grid, bins, data).unwrap();
        terms.update(&map, &table, &[5]);
        assert_eq!(terms.cells.prior[5], 1);
        let fresh = MapTerms::new(&map, &table, StopCoverage::MaximumLikelihood);
        assert_eq!(terms.cells.prior_gain, fresh.cells.prior_gain);
        assert!(!fresh.cells.prior_gain.is_empty());
    }
}
