//! Per-cell histograms: bin values, the Bayesian update, entropy.
//!
//! A histogram of `n` bins gives the probability that a cell's coverage is the
//! bin's value `x_b = b / (n - 1)`: the first bin is "empty" (0), the last "fully
//! covered" (1), both exactly representable, which matters because most cells are
//! one or the other.

use crate::error::{Result, check_parameter};
use crate::numeric::x_ln_x;

/// The fewest bins a histogram may have.
pub const MIN_BINS: usize = 2;
/// The most bins a histogram may have.
pub const MAX_BINS: usize = 256;
/// The default: 16 `f32` bins fill one 64-byte cache line, so one cell update
/// touches exactly one line; 1/15 steps resolve coverage finer than the sensor
/// model can (see BENCHMARKS.md for the measured cost of 8, 16 and 32 bins).
pub const DEFAULT_BINS: usize = 16;

/// The smallest probability a bin of a map's histogram holds, whatever the
/// bin count.
///
/// A map keeps each cell's evidence as log-likelihoods
/// ([`CoverageMap::evidence`](crate::CoverageMap::evidence)), which no floor clamps; its histograms are read off
/// them, and a bin whose probability is below the floor (beyond `f32`'s
/// normal range, or of no use to anything that reads a histogram) is held
/// at it there. So no bin of a histogram is 0, every `p ln p` is finite,
/// and the floor changes nothing of what a later reading does to the
/// cell. It stays above the `f32` normal range (1.2e-38) times the
/// smallest kernel value, so that a histogram multiplied by a kernel
/// without a map's evidence (as the expected gain predicts an update)
/// never computes with subnormal numbers for sane models.
pub const BIN_FLOOR: f32 = 1e-30;

/// Evaluates `$body` with the constant `$n` set to the bin count `$bins` if
/// it is one of the counts with a path of their own (8, 16, 32), else to 0
/// (any count). Fixed at compile time, so that the per-cell loops the body
/// calls are straight vector code; picked once per scan or beam, outside
/// those loops.
macro_rules! with_bins {
    ($bins:expr, |$n:ident| $body:expr) => {
        match $bins {
            8 => {
                const $n: usize = 8;
                $body
            }
            16 => {
                const $n: usize = 16;
                $body
            }
            32 => {
                const $n: usize = 32;
                $body
            }
            _ => {
                const $n: usize = 0;
                $body
            }
        }
    };
}
pub(crate) use with_bins;

/// Errors unless `bins` lies in `[MIN_BINS, MAX_BINS]`.
pub fn check_bins(bins: usize) -> Result<()> {
    check_parameter(
        (MIN_BINS..=MAX_BINS).contains(&bins),
        "bins",
        bins as f64,
        "a bin count from 2 to 256",
    )
}

/// The coverage value of bin `b` of `bins`.
#[inline]
pub fn bin_value(b: usize, bins: usize) -> f64 {
    b as f64 / (bins - 1) as f64
}

/// Multiply `h` by `k` bin by bin, renormalise, and floor each bin.
///
/// Dispatches on the length; the hot loops pick [`update_bins`] once per scan
/// instead.
#[inline]
pub(crate) fn update(h: &mut [f32], k: &[f32], floor: f32) {
    debug_assert_eq!(h.len(), k.len());
    with_bins!(h.len(), |N| update_bins::<N>(h, k, floor))
}

/// [`update`] for `N` bins ([`update_fixed`]), or any number for `N = 0`
/// ([`update_any`]).
#[inline(always)]
pub(crate) fn update_bins<const N: usize>(h: &mut [f32], k: &[f32], floor: f32) {
    if N == 0 {
        update_any(h, k, floor)
    } else {
        update_fixed::<N>(h, k, floor)
    }
}

