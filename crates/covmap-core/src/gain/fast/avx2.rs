//! The batch's sums in AVX2 registers with fused multiply-adds.

use super::arith::{AVX2, Has};
use super::batch::{Queue, Rows, weighted_gains_with};

/// [`weighted_gains_with`] compiled for AVX2 and FMA.
#[target_feature(enable = "avx2,fma")]
pub(super) fn weighted_gains_avx2<const N: usize>(rows: &Rows<'_, N>, jobs: &Queue) -> f64 {
    // SAFETY: this function is compiled for AVX2 and FMA, so it may only be
    // called where the processor has them.
    weighted_gains_with::<N, AVX2>(unsafe { Has::new() }, rows, jobs)
}

/// [`sums`](super::batch) in AVX2 registers with fused multiply-adds: the same four lanes,
/// added in the same order (the fused roundings make the last bits differ).
#[target_feature(enable = "avx2,fma")]
#[inline]
pub(super) fn sums_avx2<const N: usize>(
    h: &[f32; N],
    h_ln_h: &[f64; N],
    k: &[f64; N],
    k_ln_k: &[f64; N],
) -> (f64, f64) {
    use std::arch::x86_64::*;
    let (mut z, mut a) = (_mm256_setzero_pd(), _mm256_setzero_pd());
    for c in 0..N / 4 {
        // SAFETY: `4 c + 3 < N`, the length of every array.
        let (h_v, h_ln_h_v, k_v, k_ln_k_v) = unsafe {
            (
                _mm256_cvtps_pd(_mm_loadu_ps(h.as_ptr().add(4 * c))),
                _mm256_loadu_pd(h_ln_h.as_ptr().add(4 * c)),
                _mm256_loadu_pd(k.as_ptr().add(4 * c)),
                _mm256_loadu_pd(k_ln_k.as_ptr().add(4 * c)),
            )
        };
        z = _mm256_fmadd_pd(h_v, k_v, z);
        a = _mm256_fmadd_pd(h_ln_h_v, k_v, _mm256_fmadd_pd(h_v, k_ln_k_v, a));
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
