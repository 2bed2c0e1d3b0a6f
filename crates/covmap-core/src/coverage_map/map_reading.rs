//! The parts of an update that read the map itself: an echo's marks shared
//! out by what the arc already holds (`end_attribution`), free-space updates
//! that spare cells the map holds covered (`free_yield`), and the posterior
//! floor mixed in where a reading contradicts a cell (`posterior_floor`).
//! All three are off in the paper's reading (every weight 0), and the update
//! then never looks at a cell before multiplying its kernel in.
//!
//! One beam is one pass over its footprint: free cells are updated as they
//! are met, and with attribution on, the cells an echo marks are set aside
//! until the pass has seen the whole arc (how covered its most covered cell
//! was before the reading), then updated.

use crate::grid::Grid;
use crate::histogram;
use crate::sensor::RangeModel;

/// The model's map-reading weights, and one beam's state.
#[derive(Clone, Debug)]
pub(super) struct MapReading {
    attribution: f32,
    free_yield: f32,
    /// The weight of the uniform prior mixed into a contradicted histogram:
    /// `posterior_floor` times the bin count.
    mix: f32,
    half_m: f64,
    /// The beam's reading (at most the maximum range), metres.
    range_m: f64,
    /// Cells at or beyond this distance are marked (the end band and the
    /// band behind it); infinite for a no-echo reading.
    marks_from_m: f64,
    /// The largest mean coverage among the end band's cells before the
    /// reading, at least 1/2.
    most_covered: f32,
    /// The marked cells set aside while the pass goes on: index, distance
    /// and mean coverage before the reading.
    marked: Vec<(usize, f64, f32)>,
    /// A kernel mixed with the prior, one bin count long.
    mixed: Vec<f32>,
}

impl MapReading {
    /// The terms of `range` on `grid`'s histograms of `bins` bins, or `None`
    /// if every weight is 0 (the update need not read the map).
    pub(super) fn of(range: &RangeModel, grid: &Grid, bins: usize) -> Option<Self> {
        let terms = Self {
            attribution: range.end_attribution as f32,
            free_yield: range.free_yield as f32,
            mix: (range.posterior_floor * bins as f64) as f32,
            half_m: 0.5 * grid.resolution_m(),
            range_m: 0.0,
            marks_from_m: f64::INFINITY,
            most_covered: 0.5,
            marked: Vec::new(),
            mixed: vec![0.0; bins],
        };
        (terms.attribution > 0.0 || terms.free_yield > 0.0 || terms.mix > 0.0).then_some(terms)
    }

    /// Start a beam of `range_m` metres (at most the maximum range), an
    /// echo if `echo`.
    pub(super) fn begin(&mut self, range_m: f64, echo: bool) {
        self.range_m = range_m;
        self.marks_from_m = if echo {
            range_m - self.half_m
        } else {
            f64::INFINITY
        };
        self.most_covered = 0.5;
        self.marked.clear();
    }

    /// Whether the cell `d_l` metres along the beam, of histogram `h`,
    /// waits for the end of the pass; if so it is set aside with its mean
    /// coverage (noted for the arc's if the cell is in the end band).
    #[inline]
    pub(super) fn defer(&mut self, index: usize, d_l: f64, h: &[f32]) -> bool {
        if self.attribution <= 0.0 || d_l < self.marks_from_m {
            return false;
        }
        let m = histogram::mean_in_lanes(h);
        if d_l <= self.range_m + self.half_m {
            self.most_covered = self.most_covered.max(m);
        }
        self.marked.push((index, d_l, m));
        true
    }