/// [`update`] for `N` bins (a multiple of 4): the product, the sum and the
/// scaling each compile to straight vector code. The sum is accumulated in
/// four lanes, added in a fixed order, so the result depends only on the
/// inputs.
#[inline(always)]
fn update_fixed<const N: usize>(h: &mut [f32], k: &[f32], floor: f32) {
    let (Ok(h), Ok(k)) = (<&mut [f32; N]>::try_from(h), <&[f32; N]>::try_from(k)) else {
        unreachable!("the caller passes slices of N bins")
    };
    // Work on a local copy: loads, then arithmetic, then one store per lane
    // group, so that the compiler need not reason about the two slices.
    let mut x = [0.0f32; N];
    for ((x, a), b) in x.iter_mut().zip(h.iter()).zip(k) {
        *x = a * b;
    }
    let mut lanes = [0.0f32; 4];
    for chunk in x.chunks_exact(4) {
        for (l, v) in lanes.iter_mut().zip(chunk) {
            *l += v;
        }
    }
    let inv = 1.0 / ((lanes[0] + lanes[2]) + (lanes[1] + lanes[3]));
    for (v, x) in h.iter_mut().zip(x) {
        let y = x * inv;
        // Not `f32::max`: its NaN handling costs three instructions a lane,
        // and nothing here is NaN.
        *v = if y > floor { y } else { floor };
    }
}

/// [`update`] for any bin count.
#[inline]
fn update_any(h: &mut [f32], k: &[f32], floor: f32) {
    let mut sum = 0.0f32;
    for (v, &kv) in h.iter_mut().zip(k) {
        *v *= kv;
        sum += *v;
    }
    let inv = 1.0 / sum;
    for v in h.iter_mut() {
        *v = (*v * inv).max(floor);
    }
}

/// `e^x` for `x <= 0` in `f32`, to within two units in the last place:
/// `x = n ln 2 + r` with `|r| <= ln 2 / 2`, `e^r` by its Taylor polynomial of
/// degree 6 (remainder below `1.3e-7` relative), times `2^n` put together
/// from its bits. Below `-87` (where `e^x` leaves the normal `f32` range) it
/// gives `e^-87`. Every step is lane-wise arithmetic, so a loop over a
/// histogram compiles to vector code.
#[inline(always)]
pub(crate) fn exp_non_positive(x: f32) -> f32 {
    const LOG2_E: f32 = std::f32::consts::LOG2_E;
    // ln 2 in two parts, the first with few enough bits that `n * LN2_HI`
    // is exact for every `|n| <= 126`.
    const LN2_HI: f32 = 0.693_145_75;
    const LN2_LO: f32 = 1.428_606_8e-6;
    // 1.5 * 2^23: adding it rounds to an integer (to nearest, ties to even).
    const ROUND: f32 = 12_582_912.0;
    let x = if x > -87.0 { x } else { -87.0 };
    let rounded = x * LOG2_E + ROUND;
    let n = rounded - ROUND;
    let r = (x - n * LN2_HI) - n * LN2_LO;
    let p = 1.0
        + r * (1.0
            + r * (0.5
                + r * (1.0 / 6.0 + r * (1.0 / 24.0 + r * (1.0 / 120.0 + r * (1.0 / 720.0))))));
    // `n` is an integer in [-126, 0]: `2^n` is a normal number. Between
    // 2^23 and 2^24 a float's last bit is worth 1, so `n` is the
    // difference of the two floats' bits: integer arithmetic that stays in
    // vector lanes (a float-to-integer cast, which Rust saturates, does not).
    let biased = rounded
        .to_bits()
        .wrapping_sub(ROUND.to_bits())
        .wrapping_add(127);
    let scale = f32::from_bits(biased << 23);
    p * scale
}

/// Bayes' rule in logarithms: add the kernel's logarithms `ln_k` to the
/// cell's log-likelihoods `l` (shifted so that the largest is 0), and write
/// the histogram they give into `h`, each bin at least `floor`. `N` bins
/// (`N = 0`: any number).
///
/// The log-likelihoods are sums, in any order the same but for rounding;
/// the histogram is a function of them alone. No bin's evidence is cut off:
/// a bin far below the floor in `h` keeps its place in `l`, and contrary
/// readings bring it back exactly as far as the evidence says.
#[inline(always)]
pub(crate) fn update_log<const N: usize>(l: &mut [f32], h: &mut [f32], ln_k: &[f32], floor: f32) {
    if N == 0 {
        update_log_any(l, h, ln_k, floor)
    } else {
        update_log_fixed::<N>(l, h, ln_k, floor)
    }
}

