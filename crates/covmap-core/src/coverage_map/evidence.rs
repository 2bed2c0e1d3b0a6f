//! The evidence behind the histograms: each cell's log-likelihoods.

use super::CoverageMap;
use crate::error::{CovmapError, Result};
use crate::histogram::{self, with_bins};

/// How far a histogram may lie from the one its evidence gives, per bin.
const TOLERANCE: f32 = 1e-5;

impl CoverageMap {
    /// Each cell's log-likelihoods, cell-major as [`Self::histograms`]: the
    /// evidence the histograms are read off (`h_b ∝ exp(l_b)`), shifted so
    /// that each cell's largest is 0. Integrating a reading adds its
    /// kernel's logarithms; a bin the histogram holds at the floor keeps
    /// here all the evidence against it.
    pub fn evidence(&self) -> &[f32] {
        &self.log
    }

    /// Make `evidence` (from [`Self::evidence`] of a map with the same grid,
    /// bins and histograms) this map's, so that further scans continue it
    /// as they would have continued the original (a map rebuilt from its
    /// histograms alone, [`Self::from_histograms`], holds no more evidence
    /// against a bin than the floor's).
    ///
    /// # Errors
    /// [`CovmapError::LengthMismatch`] if `evidence` is not one value a bin;
    /// [`CovmapError::InvalidHistogram`] if a cell's values are not finite,
    /// not at most 0 with the largest 0, or do not give the cell's histogram
    /// (within `1e-5` a bin). The map is unchanged then.
    pub fn restore_evidence(&mut self, evidence: Vec<f32>) -> Result<()> {
        let bins = self.bins;
        if evidence.len() != self.data.len() {
            return Err(CovmapError::LengthMismatch {
                what: "evidence values and grid cells x bins",
                left: evidence.len(),
                right: self.data.len(),
            });
        }
        let zeros = vec![0.0f32; bins];
        let mut l = vec![0.0f32; bins];
        let mut h = vec![0.0f32; bins];
        for (i, (cell, held)) in evidence
            .chunks_exact(bins)
            .zip(self.data.chunks_exact(bins))
            .enumerate()
        {
            let top = cell.iter().copied().fold(f32::NEG_INFINITY, f32::max);
            if cell.iter().any(|v| !(v.is_finite() && *v <= 0.0)) || top != 0.0 {
                return Err(CovmapError::InvalidHistogram(format!(
                    "cell {i}: evidence must be finite log-likelihoods, the largest 0"
                )));
            }
            l.copy_from_slice(cell);
            with_bins!(bins, |N| histogram::update_log::<N>(
                &mut l,
                &mut h,
                &zeros,
                histogram::BIN_FLOOR
            ));
            if h.iter().zip(held).any(|(a, b)| (a - b).abs() > TOLERANCE) {
                return Err(CovmapError::InvalidHistogram(format!(
                    "cell {i}: the evidence does not give the map's histogram"
                )));
            }
        }
        self.log.copy_from_slice(&evidence);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use crate::{CoverageMap, Grid, Pose, ScanMap, SonarModel};

    fn scanned() -> CoverageMap {
        let mut map = CoverageMap::new(Grid::new([0.0, 0.0], 0.05, 40, 40).unwrap());
        let sonar = SonarModel::default();
        for k in 0..200 {
            let pose = Pose::new(0.5 + 0.002 * f64::from(k), 1.0, 0.0);
            map.integrate(&pose, &[1.0, 5.0, 0.6], &[0.0, 1.5, -1.5], &sonar)
                .unwrap();
        }
        map
    }

    /// A map rebuilt from its histograms and given its evidence goes on as
    /// the original does; rebuilt from its histograms alone it does not
    /// (the evidence beyond the floor is gone).
    #[test]
    fn restored_evidence_continues_the_map() {
        let mut map = scanned();
        let mut alone =
            CoverageMap::from_histograms(*map.grid(), map.bins(), map.histograms().to_vec())
                .unwrap();
        let mut restored = alone.try_clone().unwrap();
        restored.restore_evidence(map.evidence().to_vec()).unwrap();
        let sonar = SonarModel::default();
        for m in [&mut map, &mut alone, &mut restored] {
            for _ in 0..50 {
                m.integrate(&Pose::new(0.5, 1.0, 0.0), &[0.45], &[0.0], &sonar)
                    .unwrap();
            }
        }
        assert_eq!(map.histograms(), restored.histograms());
        assert_eq!(map.evidence(), restored.evidence());
        assert_ne!(map.histograms(), alone.histograms());
    }

    /// Evidence that is not finite, not shifted to a largest 0, of the wrong
    /// length or of other histograms is refused, and the map is unchanged.
    #[test]
    fn bad_evidence_is_refused_and_changes_nothing() {
        let map = scanned();
        let good = map.evidence().to_vec();
        let mut target = map.try_clone().unwrap();
        let mut nan = good.clone();
        nan[3] = f32::NAN;
        let mut shifted = good.clone();
        for v in &mut shifted[..16] {
            *v -= 1.0;
        }
        let other = CoverageMap::new(*map.grid()).evidence().to_vec();
        let changed: Vec<usize> = (0..map.grid().len())
            .filter(|&i| map.histograms()[i * 16] != 1.0 / 16.0)
            .collect();
        assert!(!changed.is_empty());
        for bad in [nan, shifted, other, good[1..].to_vec()] {
            assert!(target.restore_evidence(bad).is_err());
            assert_eq!(target.evidence(), map.evidence());
            assert_eq!(target.histograms(), map.histograms());
        }
    }
}
