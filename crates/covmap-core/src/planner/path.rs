//! Shortest paths for the robot: Dijkstra between cell centres, 8-connected,
//! with Euclidean step lengths and no corner cutting, and the paths it finds.

use std::cmp::Reverse;
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
        path_of(&self.grid, &self.cost, &self.previous, index)
    }
}

/// A heap entry: a path length (metres) and a cell, popped in increasing
/// order of length, ties in increasing order of index (deterministic). Both
/// are kept in one integer, the length's bits above the index: lengths are
/// never negative (nor NaN), and the bits of such numbers order as the
/// numbers do (as `f64::total_cmp` orders them), so one integer comparison
/// orders the entries, where a comparison of the lengths and then the
/// indices took a fifth of the search.
#[derive(PartialEq, Eq, PartialOrd, Ord)]
struct Entry(Reverse<u128>);

impl Entry {
    #[inline]
    fn new(cost_m: f64, index: usize) -> Self {
        debug_assert!(cost_m >= 0.0, "a path length is never negative");
        Self(Reverse(
            (u128::from(cost_m.to_bits()) << 64) | index as u128,
        ))
    }

    /// The path length and the cell.
    #[inline]
    fn get(&self) -> (f64, usize) {
        let key = self.0.0;
        (f64::from_bits((key >> 64) as u64), key as u64 as usize)
    }
}

/// Dijkstra over the 8-connected cells where `passable` holds, from `start`.
pub fn shortest_paths(grid: &Grid, passable: &[bool], start: Cell) -> Result<Reachability> {
    let mut search = Search::new(grid, passable, start)?;
    while search.settle_next().is_some() {}
    Ok(search.into_reachability())
}

/// [`shortest_paths`] one cell at a time: each call of
/// [`Search::settle_next`] settles the next cell, in increasing order of
/// path length, ties in increasing order of index (the heap's order). A
/// caller that wants the nearest cell with some property stops at the
/// first one settled; [`shortest_paths`] is this search run to its end, so
/// every settled cell has the path length and path the whole search gives
/// it: a cell's length is final once it is settled (every later cell is
/// at least as far, and a step adds a positive length), and the cells on
/// its path are settled before it.
pub(crate) struct Search<'p> {
    grid: Grid,
    passable: &'p [bool],
    cost: Vec<f64>,
    previous: Vec<usize>,
    heap: BinaryHeap<Entry>,
    /// The cells whose length was set, to be reset when the memory is
    /// handed back ([`Search::into_memory`]).
    touched: Vec<usize>,
}

/// The memory of a [`Search`], handed from one search to the next: a loop
/// that searches a large grid at every step, and stops early, would
/// otherwise allocate (and the system zero) two values a cell each time,
/// and fill them all. Every length is infinite and every previous cell
/// unset between searches: a search resets the cells it touched.
#[derive(Default)]
pub(crate) struct SearchMemory {
    cost: Vec<f64>,
    previous: Vec<usize>,
    heap: BinaryHeap<Entry>,
    touched: Vec<usize>,
}

impl<'p> Search<'p> {
    /// A search from `start` over the cells where `passable` holds (one flag
    /// a cell of `grid`), nothing settled yet.
    ///
    /// # Errors
    /// [`CovmapError::LengthMismatch`] if `passable` does not hold one flag
    /// a cell, [`CovmapError::CellOutOfBounds`] if `start` is not on the grid.
    pub(crate) fn new(grid: &Grid, passable: &'p [bool], start: Cell) -> Result<Self> {
        Self::with_memory(grid, passable, start, SearchMemory::default())
    }

    /// [`Search::new`], in the memory of an earlier search.
    ///
    /// # Errors
    /// As [`Search::new`].
    pub(crate) fn with_memory(
        grid: &Grid,
        passable: &'p [bool],
        start: Cell,
        memory: SearchMemory,
    ) -> Result<Self> {
        let start = check_search(grid, passable, start)?;
        let SearchMemory {
            mut cost,
            mut previous,
            mut heap,
            mut touched,
        } = memory;
        if cost.len() != grid.len() {
            cost = vec![f64::INFINITY; grid.len()];
            previous = vec![usize::MAX; grid.len()];
        }
        heap.clear();
        touched.clear();
        cost[start] = 0.0;
        touched.push(start);
        heap.push(Entry::new(0.0, start));
        Ok(Self {
            grid: *grid,
            passable,
            cost,
            previous,
            heap,
            touched,
        })
    }

