//! The entropy history of each cell, for the paper's termination rule: has a
//! cell's entropy stopped changing?

use super::CoverageMap;
use crate::error::{CovmapError, Result};
use crate::grid::Cell;
use crate::histogram;
use crate::memory;

/// Measurements of a cell an entropy change is judged over.
pub const STAGNATION_MEASUREMENTS: usize = 5;
/// Entropy change (nats) below which a cell has stagnated.
pub const STAGNATION_NATS: f32 = 0.001;

/// The entropies of each cell after its last measurements, for the paper's
/// termination rule.
#[derive(Clone, Debug)]
pub(super) struct History {
    /// A ring of the last `STAGNATION_MEASUREMENTS + 1` entropies of each cell.
    entropies: Vec<[f32; STAGNATION_MEASUREMENTS + 1]>,
    /// Measurements of each cell so far.
    count: Vec<u32>,
    /// The cells the scan being integrated touches, each once, in the order
    /// it first does (kept between scans for its memory).
    touched: Vec<usize>,
}

/// The persistent part of a map's entropy history, to save a map with it and
/// load it again ([`CoverageMap::history_state`],
/// [`CoverageMap::restore_history`]).
///
/// Cell `i`'s last `STAGNATION_MEASUREMENTS + 1` entropies are a ring at
/// `entropies[i * (STAGNATION_MEASUREMENTS + 1)..][..STAGNATION_MEASUREMENTS + 1]`:
/// slot `k` holds the entropy (nats) after the cell's measurement `n`
/// (counting from 0) with `n % (STAGNATION_MEASUREMENTS + 1) == k`, and slots
/// not written yet hold 0. `count[i]` is the number of measurements of cell
/// `i`. Both are row-major over the cells.
///
/// # Example
/// ```
/// use covmap_core::{CoverageMap, Grid, LaserModel, Pose, ScanMap};
/// let grid = Grid::new([0.0, 0.0], 0.05, 4, 40).unwrap();
/// let mut map = CoverageMap::new(grid);
/// map.track_history(true);
/// map.integrate(&Pose::new(0.01, 0.1, 0.0), &[1.0], &[0.0], &LaserModel::default()).unwrap();
/// let state = map.history_state().unwrap();
/// // Saved and loaded: the histograms and the history.
/// let mut loaded = CoverageMap::from_histograms(grid, map.bins(), map.histograms().to_vec()).unwrap();
/// loaded.restore_history(state.clone()).unwrap();
/// assert!(loaded.tracks_history());
/// assert_eq!(loaded.measurement_counts(), map.measurement_counts());
/// assert_eq!(loaded.history_state(), Some(state));
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct HistoryState {
    /// Each cell's ring of its last `STAGNATION_MEASUREMENTS + 1` entropies,
    /// nats, `grid.len() * (STAGNATION_MEASUREMENTS + 1)` values.
    pub entropies: Vec<f32>,
    /// Measurements of each cell, `grid.len()` values.
    pub count: Vec<u32>,
}

impl CoverageMap {
    /// Keep (or stop keeping) each cell's entropy after its last measurements,
    /// for [`CoverageMap::stagnated`]. A scan that updates a cell counts as one
    /// measurement of it, however many of its beams do. Off by default: it
    /// costs an entropy per touched cell per scan. Turning it on starts an
    /// empty history.
    ///
    /// # Panics
    /// If the history (36 bytes a cell) cannot be allocated
    /// ([`CoverageMap::try_track_history`] returns an error instead).
    pub fn track_history(&mut self, on: bool) {
        self.history = on.then(|| {
            Box::new(History {
                entropies: vec![[0.0; STAGNATION_MEASUREMENTS + 1]; self.grid.len()],
                count: vec![0; self.grid.len()],
                touched: Vec::new(),
            })
        });
    }

    /// [`CoverageMap::track_history`], or [`crate::CovmapError::OutOfMemory`]
    /// where the history cannot be allocated (the map is then unchanged).
    pub fn try_track_history(&mut self, on: bool) -> Result<()> {
        let cells = self.grid.len();
        self.history = match on {
            false => None,
            true => Some(Box::new(History {
                entropies: memory::try_filled(
                    [0.0; STAGNATION_MEASUREMENTS + 1],
                    cells,
                    "the entropy history",
                )?,
                count: memory::try_filled(0, cells, "the measurement counts")?,
                touched: Vec::new(),
            })),
        };
        Ok(())
    }

    /// Whether the history is kept.
    pub fn tracks_history(&self) -> bool {
        self.history.is_some()
    }

    /// Measurements of `cell` since the history was turned on (0 while it is
    /// off).
    pub fn measurements(&self, cell: Cell) -> Result<u32> {
        let i = self.grid.index(cell)?;
        Ok(self.history.as_ref().map_or(0, |history| history.count[i]))
    }

