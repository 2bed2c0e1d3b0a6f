//! What the loop reads out of its coverage map between steps, kept up to
//! date from the map's change feed: the entropy and ML coverage of every
//! cell, how many report cells are uncertain, and which cells changed
//! since the last decision.
//!
//! A step's scans touch a small part of a large map: the read-outs of the
//! cells the feed names are read again and no others, the same bits as
//! reading the whole map out anew.

use crate::coverage_map::{ChangeCursor, Changes, CoverageMap};

/// The loop's read-outs of its coverage map.
pub(super) struct Bookkeeping {
    /// Where the feed was last read.
    cursor: ChangeCursor,
    /// The entropy of every cell, nats.
    pub entropy: Vec<f32>,
    /// The ML coverage of every cell.
    pub ml: Vec<f32>,
    /// The cells changed between the last two readings of the feed,
    /// ascending.
    pub changed: Vec<usize>,
    /// The cells the uncertain fraction is of (`None`: every cell).
    report_cells: Option<Vec<bool>>,
    /// Entropy above which a cell is uncertain, nats.
    epsilon: f64,
    /// The report cells whose entropy is above epsilon, and all of them.
    uncertain: (usize, usize),
}

impl Bookkeeping {
    /// The read-outs of `map` as it is now, the fraction of `report_cells`
    /// whose entropy is above `epsilon` counted (every cell for `None`).
    pub fn new(map: &CoverageMap, report_cells: Option<Vec<bool>>, epsilon: f64) -> Self {
        let total = report_cells.as_ref().map_or(map.grid().len(), |cells| {
            cells.iter().filter(|&&c| c).count()
        });
        let mut kept = Self {
            cursor: ChangeCursor::default(),
            entropy: map.entropy(),
            ml: map.ml(),
            changed: Vec::new(),
            report_cells,
            epsilon,
            uncertain: (0, total),
        };
        kept.uncertain.0 = (0..kept.entropy.len())
            .filter(|&i| kept.reported(i) && kept.is_uncertain(i))
            .count();
        kept
    }

    /// Read the cells `map` changed since the last call (every cell at the
    /// first) and bring the read-outs up to date.
    pub fn take_in(&mut self, map: &CoverageMap) {
        self.changed = match map.changes_since(&self.cursor) {
            Changes::Cells(cells) => cells,
            Changes::All => (0..map.grid().len()).collect(),
        };
        self.cursor = map.change_cursor();
        let changed = std::mem::take(&mut self.changed);
        for &i in &changed {
            let was = self.is_uncertain(i);
            self.entropy[i] = map.entropy_at(i);
            self.ml[i] = map.ml_at(i);
            if self.reported(i) {
                let now = self.is_uncertain(i);
                self.uncertain.0 = self.uncertain.0 + usize::from(now) - usize::from(was);
            }
        }
        self.changed = changed;
        debug_assert_eq!(self.entropy, map.entropy());
        debug_assert_eq!(self.ml, map.ml());
    }

    /// The fraction of the report cells whose entropy is above epsilon.
    pub fn uncertain_fraction(&self) -> f64 {
        match self.uncertain {
            (_, 0) => 0.0,
            (count, total) => count as f64 / total as f64,
        }
    }

    fn reported(&self, i: usize) -> bool {
        self.report_cells.as_ref().is_none_or(|cells| cells[i])
    }

    fn is_uncertain(&self, i: usize) -> bool {
        f64::from(self.entropy[i]) > self.epsilon
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grid::{Cell, Grid};
    use crate::pose::Pose;
    use crate::scan_map::ScanMap;
    use crate::sensor::SonarModel;

    /// Scans, contacts and pinned cells, with and without the history:
    /// the kept read-outs are the map's, and the count of uncertain cells
    /// the one counted anew.
    #[test]
    fn the_read_outs_follow_the_map() {
        let grid = Grid::new([0.0, 0.0], 0.05, 40, 60).unwrap();
        let sonar = SonarModel::default();
        let bearings: Vec<f64> = (0..24).map(|i| f64::from(i) * 0.2618).collect();
        for history in [false, true] {
            let mut map = CoverageMap::new(grid);
            map.track_history(history);
            let report: Vec<bool> = (0..grid.len()).map(|i| i % 3 != 0).collect();
            let mut kept = Bookkeeping::new(&map, Some(report.clone()), 0.65);
            for k in 0..6 {
                let pose = Pose::new(0.5 + 0.3 * f64::from(k), 1.0, 0.0);
                map.integrate(&pose, &[0.9; 24], &bearings, &sonar).unwrap();
                map.integrate_contact(Cell {
                    row: 5,
                    col: 3 * k as usize,
                })
                .unwrap();
                map.pin_covered(&[Cell {
                    row: 6,
                    col: k as usize,
                }])
                .unwrap();
                kept.take_in(&map);
                assert_eq!(kept.entropy, map.entropy());
                assert_eq!(kept.ml, map.ml());
                let entropy = map.entropy();
                let uncertain = (0..grid.len())
                    .filter(|&i| report[i] && f64::from(entropy[i]) > 0.65)
                    .count();
                let total = report.iter().filter(|&&r| r).count();
                assert_eq!(kept.uncertain, (uncertain, total));
                // Every cell at the first reading of the feed, then what changed.
                assert_eq!(kept.changed.len() == grid.len(), k == 0, "{k}");
                assert!(!kept.changed.is_empty());
            }
        }
    }
}
