//! No-echo readings occluded by the map: a no-echo reading that the map
//! says crossed an obstacle missed it (a specular reflection) and says
//! nothing of what lies behind.

use super::{CONTACT_COVERAGE, CoverageMap};
use crate::footprint::visit;
use crate::grid::Cell;
use crate::histogram;
use crate::pose::Pose;
use crate::sensor::SensorModel;

impl CoverageMap {
    /// How far each no-echo reading of a scan from `pose` should clear: to
    /// the nearest cell of its footprint that this map holds as covered (ML
    /// coverage above [`CONTACT_COVERAGE`]) or that is among `covered`
    /// (cells known to be covered otherwise, such as those a robot ran
    /// into), at most the model's no-echo reach; echo readings get the
    /// maximum range (they ignore it). The result is what
    /// [`CoverageMap::integrate_clipped`] takes. The scan is not validated:
    /// an invalid one gives reaches the update then refuses.
    pub fn no_echo_reaches<M: SensorModel + ?Sized>(
        &self,
        covered: &[Cell],
        pose: &Pose,
        ranges: &[f64],
        bearings: &[f64],
        model: &M,
    ) -> Vec<f64> {
        let grid = self.grid();
        let (bins, histograms) = (self.bins(), self.histograms());
        let range = model.range_model();
        let (max_range_m, no_echo_reach_m) = (range.max_range_m, range.no_echo_reach_m());
        let footprint = model.footprint();
        let half = 0.5 * grid.resolution_m();
        // Sorted, so that each cell of a footprint looks itself up in a
        // long list of contacts by halves.
        let mut extra: Vec<usize> = covered.iter().filter_map(|&c| grid.index(c).ok()).collect();
        extra.sort_unstable();
        let is_covered = |i: usize| {
            let ml = histogram::bin_value(
                histogram::argmax(&histograms[i * bins..(i + 1) * bins]),
                bins,
            );
            ml > CONTACT_COVERAGE || extra.binary_search(&i).is_ok()
        };
        ranges
            .iter()
            .zip(bearings)
            .map(|(&r, &bearing)| {
                let mut reach = max_range_m;
                if r >= max_range_m && r.is_finite() && bearing.is_finite() {
                    reach = no_echo_reach_m;
                    visit(
                        grid,
                        [pose.x_m, pose.y_m],
                        pose.theta_rad + bearing,
                        no_echo_reach_m,
                        footprint,
                        &mut |i: usize, d_l: f64| {
                            if d_l - half < reach && is_covered(i) {
                                reach = (d_l - half).max(0.0);
                            }
                        },
                    );
                }
                reach
            })
            .collect()
    }
}
