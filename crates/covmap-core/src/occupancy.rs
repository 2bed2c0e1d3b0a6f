//! The occupancy-grid baseline: log-odds with the usual inverse model.

use serde::{Deserialize, Serialize};

use crate::counting::ScanCounts;
use crate::error::{CovmapError, Result, check_parameter};
use crate::grid::Grid;
use crate::memory;
use crate::scan_map::{ScanBeams, ScanMap};
use crate::sensor::SensorModel;
use crate::sight::visit_reading;

/// The inverse model of the occupancy baseline.
///
/// A cell in the footprint in front of the end point's cell (`d_l < d - r/2`)
/// is observed free; the end point's cell (`|d_l - d| <= r/2`) occupied; cells
/// behind are not touched; a no-echo reading observes its whole footprint free.
/// Log-odds are clamped to `[-log_odds_limit, log_odds_limit]` (the default 5
/// keeps probabilities in `[0.0067, 0.9933]`), so that a cell can change its
/// mind after a bounded number of contrary readings.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OccupancyModel {
    /// Probability of occupancy a hit gives its cell.
    pub p_occupied: f64,
    /// Probability of occupancy a pass-through gives its cell.
    pub p_free: f64,
    /// Bound on the magnitude of a cell's log-odds.
    pub log_odds_limit: f64,
}

impl Default for OccupancyModel {
    fn default() -> Self {
        Self {
            p_occupied: 0.7,
            p_free: 0.35,
            log_odds_limit: 5.0,
        }
    }
}

impl OccupancyModel {
    /// Errors unless `0.5 < p_occupied < 1`, `0 < p_free < 0.5`, limit > 0.
    pub fn validate(&self) -> Result<()> {
        check_parameter(
            self.p_occupied > 0.5 && self.p_occupied < 1.0,
            "p_occupied",
            self.p_occupied,
            "a probability in (0.5, 1)",
        )?;
        check_parameter(
            self.p_free > 0.0 && self.p_free < 0.5,
            "p_free",
            self.p_free,
            "a probability in (0, 0.5)",
        )?;
        check_parameter(
            self.log_odds_limit.is_finite() && self.log_odds_limit > 0.0,
            "log_odds_limit",
            self.log_odds_limit,
            "a positive, finite bound",
        )
    }
}

fn logit(p: f64) -> f32 {
    (p / (1.0 - p)).ln() as f32
}

/// A standard log-odds occupancy grid, with the scan counts of the same beams.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "OccupancyGridData")]
pub struct OccupancyGrid {
    model: OccupancyModel,
    log_odds: Vec<f32>,
    counts: ScanCounts,
}

/// The serialised form of an [`OccupancyGrid`], validated on the way in: a
/// valid model, and one log-odds value per cell within its limit.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct OccupancyGridData {
    model: OccupancyModel,
    log_odds: Vec<f32>,
    counts: ScanCounts,
}

impl TryFrom<OccupancyGridData> for OccupancyGrid {
    type Error = CovmapError;
    fn try_from(d: OccupancyGridData) -> Result<Self> {
        if d.log_odds.len() != d.counts.grid().len() {
            return Err(CovmapError::LengthMismatch {
                what: "log-odds and grid cells",
                left: d.log_odds.len(),
                right: d.counts.grid().len(),
            });
        }
        d.model.validate()?;
        let limit = d.model.log_odds_limit as f32;
        if let Some(&l) = d.log_odds.iter().find(|l| !(l.abs() <= limit)) {
            return Err(CovmapError::InvalidParameter {
                name: "log_odds",
                value: f64::from(l),
                expected: "log-odds within the model's limit",
            });
        }
        Ok(Self {
            model: d.model,
            log_odds: d.log_odds,
            counts: d.counts,
        })
    }
}

impl OccupancyGrid {
    /// A copy of the grid, or [`CovmapError::OutOfMemory`] where `clone`
    /// would abort the process: the memory of its log-odds and counts is
    /// asked for first.
    ///
    /// # Errors
    /// [`CovmapError::OutOfMemory`] naming the copy.
    pub fn try_clone(&self) -> Result<Self> {
        drop(crate::memory::try_with_capacity::<f32>(
            2 * self.log_odds.len(),
            "a copy of the occupancy grid",
        )?);
        Ok(self.clone())
    }