    /// Measurements of every cell since the history was turned on, row-major.
    pub fn measurement_counts(&self) -> Vec<u32> {
        self.history
            .as_ref()
            .map_or_else(|| vec![0; self.grid.len()], |history| history.count.clone())
    }

    /// The entropy history (`None` while it is off), to be handed to
    /// [`CoverageMap::restore_history`] of a map loaded from this one's
    /// histograms.
    pub fn history_state(&self) -> Option<HistoryState> {
        self.history.as_ref().map(|history| HistoryState {
            entropies: history.entropies.as_flattened().to_vec(),
            count: history.count.clone(),
        })
    }

    /// Track the history and make it `state` (from
    /// [`CoverageMap::history_state`] of a map with the same grid), so that
    /// further scans continue it as they would have continued the original.
    ///
    /// A state whose lengths do not fit the grid, or with an entropy that is
    /// not finite and non-negative, is an error and leaves the map exactly as
    /// it was.
    pub fn restore_history(&mut self, state: HistoryState) -> Result<()> {
        const LEN: usize = STAGNATION_MEASUREMENTS + 1;
        let cells = self.grid.len();
        if state.count.len() != cells {
            return Err(CovmapError::LengthMismatch {
                what: "history measurement counts and grid cells",
                left: state.count.len(),
                right: cells,
            });
        }
        if state.entropies.len() != cells * LEN {
            return Err(CovmapError::LengthMismatch {
                what: "history entropies and grid cells x (STAGNATION_MEASUREMENTS + 1)",
                left: state.entropies.len(),
                right: cells * LEN,
            });
        }
        // No histogram's entropy exceeds the prior's, `ln bins` (with room
        // for the rounding of an `f32` entropy).
        let most = (self.bins as f32).ln() * (1.0 + 1e-5) + 1e-6;
        let impossible = |v: &f32| !(v.is_finite() && *v >= 0.0 && *v <= most);
        if let Some((i, &value)) = state
            .entropies
            .iter()
            .enumerate()
            .find(|(_, v)| impossible(v))
        {
            return Err(CovmapError::InvalidHistory {
                cell: i / LEN,
                value: f64::from(value),
            });
        }
        let entropies = state
            .entropies
            .chunks_exact(LEN)
            .map(|ring| std::array::from_fn(|k| ring[k]))
            .collect();
        self.history = Some(Box::new(History {
            entropies,
            count: state.count,
            touched: Vec::new(),
        }));
        Ok(())
    }

    /// Whether `cell`'s entropy changed by less than [`STAGNATION_NATS`] over
    /// its last [`STAGNATION_MEASUREMENTS`] measurements (false while the
    /// history is off or too short).
    pub fn stagnated(&self, cell: Cell) -> Result<bool> {
        Ok(self.stagnated_at(self.grid.index(cell)?))
    }

    /// [`CoverageMap::stagnated`] for every cell, row-major.
    pub fn stagnation(&self) -> Vec<bool> {
        (0..self.grid.len()).map(|i| self.stagnated_at(i)).collect()
    }

    /// [`CoverageMap::stagnation`], or [`crate::CovmapError::OutOfMemory`]
    /// where the result cannot be allocated.
    pub fn try_stagnation(&self) -> Result<Vec<bool>> {
        let stagnated = (0..self.grid.len()).map(|i| self.stagnated_at(i));
        memory::try_collect(stagnated, "the stagnated cells")
    }

    /// [`CoverageMap::measurement_counts`], or
    /// [`crate::CovmapError::OutOfMemory`] where the result cannot be allocated.
    pub fn try_measurement_counts(&self) -> Result<Vec<u32>> {
        match &self.history {
            Some(history) => {
                memory::try_collect(history.count.iter().copied(), "the measurement counts")
            }
            None => memory::try_filled(0, self.grid.len(), "the measurement counts"),
        }
    }

    /// [`CoverageMap::stagnated`] by row-major index (below `grid.len()`).
    pub(crate) fn stagnated_at(&self, index: usize) -> bool {
        let Some(history) = &self.history else {
            return false;
        };
        let measured = history.count[index] as usize;
        if measured <= STAGNATION_MEASUREMENTS {
            return false;
        }
        let ring = &history.entropies[index];
        let len = STAGNATION_MEASUREMENTS + 1;
        (ring[(measured - 1) % len] - ring[(measured - 1 - STAGNATION_MEASUREMENTS) % len]).abs()
            < STAGNATION_NATS
    }

