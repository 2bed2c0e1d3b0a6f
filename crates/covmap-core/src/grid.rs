//! Grid geometry: where cells are in the world.

use serde::{Deserialize, Serialize};

use crate::error::{CovmapError, Result};

/// A cell address: `row` runs along y, `col` along x.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub struct Cell {
    /// Row index (along y, growing with y).
    pub row: usize,
    /// Column index (along x, growing with x).
    pub col: usize,
}

/// A regular grid of square cells.
///
/// The origin is the world position of the lower-left corner of cell
/// `(row 0, col 0)`. Cell `(row, col)` covers
/// `[ox + col r, ox + (col + 1) r) x [oy + row r, oy + (row + 1) r)`; cells are
/// stored row-major (row `row` starts at index `row * cols`).
///
/// # Example
/// ```
/// use covmap_core::{Cell, Grid};
/// let grid = Grid::new([-1.0, -1.0], 0.05, 40, 60).unwrap();
/// assert_eq!(grid.world_to_cell(0.0, 0.0), Some(Cell { row: 20, col: 20 }));
/// assert_eq!(grid.cell_center(Cell { row: 0, col: 0 }), [-0.975, -0.975]);
/// assert!(Grid::new([0.0, 0.0], -0.05, 10, 10).is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "GridSpec", into = "GridSpec")]
pub struct Grid {
    origin_m: [f64; 2],
    resolution_m: f64,
    rows: usize,
    cols: usize,
}

/// The serialised form of a [`Grid`], validated on the way in.
#[derive(Serialize, Deserialize)]
struct GridSpec {
    origin_m: [f64; 2],
    resolution_m: f64,
    rows: usize,
    cols: usize,
}

impl TryFrom<GridSpec> for Grid {
    type Error = CovmapError;
    fn try_from(s: GridSpec) -> Result<Self> {
        Grid::new(s.origin_m, s.resolution_m, s.rows, s.cols)
    }
}

impl From<Grid> for GridSpec {
    fn from(g: Grid) -> Self {
        GridSpec {
            origin_m: g.origin_m,
            resolution_m: g.resolution_m,
            rows: g.rows,
            cols: g.cols,
        }
    }
}

/// The finest grid resolution, metres (a micrometre).
pub const MIN_RESOLUTION_M: f64 = 1e-6;

/// How many cells from zero a grid's corners may lie (2^32): a coordinate
/// of that size keeps 20 bits within a cell.
pub const MAX_CELLS_FROM_ZERO: f64 = 4_294_967_296.0;

/// Upper bound on the number of cells of one grid (2^31): keeps every index
/// and every `cells x bins` product far from overflow.
pub const MAX_CELLS: usize = 1 << 31;

impl Grid {
    /// A grid with its lower-left corner at `origin_m`, square cells of side
    /// `resolution_m`, `rows` cells along y and `cols` along x.
    ///
    /// Errors ([`CovmapError::InvalidGrid`]) if the resolution is not finite
    /// or below [`MIN_RESOLUTION_M`], the origin is not finite, a dimension
    /// is zero, the grid has more than [`MAX_CELLS`], or a corner lies more
    /// than [`MAX_CELLS_FROM_ZERO`] cells from zero (where `f64` coordinates
    /// would no longer tell points within a cell apart).
    pub fn new(origin_m: [f64; 2], resolution_m: f64, rows: usize, cols: usize) -> Result<Self> {
        if !(resolution_m.is_finite() && resolution_m >= MIN_RESOLUTION_M) {
            return Err(CovmapError::InvalidGrid(format!(
                "resolution must be finite and at least 1e-6 m, got {resolution_m}"
            )));
        }
        if !(origin_m[0].is_finite() && origin_m[1].is_finite()) {
            return Err(CovmapError::InvalidGrid(format!(
                "origin must be finite, got ({}, {})",
                origin_m[0], origin_m[1]
            )));
        }
        if rows == 0 || cols == 0 {
            return Err(CovmapError::InvalidGrid(format!(
                "shape must have at least one row and one column, got {rows} x {cols}"
            )));
        }
        if rows.checked_mul(cols).is_none_or(|n| n > MAX_CELLS) {
            return Err(CovmapError::InvalidGrid(format!(
                "{rows} x {cols} cells exceed the limit of {MAX_CELLS}"
            )));
        }
        let far = [
            origin_m[0] + cols as f64 * resolution_m,
            origin_m[1] + rows as f64 * resolution_m,
        ];
        if !(far[0].is_finite() && far[1].is_finite()) {
            return Err(CovmapError::InvalidGrid(format!(
                "the far corner ({:e}, {:e}) of {rows} x {cols} cells of {resolution_m:e} m from \
                 ({:e}, {:e}) is not finite: the bounds overflow",
                far[0], far[1], origin_m[0], origin_m[1]
            )));
        }
        let largest = origin_m
            .iter()
            .chain(&far)
            .fold(0.0f64, |m, v| m.max(v.abs()));
        if !(largest <= MAX_CELLS_FROM_ZERO * resolution_m) {
            return Err(CovmapError::InvalidGrid(format!(
                "a corner lies {largest} m from zero, more than 2^32 cells of {resolution_m} m: \
                 coordinates that large cannot resolve a cell"
            )));
        }
        Ok(Self {
            origin_m,
            resolution_m,
            rows,
            cols,
        })
    }

