//! Per-cell histograms: bin values, the Bayesian update, entropy.
//!
//! A histogram of `n` bins gives the probability that a cell's coverage is the
//! bin's value `x_b = b / (n - 1)`: the first bin is "empty" (0), the last "fully
//! covered" (1), both exactly representable, which matters because most cells are
//! one or the other.

use crate::error::{CovmapError, Result};

/// The fewest bins a histogram may have.
pub const MIN_BINS: usize = 2;
/// The most bins a histogram may have.
pub const MAX_BINS: usize = 256;
/// The default: 16 `f32` bins fill one 64-byte cache line, so one cell update
/// touches exactly one line; 1/15 steps resolve coverage finer than the sensor
/// model can (see BENCHMARKS.md for the measured cost of 8, 16 and 32 bins).
pub const DEFAULT_BINS: usize = 16;

/// The smallest probability a bin keeps after an update, for a histogram of
/// `bins` bins: no bin ever becomes exactly 0, so a cell can always change its
/// mind, and a histogram's sum stays within `1e-6` of 1 after the floor.
pub fn bin_floor(bins: usize) -> f32 {
    1e-6 / bins as f32
}

/// Errors unless `bins` lies in `[MIN_BINS, MAX_BINS]`.
pub fn check_bins(bins: usize) -> Result<()> {
    if (MIN_BINS..=MAX_BINS).contains(&bins) {
        Ok(())
    } else {
        Err(CovmapError::InvalidParameter {
            name: "bins",
            value: bins as f64,
            expected: "a bin count from 2 to 256",
        })
    }
}

/// The coverage value of bin `b` of `bins`.
#[inline]
pub fn bin_value(b: usize, bins: usize) -> f64 {
    b as f64 / (bins - 1) as f64
}

/// Multiply `h` by `k` bin by bin, renormalise, and floor each bin.
///
/// The sum is accumulated in eight lanes so that it vectorises; the lanes are
/// added in a fixed order, so the result does not depend on anything but the
/// inputs.
#[inline(always)]
pub(crate) fn update(h: &mut [f32], k: &[f32], floor: f32) {
    debug_assert_eq!(h.len(), k.len());
    match h.len() {
        16 => update_fixed::<16>(h, k, floor),
        8 => update_fixed::<8>(h, k, floor),
        32 => update_fixed::<32>(h, k, floor),
        _ => update_any(h, k, floor),
    }
}

#[inline(always)]
fn update_fixed<const N: usize>(h: &mut [f32], k: &[f32], floor: f32) {
    let (Ok(h), Ok(k)) = (<&mut [f32; N]>::try_from(h), <&[f32; N]>::try_from(k)) else {
        unreachable!("lengths checked by the caller")
    };
    let mut lanes = [0.0f32; 8];
    for c in 0..N / 8 {
        for j in 0..8 {
            let v = h[c * 8 + j] * k[c * 8 + j];
            h[c * 8 + j] = v;
            lanes[j] += v;
        }
    }
    let sum = ((lanes[0] + lanes[4]) + (lanes[1] + lanes[5]))
        + ((lanes[2] + lanes[6]) + (lanes[3] + lanes[7]));
    let inv = 1.0 / sum;
    for v in h.iter_mut() {
        *v = (*v * inv).max(floor);
    }
}

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

/// Shannon entropy in nats; `0 * ln 0` counts as 0.
pub fn entropy(h: &[f32]) -> f32 {
    -h.iter()
        .filter(|&&p| p > 0.0)
        .map(|&p| p * p.ln())
        .sum::<f32>()
}

/// The index of the most probable bin (the first on ties).
pub fn argmax(h: &[f32]) -> usize {
    let mut best = 0;
    for (b, &p) in h.iter().enumerate() {
        if p > h[best] {
            best = b;
        }
    }
    best
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

    #[test]
    fn fixed_and_generic_updates_agree() {
        for n in [8usize, 16, 32] {
            let mut a: Vec<f32> = (0..n).map(|i| 1.0 + i as f32).collect();
            let s: f32 = a.iter().sum();
            a.iter_mut().for_each(|v| *v /= s);
            let mut b = a.clone();
            let k: Vec<f32> = (0..n).map(|i| 0.5 + ((i * 7) % 5) as f32).collect();
            update(&mut a, &k, bin_floor(n));
            update_any(&mut b, &k, bin_floor(n));
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

    #[test]
    fn bins_validated() {
        assert!(check_bins(1).is_err());
        assert!(check_bins(257).is_err());
        assert!(check_bins(16).is_ok());
    }
}
