//! What the fast evaluator knows of every cell before any beam is walked:
//! its `h ln h`, its entropy, whether it is at the prior, and what the prior
//! gains under each kernel.

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
pub(in crate::gain) struct LogCache {
    /// Laid out as the histograms, from the start of a cache line.
    pub(super) h_ln_h: Aligned<f64>,
    pub(super) entropy: Vec<f64>,
    /// 1 for a cell at the uniform prior, else 0 (bytes, so that a row block
    /// reads its eight flags as one word).
    pub(super) prior: Vec<u8>,
    /// The gain of the prior histogram under each kernel of the table, by
    /// kernel index (offset / bins). Empty if no cell is at the prior.
    pub(super) prior_gain: Vec<f64>,
}

impl LogCache {
    pub(in crate::gain) fn new(map: &CoverageMap, table: &KernelTable) -> Self {
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
        parallel::map(pieces, fill);
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
