//! The measures of a run against the truth: the paper's Table I figure and
//! the maps' errors, over a set of cells.

use crate::error::{CovmapError, Result};

/// The fraction of the cells flagged in `cells` whose entropy is above
/// `epsilon` nats: Table I's "cells with H > epsilon" (0 if no cell is
/// flagged).
///
/// # Errors
/// [`CovmapError::LengthMismatch`] if `entropy` and `cells` differ in length.
///
/// # Example
/// ```
/// use covmap_core::exploration::high_entropy_fraction;
/// let f = high_entropy_fraction(&[0.1, 2.0, 0.9, 2.7], &[true, true, true, false], 0.65).unwrap();
/// assert!((f - 2.0 / 3.0).abs() < 1e-12);
/// ```
pub fn high_entropy_fraction(entropy: &[f32], cells: &[bool], epsilon: f64) -> Result<f64> {
    check_lengths("entropy and cells", entropy.len(), cells.len())?;
    let (high, total) = entropy
        .iter()
        .zip(cells)
        .filter(|(_, c)| **c)
        .fold((0usize, 0usize), |(h, t), (&e, _)| {
            (h + usize::from(f64::from(e) > epsilon), t + 1)
        });
    Ok(if total == 0 {
        0.0
    } else {
        high as f64 / total as f64
    })
}

/// The mean absolute difference between a map's estimate of each cell's
/// coverage (a coverage map's mean, an occupancy grid's probability) and
/// the true coverage, over the cells flagged in `cells` (0 if none is).
///
/// # Errors
/// [`CovmapError::LengthMismatch`] if the three lengths differ.
///
/// # Example
/// ```
/// use covmap_core::exploration::mean_absolute_error;
/// let e = mean_absolute_error(&[0.0, 0.5, 1.0], &[0.0, 1.0, 1.0], &[true, true, false]).unwrap();
/// assert_eq!(e, 0.25);
/// ```
pub fn mean_absolute_error(estimate: &[f32], truth: &[f64], cells: &[bool]) -> Result<f64> {
    check_lengths("estimate and truth", estimate.len(), truth.len())?;
    check_lengths("estimate and cells", estimate.len(), cells.len())?;
    let (sum, total) = estimate
        .iter()
        .zip(truth)
        .zip(cells)
        .filter(|(_, c)| **c)
        .fold((0.0f64, 0usize), |(s, t), ((&e, &v), _)| {
            (s + (f64::from(e) - v).abs(), t + 1)
        });
    Ok(if total == 0 { 0.0 } else { sum / total as f64 })
}

fn check_lengths(what: &'static str, left: usize, right: usize) -> Result<()> {
    if left == right {
        Ok(())
    } else {
        Err(CovmapError::LengthMismatch { what, left, right })
    }
}
