//! Which cells a candidate's expected gain reads, as tiles of the map: what
//! the planning cache compares with the cells a scan changed, to tell which
//! candidates' gains a scan can have changed.
//!
//! The fast evaluator computes a beam's gain from the cells of two walks,
//! and from nothing else of the map (the kernels and the prior's gains
//! depend on the sensor model alone):
//! - the trace of the beam's axis that predicts its readings
//!   (`trace_readings`): every cell of the ray out to the maximum range, up
//!   to and including the first that stops the beam with certainty (where
//!   the probability of getting through falls to 0; the trace reads no cell
//!   after it);
//! - the walk of its footprint out to the reach of its farthest possible
//!   reading ([`GainEvaluator::walked_reach`](super::GainEvaluator::walked_reach)), reading each cell's
//!   histogram and terms: a ray's cell by cell, a cone's in blocks of a
//!   row's neighbouring cells.
//!
//! The walks mark what they read as they read it ([`Marks`]): the trace the
//! tile of every cell it reads (`trace_readings_with`), the footprint's walk
//! ([`Recording`]) the tile of every cell it hands the gain and, of a row
//! block, the tiles of its two ends, which hold the cells between (a block
//! is at most 8 cells of one row, a tile's width). So the tiles are those of
//! exactly the cells read, found at the cost of a few bit operations a
//! block, instead of by walks of their own: a gain whose tiles meet no
//! changed cell's tile is the one it was, bit for bit. (Marking a cone's
//! tiles apart from its gain, from the extent of its sector across each band
//! of tiles, took a sixth of the planning time and marked a few tiles more.)

use crate::footprint::{CellVisitor, ROW_BLOCK};
use crate::grid::Grid;

/// Tiles are `2^TILE_SHIFT` cells a side (8: a row block of the cone walk
/// spans at most two).
const TILE_SHIFT: u32 = 3;
const _: () = assert!(1 << TILE_SHIFT >= ROW_BLOCK);

/// A grid cut into square tiles of 8 x 8 cells (the last row and column of
/// tiles may be cut short), and sets of tiles as bitsets.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Tiles {
    /// Columns of cells.
    cols: usize,
    /// Columns of tiles.
    tile_cols: usize,
    /// Tiles in all.
    len: usize,
}

impl Tiles {
    /// The tiles of `grid`.
    pub(crate) fn new(grid: &Grid) -> Self {
        let tile_cols = grid.cols().div_ceil(1 << TILE_SHIFT);
        let tile_rows = grid.rows().div_ceil(1 << TILE_SHIFT);
        Self {
            cols: grid.cols(),
            tile_cols,
            len: tile_cols * tile_rows,
        }
    }

    /// The tile of the cell at row-major `index`.
    #[inline]
    fn of(&self, index: usize) -> usize {
        let (row, col) = (index / self.cols, index % self.cols);
        (row >> TILE_SHIFT) * self.tile_cols + (col >> TILE_SHIFT)
    }

    /// Words of a bitset over every tile.
    fn words(&self) -> usize {
        self.len.div_ceil(64)
    }

    /// The bitset of the tiles that hold `cells` (row-major indices).
    pub(crate) fn of_cells(&self, cells: &[usize]) -> Vec<u64> {
        let mut bits = vec![0u64; self.words()];
        for &cell in cells {
            mark(&mut bits, self.of(cell));
        }
        bits
    }
}

/// Set bit `tile`.
#[inline]
fn mark(bits: &mut [u64], tile: usize) {
    bits[tile / 64] |= 1 << (tile % 64);
}

/// A set of tiles: a bitset over the tiles, stored from its first word that
/// is not 0 to its last.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub(crate) struct TileSet {
    first: usize,
    words: Vec<u64>,
}

impl TileSet {
    /// The set of the bitset `bits` over every tile.
    fn from_bits(bits: &[u64]) -> Self {
        let Some(first) = bits.iter().position(|&w| w != 0) else {
            return Self::default();
        };
        let last = bits.iter().rposition(|&w| w != 0).unwrap_or(first);
        Self {
            first,
            words: bits[first..=last].to_vec(),
        }
    }