    /// Settle the nearest cell not settled yet: its row-major index and path
    /// length (metres), or `None` when every reachable cell is settled.
    pub(crate) fn settle_next(&mut self) -> Option<(usize, f64)> {
        let cols = self.grid.cols();
        let resolution_m = self.grid.resolution_m();
        // The lengths of a straight and a diagonal step, metres.
        let (straight, diagonal) = (resolution_m, std::f64::consts::SQRT_2 * resolution_m);
        let passable = self.passable;
        while let Some(entry) = self.heap.pop() {
            let (cost_m, index) = entry.get();
            if cost_m > self.cost[index] {
                continue;
            }
            let Cell { row, col } = self.grid.cell(index);
            // The four straight neighbours, where on the grid and passable;
            // a diagonal step needs both its side cells passable (no corner
            // cutting), and its own cell.
            let up = row > 0 && passable[index - cols];
            let down = row + 1 < self.grid.rows() && passable[index + cols];
            let left = col > 0 && passable[index - 1];
            let right = col + 1 < cols && passable[index + 1];
            let (down_right, down_left) = (index + cols + 1, (index + cols).wrapping_sub(1));
            let (up_right, up_left) = (
                index.wrapping_sub(cols).wrapping_add(1),
                index.wrapping_sub(cols + 1),
            );
            let steps = [
                (right, index + 1, straight),
                (down, index + cols, straight),
                (left, index.wrapping_sub(1), straight),
                (up, index.wrapping_sub(cols), straight),
                (down && right && passable[down_right], down_right, diagonal),
                (down && left && passable[down_left], down_left, diagonal),
                (up && right && passable[up_right], up_right, diagonal),
                (up && left && passable[up_left], up_left, diagonal),
            ];
            for (open, neighbour, step_m) in steps {
                if !open {
                    continue;
                }
                let next = cost_m + step_m;
                if next < self.cost[neighbour] {
                    if self.cost[neighbour] == f64::INFINITY {
                        self.touched.push(neighbour);
                    }
                    self.cost[neighbour] = next;
                    self.previous[neighbour] = index;
                    self.heap.push(Entry::new(next, neighbour));
                }
            }
            return Some((index, cost_m));
        }
        None
    }

    /// The cell centres of a shortest path from the start to the settled
    /// cell `index` (as [`Reachability::path_to`] gives it).
    ///
    /// # Panics
    /// If `index` is not a cell of the grid.
    pub(crate) fn path_to(&self, index: usize) -> Vec<[f64; 2]> {
        path_of(&self.grid, &self.cost, &self.previous, index)
    }

    /// The search's memory, every cell it touched reset, for the next.
    pub(crate) fn into_memory(self) -> SearchMemory {
        let Self {
            mut cost,
            mut previous,
            mut heap,
            mut touched,
            ..
        } = self;
        for &i in &touched {
            cost[i] = f64::INFINITY;
            previous[i] = usize::MAX;
        }
        heap.clear();
        touched.clear();
        SearchMemory {
            cost,
            previous,
            heap,
            touched,
        }
    }

    /// The path lengths and paths found so far (all of them, once
    /// [`Search::settle_next`] has returned `None`).
    pub(crate) fn into_reachability(self) -> Reachability {
        Reachability {
            grid: self.grid,
            cost: self.cost,
            previous: self.previous,
        }
    }
}

/// The cell centres of the path to `index` that `previous` holds, for the
/// path lengths `cost` (none where `index` is unreachable).
fn path_of(grid: &Grid, cost: &[f64], previous: &[usize], index: usize) -> Vec<[f64; 2]> {
    if !cost[index].is_finite() {
        return Vec::new();
    }
    let mut cells = vec![index];
    let mut at = index;
    while previous[at] != usize::MAX {
        at = previous[at];
        cells.push(at);
    }
    cells
        .iter()
        .rev()
        .map(|&i| grid.cell_center(grid.cell(i)))
        .collect()
}

