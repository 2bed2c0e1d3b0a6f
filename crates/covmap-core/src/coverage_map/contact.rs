//! Evidence that is no range reading: a bumper's contact, and which cells
//! any evidence has reached.

use super::CoverageMap;
use crate::error::Result;
use crate::grid::Cell;
use crate::histogram;

/// The least coverage a cell the robot ran into is taken to have: the
/// planner's default `blocked_coverage`, so that a contact makes its cell
/// block the robot.
pub const CONTACT_COVERAGE: f64 = 0.5;

impl CoverageMap {
    /// Integrate a contact: the robot's disc touched an obstacle in `cell`.
    ///
    /// The likelihood of a contact is taken as 1 for a coverage of at least
    /// [`CONTACT_COVERAGE`] and 0 below it: a bumper is far more reliable
    /// than a sonar, and a cell that lets the disc pass does not stop it.
    /// The bins below get the likelihood of the floor
    /// ([`BIN_FLOOR`](crate::histogram::BIN_FLOOR), 69 nats against them),
    /// so that later readings can still revise the cell, but only many of
    /// them: a wall no echo
    /// shows (a specular surface, glass) stays in the way after the robot
    /// has run into it, instead of being cleared by the next no-echo
    /// readings and planned through again. It counts as one measurement of
    /// the cell for the entropy history.
    ///
    /// # Errors
    /// [`CovmapError::CellOutOfBounds`](crate::CovmapError::CellOutOfBounds)
    /// if the cell is not on the grid; the map is unchanged.
    ///
    /// # Example
    /// ```
    /// use covmap_core::{Cell, CoverageMap, Grid};
    /// let mut map = CoverageMap::new(Grid::new([0.0, 0.0], 0.05, 10, 10).unwrap());
    /// let cell = Cell { row: 4, col: 7 };
    /// map.integrate_contact(cell).unwrap();
    /// let i = map.grid().index(cell).unwrap();
    /// assert!(map.ml()[i] >= 0.5);
    /// assert!(map.observed()[i] && !map.observed()[0]);
    /// ```
    pub fn integrate_contact(&mut self, cell: Cell) -> Result<()> {
        let i = self.grid.index(cell)?;
        let bins = self.bins;
        let ln_likelihood: Vec<f32> = (0..bins)
            .map(|b| {
                if histogram::bin_value(b, bins) >= CONTACT_COVERAGE {
                    0.0
                } else {
                    histogram::BIN_FLOOR.ln()
                }
            })
            .collect();
        let cell = i * bins..(i + 1) * bins;
        histogram::update_log::<0>(
            &mut self.log[cell.clone()],
            &mut self.data[cell],
            &ln_likelihood,
            histogram::BIN_FLOOR,
        );
        self.changes.begin().mark(i);
        self.record_cell_history(i);
        Ok(())
    }

    /// Hold each of `cells` certainly covered: its histogram all but the
    /// floor in the top bin, what a robot holds of a cell it ran into (its
    /// bumper is far more reliable than a sonar, and a specular surface no
    /// echo shows stays in the way). A cell not so already changes (one
    /// measurement of it for the entropy history); the others are left as
    /// they are. The exploration loop pins the cells the robot ran into
    /// after every scan, so that the map it plans on, reports and is judged
    /// by is one map.
    ///
    /// # Errors
    /// [`CovmapError::CellOutOfBounds`](crate::CovmapError::CellOutOfBounds)
    /// if a cell is not on the grid; the map is unchanged then.
    ///
    /// # Example
    /// ```
    /// use covmap_core::{Cell, CoverageMap, Grid};
    /// let mut map = CoverageMap::new(Grid::new([0.0, 0.0], 0.05, 10, 10).unwrap());
    /// let cell = Cell { row: 4, col: 7 };
    /// map.pin_covered(&[cell]).unwrap();
    /// let i = map.grid().index(cell).unwrap();
    /// assert_eq!(map.ml()[i], 1.0);
    /// assert!(map.entropy()[i] < 1e-6);
    /// ```
    pub fn pin_covered(&mut self, cells: &[Cell]) -> Result<()> {
        let indices = cells
            .iter()
            .map(|&cell| self.grid.index(cell))
            .collect::<Result<Vec<_>>>()?;
        let bins = self.bins;
        let pinned = pinned_histogram(bins);
        let unpinned: Vec<usize> = indices
            .into_iter()
            .filter(|&i| self.data[i * bins..(i + 1) * bins] != pinned[..])
            .collect();
        if unpinned.is_empty() {
            return Ok(());
        }
        let mut ln_pinned = vec![0.0f32; bins];
        histogram::log_of(&pinned, &mut ln_pinned);
        let mut stamper = self.changes.begin();
        for &i in &unpinned {
            self.data[i * bins..(i + 1) * bins].copy_from_slice(&pinned);
            self.log[i * bins..(i + 1) * bins].copy_from_slice(&ln_pinned);
            stamper.mark(i);
        }
        for i in unpinned {
            self.record_cell_history(i);
        }
        Ok(())
    }

