//! The log-likelihood of a ground truth under a map's histograms.

use crate::coverage_map::CoverageMap;
use crate::error::{CovmapError, Result};
use crate::grid::Grid;

/// `sum over cells of ln p_cell(truth_cell)`: the log-probability of the
/// ground-truth coverage `truth` (one value in `[0, 1]` per cell, row-major)
/// under `map`'s histograms, over every cell or those where `cells` is true.
///
/// A truth value between two bin values `b / (bins - 1)` and
/// `(b + 1) / (bins - 1)` is scored by linear interpolation of the two
/// bins' probabilities: `p = (1 - f) h[b] + f h[b + 1]` with `f` the value's
/// fraction of the way from one to the other. A value on a bin (0 and 1
/// always are) is scored by that bin alone. A cell at the uniform prior
/// scores `ln(1 / bins)` whatever its truth, so over a fixed set of cells,
/// maps built with different sensor models compare fairly: cells a model's
/// readings never reach cost every model the same.
///
/// The sum runs over the cells in order, in `f64`: the same inputs give the
/// same result, bit for bit.
///
/// # Errors
/// [`CovmapError::LengthMismatch`] unless `truth` (and `cells`) hold one
/// value per cell of the map's grid; [`CovmapError::InvalidParameter`] for
/// a truth value that is NaN or outside `[0, 1]`.
pub fn log_likelihood(map: &CoverageMap, truth: &[f64], cells: Option<&[bool]>) -> Result<f64> {
    check_truth(map.grid(), truth, cells)?;
    Ok(cell_scores(map, truth)
        .enumerate()
        .filter(|(i, _)| cells.is_none_or(|c| c[*i]))
        .map(|(_, score)| score)
        .sum())
}

/// Each cell's term of [`log_likelihood`], row-major: the log-probability of
/// its truth under its histogram. Where a few cells dominate the sum, these
/// show which.
///
/// # Errors
/// As [`log_likelihood`].
pub fn cell_log_likelihoods(map: &CoverageMap, truth: &[f64]) -> Result<Vec<f64>> {
    check_truth(map.grid(), truth, None)?;
    Ok(cell_scores(map, truth).collect())
}

/// The cells' terms of checked inputs.
fn cell_scores<'a>(map: &'a CoverageMap, truth: &'a [f64]) -> impl Iterator<Item = f64> + 'a {
    let bins = map.bins();
    let top = (bins - 1) as f64;
    map.histograms()
        .chunks_exact(bins)
        .zip(truth)
        .map(move |(h, &t)| {
            let x = t * top;
            let b = (x.floor() as usize).min(bins - 2);
            let f = x - b as f64;
            ((1.0 - f) * f64::from(h[b]) + f * f64::from(h[b + 1])).ln()
        })
}

/// Errors unless `truth` holds one coverage value in `[0, 1]` per cell of
/// `grid`, and `cells`, if given, one flag per cell.
pub fn check_truth(grid: &Grid, truth: &[f64], cells: Option<&[bool]>) -> Result<()> {
    if truth.len() != grid.len() {
        return Err(CovmapError::LengthMismatch {
            what: "truth values and grid cells",
            left: truth.len(),
            right: grid.len(),
        });
    }
    if let Some(cells) = cells
        && cells.len() != grid.len()
    {
        return Err(CovmapError::LengthMismatch {
            what: "cell mask and grid cells",
            left: cells.len(),
            right: grid.len(),
        });
    }
    match truth.iter().find(|t| !(0.0..=1.0).contains(*t)) {
        Some(&value) => Err(CovmapError::InvalidParameter {
            name: "truth",
            value,
            expected: "a coverage in [0, 1] for every cell",
        }),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn prior_scores_ln_one_over_bins_and_values_between_bins_interpolate() {
        let grid = Grid::new([0.0, 0.0], 0.1, 2, 2).unwrap();
        let map = CoverageMap::new(grid);
        let ll = log_likelihood(&map, &[0.0, 0.3, 0.77, 1.0], None).unwrap();
        assert!((ll - 4.0 * (1.0f64 / 16.0).ln()).abs() < 1e-9);
        // One cell sure of 0.2 (bin 3), the rest at the prior.
        let mut h = vec![1.0 / 16.0; 4 * 16];
        h[..16].fill(0.0);
        h[3] = 1.0;
        let map = CoverageMap::from_histograms(grid, 16, h).unwrap();
        let mask = [true, false, false, false];
        let on_bin = log_likelihood(&map, &[0.2, 0.0, 0.0, 0.0], Some(&mask)).unwrap();
        assert!(on_bin.abs() < 1e-6, "{on_bin}");
        // A third of the way from bin 3 to bin 4.
        let between = log_likelihood(&map, &[0.2 + 1.0 / 45.0, 0.0, 0.0, 0.0], Some(&mask));
        assert!((between.unwrap() - (2.0f64 / 3.0).ln()).abs() < 1e-5);
        // A truth the map calls impossible scores low, not minus infinity.
        let far = log_likelihood(&map, &[1.0, 0.0, 0.0, 0.0], Some(&mask)).unwrap();
        assert!(far.is_finite() && far < -50.0, "{far}");
    }

    #[test]
    fn rejects_bad_truth() {
        let grid = Grid::new([0.0, 0.0], 0.1, 2, 2).unwrap();
        let map = CoverageMap::new(grid);
        assert!(log_likelihood(&map, &[0.0; 3], None).is_err());
        assert!(log_likelihood(&map, &[0.0, 0.0, f64::NAN, 0.0], None).is_err());
        assert!(log_likelihood(&map, &[0.0, 0.0, 1.5, 0.0], None).is_err());
        assert!(log_likelihood(&map, &[0.0; 4], Some(&[true; 3])).is_err());
    }
}