/// The cells [`shortest_paths`] reaches from `start` over `passable`, one
/// flag a cell, without their path lengths: a breadth-first fill through
/// the 4-neighbours. A diagonal step needs both its side cells passable, so
/// it reaches nothing two straight steps do not: the 4-connected cells are
/// the 8-connected search's.
///
/// # Errors
/// As [`shortest_paths`].
pub(crate) fn reachable_cells(grid: &Grid, passable: &[bool], start: Cell) -> Result<Vec<bool>> {
    let start = check_search(grid, passable, start)?;
    let (cells, cols) = (grid.len(), grid.cols());
    let mut reached = vec![false; cells];
    reached[start] = true;
    let mut queue = vec![start];
    while let Some(i) = queue.pop() {
        // Rows from the index alone: one division a cell, for the column.
        let col = i % cols;
        let neighbours = [
            (col + 1 < cols).then(|| i + 1),
            (col > 0).then(|| i - 1),
            (i + cols < cells).then(|| i + cols),
            (i >= cols).then(|| i - cols),
        ];
        for n in neighbours.into_iter().flatten() {
            if passable[n] && !reached[n] {
                reached[n] = true;
                queue.push(n);
            }
        }
    }
    Ok(reached)
}

/// The index of `start`, once the mask `passable` is checked to have a
/// value for every cell of `grid` and `start` to be on it.
fn check_search(grid: &Grid, passable: &[bool], start: Cell) -> Result<usize> {
    if passable.len() != grid.len() {
        return Err(CovmapError::LengthMismatch {
            what: "passable mask and grid cells",
            left: passable.len(),
            right: grid.len(),
        });
    }
    grid.index(start)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Random masks of passable cells (scattered and in blobs, from nearly
    /// open to nearly closed) on a grid of `rows x cols`, with a start cell.
    fn random_masks(seed: u64, count: usize) -> Vec<(Grid, Vec<bool>, Cell)> {
        let mut next = crate::test_rng::uniform(seed);
        (0..count)
            .map(|trial| {
                let (rows, cols) = (5 + (40.0 * next()) as usize, 5 + (40.0 * next()) as usize);
                let grid = Grid::new([0.0, 0.0], [0.05, 0.1, 1.0][trial % 3], rows, cols).unwrap();
                let density = [0.05, 0.25, 0.45, 0.6][trial % 4];
                let (cr, cc, blob) = (rows as f64 * next(), cols as f64 * next(), 8.0 * next());
                let passable = (0..grid.len())
                    .map(|i| {
                        let (dr, dc) = ((i / cols) as f64 - cr, (i % cols) as f64 - cc);
                        next() >= density && dr.hypot(dc) >= blob
                    })
                    .collect();
                let start = Cell {
                    row: (rows as f64 * next()) as usize,
                    col: (cols as f64 * next()) as usize,
                };
                (grid, passable, start)
            })
            .collect()
    }

    /// Settling one cell at a time gives the cells in increasing order of
    /// path length, ties to the lower index, each with the length and path
    /// of the whole search: so the first settled cell with a property is
    /// the nearest such cell of the whole search (ties to the lower index),
    /// with its path.
    #[test]
    fn a_search_settles_in_the_order_of_the_whole_searchs_lengths() {
        let mut memory = SearchMemory::default();
        for (trial, (grid, passable, start)) in random_masks(11, 300).into_iter().enumerate() {
            let whole = shortest_paths(&grid, &passable, start).unwrap();
            let mut order: Vec<usize> = (0..grid.len()).filter(|&i| whole.reachable(i)).collect();
            order.sort_by(|&a, &b| whole.cost(a).total_cmp(&whole.cost(b)).then(a.cmp(&b)));
            let mut search = Search::new(&grid, &passable, start).unwrap();
            let mut settled = Vec::new();
            while let Some((i, cost)) = search.settle_next() {
                assert_eq!(
                    cost.to_bits(),
                    whole.cost(i).to_bits(),
                    "trial {trial}, cell {i}"
                );
                assert_eq!(
                    search.path_to(i),
                    whole.path_to(i),
                    "trial {trial}, cell {i}"
                );
                settled.push(i);
            }
            assert_eq!(settled, order, "trial {trial}");
            // Stopped early, at the nearest cell of every seventh column and
            // then of every fifth, in the memory of the searches before (on
            // this grid and others).
            for (k, column) in [(7, 3), (5, 1)] {
                let mut search = Search::with_memory(&grid, &passable, start, memory).unwrap();
                let wanted = |i: usize| i % grid.cols() % k == column;
                let first = std::iter::from_fn(|| search.settle_next()).find(|&(i, _)| wanted(i));
                let nearest = order.iter().copied().find(|&i| wanted(i));
                assert_eq!(first.map(|(i, _)| i), nearest, "trial {trial}");
                if let Some(i) = nearest {
                    assert_eq!(search.path_to(i), whole.path_to(i), "trial {trial}");
                }
                memory = search.into_memory();
            }
            assert!(memory.cost.iter().all(|c| *c == f64::INFINITY));
            assert!(memory.previous.iter().all(|p| *p == usize::MAX));
        }
    }

    /// The breadth-first fill reaches the cells the search does.
    #[test]
    fn the_fill_reaches_what_the_search_reaches() {
        for (trial, (grid, passable, start)) in random_masks(12, 400).into_iter().enumerate() {
            let whole = shortest_paths(&grid, &passable, start).unwrap();
            let reached = reachable_cells(&grid, &passable, start).unwrap();
            let expected: Vec<bool> = (0..grid.len()).map(|i| whole.reachable(i)).collect();
            assert_eq!(reached, expected, "trial {trial}");
        }
        let grid = Grid::new([0.0, 0.0], 1.0, 3, 3).unwrap();
        assert!(reachable_cells(&grid, &[true; 8], Cell { row: 0, col: 0 }).is_err());
        assert!(reachable_cells(&grid, &[true; 9], Cell { row: 3, col: 0 }).is_err());
    }

    /// The search as it was first written (a step at a time from a table of
    /// steps, the heap ordered by `f64::total_cmp` and then the index): the
    /// lengths and paths the search must keep giving, bit for bit.
    fn reference_paths(grid: &Grid, passable: &[bool], start: Cell) -> (Vec<f64>, Vec<usize>) {
        use std::cmp::Ordering;
        #[derive(PartialEq)]
        struct Old(f64, usize);
        impl Eq for Old {}
        impl Ord for Old {
            fn cmp(&self, other: &Self) -> Ordering {
                other
                    .0
                    .total_cmp(&self.0)
                    .then_with(|| other.1.cmp(&self.1))
            }
        }
        impl PartialOrd for Old {
            fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
                Some(self.cmp(other))
            }
        }
        let sqrt2 = std::f64::consts::SQRT_2;
        let steps = [
            (0, 1, 1.0),
            (1, 0, 1.0),
            (0, -1, 1.0),
            (-1, 0, 1.0),
            (1, 1, sqrt2),
            (1, -1, sqrt2),
            (-1, 1, sqrt2),
            (-1, -1, sqrt2),
        ];
        let (rows, cols) = (grid.rows() as i64, grid.cols() as i64);
        let mut cost = vec![f64::INFINITY; grid.len()];
        let mut previous = vec![usize::MAX; grid.len()];
        let start = grid.index(start).unwrap();
        cost[start] = 0.0;
        let mut heap = BinaryHeap::from([Old(0.0, start)]);
        while let Some(Old(cost_m, index)) = heap.pop() {
            if cost_m > cost[index] {
                continue;
            }
            let (row, col) = ((index / grid.cols()) as i64, (index % grid.cols()) as i64);
            for (dr, dc, len) in steps {
                let (nr, nc) = (row + dr, col + dc);
                if nr < 0 || nc < 0 || nr >= rows || nc >= cols {
                    continue;
                }
                let n = (nr * cols + nc) as usize;
                let corner = dr != 0
                    && dc != 0
                    && !(passable[(row * cols + nc) as usize]
                        && passable[(nr * cols + col) as usize]);
                if !passable[n] || corner {
                    continue;
                }
                let next = cost_m + len * grid.resolution_m();
                if next < cost[n] {
                    cost[n] = next;
                    previous[n] = index;
                    heap.push(Old(next, n));
                }
            }
        }
        (cost, previous)
    }

    /// The search gives the lengths and paths of the search as first
    /// written, bit for bit.
    #[test]
    fn the_search_is_the_reference_search() {
        for (trial, (grid, passable, start)) in random_masks(13, 300).into_iter().enumerate() {
            let whole = shortest_paths(&grid, &passable, start).unwrap();
            let (cost, previous) = reference_paths(&grid, &passable, start);
            let bits = |c: &[f64]| c.iter().map(|c| c.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(whole.costs()), bits(&cost), "trial {trial}");
            assert_eq!(whole.previous, previous, "trial {trial}");
        }
    }

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
