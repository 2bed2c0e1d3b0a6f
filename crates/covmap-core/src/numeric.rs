//! Small numerical helpers of the entropy computations.
//!
//! # A natural logarithm that the compiler can vectorise
//!
//! The expected-gain evaluator needs one logarithm per cell gain, millions per
//! candidate set. The C library's `log` is a function call per value; this one
//! is straight-line arithmetic and bit manipulation, so a loop over a batch of
//! values becomes vector code. It is the classic fdlibm algorithm (as in musl):
//! reduce `x = 2^k (1 + f)` with `1 + f` in `[sqrt(2)/2, sqrt(2))`, then
//! `ln(1 + f) = 2 atanh(s)`, `s = f / (2 + f)`, by a minimax polynomial in
//! `s^2`. Its error is below one unit in the last place; the tests compare it
//! with `f64::ln`.

/// `x ln x`, continued by its limit 0 at `x = 0` (and 0 below it).
#[inline]
pub(crate) fn x_ln_x(x: f64) -> f64 {
    if x > 0.0 { x * x.ln() } else { 0.0 }
}

/// [`x_ln_x`] of a histogram value, through [`ln_normal`] (within an ulp or
/// so of `x_ln_x`): straight-line code, so a loop over many values becomes
/// vector code. Every positive `f32`, subnormal ones too, is a normal `f64`.
#[inline(always)]
pub(crate) fn x_ln_x_of_f32(v: f32) -> f64 {
    let x = f64::from(v);
    let ln = ln_normal(x.max(f64::MIN_POSITIVE));
    if x > 0.0 { x * ln } else { 0.0 }
}

// The constants as bit patterns (fdlibm's `e_log.c`), so that no decimal
// rounding stands between them and the values the error analysis assumed.
/// `ln 2` split so that `k * LN2_HI` is exact for every exponent `k`.
const LN2_HI: f64 = f64::from_bits(0x3fe6_2e42_fee0_0000);
const LN2_LO: f64 = f64::from_bits(0x3dea_39ef_3579_3c76);
/// The minimax coefficients of `(ln(1 + f) - f + f^2 / 2) / s ~ f^2 / 2 + R(s^2)`.
const LG1: f64 = f64::from_bits(0x3fe5_5555_5555_5593);
const LG2: f64 = f64::from_bits(0x3fd9_9999_9997_fa04);
const LG3: f64 = f64::from_bits(0x3fd2_4924_9422_9359);
const LG4: f64 = f64::from_bits(0x3fcc_71c5_1d8e_78af);
const LG5: f64 = f64::from_bits(0x3fc7_4664_96cb_03de);
const LG6: f64 = f64::from_bits(0x3fc3_9a09_d078_c69f);
const LG7: f64 = f64::from_bits(0x3fc2_f112_df3e_5244);

/// The high word of `sqrt(2)/2`: mantissas from it up fold to `[sqrt(2)/2, sqrt(2))`.
const SQRT_HALF_HIGH: u64 = 0x3fe6_a09e;

/// `ln x` for a positive, normal, finite `x` (other inputs give meaningless
/// results: callers check [`f64::is_normal`] and fall back to [`f64::ln`]).
#[inline(always)]
pub(crate) fn ln_normal(x: f64) -> f64 {
    // Shift the exponent so that mantissas at or above sqrt(2)/2 round up.
    let bits = x
        .to_bits()
        .wrapping_add((0x3ff0_0000 - SQRT_HALF_HIGH) << 32);
    // The exponent k as a float without an integer conversion (which has no
    // vector instruction before AVX-512): 2^52 + e, minus 2^52 + 1023.
    let k =
        f64::from_bits((bits >> 52) | 0x4330_0000_0000_0000) - (4_503_599_627_370_496.0 + 1023.0);
    let m = f64::from_bits((bits & 0x000f_ffff_ffff_ffff) + (SQRT_HALF_HIGH << 32));
    let f = m - 1.0;
    let hfsq = 0.5 * f * f;
    let s = f / (2.0 + f);
    let z = s * s;
    let w = z * z;
    let t1 = w * (LG2 + w * (LG4 + w * LG6));
    let t2 = z * (LG1 + w * (LG3 + w * (LG5 + w * LG7)));
    let r = t2 + t1;
    s * (hfsq + r) + k * LN2_LO - hfsq + f + k * LN2_HI
}

