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
//!   reading ([`GainEvaluator::walked_reach`]), reading each cell's
//!   histogram and terms.
//!
//! [`GainEvaluator::beam_reads`] traces the same axis with the same
//! recurrence on the same inputs, marking the tile of every cell it reads,
//! and marks the tiles of the footprint out to the same reach: a ray's by
//! walking it, a cone's from its sector's extent across each band of tiles
//! (a cell's width wider all round, so that every cell whose centre lies in
//! the sector is in a marked tile; a walk of the cone's cells would cost a
//! third of the gain). A superset of the cells read, close to exact: a gain
//! whose tiles meet no changed cell's tile is the one it was, bit for bit.

use super::GainEvaluator;
use crate::footprint::{CellVisitor, ROW_BLOCK, visit};
use crate::grid::Grid;
use crate::pose::Pose;
use crate::sensor::Footprint;

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

impl GainEvaluator<'_> {
    /// The tiles of every cell the fast evaluator reads for the gain of the
    /// beam at `bearing` from `pose` (valid, as [`Self::evaluate`] checks
    /// them): see the [module documentation](self).
    pub(crate) fn beam_reads(&self, pose: &Pose, bearing: f64, tiles: &Tiles) -> TileSet {
        let grid = self.map.grid();
        let mut bits = vec![0u64; tiles.words()];
        // As `evaluate` forms the beam.
        let origin = [pose.x_m, pose.y_m];
        let angle = pose.theta_rad + bearing;
        let dist = self.distribution(origin, angle);
        let mut axis = Axis {
            tiles,
            bits: &mut bits,
            stop: &self.stop,
            resolution_m: grid.resolution_m(),
            step_m: dist.step_m,
            slots: dist.probabilities.len(),
            through: 1.0,
        };
        visit(
            grid,
            origin,
            angle,
            self.range.max_range_m,
            Footprint::Ray,
            &mut axis,
        );
        debug_assert_eq!(axis.through.to_bits(), dist.no_echo.to_bits());
        let reach = self.walked_reach(&dist);
        match self.footprint {
            Footprint::Cone { half_angle_rad } => Sector {
                origin,
                axis: angle,
                half: half_angle_rad,
                reach,
            }
            .mark(grid, tiles, &mut bits),
            Footprint::Ray => {
                let mut walk = Walk {
                    tiles,
                    bits: &mut bits,
                };
                visit(grid, origin, angle, reach, Footprint::Ray, &mut walk);
            }
        }
        TileSet::from_bits(&bits)
    }
}

/// A cone's sector: the points within `half` of the direction `axis` from
/// `origin`, no farther than `reach` (`half` below pi/2, so that the sector
/// is convex).
struct Sector {
    origin: [f64; 2],
    axis: f64,
    half: f64,
    reach: f64,
}

impl Sector {
    /// Mark the tiles of `grid` that hold a cell whose centre lies within a
    /// cell's width of the sector: every cell the cone walk visits (whose
    /// centre lies in the sector, up to a rounding far below a cell), and a
    /// few more. Row band by row band of tiles, from the sector's extent
    /// across each band, instead of cell by cell.
    fn mark(&self, grid: &Grid, tiles: &Tiles, bits: &mut [u64]) {
        let r = grid.resolution_m();
        let [ox, oy] = grid.origin_m();
        let side = 1usize << TILE_SHIFT;
        // Cell indices whose centres lie in [lo, hi] (metres from the grid's
        // origin), widened by a cell and clamped to `0..n`.
        let centres = |lo: f64, hi: f64, n: usize| -> Option<(usize, usize)> {
            let first = ((lo - r) / r - 0.5).ceil().max(0.0);
            let last = ((hi + r) / r - 0.5).floor().min(n as f64 - 1.0);
            (first <= last).then_some((first as usize, last as usize))
        };
        let Some([y_lo, y_hi]) = self.extent(1, [f64::NEG_INFINITY, f64::INFINITY]) else {
            return;
        };
        let Some((row_lo, row_hi)) = centres(y_lo - oy, y_hi - oy, grid.rows()) else {
            return;
        };
        for tile_row in row_lo / side..=row_hi / side {
            let rows = [
                tile_row * side,
                (tile_row * side + side - 1).min(grid.rows() - 1),
            ];
            let [band_lo, band_hi] = rows.map(|row| oy + (row as f64 + 0.5) * r);
            let Some([x_lo, x_hi]) = self.extent(0, [band_lo - r, band_hi + r]) else {
                continue;
            };
            let Some((col_lo, col_hi)) = centres(x_lo - ox, x_hi - ox, grid.cols()) else {
                continue;
            };
            for tile_col in col_lo / side..=col_hi / side {
                mark(bits, tile_row * tiles.tile_cols + tile_col);
            }
        }
    }