    /// Which cells some evidence has reached, row-major: those whose
    /// histogram is no longer the uniform prior. Unknown is a value of its
    /// own: an unobserved cell reads 0 on the ML map ([`CoverageMap::ml`]),
    /// as an empty cell does, and this tells them apart. (A histogram that
    /// evidence brought back exactly to uniform would read unobserved; no
    /// kernel of the sensor models does that.)
    pub fn observed(&self) -> Vec<bool> {
        self.cells().map(observed).collect()
    }

    /// [`CoverageMap::observed`], or [`crate::CovmapError::OutOfMemory`]
    /// where the result cannot be allocated.
    pub fn try_observed(&self) -> crate::Result<Vec<bool>> {
        crate::memory::try_collect(self.cells().map(observed), "the observed cells")
    }
}

/// A cell certainly covered: all its mass in the top bin, the others at the
/// floor.
fn pinned_histogram(bins: usize) -> Vec<f32> {
    let mut pinned = vec![histogram::BIN_FLOOR; bins];
    pinned[bins - 1] = 1.0 - (bins - 1) as f32 * histogram::BIN_FLOOR;
    pinned
}

/// Whether a histogram has moved from the uniform prior.
fn observed(h: &[f32]) -> bool {
    h.iter().any(|&p| p != h[0])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grid::Grid;
    use crate::pose::Pose;
    use crate::scan_map::ScanMap;
    use crate::sensor::SonarModel;

    /// A wall cell that no-echo readings cleared blocks again after a
    /// contact, and stays blocking through further no-echo readings.
    #[test]
    fn a_contact_outweighs_no_echo_readings() {
        let grid = Grid::new([0.0, 0.0], 0.05, 40, 80).unwrap();
        let mut map = CoverageMap::new(grid);
        map.track_history(true);
        let sonar = SonarModel::default();
        let pose = Pose::new(0.5, 1.0, 0.0);
        let cell = grid.world_to_cell(1.5, 1.0).unwrap();
        let i = grid.index(cell).unwrap();
        let no_echo = || vec![sonar.range.max_range_m; 1];
        for _ in 0..5 {
            map.integrate(&pose, &no_echo(), &[0.0], &sonar).unwrap();
        }
        assert_eq!(map.ml()[i], 0.0, "cleared");
        let before = map.measurements(cell).unwrap();
        map.integrate_contact(cell).unwrap();
        assert_eq!(map.measurements(cell).unwrap(), before + 1);
        for _ in 0..5 {
            map.integrate(&pose, &no_echo(), &[0.0], &sonar).unwrap();
        }
        assert!(
            f64::from(map.ml()[i]) >= CONTACT_COVERAGE,
            "{}",
            map.ml()[i]
        );
        let h = map.histogram(cell).unwrap();
        assert!((h.iter().sum::<f32>() - 1.0).abs() < 1e-5);
        assert!(map.integrate_contact(Cell { row: 40, col: 0 }).is_err());
        // Cleared again by many no-echo readings; pinned, it stays covered
        // until pinned again, and pinning touches no other cell.
        for _ in 0..60 {
            map.integrate(&pose, &no_echo(), &[0.0], &sonar).unwrap();
        }
        assert_eq!(map.ml()[i], 0.0, "cleared again");
        let (before, cursor) = (map.histograms().to_vec(), map.change_cursor());
        map.pin_covered(&[cell]).unwrap();
        assert_eq!(map.ml()[i], 1.0);
        assert!(map.entropy()[i] < 1e-6);
        assert_eq!(
            map.changes_since(&cursor),
            crate::coverage_map::Changes::Cells(vec![i])
        );
        let other = grid.index(grid.world_to_cell(1.0, 1.0).unwrap()).unwrap();
        assert_eq!(
            before[other * 16..][..16],
            map.histograms()[other * 16..][..16]
        );
        // Pinned already: no change at all.
        let cursor = map.change_cursor();
        map.pin_covered(&[cell]).unwrap();
        assert_eq!(
            map.changes_since(&cursor),
            crate::coverage_map::Changes::Cells(vec![])
        );
        let held = map.histograms().to_vec();
        assert!(map.pin_covered(&[cell, Cell { row: 0, col: 80 }]).is_err());
        assert_eq!(map.histograms(), &held[..]);
    }
}