    /// A grid covering the rectangle `[x_min, x_max] x [y_min, y_max]` (rounded
    /// up to whole cells) at `resolution_m`.
    pub fn covering(
        x_min: f64,
        y_min: f64,
        x_max: f64,
        y_max: f64,
        resolution_m: f64,
    ) -> Result<Self> {
        if !(x_max > x_min && y_max > y_min) {
            return Err(CovmapError::InvalidGrid(format!(
                "empty rectangle [{x_min}, {x_max}] x [{y_min}, {y_max}]"
            )));
        }
        if !(resolution_m.is_finite() && resolution_m > 0.0) {
            return Err(CovmapError::InvalidGrid(format!(
                "resolution must be finite and positive, got {resolution_m}"
            )));
        }
        let cols = ((x_max - x_min) / resolution_m - 1e-9).ceil().max(1.0);
        let rows = ((y_max - y_min) / resolution_m - 1e-9).ceil().max(1.0);
        if !(cols.is_finite() && rows.is_finite()) || cols * rows > MAX_CELLS as f64 {
            return Err(CovmapError::InvalidGrid(
                "rectangle too large for the resolution".into(),
            ));
        }
        Self::new([x_min, y_min], resolution_m, rows as usize, cols as usize)
    }

    /// World position of the lower-left corner, metres.
    pub fn origin_m(&self) -> [f64; 2] {
        self.origin_m
    }
    /// Side of a cell, metres.
    pub fn resolution_m(&self) -> f64 {
        self.resolution_m
    }
    /// Number of rows (cells along y).
    pub fn rows(&self) -> usize {
        self.rows
    }
    /// Number of columns (cells along x).
    pub fn cols(&self) -> usize {
        self.cols
    }
    /// `(rows, cols)`.
    pub fn shape(&self) -> (usize, usize) {
        (self.rows, self.cols)
    }
    /// Number of cells.
    pub fn len(&self) -> usize {
        self.rows * self.cols
    }
    /// Always false: a grid has at least one cell.
    pub fn is_empty(&self) -> bool {
        false
    }
    /// `[x_min, y_min, x_max, y_max]` of the covered rectangle, metres.
    pub fn bounds_m(&self) -> [f64; 4] {
        let [ox, oy] = self.origin_m;
        [
            ox,
            oy,
            ox + self.cols as f64 * self.resolution_m,
            oy + self.rows as f64 * self.resolution_m,
        ]
    }
    /// Whether the world point lies inside the grid: exactly when
    /// [`Self::world_to_cell`] finds its cell. Up to the rounding of
    /// `(x - x_min) / resolution`, that is the rectangle with its upper edges
    /// excluded: a point a rounding error below an upper edge may fall
    /// outside, and one on it may round into the last cell.
    pub fn contains(&self, x: f64, y: f64) -> bool {
        self.world_to_cell(x, y).is_some()
    }
    /// The cell containing a world point, or `None` outside the grid.
    pub fn world_to_cell(&self, x: f64, y: f64) -> Option<Cell> {
        let [cx, cy] = self.world_to_grid(x, y);
        if !(cx >= 0.0 && cy >= 0.0) {
            return None;
        }
        let (col, row) = (cx.floor() as usize, cy.floor() as usize);
        (col < self.cols && row < self.rows).then_some(Cell { row, col })
    }
    /// Continuous grid coordinates `[col, row]` of a world point: cell
    /// `(r, c)` spans `[c, c + 1) x [r, r + 1)`.
    pub fn world_to_grid(&self, x: f64, y: f64) -> [f64; 2] {
        [
            (x - self.origin_m[0]) / self.resolution_m,
            (y - self.origin_m[1]) / self.resolution_m,
        ]
    }
    /// World position of a cell's centre, metres (the cell need not be inside).
    pub fn cell_center(&self, cell: Cell) -> [f64; 2] {
        [
            self.origin_m[0] + (cell.col as f64 + 0.5) * self.resolution_m,
            self.origin_m[1] + (cell.row as f64 + 0.5) * self.resolution_m,
        ]
    }
    /// Row-major index of a cell, or an error outside the grid.
    pub fn index(&self, cell: Cell) -> Result<usize> {
        if cell.row < self.rows && cell.col < self.cols {
            Ok(cell.row * self.cols + cell.col)
        } else {
            Err(CovmapError::CellOutOfBounds {
                row: cell.row,
                col: cell.col,
                rows: self.rows,
                cols: self.cols,
            })
        }
    }
    /// The cell at a row-major index (which must be below [`Grid::len`]).
    pub fn cell(&self, index: usize) -> Cell {
        Cell {
            row: index / self.cols,
            col: index % self.cols,
        }
    }