    /// The least and greatest coordinate `along` (0: x, 1: y) of the points
    /// of the sector whose other coordinate lies in `[lo, hi]`, if any: the
    /// extremes of a convex region cut by a band lie at its corners in the
    /// band, where its edges cross the band's sides, or where its arc turns
    /// back along `along`.
    fn extent(&self, along: usize, [lo, hi]: [f64; 2]) -> Option<[f64; 2]> {
        // An axis far from 0 is reduced first, as the cone walk does, so that
        // angles compare by small differences.
        let axis = if self.axis.abs() <= 1e3 {
            self.axis
        } else {
            let (s, c) = self.axis.sin_cos();
            s.atan2(c)
        };
        let across = 1 - along;
        let within = |angle: f64| {
            let d = (angle - axis).rem_euclid(std::f64::consts::TAU);
            d <= self.half || d >= std::f64::consts::TAU - self.half
        };
        let point = |angle: f64, t: f64| {
            let (s, c) = angle.sin_cos();
            [self.origin[0] + t * c, self.origin[1] + t * s]
        };
        let inside = |p: &[f64; 2]| (lo..=hi).contains(&p[across]);
        let mut points: Vec<[f64; 2]> = Vec::with_capacity(12);
        let ends = [axis - self.half, axis + self.half];
        // The corners.
        points.push(self.origin);
        points.extend(ends.map(|angle| point(angle, self.reach)));
        // Where the arc turns back along `along` (its extremes there), and
        // where the edges and the arc cross the band's sides.
        let turns = if along == 0 {
            [0.0, std::f64::consts::PI]
        } else {
            [std::f64::consts::FRAC_PI_2, -std::f64::consts::FRAC_PI_2]
        };
        points.extend(
            turns
                .iter()
                .filter(|&&a| within(a))
                .map(|&a| point(a, self.reach)),
        );
        points.retain(inside);
        for side in [lo, hi] {
            let offset = side - self.origin[across];
            for angle in ends {
                let (s, c) = angle.sin_cos();
                let direction = if across == 1 { s } else { c };
                if direction != 0.0 {
                    let t = offset / direction;
                    if (0.0..=self.reach).contains(&t) {
                        let mut p = point(angle, t);
                        p[across] = side;
                        points.push(p);
                    }
                }
            }
            if self.reach > 0.0 && offset.abs() <= self.reach {
                // The arc's points at this side: sin (or cos) of the angle.
                let ratio = offset / self.reach;
                let angles = if across == 1 {
                    let a = ratio.asin();
                    [a, std::f64::consts::PI - a]
                } else {
                    let a = ratio.acos();
                    [a, -a]
                };
                for angle in angles.into_iter().filter(|&a| within(a)) {
                    let mut p = point(angle, self.reach);
                    p[across] = side;
                    points.push(p);
                }
            }
        }
        let values = points.iter().map(|p| p[along]);
        let least = values.clone().fold(f64::INFINITY, f64::min);
        let greatest = values.fold(f64::NEG_INFINITY, f64::max);
        (least <= greatest).then_some([least, greatest])
    }
}

/// The trace of a beam's axis as `trace_readings` runs it (the same
/// recurrence of the probability of getting through), marking the tile of
/// every cell it reads until that probability is 0.
struct Axis<'a> {
    tiles: &'a Tiles,
    bits: &'a mut [u64],
    stop: &'a [f32],
    resolution_m: f64,
    step_m: f64,
    /// The trace's reading slots (readings past them change nothing).
    slots: usize,
    /// The probability that the beam gets this far.
    through: f64,
}

impl CellVisitor for Axis<'_> {
    fn cell(&mut self, index: usize, d_l: f64, _enter_m: f64) {
        if self.through <= 0.0 {
            return;
        }
        mark(self.bits, self.tiles.of(index));
        let c = f64::from(self.stop[index]);
        if c <= 0.0 {
            return;
        }
        let r = self.resolution_m;
        let d = (d_l + 0.5 * r - c * r).max(0.0);
        if ((d / self.step_m).round() as usize) < self.slots {
            self.through *= 1.0 - c;
        }
    }
}

/// The walk of a beam's footprint, marking the tile of every cell visited
/// (of a row block, the tiles of its two ends, which hold the cells between).
struct Walk<'a> {
    tiles: &'a Tiles,
    bits: &'a mut [u64],
}

