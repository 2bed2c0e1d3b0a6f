//! The queue of gains waiting to be computed, and the plain kernels that
//! compute a batch of them (the vector ones are in [`super::avx2`] and
//! [`super::avx512`]).

use super::arith::{AVX2, Has};
#[cfg(target_arch = "x86_64")]
use super::avx2::sums_avx2;
use super::walk::Beam;
use crate::footprint::ROW_BLOCK;
use crate::numeric::ln_normal;

/// Gains waiting to be computed, the first `len` of each array: cell
/// `cell[j]`'s gain under the kernel at table offset `offset[j]`, weighted by
/// `weight[j]`. Arrays side by side, not one of tuples, so that vector code
/// reads eight weights (or entropies) at once.
pub(in crate::gain) struct Queue {
    pub(super) cell: [usize; SLOTS],
    pub(super) offset: [usize; SLOTS],
    pub(super) weight: [f64; SLOTS],
    /// `H(h)` of each job's cell, read when it is queued (neighbouring cells
    /// of a row block at once), so that a batch needs no gather.
    pub(super) entropy: [f64; SLOTS],
    pub(super) len: usize,
}

impl Queue {
    /// An empty queue.
    pub(super) fn new() -> Self {
        Self {
            cell: [0; SLOTS],
            offset: [0; SLOTS],
            weight: [0.0; SLOTS],
            entropy: [0.0; SLOTS],
            len: 0,
        }
    }
}

impl Default for Queue {
    fn default() -> Self {
        Self::new()
    }
}

/// What one gain reads, cut into rows of `N` bins (empty for `N = 0`), so
/// that a row costs one bounds check.
pub(super) struct Rows<'a, const N: usize> {
    /// Histograms, per cell.
    pub(super) h: &'a [[f32; N]],
    /// `h ln h`, per cell.
    pub(super) h_ln_h: &'a [[f64; N]],
    /// Entropies, per cell.
    pub(super) entropy: &'a [f64],
    /// Kernels, per table entry.
    pub(super) k: &'a [[f64; N]],
    /// `k ln k`, per table entry.
    pub(super) k_ln_k: &'a [[f64; N]],
}

