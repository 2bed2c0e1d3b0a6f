//! Both maps as ROS's `nav_msgs/OccupancyGrid` data: one `i8` a cell,
//! row-major from the origin's cell (as the maps store cells), `-1` for
//! unknown, else the chance of occupancy in percent (`0..=100`). Unknown is
//! explicit: a cell no evidence reached, or (on a coverage map) still so
//! near the prior that it says nothing, is `-1`, never a confident 0.

use crate::coverage_map::CoverageMap;
use crate::error::{Result, check_parameter};
use crate::occupancy::OccupancyGrid;

/// The `nav_msgs/OccupancyGrid` value of unknown.
pub const ROS_UNKNOWN: i8 = -1;

/// Which read-out of a coverage map becomes its occupancy values.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CoverageValue {
    /// The most likely coverage ([`CoverageMap::ml`]): crisp, 0 or 100 at
    /// the map's bin values.
    Ml,
    /// The expected coverage ([`CoverageMap::mean`]).
    Mean,
}

fn percent(v: f32) -> i8 {
    (v.clamp(0.0, 1.0) * 100.0).round() as i8
}

impl CoverageMap {
    /// The map as `nav_msgs/OccupancyGrid` data: `value`'s coverage in
    /// percent, and [`ROS_UNKNOWN`] for every cell whose entropy lies within
    /// `unknown_within_nats` of the prior's `ln bins` (0: only cells no
    /// evidence reached).
    ///
    /// # Errors
    /// [`crate::CovmapError::InvalidParameter`] unless `unknown_within_nats`
    /// is finite and non-negative.
    ///
    /// # Example
    /// ```
    /// use covmap_core::{CoverageMap, CoverageValue, Grid, LaserModel, Pose, ROS_UNKNOWN, ScanMap};
    /// let grid = Grid::new([0.0, 0.0], 0.1, 10, 30).unwrap();
    /// let mut map = CoverageMap::new(grid);
    /// for _ in 0..3 {
    ///     map.integrate(&Pose::new(0.05, 0.55, 0.0), &[1.5], &[0.0], &LaserModel::default()).unwrap();
    /// }
    /// let data = map.ros_occupancy(CoverageValue::Ml, 0.05).unwrap();
    /// let at = |x: f64| grid.index(grid.world_to_cell(x, 0.55).unwrap()).unwrap();
    /// assert_eq!(data[at(1.0)], 0); // the beam passed: free
    /// assert!(data[at(1.55)] > 50); // its end point: more likely covered than not
    /// assert_eq!(data[at(2.8)], ROS_UNKNOWN); // never seen
    /// ```
    pub fn ros_occupancy(&self, value: CoverageValue, unknown_within_nats: f64) -> Result<Vec<i8>> {
        check_parameter(
            unknown_within_nats.is_finite() && unknown_within_nats >= 0.0,
            "unknown_within_nats",
            unknown_within_nats,
            "a finite, non-negative entropy (nats)",
        )?;
        let prior = (self.bins() as f64).ln();
        let values = match value {
            CoverageValue::Ml => self.ml(),
            CoverageValue::Mean => self.mean(),
        };
        let entropy = self.entropy();
        let observed = self.observed();
        Ok(values
            .iter()
            .zip(entropy.iter().zip(&observed))
            .map(|(&v, (&h, &seen))| {
                if !seen || f64::from(h) > prior - unknown_within_nats {
                    ROS_UNKNOWN
                } else {
                    percent(v)
                }
            })
            .collect())
    }
}

impl OccupancyGrid {
    /// The grid as `nav_msgs/OccupancyGrid` data: the probability of
    /// occupancy in percent, [`ROS_UNKNOWN`] where no evidence reached.
    pub fn ros_occupancy(&self) -> Vec<i8> {
        self.probabilities()
            .iter()
            .zip(self.observed())
            .map(|(&p, seen)| if seen { percent(p) } else { ROS_UNKNOWN })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grid::Grid;
    use crate::pose::Pose;
    use crate::scan_map::ScanMap;
    use crate::sensor::SonarModel;

    #[test]
    fn unknown_is_the_prior_and_known_cells_read_their_percent() {
        let grid = Grid::new([0.0, 0.0], 0.1, 30, 40).unwrap();
        let mut map = CoverageMap::new(grid);
        let mut occupancy = OccupancyGrid::new(grid);
        let sonar = SonarModel::default();
        for _ in 0..4 {
            let p = Pose::new(1.0, 1.5, 0.0);
            map.integrate(&p, &[1.2], &[0.0], &sonar).unwrap();
            occupancy.integrate(&p, &[1.2], &[0.0], &sonar).unwrap();
        }
        let (entropy, observed, mean) = (map.entropy(), map.observed(), map.mean());
        let strict = map.ros_occupancy(CoverageValue::Mean, 0.0).unwrap();
        let loose = map.ros_occupancy(CoverageValue::Mean, 1.0).unwrap();
        let prior = 16f32.ln();
        for i in 0..grid.len() {
            match observed[i] {
                false => assert_eq!(strict[i], ROS_UNKNOWN),
                true => assert_eq!(strict[i], (mean[i] * 100.0).round() as i8),
            }
            if entropy[i] > prior - 1.0 {
                assert_eq!(loose[i], ROS_UNKNOWN);
            }
        }
        assert!(
            loose.iter().filter(|&&v| v == ROS_UNKNOWN).count()
                > strict.iter().filter(|&&v| v == ROS_UNKNOWN).count()
        );
        assert!(map.ros_occupancy(CoverageValue::Ml, -1.0).is_err());
        let grid_data = occupancy.ros_occupancy();
        let probabilities = occupancy.probabilities();
        for (i, seen) in occupancy.observed().into_iter().enumerate() {
            let expected = if seen {
                (probabilities[i] * 100.0).round() as i8
            } else {
                -1
            };
            assert_eq!(grid_data[i], expected);
        }
        assert!(
            grid_data.contains(&-1)
                && grid_data.iter().any(|&v| v > 50)
                && grid_data.iter().any(|&v| (0..50).contains(&v))
        );
    }
}
