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
        // Sorted, so that a cell of a footprint looks itself up in a long
        // list of contacts by halves, and only if the bit of its index
        // modulo 4096 is set in `maybe`, where each contact sets its own:
        // most cells are ruled out with one look.
        let mut extra: Vec<usize> = covered.iter().filter_map(|&c| grid.index(c).ok()).collect();
        extra.sort_unstable();
        let mut maybe = [0u64; 64];
        for &i in &extra {
            maybe[i / 64 % 64] |= 1 << (i % 64);
        }
        let listed =
            |i: usize| maybe[i / 64 % 64] >> (i % 64) & 1 == 1 && extra.binary_search(&i).is_ok();
        let is_covered = |i: usize| {
            let ml = histogram::bin_value(
                histogram::argmax(&histograms[i * bins..(i + 1) * bins]),
                bins,
            );
            ml > CONTACT_COVERAGE || listed(i)
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grid::Grid;
    use crate::sensor::{LaserModel, SonarModel};

    /// The reaches with every contact looked for in the whole list, cell by
    /// cell: what the sorted list and its filter must give.
    fn reaches_listing_every_contact<M: SensorModel>(
        map: &CoverageMap,
        covered: &[Cell],
        pose: &Pose,
        ranges: &[f64],
        bearings: &[f64],
        model: &M,
    ) -> Vec<f64> {
        let grid = map.grid();
        let range = model.range_model();
        let half = 0.5 * grid.resolution_m();
        let extra: Vec<usize> = covered.iter().filter_map(|&c| grid.index(c).ok()).collect();
        let ml = map.ml();
        let is_covered = |i: usize| f64::from(ml[i]) > CONTACT_COVERAGE || extra.contains(&i);
        ranges
            .iter()
            .zip(bearings)
            .map(|(&r, &bearing)| {
                let mut reach = range.max_range_m;
                if r >= range.max_range_m {
                    let limit = range.no_echo_reach_m();
                    reach = limit;
                    let axis = pose.theta_rad + bearing;
                    let mut f = |i: usize, d_l: f64| {
                        if d_l - half < reach && is_covered(i) {
                            reach = (d_l - half).max(0.0);
                        }
                    };
                    visit(
                        grid,
                        [pose.x_m, pose.y_m],
                        axis,
                        limit,
                        model.footprint(),
                        &mut f,
                    );
                }
                reach
            })
            .collect()
    }

    /// On a map holding walls, with contact lists long and short, whose
    /// cells share their index modulo 4096 with cells the beams cross (and
    /// one off the grid), every no-echo reading stops where looking for
    /// each contact in the whole list stops it.
    #[test]
    fn contacts_stop_no_echo_readings_as_the_whole_list_does() {
        let grid = Grid::new([0.0, 0.0], 0.05, 120, 160).unwrap();
        let mut map = CoverageMap::new(grid);
        let laser = LaserModel::default();
        let bearings: Vec<f64> = (0..90).map(|k| f64::from(k) * 0.0698).collect();
        for pose in [Pose::new(2.0, 3.0, 0.0), Pose::new(6.0, 3.5, 0.0)] {
            let ranges: Vec<f64> = bearings.iter().map(|b| 1.2 + b.sin().abs()).collect();
            map.integrate(&pose, &ranges, &bearings, &laser).unwrap();
        }
        let mut next = crate::test_rng::uniform(3);
        let sonar = SonarModel::default();
        let no_echo = vec![sonar.range.max_range_m; 24];
        let ring: Vec<f64> = (0..24).map(|k| f64::from(k) * 0.2618).collect();
        let mut stopped = 0;
        for trial in 0..40 {
            let pose = Pose::new(1.0 + 6.0 * next(), 1.0 + 4.0 * next(), next());
            let near = |next: &mut dyn FnMut() -> f64| {
                let (r, a) = (2.5 * next(), 6.3 * next());
                grid.world_to_cell(pose.x_m + r * a.cos(), pose.y_m + r * a.sin())
            };
            let mut covered: Vec<Cell> = (0..[0, 3, 60][trial % 3])
                .filter_map(|_| near(&mut next))
                .collect();
            // Cells 4096 apart in the index from some of them, and one off the grid.
            let aliases: Vec<Cell> = covered
                .iter()
                .filter_map(|&c| grid.index(c).ok())
                .filter_map(|i| i.checked_sub(4096))
                .map(|i| grid.cell(i))
                .collect();
            covered.extend(aliases);
            covered.push(Cell { row: 500, col: 3 });
            let got = map.no_echo_reaches(&covered, &pose, &no_echo, &ring, &sonar);
            let want =
                reaches_listing_every_contact(&map, &covered, &pose, &no_echo, &ring, &sonar);
            assert_eq!(got, want, "trial {trial}");
            stopped += got
                .iter()
                .filter(|&&r| r < sonar.range.no_echo_reach_m())
                .count();
        }
        assert!(stopped > 100, "{stopped} readings stopped");
    }
}