impl<'a, const N: usize> Rows<'a, N> {
    /// The rows of histograms `h` and their `h ln h`, and of kernels `k` and
    /// their `k ln k`.
    ///
    /// # Panics
    /// If `h_ln_h` is not as long as `h` or `k_ln_k` not as long as `k` (the
    /// unchecked reads of the AVX-512 row sums rely on both), or `entropy` does
    /// not hold one value per histogram.
    pub(super) fn new(
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

/// Gains queued before a batch is computed.
pub(super) const BATCH: usize = 64;
/// Room for the jobs of a batch: one row block may overfill it.
pub(super) const SLOTS: usize = BATCH + ROW_BLOCK;
const _: () = assert!(SLOTS.is_multiple_of(8));

/// `sum w I(h_i | k)` over the queued jobs, each gain
/// `I = H(h) - H(h k / Z) = H(h) - ln Z + A / Z` with `Z = sum h k` and
/// `A = sum h k ln(h k) = sum k (h ln h) + h (k ln k)`: three dot products and
/// one logarithm. The logarithms of the batch are taken together, as vector
/// code. `A` names the arithmetic the caller is compiled for, which `has`
/// shows the processor to have: with [`AVX2`] (or wider) the sums are formed
/// in AVX2 registers ([`sums_avx2`]), else in plain code ([`sums`]).
#[inline(always)]
pub(super) fn weighted_gains_with<const N: usize, const A: u8>(
    has: Has<A>,
    rows: &Rows<'_, N>,
    queue: &Queue,
) -> f64 {
    let _ = has;
    let n = queue.len.min(SLOTS);
    // Unused slots hold Z = 1, A = 0.
    let mut z = [1.0f64; SLOTS];
    let mut a = [0.0f64; SLOTS];
    for j in 0..n {
        let (cell, kernel) = (queue.cell[j], queue.offset[j] / N);
        let (h, h_ln_h) = (&rows.h[cell], &rows.h_ln_h[cell]);
        let (k, k_ln_k) = (&rows.k[kernel], &rows.k_ln_k[kernel]);
        #[cfg(target_arch = "x86_64")]
        if A >= AVX2 {
            // SAFETY: `has` shows that the processor has AVX2 and FMA.
            (z[j], a[j]) = unsafe { sums_avx2::<N>(h, h_ln_h, k, k_ln_k) };
            continue;
        }
        (z[j], a[j]) = sums::<N>(h, h_ln_h, k, k_ln_k);
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
        total += queue.weight[j] * (queue.entropy[j] - h_post);
    }
    total
}

/// `Z = sum h k` and `A = sum k (h ln h) + h (k ln k)` for `N` bins (a
/// multiple of 4), in four lanes added in a fixed order.
#[inline(always)]
fn sums<const N: usize>(
    h: &[f32; N],
    h_ln_h: &[f64; N],
    k: &[f64; N],
    k_ln_k: &[f64; N],
) -> (f64, f64) {
    let mut z = [0.0f64; 4];
    let mut a = [0.0f64; 4];
    for chunk in 0..N / 4 {
        for lane in 0..4 {
            let b = 4 * chunk + lane;
            let hb = f64::from(h[b]);
            z[lane] += hb * k[b];
            a[lane] += h_ln_h[b] * k[b] + hb * k_ln_k[b];
        }
    }
    ((z[0] + z[2]) + (z[1] + z[3]), (a[0] + a[2]) + (a[1] + a[3]))
}

/// [`weighted_gains`](super::arith::weighted_gains) for any bin count,
/// plainly.
pub(super) fn weighted_gains_any(beam: &Beam<'_>, queue: &Queue) -> f64 {
    let bins = beam.map.bins();
    let (kernels, k_ln_k) = (beam.table.values_f64(), beam.table.k_ln_k());
    let mut total = 0.0;
    for (((&cell, &offset), &weight), &entropy) in queue
        .cell
        .iter()
        .zip(&queue.offset)
        .zip(&queue.weight)
        .zip(&queue.entropy)
        .take(queue.len)
    {
        let histogram = cell * bins..(cell + 1) * bins;
        let (h, h_ln_h) = (
            &beam.map.histograms()[histogram.clone()],
            &beam.terms.h_ln_h[histogram],
        );
        let kernel = offset..offset + bins;
        let h_and_h_ln_h = h.iter().map(|&v| f64::from(v)).zip(h_ln_h.iter().copied());
        total += weight
            * plain_gain(
                h_and_h_ln_h,
                entropy,
                &kernels[kernel.clone()],
                &k_ln_k[kernel],
            );
    }
    total
}

/// `H(h) - H(h k / Z) = H(h) - ln Z + A / Z` (see [`weighted_gains_with`]),
/// plainly, for any bin count: `h_and_h_ln_h` gives each bin's
/// `(h, h ln h)`, `entropy` is `H(h)`, `k` the kernel and `k_ln_k` its
/// `k ln k`.
pub(super) fn plain_gain(
    h_and_h_ln_h: impl Iterator<Item = (f64, f64)>,
    entropy: f64,
    k: &[f64],
    k_ln_k: &[f64],
) -> f64 {
    let (mut z, mut a) = (0.0, 0.0);
    for ((h, h_ln_h), (&k, &k_ln_k)) in h_and_h_ln_h.zip(k.iter().zip(k_ln_k)) {
        z += h * k;
        a += h_ln_h * k + h * k_ln_k;
    }
    entropy - (z.ln() - a / z)
}

/// `sum g`, added in pairs, then pairs of pairs (a short chain of additions).
#[inline(always)]
pub(super) fn pairwise_sum(g: &[f64; ROW_BLOCK]) -> f64 {
    const { assert!(ROW_BLOCK == 8) };
    ((g[0] + g[1]) + (g[2] + g[3])) + ((g[4] + g[5]) + (g[6] + g[7]))
}