    /// Update the cells set aside, once the pass is over: each cell of
    /// `data` (`bins` bins a cell) with its kernel `kernel(d_l)`, as
    /// [`Self::update`].
    pub(super) fn update_marked<'k, const N: usize>(
        &mut self,
        data: &mut [f32],
        bins: usize,
        kernel: impl Fn(f64) -> &'k [f32],
        floor: f32,
    ) {
        let marked = std::mem::take(&mut self.marked);
        for &(i, d_l, m) in &marked {
            let h = &mut data[i * bins..(i + 1) * bins];
            self.update_with_mean::<N>(h, kernel(d_l), d_l, m, floor);
        }
        self.marked = marked;
    }

    /// Multiply kernel `k` (normalised) into histogram `h` of a cell `d_l`
    /// metres along the beam: `k` mixed with the uniform prior by the
    /// attribution or yield weight, then, if the reading contradicts the
    /// cell, the floor mixed in. `floor` as [`histogram::update_bins`].
    ///
    /// The reading contradicts a cell if its mean coverage for the cell
    /// (`mu`: 0 in free space, 1 behind the end, `1/2 + o/r` in the end
    /// band) and the cell's mean lie on opposite sides of 1/2; the kernel's
    /// own mean lies on `mu`'s side, as the density falls away from `mu`.
    #[inline]
    pub(super) fn update<const N: usize>(
        &mut self,
        h: &mut [f32],
        k: &[f32],
        d_l: f64,
        floor: f32,
    ) {
        let m = histogram::mean_in_lanes(h);
        self.update_with_mean::<N>(h, k, d_l, m, floor);
    }

    /// [`Self::update`] of a cell whose mean coverage `m` is known.
    #[inline]
    fn update_with_mean<const N: usize>(
        &mut self,
        h: &mut [f32],
        k: &[f32],
        d_l: f64,
        m: f32,
        floor: f32,
    ) {
        let marked = d_l >= self.marks_from_m;
        let w = if marked {
            1.0 - self.attribution + self.attribution * (m / self.most_covered).min(1.0)
        } else {
            1.0 - self.free_yield * (2.0 * m - 1.0).clamp(0.0, 1.0)
        };
        if w < 1.0 {
            let share = (1.0 - w) / k.len() as f32;
            for (v, &kv) in self.mixed.iter_mut().zip(k) {
                *v = w * kv + share;
            }
            histogram::update_bins::<N>(h, &self.mixed, floor);
        } else {
            histogram::update_bins::<N>(h, k, floor);
        }
        if self.mix > 0.0 {
            // The sign of mu - 1/2 (0 at the end point itself: no side).
            let side = if !marked {
                -1.0
            } else {
                (d_l - self.range_m).signum() as f32
            };
            if side * (m - 0.5) < 0.0 {
                histogram::mix_uniform(h, self.mix);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::coverage_map::CoverageMap;
    use crate::scan_map::ScanMap;
    use crate::sensor::{LaserModel, SonarModel};

    const BINS: usize = 16;

    fn grid() -> Grid {
        Grid::new([0.0, 0.0], 0.05, 60, 60).unwrap()
    }

    /// A 3 m square map at 5 cm, every cell at the prior but `set`, and the
    /// index of the cell at `(x, y)` (metres).
    fn map_with(set: &[([f64; 2], [f32; BINS])]) -> (CoverageMap, Vec<usize>) {
        let grid = grid();
        let mut data = vec![1.0 / BINS as f32; grid.len() * BINS];
        let mut at = Vec::new();
        for (xy, h) in set {
            let i = grid
                .index(grid.world_to_cell(xy[0], xy[1]).unwrap())
                .unwrap();
            data[i * BINS..(i + 1) * BINS].copy_from_slice(h);
            at.push(i);
        }
        (CoverageMap::from_histograms(grid, BINS, data).unwrap(), at)
    }

    /// A histogram with `p` on bin `b` and the rest shared by the others.
    fn peaked(b: usize, p: f32) -> [f32; BINS] {
        let mut h = [(1.0 - p) / (BINS - 1) as f32; BINS];
        h[b] = p;
        h
    }

    fn hist(map: &CoverageMap, i: usize) -> &[f32] {
        &map.histograms()[i * BINS..(i + 1) * BINS]
    }

    #[test]
    fn the_papers_update_reads_nothing() {
        assert!(MapReading::of(&SonarModel::default().range, &grid(), BINS).is_none());
        assert!(MapReading::of(&LaserModel::default().range, &grid(), BINS).is_none());
        let mut m = SonarModel::default();
        m.range.free_yield = 0.5;
        assert!(MapReading::of(&m.range, &grid(), BINS).is_some());
    }

    #[test]
    fn an_attributed_echo_spares_the_arc_cells_the_map_holds_free() {
        // A sonar at (0.5, 1.525) looking along +x, an echo at 1 m: its arc
        // runs through (1.5, 1.525), held free, and (1.5, 1.575), at the prior.
        let free = peaked(0, 0.97);
        let pose = crate::Pose::new(0.5, 1.525, 0.0);
        let attributed = SonarModel {
            range: RangeModel {
                end_attribution: 1.0,
                ..SonarModel::default().range
            },
            ..SonarModel::default()
        };
        let mut maps = Vec::new();
        for model in [SonarModel::default(), attributed] {
            let (mut map, at) = map_with(&[([1.51, 1.525], free)]);
            map.integrate(&pose, &[1.0], &[0.0], &model).unwrap();
            maps.push((map, at[0]));
        }
        let (plain, i) = &maps[0];
        let (shared, _) = &maps[1];
        let mean = |m: &CoverageMap, i| histogram::mean(hist(m, i));
        // The paper's update marks the free cell as the arc's others; the
        // attributed one leaves it nearly as it was.
        let was = histogram::mean(&free);
        assert!(mean(plain, *i) > was + 0.05, "{} {was}", mean(plain, *i));
        assert!(mean(shared, *i) < was + 0.01, "{} {was}", mean(shared, *i));
        // A cell at the prior is marked alike by both.
        let g = plain.grid();
        let prior = g.index(g.world_to_cell(1.51, 1.575).unwrap()).unwrap();
        assert!(mean(plain, prior) > 0.6);
        assert_eq!(hist(plain, prior), hist(shared, prior));
    }

    #[test]
    fn a_yielding_free_update_spares_a_covered_cell() {
        let covered = peaked(BINS - 1, 0.97);
        let pose = crate::Pose::new(0.5, 1.525, 0.0);
        let yielding = LaserModel {
            range: RangeModel {
                free_yield: 1.0,
                ..LaserModel::default().range
            },
        };
        let mut means = Vec::new();
        for model in [LaserModel::default(), yielding] {
            let (mut map, at) = map_with(&[([1.01, 1.525], covered)]);
            // The beam passes the covered cell and ends 1 m behind it.
            map.integrate(&pose, &[1.5], &[0.0], &model).unwrap();
            means.push(histogram::mean(hist(&map, at[0])));
        }
        let before = histogram::mean(&covered);
        assert!(means[0] < before - 0.3, "{means:?}");
        assert!((means[1] - before).abs() < 0.02, "{means:?} {before}");
    }

    #[test]
    fn the_floor_holds_only_where_readings_contradict_a_cell() {
        let floored = LaserModel {
            range: RangeModel {
                posterior_floor: 0.002,
                ..LaserModel::default().range
            },
        };
        let pose = crate::Pose::new(0.05, 1.525, 0.0);
        let (mut map, at) = map_with(&[([0.51, 1.525], peaked(BINS - 1, 0.97))]);
        // The map holds the cell covered; a reading through it contradicts
        // it and leaves every bin at the floor or above.
        map.integrate(&pose, &[2.0], &[0.0], &floored).unwrap();
        let h = hist(&map, at[0]);
        assert!(h.iter().all(|&v| v >= 0.002 * (1.0 - 1e-4)), "{h:?}");
        // The readings after it agree with the cell: the floor fades.
        for _ in 0..200 {
            map.integrate(&pose, &[2.0], &[0.0], &floored).unwrap();
        }
        assert!(hist(&map, at[0]).iter().any(|&v| v < 1e-20));
        // A cell every reading found free was never contradicted: unfloored.
        let g = map.grid();
        let free = g.index(g.world_to_cell(0.3, 1.525).unwrap()).unwrap();
        assert!(hist(&map, free).iter().any(|&v| v < 1e-20));
        assert!(histogram::mean(hist(&map, free)) < 1e-6);
    }
}
