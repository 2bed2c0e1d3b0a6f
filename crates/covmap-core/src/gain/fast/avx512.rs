//! The batch in AVX-512 registers, eight gains at a time.

use super::batch::{Queue, Rows, SLOTS, pairwise_sum};
use crate::numeric::ln_normal_zmm;

/// [`weighted_gains_zmm`], compiled for AVX-512.
#[target_feature(enable = "avx512f,avx512dq,avx512vl,avx2,fma")]
pub(super) fn weighted_gains_avx512<const N: usize>(rows: &Rows<'_, N>, jobs: &Queue) -> f64 {
    weighted_gains_zmm::<N>(rows, jobs)
}

/// [`weighted_gains_with`](super::batch::weighted_gains_with) in AVX-512
/// registers, eight gains at a time from the sums to the weighted total (`N`
/// a multiple of 8): each job's products fill eight lanes
/// ([`row_sums_zmm`]), the eight jobs' lanes are summed together by a
/// transposing tree ([`sum_pairs`], [`sum_quads`]), and the logarithm
/// ([`ln_normal_zmm`], the same operations as
/// [`ln_normal`](crate::numeric::ln_normal)), the two divisions and the
/// weighting take the same instructions for all eight as for one. The weighted gains go into eight running sums, added pairwise
/// at the end. Each job's gain is formed in the same order whatever its
/// neighbours, and each beam's total in an order fixed by its own queue.
#[target_feature(enable = "avx512f,avx512dq,avx512vl,avx2,fma")]
fn weighted_gains_zmm<const N: usize>(rows: &Rows<'_, N>, queue: &Queue) -> f64 {
    use std::arch::x86_64::*;
    // The bin counts with a path of their own (8, 16, 32) fill whole registers.
    const { assert!(N.is_multiple_of(8)) };
    const GROUPS: usize = SLOTS.div_ceil(8);
    let n = queue.len.min(SLOTS);
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
        let (za, aa) = row_sums_zmm::<N>(rows, queue.cell[j[0]], queue.offset[j[0]] / N);
        let (zb, ab) = row_sums_zmm::<N>(rows, queue.cell[j[1]], queue.offset[j[1]] / N);
        let (z01, a01) = (sum_pairs(za, zb), sum_pairs(aa, ab));
        let (za, aa) = row_sums_zmm::<N>(rows, queue.cell[j[2]], queue.offset[j[2]] / N);
        let (zb, ab) = row_sums_zmm::<N>(rows, queue.cell[j[3]], queue.offset[j[3]] / N);
        let (z23, a23) = (sum_pairs(za, zb), sum_pairs(aa, ab));
        let (z0, a0) = (sum_quads(z01, z23), sum_quads(a01, a23));
        let (za, aa) = row_sums_zmm::<N>(rows, queue.cell[j[4]], queue.offset[j[4]] / N);
        let (zb, ab) = row_sums_zmm::<N>(rows, queue.cell[j[5]], queue.offset[j[5]] / N);
        let (z45, a45) = (sum_pairs(za, zb), sum_pairs(aa, ab));
        let (za, aa) = row_sums_zmm::<N>(rows, queue.cell[j[6]], queue.offset[j[6]] / N);
        let (zb, ab) = row_sums_zmm::<N>(rows, queue.cell[j[7]], queue.offset[j[7]] / N);
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
        let (weight, entropy) = unsafe {
            (
                _mm512_maskz_loadu_pd(used, queue.weight.as_ptr().add(8 * g)),
                _mm512_maskz_loadu_pd(used, queue.entropy.as_ptr().add(8 * g)),
            )
        };
        // Unused lanes keep `acc` as it is (whatever their posterior).
        acc = _mm512_mask3_fmadd_pd(weight, _mm512_sub_pd(entropy, posterior), acc, used);
    }
    let mut lanes = [0.0f64; 8];
    // SAFETY: `lanes` holds eight values.
    unsafe { _mm512_storeu_pd(lanes.as_mut_ptr(), acc) };
    pairwise_sum(&lanes)
}

/// `Z` and `A` of `cell` under `kernel`, each as eight lane sums (`N` a
/// multiple of 8).
#[target_feature(enable = "avx512f")]
#[inline]
fn row_sums_zmm<const N: usize>(
    rows: &Rows<'_, N>,
    cell: usize,
    kernel: usize,
) -> (std::arch::x86_64::__m512d, std::arch::x86_64::__m512d) {
    use std::arch::x86_64::*;
    assert!(
        cell < rows.h.len() && kernel < rows.k.len(),
        "cell or kernel out of range"
    );
    // SAFETY: `Rows::new` made `h_ln_h` as long as `h` and `k_ln_k` as long
    // as `k`, and the two indices were checked against those.
    let (h, h_ln_h, k, k_ln_k) = unsafe {
        (
            rows.h.get_unchecked(cell),
            rows.h_ln_h.get_unchecked(cell),
            rows.k.get_unchecked(kernel),
            rows.k_ln_k.get_unchecked(kernel),
        )
    };
    // Each chunk of eight bins on its own, then the chunks added pairwise.
    let mut z = [_mm512_setzero_pd(); 4];
    let mut a = [_mm512_setzero_pd(); 4];
    for c in 0..N / 8 {
        // SAFETY: `8 c + 7 < N`, the length of every row.
        let (h_v, h_ln_h_v, k_v, k_ln_k_v) = unsafe {
            (
                _mm512_cvtps_pd(_mm256_loadu_ps(h.as_ptr().add(8 * c))),
                _mm512_loadu_pd(h_ln_h.as_ptr().add(8 * c)),
                _mm512_loadu_pd(k.as_ptr().add(8 * c)),
                _mm512_loadu_pd(k_ln_k.as_ptr().add(8 * c)),
            )
        };
        let (zc, ac) = (
            _mm512_mul_pd(h_v, k_v),
            _mm512_fmadd_pd(h_ln_h_v, k_v, _mm512_mul_pd(h_v, k_ln_k_v)),
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

#[cfg(test)]
mod tests {
    use super::super::arith::{AVX512, Arith, BASELINE, Has, weighted_gains};
    use super::super::batch::weighted_gains_with;
    use super::*;
    use crate::aligned::Aligned;
    use crate::numeric::x_ln_x;
    use crate::test_rng::uniform;

    /// The AVX-512 batch gives the plain batch's sum, for every bin count it
    /// serves and every queue length, with cells whose normaliser `Z` is
    /// subnormal (which the fast logarithm cannot take) among them.
    #[test]
    fn the_avx512_batch_is_the_plain_one() {
        if Arith::detect() != Arith::Avx512 {
            return;
        }
        fn check<const N: usize>() {
            let mut next = uniform(0x9e37_79b9_7f4a_7c15);
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
}