    /// Count one measurement of the cell at row-major `index` (below
    /// `grid.len()`) that is no scan, and keep its entropy, if the history
    /// is kept.
    pub(super) fn record_cell_history(&mut self, index: usize) {
        if let Some(history) = self.history.as_deref_mut() {
            history.measure(
                index,
                &self.data[index * self.bins..(index + 1) * self.bins],
            );
        }
    }

    /// Count the scan just integrated (its cells put on the list of
    /// [`History::begin_scan`]) as one measurement of every
    /// cell it updated, and keep their entropies, if the history is kept.
    pub(super) fn record_history(&mut self) {
        let Self {
            bins,
            data,
            history,
            ..
        } = self;
        let Some(history) = history.as_deref_mut() else {
            return;
        };
        let touched = std::mem::take(&mut history.touched);
        for &i in &touched {
            history.measure(i, &data[i * *bins..(i + 1) * *bins]);
        }
        history.touched = touched;
    }
}

impl History {
    /// Start a scan: the list its cells are put on (each once, as the
    /// update first reaches it), to be measured by
    /// [`CoverageMap::record_history`].
    pub(super) fn begin_scan(&mut self) -> &mut Vec<usize> {
        self.touched.clear();
        &mut self.touched
    }

    /// Count one measurement of cell `i`, whose histogram is now `h`.
    fn measure(&mut self, i: usize, h: &[f32]) {
        let measured = self.count[i] as usize;
        let entropy = histogram::entropy(h);
        self.entropies[i][measured % (STAGNATION_MEASUREMENTS + 1)] = entropy;
        self.count[i] = self.count[i].saturating_add(1);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grid::Grid;
    use crate::pose::Pose;
    use crate::scan_map::ScanMap;
    use crate::sensor::{LaserModel, SonarModel};

    #[test]
    fn stagnation_needs_five_measurements_of_little_change() {
        let g = Grid::new([0.0, 0.0], 0.05, 4, 40).unwrap();
        let mut map = CoverageMap::new(g);
        map.track_history(true);
        let laser = LaserModel::default();
        let pose = Pose::new(0.01, 0.1, 0.0);
        let cell = g.world_to_cell(0.5, 0.1).unwrap();
        for k in 0..5 {
            map.integrate(&pose, &[1.0], &[0.0], &laser).unwrap();
            assert_eq!(map.measurements(cell).unwrap(), k + 1);
            assert!(
                !map.stagnated(cell).unwrap(),
                "not after {} measurements",
                k + 1
            );
        }
        // Many readings per scan: the cell's entropy has settled.
        for _ in 0..40 {
            map.integrate(&pose, &vec![1.0; 50], &[0.0; 50], &laser)
                .unwrap();
        }
        assert!(map.stagnated(cell).unwrap());
        let all = map.stagnation();
        for (i, &stagnated) in all.iter().enumerate() {
            assert_eq!(stagnated, map.stagnated(g.cell(i)).unwrap());
        }
        assert!(
            all.iter().any(|&s| !s),
            "cells the beam never reached have no history"
        );
        let untouched = g.world_to_cell(1.9, 0.1).unwrap();
        assert_eq!(map.measurements(untouched).unwrap(), 0);
        assert!(!map.stagnated(untouched).unwrap());
        assert!(map.stagnated(Cell { row: 4, col: 0 }).is_err());
    }

    /// The scans of the history tests: one beam, then many beams per scan, so
    /// that the cells along the beam settle and stagnate.
    fn settling_scans(map: &mut CoverageMap, scans: std::ops::Range<usize>) {
        let laser = LaserModel::default();
        let sonar = SonarModel::default();
        for k in scans {
            let pose = Pose::new(0.01 + 0.002 * (k % 3) as f64, 0.1, 0.0);
            let beams = if k < 5 { 1 } else { 50 };
            if k % 4 == 3 {
                map.integrate(&pose, &vec![1.2; beams], &vec![0.1; beams], &sonar)
                    .unwrap();
            } else {
                map.integrate(&pose, &vec![1.0; beams], &vec![0.0; beams], &laser)
                    .unwrap();
            }
        }
    }

    /// The change feed names exactly the cells scans and contacts
    /// measured (the history's counts grow there and nowhere else), each
    /// once, whether or not the history is kept; a cursor of another map
    /// reads every cell.
    #[test]
    fn the_change_feed_names_each_changed_cell() {
        use crate::coverage_map::Changes;
        let g = Grid::new([0.0, 0.0], 0.05, 4, 40).unwrap();
        let mut tracked = CoverageMap::new(g);
        tracked.track_history(true);
        let mut untracked = CoverageMap::new(g);
        for round in 0..3 {
            let cursors = (tracked.change_cursor(), untracked.change_cursor());
            let (counts, before) = (tracked.measurement_counts(), tracked.histograms().to_vec());
            let contact = Cell {
                row: 2,
                col: 10 + round,
            };
            for map in [&mut tracked, &mut untracked] {
                settling_scans(map, 4 * round..4 * round + 4);
                map.integrate_contact(contact).unwrap();
            }
            let Changes::Cells(named) = tracked.changes_since(&cursors.0) else {
                panic!("the map's own cursor");
            };
            assert_eq!(
                untracked.changes_since(&cursors.1),
                Changes::Cells(named.clone())
            );
            let measured: Vec<usize> = (0..g.len())
                .filter(|&i| tracked.measurement_counts()[i] > counts[i])
                .collect();
            assert_eq!(named, measured);
            let changed = (0..g.len()).filter(|&i| {
                tracked.histograms()[16 * i..16 * (i + 1)] != before[16 * i..16 * (i + 1)]
            });
            for i in changed {
                assert!(named.contains(&i), "cell {i}");
            }
            assert!(named.len() < g.len());
            assert_eq!(
                tracked.changes_since(&tracked.change_cursor()),
                Changes::Cells(vec![])
            );
        }
        assert_eq!(
            tracked.clone().changes_since(&tracked.change_cursor()),
            Changes::All
        );
    }

    #[test]
    fn restored_history_continues_like_the_original() {
        let g = Grid::new([0.0, 0.0], 0.05, 4, 40).unwrap();
        let total = 45;
        // Before any cell has five measurements, and after the rings have wrapped.
        for split in [3, 20] {
            let mut original = CoverageMap::new(g);
            original.track_history(true);
            settling_scans(&mut original, 0..split);
            let state = original.history_state().unwrap();
            assert!(
                state.count.iter().any(|&n| n as usize == split),
                "a cell measured by every scan"
            );

            let mut loaded =
                CoverageMap::from_histograms(g, original.bins(), original.histograms().to_vec())
                    .unwrap();
            assert!(!loaded.tracks_history());
            loaded.restore_history(state.clone()).unwrap();
            assert!(loaded.tracks_history());
            assert_eq!(loaded.history_state().as_ref(), Some(&state));
            assert_eq!(loaded.stagnation(), original.stagnation());
            assert_eq!(loaded.measurement_counts(), original.measurement_counts());

            settling_scans(&mut original, split..total);
            settling_scans(&mut loaded, split..total);
            assert_eq!(loaded.histograms(), original.histograms());
            assert_eq!(loaded.measurement_counts(), original.measurement_counts());
            assert_eq!(loaded.history_state(), original.history_state());
            let stagnation = original.stagnation();
            assert_eq!(loaded.stagnation(), stagnation);
            assert!(
                stagnation.iter().any(|&s| s) && stagnation.iter().any(|&s| !s),
                "split {split}"
            );
        }
    }

    #[test]
    fn restore_history_rejects_bad_state_and_leaves_map_unchanged() {
        let g = Grid::new([0.0, 0.0], 0.05, 4, 40).unwrap();
        let mut tracked = CoverageMap::new(g);
        tracked.track_history(true);
        settling_scans(&mut tracked, 0..8);
        let good = tracked.history_state().unwrap();
        let mut untracked = CoverageMap::new(g);
        assert_eq!(untracked.history_state(), None);

        let len = STAGNATION_MEASUREMENTS + 1;
        let with = |edit: &dyn Fn(&mut HistoryState)| {
            let mut s = good.clone();
            edit(&mut s);
            s
        };
        let cases = [
            with(&|s| s.count.truncate(g.len() - 1)),
            with(&|s| s.count.push(0)),
            with(&|s| s.entropies.truncate(g.len() * len - 1)),
            with(&|s| s.entropies.truncate(g.len() * (len - 1))),
            with(&|s| s.entropies[7 * len + 2] = f32::NAN),
            with(&|s| s.entropies[7 * len + 2] = f32::INFINITY),
            with(&|s| s.entropies[7 * len + 2] = -0.5),
            // More than the prior's ln 16 = 2.77 nats.
            with(&|s| s.entropies[7 * len + 2] = 2.8),
        ];
        for map in [&mut tracked, &mut untracked] {
            let (histograms, history) = (map.histograms().to_vec(), map.history_state());
            for bad in &cases {
                let err = map.restore_history(bad.clone()).unwrap_err();
                if bad.count.len() != g.len() || bad.entropies.len() != g.len() * len {
                    assert!(matches!(err, CovmapError::LengthMismatch { .. }), "{err}");
                } else {
                    assert!(
                        matches!(err, CovmapError::InvalidHistory { cell: 7, .. }),
                        "{err}"
                    );
                }
                assert_eq!(map.histograms(), &histograms[..]);
                assert_eq!(map.history_state(), history);
                assert_eq!(map.tracks_history(), history.is_some());
            }
        }
    }
}