    /// An unknown (p = 0.5) grid with the default model and undiscounted counts.
    ///
    /// # Panics
    /// If its 8 bytes a cell cannot be allocated ([`OccupancyGrid::try_new`]
    /// returns an error instead).
    pub fn new(grid: Grid) -> Self {
        Self {
            model: OccupancyModel::default(),
            log_odds: vec![0.0; grid.len()],
            counts: ScanCounts::new(grid),
        }
    }

    /// [`OccupancyGrid::new`], or [`CovmapError::OutOfMemory`] where its 8
    /// bytes a cell cannot be allocated.
    pub fn try_new(grid: Grid) -> Result<Self> {
        Self::with_model(OccupancyModel::default(), ScanCounts::try_new(grid)?)
    }

    /// An unknown grid with `model`, counting into `counts` (which sets the
    /// grid); [`CovmapError::OutOfMemory`] where its log-odds cannot be
    /// allocated.
    pub fn with_model(model: OccupancyModel, counts: ScanCounts) -> Result<Self> {
        model.validate()?;
        Ok(Self {
            model,
            log_odds: memory::try_filled(
                0.0,
                counts.grid().len(),
                "the occupancy grid's log-odds",
            )?,
            counts,
        })
    }

    /// The grid.
    pub fn grid(&self) -> &Grid {
        self.counts.grid()
    }
    /// The inverse model.
    pub fn model(&self) -> &OccupancyModel {
        &self.model
    }
    /// Log-odds of occupancy, row-major.
    pub fn log_odds(&self) -> &[f32] {
        &self.log_odds
    }
    /// Probability of occupancy, row-major.
    pub fn probabilities(&self) -> Vec<f32> {
        self.log_odds.iter().map(probability).collect()
    }
    /// [`OccupancyGrid::probabilities`], or [`CovmapError::OutOfMemory`]
    /// where the result cannot be allocated.
    pub fn try_probabilities(&self) -> Result<Vec<f32>> {
        memory::try_collect(
            self.log_odds.iter().map(probability),
            "the occupancy probabilities",
        )
    }
    /// The scan counts of the same beams.
    pub fn counts(&self) -> &ScanCounts {
        &self.counts
    }

    /// Which cells some evidence has reached, row-major: a beam intercepted
    /// them (their scan count is above 0) or a contact marked them. The
    /// others are unknown, whatever their probability reads (0.5).
    pub fn observed(&self) -> Vec<bool> {
        self.observations().collect()
    }
    /// [`OccupancyGrid::observed`], or [`CovmapError::OutOfMemory`] where
    /// the result cannot be allocated.
    pub fn try_observed(&self) -> Result<Vec<bool>> {
        memory::try_collect(self.observations(), "the observed cells")
    }
    /// Whether evidence has reached each cell, row-major.
    fn observations(&self) -> impl ExactSizeIterator<Item = bool> + '_ {
        self.log_odds
            .iter()
            .zip(self.counts.counts())
            .map(|(&l, &c)| l != 0.0 || c > 0.0)
    }

    /// Integrate a contact: the robot touched an obstacle in `cell`, which
    /// becomes as occupied as the grid allows (its log-odds at the limit). A
    /// contact is no beam: the counts are unchanged.
    ///
    /// # Errors
    /// [`CovmapError::CellOutOfBounds`] if the cell is not on the grid; the
    /// grid is unchanged.
    pub fn integrate_contact(&mut self, cell: crate::grid::Cell) -> Result<()> {
        let i = self.grid().index(cell)?;
        self.log_odds[i] = self.model.log_odds_limit as f32;
        Ok(())
    }
}

/// The probability of occupancy of log-odds `l`.
fn probability(l: &f32) -> f32 {
    1.0 / (1.0 + (-l).exp())
}

impl ScanMap for OccupancyGrid {
    fn grid(&self) -> &Grid {
        self.counts.grid()
    }