/// [`ln_normal`] of eight values at once in AVX-512 registers: the same
/// operations in the same order (no fused multiply-adds), so each lane is
/// bit for bit what [`ln_normal`] gives.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
#[inline]
pub(crate) fn ln_normal_zmm(x: std::arch::x86_64::__m512d) -> std::arch::x86_64::__m512d {
    use std::arch::x86_64::*;
    let c = _mm512_set1_pd;
    let bits = _mm512_add_epi64(
        _mm512_castpd_si512(x),
        _mm512_set1_epi64(((0x3ff0_0000 - SQRT_HALF_HIGH) << 32) as i64),
    );
    let k = _mm512_sub_pd(
        _mm512_castsi512_pd(_mm512_or_si512(
            _mm512_srli_epi64::<52>(bits),
            _mm512_set1_epi64(0x4330_0000_0000_0000),
        )),
        c(4_503_599_627_370_496.0 + 1023.0),
    );
    let m = _mm512_castsi512_pd(_mm512_add_epi64(
        _mm512_and_si512(bits, _mm512_set1_epi64(0x000f_ffff_ffff_ffff)),
        _mm512_set1_epi64((SQRT_HALF_HIGH << 32) as i64),
    ));
    let (mul, add, sub) = (_mm512_mul_pd, _mm512_add_pd, _mm512_sub_pd);
    let f = sub(m, c(1.0));
    let hfsq = mul(mul(c(0.5), f), f);
    let s = _mm512_div_pd(f, add(c(2.0), f));
    let z = mul(s, s);
    let w = mul(z, z);
    let t1 = mul(w, add(c(LG2), mul(w, add(c(LG4), mul(w, c(LG6))))));
    let t2 = mul(
        z,
        add(
            c(LG1),
            mul(w, add(c(LG3), mul(w, add(c(LG5), mul(w, c(LG7)))))),
        ),
    );
    let r = add(t2, t1);
    // s * (hfsq + r) + k * LN2_LO - hfsq + f + k * LN2_HI, left to right.
    let sum = add(mul(s, add(hfsq, r)), mul(k, c(LN2_LO)));
    add(add(sub(sum, hfsq), f), mul(k, c(LN2_HI)))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Distance in units in the last place between two finite floats of one sign.
    fn ulps(a: f64, b: f64) -> u64 {
        if a.signum() != b.signum() {
            return if a == b { 0 } else { u64::MAX };
        }
        a.to_bits().abs_diff(b.to_bits())
    }

    #[test]
    fn matches_the_library_logarithm() {
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut worst = 0;
        for n in 0..2_000_000u64 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            // Every normal exponent, random mantissas; and the neighbourhood of 1.
            let x = if n % 4 == 0 {
                1.0 + ((state >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * 1e-3
            } else {
                let exponent = 1 + (state >> 53) % 2046;
                f64::from_bits((exponent << 52) | (state & 0x000f_ffff_ffff_ffff))
            };
            let (got, want) = (ln_normal(x), x.ln());
            // Near 1 the result is tiny: compare in absolute terms there.
            if want.abs() < 1e-3 {
                assert!(
                    (got - want).abs() <= 2.0 * f64::EPSILON * want.abs().max(1e-300),
                    "ln({x:e}): {got:e} vs {want:e}"
                );
            } else {
                worst = worst.max(ulps(got, want));
            }
        }
        assert!(worst <= 1, "worst error {worst} ulps");
    }

    #[test]
    fn x_ln_x_of_histogram_values() {
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        let specials = [
            0.0f32,
            -0.0,
            1.0,
            f32::MIN_POSITIVE,
            f32::from_bits(1),
            0.5,
            1e-30,
            0.999_999_9,
        ];
        for n in 0..1_000_000u32 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let v = specials.get(n as usize).copied().unwrap_or_else(|| {
                // Every non-negative f32 up to 1 (and a little past it).
                f32::from_bits((state >> 32) as u32 % 0x3f80_0100)
            });
            let (got, want) = (x_ln_x_of_f32(v), x_ln_x(f64::from(v)));
            assert!(
                (got - want).abs() <= 2.0 * f64::EPSILON * want.abs(),
                "{v:e}: {got:e} vs {want:e}"
            );
        }
    }

    /// The AVX-512 logarithm is the scalar one, lane for lane, bit for bit.
    #[cfg(target_arch = "x86_64")]
    #[test]
    fn the_vector_logarithm_is_the_scalar_one() {
        if !std::arch::is_x86_feature_detected!("avx512f") {
            return;
        }
        let mut state = 0x5851_f42d_4c95_7f2du64;
        let mut x = [0.0f64; 8];
        for n in 0..200_000u64 {
            for v in x.iter_mut() {
                state ^= state << 13;
                state ^= state >> 7;
                state ^= state << 17;
                let exponent = 1 + (state >> 53) % 2046;
                *v = if n % 2 == 0 {
                    f64::from_bits((exponent << 52) | (state & 0x000f_ffff_ffff_ffff))
                } else {
                    // Gains' normalisers lie in (0, 1].
                    (state >> 11) as f64 / (1u64 << 53) as f64 + f64::MIN_POSITIVE
                };
            }
            let mut got = [0.0f64; 8];
            // SAFETY: AVX-512 F was detected; both arrays hold eight values.
            unsafe {
                use std::arch::x86_64::*;
                _mm512_storeu_pd(got.as_mut_ptr(), ln_normal_zmm(_mm512_loadu_pd(x.as_ptr())));
            }
            for (g, &v) in got.iter().zip(&x) {
                assert_eq!(g.to_bits(), ln_normal(v).to_bits(), "ln({v:e})");
            }
        }
    }

    #[test]
    fn exact_at_powers_of_two_and_one() {
        assert_eq!(ln_normal(1.0), 0.0);
        for e in -1020..1020 {
            let x = 2f64.powi(e);
            assert!(ulps(ln_normal(x), x.ln()) <= 1, "2^{e}");
        }
        assert!(ulps(ln_normal(f64::MIN_POSITIVE), f64::MIN_POSITIVE.ln()) <= 1);
        assert!(ulps(ln_normal(f64::MAX), f64::MAX.ln()) <= 1);
    }
}
