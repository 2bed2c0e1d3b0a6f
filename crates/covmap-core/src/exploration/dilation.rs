//! A mask grown by a disc of offsets, kept from step to step: the
//! counting strategy's free space (the blocked cells grown by the planning
//! radius) and region (the reachable cells grown by the radius and a cell)
//! change by a few cells a step, on a map of tens of thousands, so growing
//! the whole mask again at every step would cost far more than the change.
//!
//! Each cell keeps how many cells of the mask lie at one of the offsets
//! from it; the grown mask is where that number is above 0. A step takes in
//! the new mask and moves the numbers of the cells around those that
//! changed, and only those: the grown mask is the one growing the whole
//! mask gives (every cell of the mask, not only those on its edge: the two
//! agree for a disc, see `region::grow`).

use crate::grid::Grid;

/// A mask grown by `offsets`, kept up to date with [`Dilation::take_in`].
pub(super) struct Dilation {
    grid: Grid,
    /// The offsets `(rows, columns)` a mask cell takes into the grown mask,
    /// `(0, 0)` among them.
    offsets: Vec<(i64, i64)>,
    /// The mask last taken in, one flag a cell.
    mask: Vec<bool>,
    /// How many cells of `mask` lie at one of the offsets from each cell.
    near: Vec<u32>,
}

impl Dilation {
    /// The empty mask on `grid`, grown by `offsets` (with `(0, 0)` added if
    /// missing: the grown mask holds the mask).
    pub fn new(grid: &Grid, offsets: &[(i64, i64)]) -> Self {
        let mut offsets = offsets.to_vec();
        if !offsets.contains(&(0, 0)) {
            offsets.push((0, 0));
        }
        Self {
            grid: *grid,
            offsets,
            mask: vec![false; grid.len()],
            near: vec![0; grid.len()],
        }
    }

    /// Take in `mask` (one flag a cell of the grid): the cells that joined
    /// it or left it since the last call move their neighbours' numbers.
    ///
    /// # Panics
    /// If `mask` does not hold one flag a cell.
    pub fn take_in(&mut self, mask: &[bool]) {
        assert_eq!(mask.len(), self.mask.len(), "one flag a cell");
        // Compared a block of cells at a time: most blocks did not change.
        const BLOCK: usize = 64;
        let changed: Vec<usize> = mask
            .chunks(BLOCK)
            .zip(self.mask.chunks(BLOCK))
            .enumerate()
            .filter(|(_, (now, was))| now != was)
            .flat_map(|(k, (now, was))| {
                (0..now.len())
                    .filter(move |&j| now[j] != was[j])
                    .map(move |j| k * BLOCK + j)
            })
            .collect();
        for i in changed {
            self.set(i, mask[i]);
        }
    }

    /// Take in the mask whose flag at each of `cells` (row-major indices,
    /// each a cell of the grid) is `flag(cell)`, the other cells' flags as
    /// they were: where only those cells can have changed (the cells a
    /// map's change feed names), the same as [`Dilation::take_in`] of the
    /// whole mask, without reading it.
    ///
    /// # Panics
    /// If a cell is not on the grid.
    pub fn take_in_cells(&mut self, cells: &[usize], flag: impl Fn(usize) -> bool) {
        for &i in cells {
            self.set(i, flag(i));
        }
    }

    /// Set the mask's flag of cell `i` to `now`, moving the numbers of its
    /// neighbours if it changed.
    fn set(&mut self, i: usize, now: bool) {
        if self.mask[i] == now {
            return;
        }
        self.mask[i] = now;
        let (rows, cols) = (self.grid.rows() as i64, self.grid.cols() as i64);
        let (row, col) = (i as i64 / cols, i as i64 % cols);
        for &(dr, dc) in &self.offsets {
            let (r, c) = (row + dr, col + dc);
            if r >= 0 && c >= 0 && r < rows && c < cols {
                let near = &mut self.near[(r * cols + c) as usize];
                // A cell counts each mask cell once: the numbers stay
                // within the offsets' count, and a cell leaves only a mask
                // it joined.
                *near = if now { *near + 1 } else { *near - 1 };
            }
        }
    }

    /// Whether the cell at row-major `index` is in the grown mask: some cell
    /// of the mask lies at one of the offsets from it.
    ///
    /// # Panics
    /// If `index` is not a cell of the grid.
    pub fn covers(&self, index: usize) -> bool {
        self.near[index] > 0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::exploration::region::{clear_of, clearance_offsets, dilate, dilation_offsets};

    /// Masks that change from step to step as exploration changes them (a
    /// growing blob, scattered cells appearing and going, the map's
    /// border), taken in one after another: the grown mask is always the
    /// one `dilate` and `clear_of` grow from scratch.
    #[test]
    fn a_kept_dilation_is_the_dilation_of_the_mask_now() {
        let mut next = crate::test_rng::uniform(5);
        for (trial, radius_m) in [0.0, 0.05, 0.12, 0.3, 0.35].into_iter().enumerate() {
            let grid = Grid::new([0.0, 0.0], 0.05, 30 + 5 * trial, 41).unwrap();
            let mut grown = Dilation::new(&grid, &dilation_offsets(&grid, radius_m));
            let mut cleared = Dilation::new(&grid, &clearance_offsets(&grid, radius_m));
            let (cr, cc) = (grid.rows() as f64 * next(), 41.0 * next());
            let mut before = vec![false; grid.len()];
            for step in 0..25 {
                let (blob, density) = (step as f64 * 0.8, 0.02 + 0.1 * next());
                let mask: Vec<bool> = (0..grid.len())
                    .map(|i| {
                        let (r, c) = (i / 41, i % 41);
                        let (dr, dc) = (r as f64 - cr, c as f64 - cc);
                        dr.hypot(dc) < blob || next() < density || (step % 5 == 4 && c == 0)
                    })
                    .collect();
                grown.take_in(&mask);
                // Taken in cell by cell: the cells that changed, and some
                // that did not, as a change feed names them.
                let named: Vec<usize> = (0..grid.len())
                    .filter(|&i| mask[i] != before[i] || i % 7 == step % 7)
                    .collect();
                cleared.take_in_cells(&named, |i| mask[i]);
                before = mask.clone();
                let dilated = dilate(&grid, &mask, radius_m);
                let free = clear_of(&grid, &mask, radius_m);
                for i in 0..grid.len() {
                    assert_eq!(
                        grown.covers(i),
                        dilated[i],
                        "radius {radius_m}, step {step}, cell {i}"
                    );
                    assert_eq!(
                        !cleared.covers(i),
                        free[i],
                        "radius {radius_m}, step {step}, cell {i}"
                    );
                }
            }
        }
    }
}
