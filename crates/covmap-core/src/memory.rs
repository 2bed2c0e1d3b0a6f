//! Fallible allocation of maps and read-outs.
//!
//! A map's arrays and every per-cell result grow with the grid, and a grid
//! may hold up to [`crate::MAX_CELLS`] cells: a read-out of a large map can
//! ask for more memory than there is. `Vec::with_capacity`, `vec![..]` and
//! `collect` abort the process when the allocator says no; these ask with
//! `try_reserve_exact` and answer [`CovmapError::OutOfMemory`] instead. The
//! simulator allocates its ground truth and decoded images through them.

use crate::error::{CovmapError, Result};

/// The error for `len` elements of `T` for `what` that could not be had.
pub fn out_of_memory<T>(what: &str, len: usize) -> CovmapError {
    CovmapError::OutOfMemory {
        what: what.to_owned(),
        bytes: len as u128 * size_of::<T>() as u128,
    }
}

/// An empty vector with room for `len` elements of `T`, or
/// [`CovmapError::OutOfMemory`] naming `what`.
pub fn try_with_capacity<T>(len: usize, what: &str) -> Result<Vec<T>> {
    let mut values = Vec::new();
    values
        .try_reserve_exact(len)
        .map_err(|_| out_of_memory::<T>(what, len))?;
    Ok(values)
}

/// `len` copies of `value`, or [`CovmapError::OutOfMemory`] naming `what`.
pub fn try_filled<T: Clone>(value: T, len: usize, what: &str) -> Result<Vec<T>> {
    let mut values = try_with_capacity(len, what)?;
    values.resize(len, value);
    Ok(values)
}

/// The items of `items` (exactly `len` of them, as an `ExactSizeIterator`
/// says), collected into memory asked for first, or
/// [`CovmapError::OutOfMemory`] naming `what`.
pub fn try_collect<T>(items: impl ExactSizeIterator<Item = T>, what: &str) -> Result<Vec<T>> {
    let mut values = try_with_capacity(items.len(), what)?;
    values.extend(items);
    Ok(values)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn more_than_an_address_spans_is_out_of_memory() {
        let err = try_filled(0u64, usize::MAX / 4, "a test").unwrap_err();
        assert!(matches!(err, CovmapError::OutOfMemory { .. }), "{err}");
        assert!(err.to_string().contains("a test needs"), "{err}");
    }

    #[test]
    fn what_fits_is_filled() {
        assert_eq!(try_filled(7u8, 3, "a test").unwrap(), vec![7, 7, 7]);
        let doubled = try_collect([1, 2].into_iter().map(|x| 2 * x), "a test").unwrap();
        assert_eq!(doubled, vec![2, 4]);
    }
}
