//! The order candidates and their beams are evaluated in.
//!
//! Candidates are taken in groups of neighbours (in Z order over the map),
//! and a group's beams in the order of their direction: beams that follow
//! each other then cover much the same cells, which are still in the
//! processor's cache. Every candidate's beams are summed in the order of
//! their direction whatever the other candidates are, so a result depends
//! neither on scheduling nor on the company a candidate keeps.

use crate::grid::Grid;
use crate::parallel;
use crate::pose::Pose;

/// Candidates evaluated together.
const GROUP: usize = 16;

/// Interleave the bits of two cell coordinates (Z order).
fn z_order(x: u32, y: u32) -> u64 {
    let spread = |v: u32| {
        let mut v = u64::from(v);
        v = (v | (v << 16)) & 0x0000_ffff_0000_ffff;
        v = (v | (v << 8)) & 0x00ff_00ff_00ff_00ff;
        v = (v | (v << 4)) & 0x0f0f_0f0f_0f0f_0f0f;
        v = (v | (v << 2)) & 0x3333_3333_3333_3333;
        (v | (v << 1)) & 0x5555_5555_5555_5555
    };
    spread(x) | (spread(y) << 1)
}

/// The gain of each of `poses`: the sum over `bearings` of
/// `beam(pose, bearing, scratch)`, in the order of the beams' directions,
/// each group of candidates with one `scratch` (which each beam leaves as it
/// found it). In parallel with the feature `parallel`.
pub(super) fn in_groups<S: Default>(
    grid: &Grid,
    poses: &[Pose],
    bearings: &[f64],
    beam: impl Fn(&Pose, f64, &mut S) -> f64 + Sync,
) -> Vec<f64> {
    let mut order: Vec<(u64, usize)> = poses
        .iter()
        .enumerate()
        .map(|(index, pose)| {
            let [gx, gy] = grid.world_to_grid(pose.x_m, pose.y_m);
            (z_order(gx as u32, gy as u32), index)
        })
        .collect();
    order.sort_unstable();
    let group = |members: &[(u64, usize)]| -> Vec<(usize, f64)> {
        let mut beams: Vec<(f64, usize, f64)> = Vec::with_capacity(members.len() * bearings.len());
        for (slot, &(_, index)) in members.iter().enumerate() {
            for &bearing in bearings {
                beams.push((direction(&poses[index], bearing), slot, bearing));
            }
        }
        beams.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
        let mut totals: Vec<(usize, f64)> =
            members.iter().map(|&(_, index)| (index, 0.0)).collect();
        // One scratch for the group's beams (for the fast evaluator, a queue
        // of gains, which each beam leaves empty).
        let mut scratch = S::default();
        for (_, slot, bearing) in beams {
            totals[slot].1 += beam(&poses[totals[slot].0], bearing, &mut scratch);
        }
        totals
    };
    let groups: Vec<&[(u64, usize)]> = order.chunks(GROUP).collect();
    let mut gains = vec![0.0; poses.len()];
    for (index, gain) in parallel::map(groups, group).into_iter().flatten() {
        gains[index] = gain;
    }
    gains
}

/// The direction of the beam at `bearing` from `pose`, in `[0, 2 pi)`: the
/// order a candidate's beams are summed in.
fn direction(pose: &Pose, bearing: f64) -> f64 {
    (pose.theta_rad + bearing).rem_euclid(std::f64::consts::TAU)
}

/// The gain of the candidate at `pose` from the gains of its beams
/// (`beams[j]` of the beam at `bearings[j]`), summed as [`in_groups`] sums
/// them: from 0, in the order of their directions (beams of one direction in
/// the order of their bearings). The same bits as the candidate's
/// [`GainEvaluator::evaluate`](super::GainEvaluator::evaluate).
pub(crate) fn beam_sum(pose: &Pose, bearings: &[f64], beams: &[f64]) -> f64 {
    debug_assert_eq!(bearings.len(), beams.len());
    let mut order: Vec<(f64, usize)> = bearings
        .iter()
        .enumerate()
        .map(|(j, &bearing)| (direction(pose, bearing), j))
        .collect();
    order.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
    let mut total = 0.0;
    for (_, j) in order {
        total += beams[j];
    }
    total
}

#[cfg(test)]
mod tests {
    use crate::gain::test_maps::{ring_of_eight, scanned};
    use crate::gain::{GainEvaluator, GainMethod, GainOptions};
    use crate::grid::Grid;
    use crate::pose::Pose;
    use crate::sensor::SonarModel;

    #[test]
    fn a_candidate_gains_the_same_alone_and_in_company() {
        let grid = Grid::new([0.0, 0.0], 0.1, 40, 50).unwrap();
        let sonar = SonarModel::default();
        let bearings = ring_of_eight();
        let scan: (Pose, &[f64]) = (
            Pose::new(2.0, 2.0, 0.3),
            &[1.2, 2.0, 6.0, 0.7, 1.5, 2.2, 3.0, 0.4],
        );
        let map = scanned(grid, &[scan], &bearings, &sonar);
        let eval = GainEvaluator::new(&map, &sonar, GainOptions::default()).unwrap();
        let poses: Vec<Pose> = (0..40)
            .map(|k| Pose::new(0.3 + 0.12 * k as f64, 0.4 + 0.09 * k as f64, 0.7 * k as f64))
            .collect();
        let together = eval.evaluate(&poses, &bearings, GainMethod::Fast).unwrap();
        for (pose, g) in poses.iter().zip(&together) {
            let alone = eval
                .evaluate(std::slice::from_ref(pose), &bearings, GainMethod::Fast)
                .unwrap();
            assert_eq!(alone[0].to_bits(), g.to_bits());
        }
    }
}
