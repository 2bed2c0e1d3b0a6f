//! Shortest paths for the robot: Dijkstra between cell centres, 8-connected,
//! with Euclidean step lengths and no corner cutting, and the paths it finds.

use std::cmp::Ordering;
use std::collections::BinaryHeap;

use crate::error::{CovmapError, Result};
use crate::grid::{Cell, Grid};

/// Shortest path lengths over the free cells from one start cell.
#[derive(Clone, Debug)]
pub struct Reachability {
    grid: Grid,
    /// Path length to each cell, metres (`inf` where unreachable).
    cost: Vec<f64>,
    /// The previous cell on a shortest path (`usize::MAX` at the start and
    /// unreachable cells).
    previous: Vec<usize>,
}

/// Cells are named by their row-major index on the map's grid
/// ([`Grid::index`]); like a slice, the methods taking an index panic if it is
/// not below [`Grid::len`].
impl Reachability {
    /// Path length to a cell, metres (`inf` where unreachable).
    ///
    /// # Panics
    /// If `index` is not a cell of the grid.
    pub fn cost(&self, index: usize) -> f64 {
        self.cost[index]
    }
    /// All path lengths, row-major.
    pub fn costs(&self) -> &[f64] {
        &self.cost
    }
    /// Whether the cell can be reached.
    ///
    /// # Panics
    /// If `index` is not a cell of the grid.
    pub fn reachable(&self, index: usize) -> bool {
        self.cost[index].is_finite()
    }
    /// The cell centres of a shortest path from the start to `index`.
    ///
    /// # Panics
    /// If `index` is not a cell of the grid.
    pub fn path_to(&self, index: usize) -> Vec<[f64; 2]> {
        if !self.reachable(index) {
            return Vec::new();
        }
        let mut cells = vec![index];
        let mut at = index;
        while self.previous[at] != usize::MAX {
            at = self.previous[at];
            cells.push(at);
        }
        cells
            .iter()
            .rev()
            .map(|&i| self.grid.cell_center(self.grid.cell(i)))
            .collect()
    }
}

/// A heap entry ordered by increasing cost, then index (deterministic ties).
#[derive(PartialEq)]
struct Entry(f64, usize);
impl Eq for Entry {}
impl Ord for Entry {
    fn cmp(&self, other: &Self) -> Ordering {
        other
            .0
            .total_cmp(&self.0)
            .then_with(|| other.1.cmp(&self.1))
    }
}
impl PartialOrd for Entry {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

/// Dijkstra over the 8-connected cells where `passable` holds, from `start`.
pub fn shortest_paths(grid: &Grid, passable: &[bool], start: Cell) -> Result<Reachability> {
    if passable.len() != grid.len() {
        return Err(CovmapError::LengthMismatch {
            what: "passable mask and grid cells",
            left: passable.len(),
            right: grid.len(),
        });
    }
    let start = grid.index(start)?;
    let (rows, cols) = (grid.rows() as i64, grid.cols() as i64);
    let resolution_m = grid.resolution_m();
    let mut cost = vec![f64::INFINITY; grid.len()];
    let mut previous = vec![usize::MAX; grid.len()];
    let mut heap = BinaryHeap::new();
    cost[start] = 0.0;
    heap.push(Entry(0.0, start));
    const STEPS: [(i64, i64, f64); 8] = [
        (0, 1, 1.0),
        (1, 0, 1.0),
        (0, -1, 1.0),
        (-1, 0, 1.0),
        (1, 1, std::f64::consts::SQRT_2),
        (1, -1, std::f64::consts::SQRT_2),
        (-1, 1, std::f64::consts::SQRT_2),
        (-1, -1, std::f64::consts::SQRT_2),
    ];
    while let Some(Entry(cost_m, index)) = heap.pop() {
        if cost_m > cost[index] {
            continue;
        }
        let cell = grid.cell(index);
        let (row, col) = (cell.row as i64, cell.col as i64);
        for &(dr, dc, len) in &STEPS {
            let (nr, nc) = (row + dr, col + dc);
            if nr < 0 || nc < 0 || nr >= rows || nc >= cols {
                continue;
            }
            let neighbour = (nr * cols + nc) as usize;
            // No corner cutting: a diagonal step needs both side cells free.
            if !passable[neighbour]
                || (dr != 0
                    && dc != 0
                    && !(passable[(row * cols + nc) as usize]
                        && passable[(nr * cols + col) as usize]))
            {
                continue;
            }
            let next = cost_m + len * resolution_m;
            if next < cost[neighbour] {
                cost[neighbour] = next;
                previous[neighbour] = index;
                heap.push(Entry(next, neighbour));
            }
        }
    }
    Ok(Reachability {
        grid: *grid,
        cost,
        previous,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dijkstra_lengths() {
        let grid = Grid::new([0.0, 0.0], 1.0, 5, 5).unwrap();
        let mut passable = vec![true; 25];
        passable[2 * 5 + 2] = false;
        let r = shortest_paths(&grid, &passable, Cell { row: 0, col: 0 }).unwrap();
        assert_eq!(r.cost(4), 4.0);
        assert!(
            (r.cost(24) - 4.0 * std::f64::consts::SQRT_2 - 0.0).abs() > 1e-9,
            "the centre is blocked"
        );
        assert!(!r.reachable(12));
        assert_eq!(r.path_to(4).len(), 5);
    }
}
