//! Scan counting: how often measurements intercepted each cell.

use serde::{Deserialize, Serialize};

use crate::error::{CovmapError, Result};
use crate::footprint::visit;
use crate::grid::Grid;
use crate::scan::{Pose, validate_scan};
use crate::sensor::SensorModel;

/// Per-cell scan counts, the exploration baseline of the paper's Table I.
///
/// A measurement intercepts a cell when the cell lies in its footprint no
/// further than the end point's cell (`d_l <= d + r/2`); a no-echo reading
/// intercepts every cell of its footprint up to the maximum range. Each
/// interception adds the beam's weight: 1, or, with a discount range `D`,
/// `min(1, D / d)`, so that long, less reliable beams count less.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ScanCounts {
    grid: Grid,
    discount_beyond_m: Option<f64>,
    counts: Vec<f32>,
}

impl ScanCounts {
    /// Zero counts over `grid`, every beam counting 1.
    pub fn new(grid: Grid) -> Self {
        Self { grid, discount_beyond_m: None, counts: vec![0.0; grid.len()] }
    }

    /// Zero counts over `grid`; beams longer than `discount_beyond_m` count
    /// `discount_beyond_m / d`.
    pub fn with_discount(grid: Grid, discount_beyond_m: f64) -> Result<Self> {
        if !(discount_beyond_m.is_finite() && discount_beyond_m > 0.0) {
            return Err(CovmapError::InvalidParameter {
                name: "discount_beyond_m",
                value: discount_beyond_m,
                expected: "a positive, finite distance",
            });
        }
        Ok(Self { discount_beyond_m: Some(discount_beyond_m), ..Self::new(grid) })
    }

    /// The grid.
    pub fn grid(&self) -> &Grid {
        &self.grid
    }
    /// The discount range, if any.
    pub fn discount_beyond_m(&self) -> Option<f64> {
        self.discount_beyond_m
    }
    /// The (weighted) count of every cell, row-major.
    pub fn counts(&self) -> &[f32] {
        &self.counts
    }

    /// The weight of a beam reading `range_m`.
    pub fn weight(&self, range_m: f64) -> f32 {
        match self.discount_beyond_m {
            Some(dist) if range_m > dist => (dist / range_m) as f32,
            _ => 1.0,
        }
    }

    /// Count one scan; validated like [`crate::CoverageMap::integrate`].
    pub fn integrate<M: SensorModel + ?Sized>(
        &mut self,
        pose: &Pose,
        ranges: &[f64],
        bearings: &[f64],
        model: &M,
    ) -> Result<()> {
        model.validate()?;
        validate_scan(&self.grid, pose, ranges, bearings)?;
        self.count(pose, ranges, bearings, model);
        Ok(())
    }

    /// Count a scan already validated.
    pub(crate) fn count<M: SensorModel + ?Sized>(&mut self, pose: &Pose, ranges: &[f64], bearings: &[f64], model: &M) {
        let range = model.range_model();
        let half = 0.5 * self.grid.resolution_m();
        for (&r, &bearing) in ranges.iter().zip(bearings) {
            let reach = if r >= range.max_range_m { range.max_range_m } else { r + half };
            let w = self.weight(r.min(range.max_range_m));
            let counts = &mut self.counts;
            visit(&self.grid, [pose.x_m, pose.y_m], pose.theta_rad + bearing, reach, model.footprint(), &mut |i, _| {
                counts[i] += w
            });
        }
    }
}