    /// Integrate and count the beams, both in one visit of each beam's
    /// cells (the grid's beam reaches as far as the count's).
    fn integrate_checked<M: SensorModel + ?Sized>(
        &mut self,
        scan: ScanBeams<'_>,
        model: &M,
    ) -> Result<usize> {
        let (l_occ, l_free) = (logit(self.model.p_occupied), logit(self.model.p_free));
        let limit = self.model.log_odds_limit as f32;
        let range = model.range_model();
        let grid = *self.counts.grid();
        let half = 0.5 * grid.resolution_m();
        let mut updates = 0;
        for (k, &r) in scan.ranges.iter().enumerate() {
            let echo = r < range.max_range_m;
            let (reach, weight) = self.counts.beam(range, r, k, scan.no_echo_reach_m);
            let (log_odds, counts) = (&mut self.log_odds, self.counts.counts_mut());
            visit_reading(
                &grid,
                &scan,
                k,
                echo,
                reach,
                model.footprint(),
                &mut |i: usize, d_l: f64| {
                    let l = if echo && d_l >= r - half {
                        l_occ
                    } else {
                        l_free
                    };
                    log_odds[i] = (log_odds[i] + l).clamp(-limit, limit);
                    counts[i] += weight;
                    updates += 1;
                },
            );
        }
        Ok(updates)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pose::Pose;

    /// The grid counts the cells it visits for its log-odds, and they are
    /// what counting alone gives, bit for bit: echoes, no echoes to the
    /// maximum range and clipped, discounted beams.
    #[test]
    fn the_grids_counts_are_the_counts_alone() {
        use crate::sensor::SonarModel;
        let grid = Grid::new([0.0, 0.0], 0.05, 90, 120).unwrap();
        let sonar = SonarModel::default();
        let max = sonar.range.max_range_m;
        let counts = ScanCounts::with_discount(grid, 2.0).unwrap();
        let mut occupancy =
            OccupancyGrid::with_model(OccupancyModel::default(), counts.clone()).unwrap();
        let mut alone = counts;
        let bearings: Vec<f64> = (0..24).map(|k| f64::from(k) * 0.2618).collect();
        for k in 0..12 {
            let pose = Pose::new(1.5 + 0.3 * f64::from(k), 2.0 + 0.1 * f64::from(k % 4), 0.1);
            let ranges: Vec<f64> = (0..24)
                .map(|j| {
                    if (j + k) % 5 == 0 {
                        max
                    } else {
                        0.4 + 0.13 * f64::from(j)
                    }
                })
                .collect();
            let reaches: Vec<f64> = (0..24).map(|j| 0.5 + 0.2 * f64::from(j)).collect();
            if k % 2 == 0 {
                occupancy
                    .integrate(&pose, &ranges, &bearings, &sonar)
                    .unwrap();
                alone.integrate(&pose, &ranges, &bearings, &sonar).unwrap();
            } else {
                let scan = ScanBeams {
                    pose: &pose,
                    ranges: &ranges,
                    bearings: &bearings,
                    no_echo_reach_m: Some(&reaches),
                    no_echo_sight: None,
                    echo_sources: None,
                };
                occupancy.integrate_scan(scan, &sonar).unwrap();
                alone.integrate_scan(scan, &sonar).unwrap();
            }
        }
        let bits = |c: &[f32]| c.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(occupancy.counts().counts()), bits(alone.counts()));
        let counted = alone.counts().iter().filter(|&&c| c > 0.0).count();
        assert!(counted > 1000, "{counted} cells counted");
        assert!(
            alone.counts().iter().any(|&c| c.fract() != 0.0),
            "discounted beams"
        );
    }

    /// A deserialised grid is checked as the constructors check it.
    #[test]
    fn serde_validates() {
        let grid = Grid::new([0.0, 0.0], 0.1, 4, 5).unwrap();
        let occ = OccupancyGrid::new(grid);
        let s = serde_json::to_string(&occ).unwrap();
        assert_eq!(serde_json::from_str::<OccupancyGrid>(&s).unwrap(), occ);
        let zeros = serde_json::to_string(&vec![0.0f32; 20]).unwrap();
        let log_odds = format!("\"log_odds\":{zeros}");
        for bad in [
            s.replace(&log_odds, "\"log_odds\":[]"),
            s.replace(&log_odds, &log_odds.replacen("0.0", "9.0", 1)),
            s.replace("\"p_occupied\":0.7", "\"p_occupied\":7.0"),
        ] {
            assert_ne!(bad, s);
            assert!(
                serde_json::from_str::<OccupancyGrid>(&bad).is_err(),
                "{bad}"
            );
        }
    }
}