impl CellVisitor for Walk<'_> {
    fn cell(&mut self, index: usize, _d_l: f64, _enter_m: f64) {
        mark(self.bits, self.tiles.of(index));
    }

    fn row_block(
        &mut self,
        first: usize,
        _d: &[f64; ROW_BLOCK],
        n: usize,
        _bounds: [f64; 2],
        _reach_m: f64,
    ) {
        mark(self.bits, self.tiles.of(first));
        mark(self.bits, self.tiles.of(first + n - 1));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gain::test_maps::{ring_of_eight, scanned};
    use crate::gain::{GainMethod, GainOptions};
    use crate::sensor::{LaserModel, SensorModel, SonarModel};
    use crate::test_rng::uniform;
    use crate::{CoverageMap, grid::Grid};

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
            let scans: Vec<(Pose, Vec<f64>)> = (0..5)
                .map(|_| {
                    let pose = Pose::new(0.5 + 7.0 * next(), 0.5 + 5.0 * next(), 6.0 * next());
                    (pose, bearings.iter().map(|_| 0.3 + 2.5 * next()).collect())
                })
                .collect();
            let scans: Vec<(Pose, &[f64])> = scans.iter().map(|(p, r)| (*p, &r[..])).collect();
            let map = scanned(grid, &scans, &bearings, model);
            let eval = GainEvaluator::new(&map, model, GainOptions::default()).unwrap();
            let tiles = Tiles::new(&grid);
            for _ in 0..8 {
                let pose = Pose::new(0.3 + 7.4 * next(), 0.3 + 5.4 * next(), 6.0 * next());
                let bearing = 6.0 * next();
                let read = eval.beam_reads(&pose, bearing, &tiles);
                let before = eval.beam_gains(&[(pose, bearing)]).unwrap()[0];
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
                let after = other_eval.beam_gains(&[(pose, bearing)]).unwrap()[0];
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
        let beam_gains = eval.beam_gains(&beams).unwrap();
        for (k, pose) in poses.iter().enumerate() {
            let own = &beam_gains[k * bearings.len()..(k + 1) * bearings.len()];
            let sum = crate::gain::schedule::beam_sum(pose, &bearings, own);
            assert_eq!(sum.to_bits(), gains[k].to_bits(), "{pose:?}");
        }
    }

    /// The tiles marked for a cone's sector hold every cell the cone walk
    /// visits, for random cones (huge axes, cones leaving the grid, reaches
    /// from 0 to past the grid) on grids of a few resolutions.
    #[test]
    fn a_sector_covers_the_cells_of_its_cone() {
        let mut next = uniform(77);
        for trial in 0..2000 {
            let r = [0.05, 0.1, 0.03][trial % 3];
            let grid = Grid::new([-1.0, 2.0], r, 90 + trial % 17, 70 + trial % 23).unwrap();
            let [x0, y0, x1, y1] = grid.bounds_m();
            let origin = [x0 + (x1 - x0) * next(), y0 + (y1 - y0) * next()];
            let axis = if trial % 50 == 0 {
                1e6 * next()
            } else {
                12.0 * (next() - 0.5)
            };
            let half = [0.01, 0.13, 0.6, 1.5][trial % 4] * (0.5 + next());
            let half = half.min(1.55);
            let reach = 6.0 * next() * next();
            let tiles = Tiles::new(&grid);
            let mut walked = vec![0u64; tiles.words()];
            let cone = Footprint::Cone {
                half_angle_rad: half,
            };
            visit(
                &grid,
                origin,
                axis,
                reach,
                cone,
                &mut Walk {
                    tiles: &tiles,
                    bits: &mut walked,
                },
            );
            let mut marked = vec![0u64; tiles.words()];
            Sector {
                origin,
                axis,
                half,
                reach,
            }
            .mark(&grid, &tiles, &mut marked);
            for (w, m) in walked.iter().zip(&marked) {
                assert_eq!(w & !m, 0, "trial {trial}: a visited tile not marked");
            }
            // And not much more: at most a tile or two across each band.
            let (w, m): (u32, u32) = (
                walked.iter().map(|w| w.count_ones()).sum(),
                marked.iter().map(|m| m.count_ones()).sum(),
            );
            assert!(
                m <= w + 4 * (grid.rows() as u32 / 8 + 2),
                "trial {trial}: {m} for {w}"
            );
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
            let sets: Vec<TileSet> = ring_of_eight()
                .iter()
                .map(|&b| eval.beam_reads(&pose, b, &tiles))
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
