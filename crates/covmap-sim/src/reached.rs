//! Where a recorded drive's sound or light went in the true world: the
//! cells a sensor physically reached, as opposed to those its inverse model
//! updates.
//!
//! A sonar's model clears its whole cone up to the reading, and a no-echo
//! reading its whole cone out to the maximum range, through whatever walls
//! the pulse glanced off: the model's footprint runs on behind a wall the
//! sound never crossed. Judging a map on such cells rewards a model for
//! guessing what lies behind walls. The cells *reached* here are those the
//! pulse (or the laser's light) travelled to: for every beam of every scan,
//! rays are cast through the true world across the beam's footprint (the
//! cone of a sonar, 2 rays per cell of arc at the maximum range; the one
//! ray of a laser beam), each up to the first surface it meets or the
//! maximum range, and every cell a ray runs through up to there is
//! reached, the cell of the surface it met included. A scan reaches a cell
//! once, however many of its rays do.

use covmap_core::sensor::Footprint;
use covmap_core::{Grid, Log};

use crate::world::World;

/// How many scans of `log` reached each cell of `grid` (row-major), for a
/// sensor whose beams have `footprint` (see the module documentation).
///
/// Poses and ranges are the log's; its readings do not matter, only where
/// its sensor stood and looked. Cells off the grid are skipped.
pub fn reached_counts(world: &World, grid: &Grid, log: &Log, footprint: Footprint) -> Vec<u32> {
    let r = grid.resolution_m();
    let max_range_m = log.max_range_m();
    // Rays across a cone: two per cell of arc at the maximum range.
    let ray_step_rad = 0.5 * r / max_range_m.max(r);
    let mut counts = vec![0u32; grid.len()];
    // The scan that last counted each cell (1-based; 0: none yet).
    let mut stamp = vec![0u32; grid.len()];
    for i in 0..log.len() {
        let scan = u32::try_from(i + 1).unwrap_or(u32::MAX);
        let pose = log.sensor_pose(i);
        let origin = [pose.x_m, pose.y_m];
        for &bearing in log.scan_bearings(i) {
            let axis = pose.theta_rad + bearing;
            let (first, rays, step) = match footprint {
                Footprint::Cone { half_angle_rad } => {
                    let rays = (2.0 * half_angle_rad / ray_step_rad).ceil().max(1.0) as usize + 1;
                    let step = 2.0 * half_angle_rad / (rays - 1).max(1) as f64;
                    (axis - half_angle_rad, rays, step)
                }
                Footprint::Ray => (axis, 1, 0.0),
            };
            for k in 0..rays {
                let angle = first + k as f64 * step;
                let hit = world.cast(origin, angle, max_range_m);
                // Into the surface's cell by a hair: the cell it was met in.
                let end_m = if hit.is_hit() {
                    hit.distance_m + 1e-6
                } else {
                    max_range_m
                };
                let (s, c) = angle.sin_cos();
                let samples = (end_m / (0.5 * r)).ceil() as usize;
                for j in 0..=samples {
                    let d = (j as f64 * 0.5 * r).min(end_m);
                    let Some(cell) = grid.world_to_cell(origin[0] + d * c, origin[1] + d * s)
                    else {
                        continue;
                    };
                    let Ok(index) = grid.index(cell) else {
                        continue;
                    };
                    if stamp[index] != scan {
                        stamp[index] = scan;
                        counts[index] += 1;
                    }
                }
            }
        }
    }
    counts
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Material;
    use covmap_core::Pose;

    /// A wall 1 m in front of the sensor: the sound reaches the cells up to
    /// and including the wall's face, never the wall's inside nor what lies
    /// behind it, though the model's no-echo cone would run on through it.
    #[test]
    fn sound_stops_at_the_first_surface() {
        let world = World::from_vertex_lists(
            vec![vec![[1.0, -2.0], [1.5, -2.0], [1.5, 2.0], [1.0, 2.0]]],
            Material::Wall,
        )
        .unwrap();
        let grid = Grid::new([-0.5, -1.0], 0.05, 40, 80).unwrap();
        let log = Log::new(
            vec![Pose::new(0.0, 0.0, 0.0)],
            vec![0.0],
            vec![5.0],
            covmap_core::log::Bearings::Fixed(vec![0.0]),
            5.0,
        )
        .unwrap();
        let counts = reached_counts(
            &world,
            &grid,
            &log,
            Footprint::Cone {
                half_angle_rad: 7.5f64.to_radians(),
            },
        );
        let at = |x: f64, y: f64| counts[grid.index(grid.world_to_cell(x, y).unwrap()).unwrap()];
        assert_eq!(at(0.5, 0.0), 1, "in front of the wall, on the axis");
        assert_eq!(at(0.9, 0.1), 1, "in front of the wall, off the axis");
        assert_eq!(at(1.02, 0.0), 1, "the face's cell");
        assert_eq!(at(1.2, 0.0), 0, "inside the wall");
        assert_eq!(at(2.0, 0.0), 0, "behind the wall");
        assert_eq!(at(0.5, 0.3), 0, "outside the cone");
    }
}