/// [`update_log`] for `N` bins (a multiple of 4), in straight vector code.
#[inline(always)]
fn update_log_fixed<const N: usize>(l: &mut [f32], h: &mut [f32], ln_k: &[f32], floor: f32) {
    let (Ok(l), Ok(h), Ok(ln_k)) = (
        <&mut [f32; N]>::try_from(l),
        <&mut [f32; N]>::try_from(h),
        <&[f32; N]>::try_from(ln_k),
    ) else {
        unreachable!("the caller passes slices of N bins")
    };
    let mut x = [0.0f32; N];
    for ((x, a), b) in x.iter_mut().zip(l.iter()).zip(ln_k) {
        *x = a + b;
    }
    let mut tops = [f32::NEG_INFINITY; 4];
    for chunk in x.chunks_exact(4) {
        for (t, &v) in tops.iter_mut().zip(chunk) {
            *t = if v > *t { v } else { *t };
        }
    }
    let top = tops[0].max(tops[1]).max(tops[2].max(tops[3]));
    let mut e = [0.0f32; N];
    for ((e, x), l) in e.iter_mut().zip(x.iter_mut()).zip(l.iter_mut()) {
        *x -= top;
        *l = *x;
        *e = exp_non_positive(*x);
    }
    let mut lanes = [0.0f32; 4];
    for chunk in e.chunks_exact(4) {
        for (s, v) in lanes.iter_mut().zip(chunk) {
            *s += v;
        }
    }
    let inv = 1.0 / ((lanes[0] + lanes[2]) + (lanes[1] + lanes[3]));
    for (v, e) in h.iter_mut().zip(e) {
        let y = e * inv;
        *v = if y > floor { y } else { floor };
    }
}

/// [`update_log`] for any bin count.
#[inline]
fn update_log_any(l: &mut [f32], h: &mut [f32], ln_k: &[f32], floor: f32) {
    let mut top = f32::NEG_INFINITY;
    for (v, &k) in l.iter_mut().zip(ln_k) {
        *v += k;
        top = top.max(*v);
    }
    let mut sum = 0.0f32;
    for (v, p) in l.iter_mut().zip(h.iter_mut()) {
        *v -= top;
        *p = exp_non_positive(*v);
        sum += *p;
    }
    let inv = 1.0 / sum;
    for p in h.iter_mut() {
        *p = (*p * inv).max(floor);
    }
}

/// The log-likelihoods of histogram `h` into `l`: `ln h`, shifted so that
/// the largest is 0 (a bin at 0 gets the logarithm of the smallest positive
/// `f32`).
pub(crate) fn log_of(h: &[f32], l: &mut [f32]) {
    for (v, &p) in l.iter_mut().zip(h) {
        *v = p.max(f32::MIN_POSITIVE).ln();
    }
    let top = l.iter().copied().fold(f32::NEG_INFINITY, f32::max);
    for v in l.iter_mut() {
        *v -= top;
    }
}

/// Shannon entropy in nats, in `f32` (the map's entropy); `0 * ln 0` counts
/// as 0.
///
/// Each bin's `p ln p`, summed in bin order. A bin at [`BIN_FLOOR`] (most
/// bins of a map explored for a while: 80 % of those whose entropy a
/// scan-counting run computes) takes its term from `floor_term`, the
/// same product computed once, and a bin at 1 (a certain cell's) the 0 its
/// term is, so the entropy has the same bits as with every logarithm
/// computed, and its cost is the other bins' logarithms.
pub fn entropy(h: &[f32]) -> f32 {
    let at_floor = floor_term();
    -h.iter()
        .filter(|&&p| p > 0.0)
        .map(|&p| {
            if p == BIN_FLOOR {
                at_floor
            } else if p == 1.0 {
                // `1 ln 1`: `ln` gives exactly 0 there.
                0.0
            } else {
                p * p.ln()
            }
        })
        .sum::<f32>()
}

/// `BIN_FLOOR * ln BIN_FLOOR` in `f32`, as [`entropy`] computes a bin's term,
/// computed once at run time: by the same `ln` as every other bin's (the
/// `black_box` keeps the compiler from folding it with its own logarithm,
/// which need not round as the run-time one does).
fn floor_term() -> f32 {
    static TERM: std::sync::OnceLock<f32> = std::sync::OnceLock::new();
    *TERM.get_or_init(|| {
        let p = std::hint::black_box(BIN_FLOOR);
        p * p.ln()
    })
}

/// [`entropy`] in `f64`, each bin's `p ln p` from its definition: the
/// reference the exact gain is computed with.
pub fn entropy_f64(h: &[f32]) -> f64 {
    -h.iter().map(|&p| x_ln_x(f64::from(p))).sum::<f64>()
}