    /// Whether the set shares a tile with the bitset `bits` over every tile
    /// (of the same [`Tiles`]).
    pub(crate) fn meets(&self, bits: &[u64]) -> bool {
        let theirs = bits.get(self.first..).unwrap_or(&[]);
        self.words.iter().zip(theirs).any(|(a, b)| a & b != 0)
    }
}

/// The tiles of the cells one beam's gain reads, marked by its walks as they
/// read them, one beam at a time ([`Self::take`] hands them over and starts
/// the next).
pub(crate) struct Marks<'t> {
    tiles: &'t Tiles,
    bits: Vec<u64>,
    /// The row of the cell marked last: the index of its first cell, one
    /// past its last, and the index of its first tile (the walks stay on a
    /// row for several cells, so the division that finds a cell's row is
    /// rarely needed).
    row: [usize; 3],
}

impl<'t> Marks<'t> {
    /// No tile of `tiles` marked.
    pub(crate) fn new(tiles: &'t Tiles) -> Self {
        Self {
            tiles,
            bits: vec![0; tiles.words()],
            row: [0; 3],
        }
    }

    /// Mark the tile of the cell at row-major `index`.
    #[inline(always)]
    pub(crate) fn cell(&mut self, index: usize) {
        let [first, end, tile_base] = &mut self.row;
        if !(*first..*end).contains(&index) {
            let row = index / self.tiles.cols;
            *first = row * self.tiles.cols;
            *end = *first + self.tiles.cols;
            *tile_base = (row >> TILE_SHIFT) * self.tiles.tile_cols;
        }
        mark(
            &mut self.bits,
            *tile_base + ((index - *first) >> TILE_SHIFT),
        );
    }

    /// The tiles marked since the last call, none marked after it.
    pub(crate) fn take(&mut self) -> TileSet {
        let set = TileSet::from_bits(&self.bits);
        self.bits[set.first..set.first + set.words.len()].fill(0);
        set
    }
}

/// A walk of a beam's footprint that marks the tile of every cell it hands
/// `inner` (of a row block, the tiles of its two ends, which hold the cells
/// between), and hands it on unchanged.
pub(crate) struct Recording<'a, 't, V> {
    pub(crate) marks: &'a mut Marks<'t>,
    pub(crate) inner: &'a mut V,
}

impl<V: CellVisitor> CellVisitor for Recording<'_, '_, V> {
    #[inline(always)]
    fn cell(&mut self, index: usize, d_l: f64, enter_m: f64) {
        self.marks.cell(index);
        self.inner.cell(index, d_l, enter_m);
    }

