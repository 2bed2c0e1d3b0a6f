//! Stamping a shape of cells (a disc of offsets around a cell) onto a mask:
//! the inflation of obstacles by the robot's disc and the growth of the
//! reachable region do it for every cell on an edge, with a few hundred
//! offsets each.
//!
//! A disc's offsets, listed row by row with ascending columns, form one run
//! of neighbouring columns a row; a [`Stamp`] keeps those runs, so that
//! stamping a cell clips each run to the grid once and fills it as a slice,
//! instead of testing and writing each offset's cell on its own (which took
//! most of the time of both).

use crate::grid::Grid;

/// A set of cell offsets as runs along rows: `(rows, first column, last
/// column)`, each run's columns neighbouring.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Stamp {
    runs: Vec<(i64, i64, i64)>,
}

impl Stamp {
    /// The offsets `(rows, columns)`, in any order: each run of them on one
    /// row with neighbouring columns, listed one after the other with
    /// ascending columns, is one run (any other order gives more, shorter
    /// runs of the same cells).
    pub(crate) fn new(offsets: &[(i64, i64)]) -> Self {
        let mut runs: Vec<(i64, i64, i64)> = Vec::new();
        for &(dr, dc) in offsets {
            match runs.last_mut() {
                Some((row, _, last)) if *row == dr && *last + 1 == dc => *last = dc,
                _ => runs.push((dr, dc, dc)),
            }
        }
        Self { runs }
    }

    /// Set to `value` every cell of `mask` (one flag a cell of `grid`,
    /// row-major) at one of the offsets from the cell at `row`, `col` that
    /// lies on the grid.
    #[inline]
    pub(crate) fn apply(
        &self,
        grid: &Grid,
        mask: &mut [bool],
        row: usize,
        col: usize,
        value: bool,
    ) {
        let (rows, cols) = (grid.rows() as i64, grid.cols() as i64);
        let (row, col) = (row as i64, col as i64);
        for &(dr, first, last) in &self.runs {
            let r = row + dr;
            if r < 0 || r >= rows {
                continue;
            }
            let (lo, hi) = ((col + first).max(0), (col + last).min(cols - 1));
            if lo <= hi {
                let base = (r * cols) as usize;
                mask[base + lo as usize..=base + hi as usize].fill(value);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_rng::uniform;

    /// Stamping sets exactly the cells at the offsets that lie on the grid,
    /// for random offset sets (discs and scattered offsets, in order and
    /// shuffled) at cells all over small grids, edges included.
    #[test]
    fn a_stamp_sets_the_cells_of_its_offsets() {
        let mut next = uniform(3);
        for trial in 0..200 {
            let grid = Grid::new([0.0, 0.0], 0.1, 3 + trial % 9, 2 + trial % 13).unwrap();
            let radius = 4.0 * next();
            let reach = radius.ceil() as i64 + 1;
            let mut offsets = Vec::new();
            for dr in -reach..=reach {
                for dc in -reach..=reach {
                    let keep = if trial % 2 == 0 {
                        ((dr * dr + dc * dc) as f64).sqrt() <= radius
                    } else {
                        next() < 0.4
                    };
                    if keep {
                        offsets.push((dr, dc));
                    }
                }
            }
            if trial % 4 == 3 {
                offsets.reverse();
            }
            let stamp = Stamp::new(&offsets);
            let (rows, cols) = (grid.rows(), grid.cols());
            for i in 0..grid.len() {
                let (row, col) = (i / cols, i % cols);
                let mut stamped = vec![false; grid.len()];
                stamp.apply(&grid, &mut stamped, row, col, true);
                let mut want = vec![false; grid.len()];
                for &(dr, dc) in &offsets {
                    let (r, c) = (row as i64 + dr, col as i64 + dc);
                    if r >= 0 && c >= 0 && r < rows as i64 && c < cols as i64 {
                        want[r as usize * cols + c as usize] = true;
                    }
                }
                assert_eq!(stamped, want, "trial {trial}, cell {i}");
            }
        }
    }
}
