//! Scan counting: how often measurements intercepted each cell.

use serde::{Deserialize, Serialize};

use crate::error::{CovmapError, Result, check_parameter};
use crate::grid::Grid;
use crate::scan_map::{ScanBeams, ScanMap};
use crate::sensor::{RangeModel, SensorModel};
use crate::sight::visit_reading;

/// Per-cell scan counts, the exploration baseline of the paper's Table I.
///
/// A measurement intercepts a cell when the cell lies in its footprint no
/// further than the end point's cell (`d_l <= d + r/2`); a no-echo reading
/// intercepts every cell of its footprint up to the maximum range. Each
/// interception adds the beam's weight: 1, or, with a discount range `D`,
/// `min(1, D / d)`, so that long, less reliable beams count less.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "ScanCountsData")]
pub struct ScanCounts {
    grid: Grid,
    discount_beyond_m: Option<f64>,
    counts: Vec<f32>,
}

/// The serialised form of [`ScanCounts`], validated on the way in: one
/// finite, non-negative count per cell and a valid discount range.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ScanCountsData {
    grid: Grid,
    discount_beyond_m: Option<f64>,
    counts: Vec<f32>,
}

impl TryFrom<ScanCountsData> for ScanCounts {
    type Error = CovmapError;
    fn try_from(d: ScanCountsData) -> Result<Self> {
        if d.counts.len() != d.grid.len() {
            return Err(CovmapError::LengthMismatch {
                what: "counts and grid cells",
                left: d.counts.len(),
                right: d.grid.len(),
            });
        }
        if let Some(m) = d.discount_beyond_m {
            check_discount(m)?;
        }
        if let Some(&c) = d.counts.iter().find(|c| !(c.is_finite() && **c >= 0.0)) {
            return Err(CovmapError::InvalidParameter {
                name: "counts",
                value: f64::from(c),
                expected: "finite, non-negative counts",
            });
        }
        Ok(Self {
            grid: d.grid,
            discount_beyond_m: d.discount_beyond_m,
            counts: d.counts,
        })
    }
}

/// Errors unless `discount_beyond_m` is a positive, finite distance.
fn check_discount(discount_beyond_m: f64) -> Result<()> {
    check_parameter(
        discount_beyond_m.is_finite() && discount_beyond_m > 0.0,
        "discount_beyond_m",
        discount_beyond_m,
        "a positive, finite distance",
    )
}

impl ScanCounts {
    /// Zero counts over `grid`, every beam counting 1.
    ///
    /// # Panics
    /// If its 4 bytes a cell cannot be allocated ([`ScanCounts::try_new`]
    /// returns an error instead).
    pub fn new(grid: Grid) -> Self {
        Self {
            grid,
            discount_beyond_m: None,
            counts: vec![0.0; grid.len()],
        }
    }

    /// [`ScanCounts::new`], or [`CovmapError::OutOfMemory`] where its 4
    /// bytes a cell cannot be allocated.
    pub fn try_new(grid: Grid) -> Result<Self> {
        Ok(Self {
            grid,
            discount_beyond_m: None,
            counts: crate::memory::try_filled(0.0, grid.len(), "the scan counts")?,
        })
    }

    /// Zero counts over `grid`; beams longer than `discount_beyond_m` count
    /// `discount_beyond_m / d`.
    pub fn with_discount(grid: Grid, discount_beyond_m: f64) -> Result<Self> {
        check_discount(discount_beyond_m)?;
        Ok(Self {
            discount_beyond_m: Some(discount_beyond_m),
            ..Self::try_new(grid)?
        })
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
}

impl ScanMap for ScanCounts {
    fn grid(&self) -> &Grid {
        &self.grid
    }

    /// Add each beam's weight to the cells it intercepts.
    fn integrate_checked<M: SensorModel + ?Sized>(
        &mut self,
        scan: ScanBeams<'_>,
        model: &M,
    ) -> Result<usize> {
        let range = model.range_model();
        let mut updates = 0;
        for (k, &r) in scan.ranges.iter().enumerate() {
            let (reach, w) = self.beam(range, r, k, scan.no_echo_reach_m);
            let counts = &mut self.counts;
            let echo = r < range.max_range_m;
            visit_reading(
                &self.grid,
                &scan,
                k,
                echo,
                reach,
                model.footprint(),
                &mut |i, _| {
                    counts[i] += w;
                    updates += 1;
                },
            );
        }
        Ok(updates)
    }
}

impl ScanCounts {
    /// How far reading `k` of `r` metres intercepts cells along its beam,
    /// and what it adds to each: up to the end point's cell, or for no echo
    /// up to the maximum range (or `no_echo_reach_m[k]` if less); its
    /// [`ScanCounts::weight`].
    pub(crate) fn beam(
        &self,
        range: &RangeModel,
        r: f64,
        k: usize,
        no_echo_reach_m: Option<&[f64]>,
    ) -> (f64, f32) {
        let reach = if r >= range.max_range_m {
            no_echo_reach_m.map_or(range.max_range_m, |c| c[k].min(range.max_range_m))
        } else {
            r + 0.5 * self.grid.resolution_m()
        };
        (reach, self.weight(r.min(range.max_range_m)))
    }

    /// The counts, for a caller that visits a beam's cells (as far as
    /// [`ScanCounts::beam`] says) to add its weight to each.
    pub(crate) fn counts_mut(&mut self) -> &mut [f32] {
        &mut self.counts
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pose::Pose;
    use crate::sensor::LaserModel;

    /// A deserialised count array is checked as the constructors check it,
    /// so that a later scan cannot index past it.
    #[test]
    fn serde_validates() {
        let grid = Grid::new([0.0, 0.0], 0.1, 10, 10).unwrap();
        let mut counts = ScanCounts::with_discount(grid, 2.0).unwrap();
        counts
            .integrate(
                &Pose::new(0.5, 0.5, 0.0),
                &[0.3],
                &[0.0],
                &LaserModel::default(),
            )
            .unwrap();
        let s = serde_json::to_string(&counts).unwrap();
        assert_eq!(serde_json::from_str::<ScanCounts>(&s).unwrap(), counts);
        let zeros = serde_json::to_string(&vec![0.0f32; 100]).unwrap();
        let plain = serde_json::to_string(&ScanCounts::new(grid)).unwrap();
        for bad in [
            plain.replace(&zeros, "[]"),
            plain.replace(&zeros, &zeros.replacen("0.0", "-1.0", 1)),
            s.replace("\"discount_beyond_m\":2.0", "\"discount_beyond_m\":-1.0"),
        ] {
            assert_ne!(bad, plain);
            assert!(serde_json::from_str::<ScanCounts>(&bad).is_err(), "{bad}");
        }
    }
}