/// The index of the most probable bin (the first on ties).
pub fn argmax(h: &[f32]) -> usize {
    // The largest value first, then where it first occurs: two passes without
    // a data-dependent branch, which beat one that mispredicts on every new
    // maximum. NaN, which no histogram holds, is skipped by `max`.
    let top = h.iter().copied().fold(f32::NEG_INFINITY, f32::max);
    h.iter().position(|&p| p == top).unwrap_or(0)
}

/// Expected coverage.
pub fn mean(h: &[f32]) -> f32 {
    let n = h.len();
    h.iter()
        .enumerate()
        .map(|(b, &p)| p * bin_value(b, n) as f32)
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The entropy with the floor's term computed once is the entropy with
    /// every term computed, bit for bit, on histograms with and without
    /// bins at the floor (and at 0), of any bin count.
    #[test]
    fn the_floors_term_changes_no_bit_of_the_entropy() {
        let every_term = |h: &[f32]| -> f32 {
            -h.iter()
                .filter(|&&p| p > 0.0)
                .map(|&p| p * std::hint::black_box(p).ln())
                .sum::<f32>()
        };
        let mut next = crate::test_rng::uniform(7);
        let mut floors = 0;
        for trial in 0..2000 {
            let bins = [2, 5, 8, 16, 17, 32, 256][trial % 7];
            let mut h: Vec<f32> = (0..bins).map(|_| next() as f32 + 1e-3).collect();
            let sum: f32 = h.iter().sum();
            for v in &mut h {
                *v /= sum;
                let pick = next();
                if pick < 0.5 {
                    *v = BIN_FLOOR;
                    floors += 1;
                } else if pick < 0.52 {
                    *v = 0.0;
                }
            }
            assert_eq!(entropy(&h).to_bits(), every_term(&h).to_bits(), "{h:?}");
        }
        assert!(floors > 1000);
        let mut certain = vec![BIN_FLOOR; 16];
        certain[15] = 1.0 - 15.0 * BIN_FLOOR;
        assert_eq!(entropy(&certain).to_bits(), every_term(&certain).to_bits());
        assert!(entropy(&certain) > 0.0);
    }

    #[test]
    fn fixed_and_generic_updates_agree() {
        for n in [8usize, 16, 32] {
            let mut a: Vec<f32> = (0..n).map(|i| 1.0 + i as f32).collect();
            let s: f32 = a.iter().sum();
            a.iter_mut().for_each(|v| *v /= s);
            let mut b = a.clone();
            let k: Vec<f32> = (0..n).map(|i| 0.5 + ((i * 7) % 5) as f32).collect();
            update(&mut a, &k, BIN_FLOOR);
            update_any(&mut b, &k, BIN_FLOOR);
            for (x, y) in a.iter().zip(&b) {
                assert!((x - y).abs() < 1e-6);
            }
            assert!((a.iter().sum::<f32>() - 1.0).abs() < 1e-5);
        }
    }

    #[test]
    fn entropy_bounds() {
        let u = vec![1.0 / 16.0; 16];
        assert!((entropy(&u) - 16f32.ln()).abs() < 1e-5);
        let mut c = vec![0.0; 16];
        c[3] = 1.0;
        assert_eq!(entropy(&c), 0.0);
        assert_eq!(argmax(&c), 3);
        assert!((mean(&c) - 0.2).abs() < 1e-6);
    }

    /// The first of the most probable bins, as a plain scan finds it, ties
    /// included.
    #[test]
    fn argmax_is_the_first_maximum() {
        let mut state = 0x2545_f491_4f6c_dd1du64;
        for n in 0..20_000 {
            let h: Vec<f32> = (0..2 + n % 31)
                .map(|_| {
                    state ^= state << 13;
                    state ^= state >> 7;
                    state ^= state << 17;
                    // Few distinct values, so that ties are common.
                    (state % 5) as f32 * 0.25
                })
                .collect();
            let mut want = 0;
            for (b, &p) in h.iter().enumerate() {
                if p > h[want] {
                    want = b;
                }
            }
            assert_eq!(argmax(&h), want, "{h:?}");
        }
    }

    #[test]
    fn bins_validated() {
        assert!(check_bins(1).is_err());
        assert!(check_bins(257).is_err());
        assert!(check_bins(16).is_ok());
    }
}