    #[inline(always)]
    fn row_block(
        &mut self,
        first: usize,
        d: &[f64; ROW_BLOCK],
        n: usize,
        bounds: [f64; 2],
        reach_m: f64,
    ) {
        self.marks.cell(first);
        self.marks.cell(first + n - 1);
        self.inner.row_block(first, d, n, bounds, reach_m);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::footprint::visit;
    use crate::gain::test_maps::{ring_of_eight, scanned};
    use crate::gain::{GainEvaluator, GainMethod, GainOptions};
    use crate::pose::Pose;
    use crate::sensor::{LaserModel, SensorModel, SonarModel};
    use crate::test_rng::uniform;
    use crate::{CoverageMap, grid::Grid};

    /// A map of `grid` after `count` scans from poses and with ranges drawn
    /// from `next`.
    fn randomly_scanned(
        grid: Grid,
        count: usize,
        bearings: &[f64],
        model: &dyn SensorModel,
        next: &mut impl FnMut() -> f64,
    ) -> CoverageMap {
        let scans: Vec<(Pose, Vec<f64>)> = (0..count)
            .map(|_| {
                let pose = Pose::new(0.5 + 7.0 * next(), 0.5 + 5.0 * next(), 6.0 * next());
                (pose, bearings.iter().map(|_| 0.3 + 2.5 * next()).collect())
            })
            .collect();
        let scans: Vec<(Pose, &[f64])> = scans.iter().map(|(p, r)| (*p, &r[..])).collect();
        scanned(grid, &scans, bearings, model)
    }

    /// The tiles marked for each beam, of many evaluated together, are the
    /// tiles of the cells its axis trace reads and of its footprint's cells
    /// out to the walked reach, found cell by cell: no more, no fewer.
    #[test]
    fn the_marks_are_the_tiles_of_the_cells_walked() {
        let grid = Grid::new([0.0, 0.0], 0.05, 120, 160).unwrap();
        let bearings = ring_of_eight();
        let mut next = uniform(5);
        for model in [
            &SonarModel::default() as &dyn SensorModel,
            &LaserModel::default(),
        ] {
            let map = randomly_scanned(grid, 4, &bearings, model, &mut next);
            let eval = GainEvaluator::new(&map, model, GainOptions::default()).unwrap();
            let tiles = Tiles::new(&grid);
            let beams: Vec<(Pose, f64)> = (0..150)
                .map(|_| {
                    let pose = Pose::new(0.1 + 7.8 * next(), 0.1 + 5.8 * next(), 6.0 * next());
                    (pose, 6.0 * next())
                })
                .collect();
            let marked = eval.beam_gains_and_reads(&beams, &tiles).unwrap();
            for (&(pose, bearing), (_, marked)) in beams.iter().zip(&marked) {
                let origin = [pose.x_m, pose.y_m];
                let angle = pose.theta_rad + bearing;
                let mut cells = Vec::new();
                let dist = eval.distribution_with(origin, angle, |i| cells.push(i));
                let reach = eval.walked_reach(&dist);
                visit(
                    &grid,
                    origin,
                    angle,
                    reach,
                    model.footprint(),
                    &mut |i, _| {
                        cells.push(i);
                    },
                );
                let walked = TileSet::from_bits(&tiles.of_cells(&cells));
                assert_eq!(marked, &walked, "{pose:?} {bearing}");
            }
        }
    }

    /// Changing any cell outside a beam's tiles leaves its gain as it was,
    /// bit for bit, for sonar cones and laser rays.
    #[test]
    fn a_gain_reads_no_cell_outside_its_tiles() {
        let grid = Grid::new([0.0, 0.0], 0.05, 120, 160).unwrap();
        let bearings = ring_of_eight();
        let mut next = uniform(23);
        for model in [
            &SonarModel::default() as &dyn SensorModel,
            &LaserModel::default(),
        ] {
            let map = randomly_scanned(grid, 5, &bearings, model, &mut next);
            let eval = GainEvaluator::new(&map, model, GainOptions::default()).unwrap();
            let tiles = Tiles::new(&grid);
            for _ in 0..8 {
                let pose = Pose::new(0.3 + 7.4 * next(), 0.3 + 5.4 * next(), 6.0 * next());
                let bearing = 6.0 * next();
                let (before, read) = eval
                    .beam_gains_and_reads(&[(pose, bearing)], &tiles)
                    .unwrap()
                    .remove(0);
                // Scramble every cell outside the tiles read.
                let mut data = map.histograms().to_vec();
                let mut outside = 0;
                for i in 0..grid.len() {
                    if !read.meets(&tiles.of_cells(&[i])) {
                        outside += 1;
                        let h = &mut data[i * 16..(i + 1) * 16];
                        h.fill(0.001);
                        h[(7 * i) % 16] = 1.0 - 15.0 * 0.001;
                    }
                }
                assert!(outside > 0);
                let other = CoverageMap::from_histograms(grid, 16, data).unwrap();
                let other_eval = GainEvaluator::new(&other, model, GainOptions::default()).unwrap();
                let after = other_eval
                    .beam_gains_and_reads(&[(pose, bearing)], &tiles)
                    .unwrap()[0]
                    .0;
                assert_eq!(before.to_bits(), after.to_bits(), "{pose:?} {bearing}");
            }
        }
    }

    /// The beams' gains summed as a candidate's are its gain, bit for bit.
    #[test]
    fn beam_gains_sum_to_the_candidates_gain() {
        let grid = Grid::new([0.0, 0.0], 0.05, 80, 100).unwrap();
        let sonar = SonarModel::default();
        let bearings = ring_of_eight();
        let scan: (Pose, &[f64]) = (
            Pose::new(2.0, 2.0, 0.3),
            &[1.2, 2.0, 6.0, 0.7, 1.5, 2.2, 3.0, 0.4],
        );
        let map = scanned(grid, &[scan], &bearings, &sonar);
        let eval = GainEvaluator::new(&map, &sonar, GainOptions::default()).unwrap();
        let poses: Vec<Pose> = (0..30)
            .map(|k| Pose::new(0.3 + 0.15 * k as f64, 0.4 + 0.12 * k as f64, 0.9 * k as f64))
            .collect();
        let gains = eval.evaluate(&poses, &bearings, GainMethod::Fast).unwrap();
        let beams: Vec<(Pose, f64)> = poses
            .iter()
            .flat_map(|&p| bearings.iter().map(move |&b| (p, b)))
            .collect();
        let beam_gains: Vec<f64> = eval
            .beam_gains_and_reads(&beams, &Tiles::new(&grid))
            .unwrap()
            .into_iter()
            .map(|(gain, _)| gain)
            .collect();
        for (k, pose) in poses.iter().enumerate() {
            let own = &beam_gains[k * bearings.len()..(k + 1) * bearings.len()];
            let sum = crate::gain::schedule::beam_sum(pose, &bearings, own);
            assert_eq!(sum.to_bits(), gains[k].to_bits(), "{pose:?}");
        }
    }

    /// The tiles of a candidate inside a closed room stop at its walls.
    #[test]
    fn walls_bound_the_tiles() {
        // A closed square room of certain walls in a map otherwise at the prior.
        let grid = Grid::new([0.0, 0.0], 0.05, 200, 200).unwrap();
        let bins = 16;
        let mut data = vec![1.0 / bins as f32; grid.len() * bins];
        for (i, h) in data.chunks_exact_mut(bins).enumerate() {
            let (row, col) = (i / 200, i % 200);
            let wall = (row == 40 || row == 80) && (40..=80).contains(&col)
                || (col == 40 || col == 80) && (40..=80).contains(&row);
            let inside = (41..80).contains(&row) && (41..80).contains(&col);
            if wall || inside {
                h.fill(0.0);
                h[if wall { bins - 1 } else { 0 }] = 1.0;
            }
        }
        let map = CoverageMap::from_histograms(grid, bins, data).unwrap();
        let sonar = SonarModel::default();
        let eval = GainEvaluator::new(&map, &sonar, GainOptions::default()).unwrap();
        let tiles = Tiles::new(&grid);
        let reads = |pose: Pose| {
            let beams: Vec<(Pose, f64)> = ring_of_eight().iter().map(|&b| (pose, b)).collect();
            let sets: Vec<TileSet> = eval
                .beam_gains_and_reads(&beams, &tiles)
                .unwrap()
                .into_iter()
                .map(|(_, reads)| reads)
                .collect();
            move |cell: usize| sets.iter().any(|s| s.meets(&tiles.of_cells(&[cell])))
        };
        let read = reads(Pose::new(3.0, 3.0, 0.0));
        // 4.5 m east of the first candidate, behind the room's east wall;
        // 4.5 m south of the second, on one of its beams' axes.
        let far = grid.index(crate::Cell { row: 60, col: 150 }).unwrap();
        let wall = grid.index(crate::Cell { row: 80, col: 60 }).unwrap();
        assert!(!read(far));
        assert!(read(wall));
        let open = reads(Pose::new(7.5, 7.5, 0.0));
        assert!(open(far));
    }
}
