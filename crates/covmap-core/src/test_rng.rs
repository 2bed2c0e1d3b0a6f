//! Seeded random numbers for the unit tests.

/// Uniform values in `[0, 1)` from a xorshift generator started at `seed`
/// (not 0): the same sequence on every run and platform.
pub(crate) fn uniform(seed: u64) -> impl FnMut() -> f64 {
    let mut state = seed;
    move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    }
}