    /// Errors unless `(x, y)` lies inside the grid.
    pub(crate) fn check_inside(&self, x: f64, y: f64) -> Result<Cell> {
        if let Some(cell) = self.world_to_cell(x, y) {
            return Ok(cell);
        }
        let [x_min, y_min, x_max, y_max] = self.bounds_m();
        Err(CovmapError::PoseOutsideMap {
            x,
            y,
            x_min,
            x_max,
            y_min,
            y_max,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rejects_bad_geometry() {
        for r in [0.0, -0.1, f64::NAN, f64::INFINITY] {
            assert!(matches!(
                Grid::new([0.0, 0.0], r, 3, 3),
                Err(CovmapError::InvalidGrid(_))
            ));
        }
        assert!(Grid::new([0.0, 0.0], 0.1, 0, 3).is_err());
        assert!(Grid::new([0.0, 0.0], 0.1, 3, 0).is_err());
        assert!(Grid::new([f64::NAN, 0.0], 0.1, 3, 3).is_err());
        assert!(Grid::new([0.0, 0.0], 0.1, usize::MAX, 2).is_err());
        // Cells too small to compute with, or too far out to resolve.
        assert!(Grid::new([0.0, 0.0], 1e-310, 1, 40).is_err());
        assert!(Grid::new([0.0, 0.0], 1e-7, 1, 40).is_err());
        assert!(Grid::new([1e17, 0.0], 0.05, 4, 4).is_err());
        assert!(Grid::new([-3e8, 0.0], 0.05, 4, 4).is_err());
        assert!(
            Grid::new([6e6, 4e6], 0.05, 400, 400).is_ok(),
            "UTM coordinates"
        );
        assert!(Grid::new([0.0, 0.0], 1e-6, 1, 40).is_ok());
        // Bounds that overflow to infinity, though no corner is many cells out.
        let err = Grid::new([1.7e308, 0.0], 1e300, 1, 10_000_000).unwrap_err();
        assert!(err.to_string().contains("overflow"), "{err}");
    }

    #[test]
    fn world_cell_round_trip() {
        let g = Grid::new([-2.0, 1.0], 0.25, 8, 12).unwrap();
        for index in 0..g.len() {
            let cell = g.cell(index);
            let [x, y] = g.cell_center(cell);
            assert_eq!(g.world_to_cell(x, y), Some(cell));
            assert_eq!(g.index(cell).unwrap(), index);
        }
        assert_eq!(g.world_to_cell(-2.0001, 1.5), None);
        assert_eq!(g.world_to_cell(1.0, 1.5), None, "upper x edge excluded");
        assert_eq!(
            g.world_to_cell(0.999, 2.999),
            Some(Cell { row: 7, col: 11 })
        );
        assert!(g.index(Cell { row: 8, col: 0 }).is_err());
    }

    /// A point a rounding error below an upper edge is inside exactly when it
    /// falls in a cell: `contains`, `world_to_cell` and `check_inside` agree.
    #[test]
    fn inside_means_in_a_cell() {
        let g = Grid::new([-1.3, 0.0], 0.3, 2, 5).unwrap();
        let [_, _, x_max, y_max] = g.bounds_m();
        let below = |v: f64| f64::from_bits(v.to_bits() - 1);
        // Rounds up to the far edge in grid coordinates: in no cell.
        assert_eq!(g.world_to_grid(below(x_max), 0.05)[0], 5.0);
        for (x, y) in [
            (below(x_max), 0.05),
            (0.05, below(y_max)),
            (below(below(x_max)), 0.05),
            (-1.3, 0.0),
        ] {
            let cell = g.world_to_cell(x, y);
            assert_eq!(g.contains(x, y), cell.is_some(), "({x}, {y})");
            assert_eq!(g.check_inside(x, y).ok(), cell, "({x}, {y})");
        }
        assert!(!g.contains(below(x_max), 0.05));
    }

    #[test]
    fn covering_rounds_up() {
        let g = Grid::covering(0.0, 0.0, 20.0, 20.0, 0.05).unwrap();
        assert_eq!(g.shape(), (400, 400));
        let g = Grid::covering(0.0, 0.0, 1.01, 0.5, 0.1).unwrap();
        assert_eq!(g.shape(), (5, 11));
    }

    #[test]
    fn serde_validates() {
        let g = Grid::new([0.5, -0.5], 0.05, 3, 4).unwrap();
        let s = serde_json::to_string(&g).unwrap();
        assert_eq!(serde_json::from_str::<Grid>(&s).unwrap(), g);
        let bad = s.replace("0.05", "-0.05");
        assert!(serde_json::from_str::<Grid>(&bad).is_err());
    }
}
