//! What the fast evaluator knows of every cell before any beam is walked:
//! its `h ln h`, its entropy, whether it is at the prior, and what the prior
//! gains under each kernel (the per-cell terms of every gain).

use super::batch::plain_gain;
use crate::aligned::Aligned;
use crate::coverage_map::CoverageMap;
use crate::numeric::x_ln_x_of_f32;
use crate::parallel;
use crate::sensor::KernelTable;

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
#[derive(Clone)]
pub(in crate::gain) struct CellTerms {
    /// `h ln h` of every bin, laid out as the histograms, from the start of a
    /// cache line.
    pub(in crate::gain) h_ln_h: Aligned<f64>,
    /// Each cell's entropy.
    pub(in crate::gain) entropy: Vec<f64>,
    /// 1 for a cell at the uniform prior, else 0 (bytes, so that a row block
    /// reads its eight flags as one word).
    pub(in crate::gain) prior: Vec<u8>,
    /// The gain of the prior histogram under each kernel of the table, by
    /// kernel index (offset / bins). Empty if no cell is at the prior.
    pub(in crate::gain) prior_gain: Vec<f64>,
}

impl CellTerms {
    /// The terms of every cell of `map`, and the prior's gains under the
    /// kernels of `table`.
    pub(in crate::gain) fn new(map: &CoverageMap, table: &KernelTable) -> Self {
        let bins = map.bins();
        let histograms = map.histograms();
        let mut h_ln_h = Aligned::zeroed(histograms.len());
        let mut entropy = vec![0.0; histograms.len() / bins];
        let mut prior = vec![0u8; histograms.len() / bins];
        // One pass per piece of the map.
        const CELLS: usize = 4096;
        let pieces: Vec<Piece<'_>> = h_ln_h
            .chunks_mut(CELLS * bins)
            .zip(entropy.chunks_mut(CELLS))
            .zip(prior.chunks_mut(CELLS))
            .zip(histograms.chunks(CELLS * bins))
            .map(|(((h_ln_h, entropy), prior), histograms)| Piece {
                h_ln_h,
                entropy,
                prior,
                histograms,
                bins,
            })
            .collect();
        parallel::map(pieces, Piece::fill);
        let mut terms = Self {
            h_ln_h,
            entropy,
            prior,
            prior_gain: Vec::new(),
        };
        terms.add_prior_gains(bins, table);
        terms
    }

    /// Compute the prior's gains under the kernels of `table` if some cell
    /// is at the prior and they are not computed yet. (Once computed they
    /// stay, whether or not a cell is still at the prior: they depend on the
    /// bin count and the table alone, and are read only for cells at the
    /// prior.)
    pub(in crate::gain) fn add_prior_gains(&mut self, bins: usize, table: &KernelTable) {
        if self.prior_gain.is_empty() && self.prior.contains(&1) {
            self.prior_gain = prior_gains(bins, table);
        }
    }
}

/// A piece of the map, cells `first .. first + n` for some `first`: the
/// histograms, and the terms [`Piece::fill`] writes from them.
pub(in crate::gain) struct Piece<'p> {
    /// Its `h ln h`, to be written (`n * bins` values).
    pub(in crate::gain) h_ln_h: &'p mut [f64],
    /// Its cells' entropies, to be written (`n`).
    pub(in crate::gain) entropy: &'p mut [f64],
    /// Its cells' prior flags, to be written (`n`).
    pub(in crate::gain) prior: &'p mut [u8],
    /// Its histograms (`n * bins` values).
    pub(in crate::gain) histograms: &'p [f32],
    /// Bins per histogram.
    pub(in crate::gain) bins: usize,
}

impl Piece<'_> {
    /// Write the piece's terms: its `h ln h`, then its entropies and which
    /// of its cells are at the prior. A cell's terms depend on its
    /// histogram alone, whatever piece holds it: a piece of one cell (as the
    /// planning cache refreshes a changed cell) gets the same bits as the
    /// pass over the whole map.
    pub(in crate::gain) fn fill(self) {
        let bins = self.bins;
        let prior_bits = (1.0 / bins as f32).to_bits();
        self.h_ln_h
            .iter_mut()
            .zip(self.histograms)
            .for_each(|(h_ln_h, &h)| *h_ln_h = x_ln_x_of_f32(h));
        self.entropy
            .iter_mut()
            .zip(self.h_ln_h.chunks_exact(bins))
            .for_each(|(entropy, h_ln_h)| *entropy = -h_ln_h.iter().sum::<f64>());
        self.prior
            .iter_mut()
            .zip(self.histograms.chunks_exact(bins))
            .for_each(|(prior, histogram)| {
                *prior = u8::from(histogram.iter().all(|h| h.to_bits() == prior_bits))
            });
    }
}

/// The gain `H(h) - H(h k / Z)` of the uniform prior `h` under every kernel
/// `k` of `table`, with the prior's `h ln h` and entropy computed as
/// [`CellTerms`] computes every cell's.
fn prior_gains(bins: usize, table: &KernelTable) -> Vec<f64> {
    let p = 1.0 / bins as f32;
    let (h, h_ln_h) = (f64::from(p), x_ln_x_of_f32(p));
    let entropy = -(0..bins).map(|_| h_ln_h).sum::<f64>();
    table
        .values_f64()
        .chunks_exact(bins)
        .zip(table.k_ln_k().chunks_exact(bins))
        .map(|(k, k_ln_k)| plain_gain(std::iter::repeat_n((h, h_ln_h), bins), entropy, k, k_ln_k))
        .collect()
}
