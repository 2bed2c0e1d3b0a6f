//! Whether a building is valid: every room reachable by the robot's disc.
//!
//! The free space of a disc of [`ROBOT_RADIUS_M`] is rasterised at
//! [`RESOLUTION_M`] (the cells whose centre keeps the radius from every
//! obstacle, [`clearances`]), and split into regions as the planner
//! connects cells (8-connected, no corner cut, [`free_regions`]). A room is
//! reachable from a point when the region of the point's cell holds a cell
//! whose centre lies on the room's floor: a disc starting there can drive
//! into the room, through its doors, on the grid the exploration runs on.

use covmap_core::Grid;

use super::building::Room;
use super::options::ROBOT_RADIUS_M;
use crate::error::Result;
use crate::exploration::{clearances, free_regions};
use crate::robot::Robot;
use crate::world::World;

/// The cell size of the check, metres: the exploration's default.
pub const RESOLUTION_M: f64 = 0.05;

/// Where a disc of [`ROBOT_RADIUS_M`] starting at a point can go: the
/// grid of the check, the cells where it fits, and those of them it
/// reaches.
pub(crate) struct Reach {
    pub(crate) grid: Grid,
    #[cfg_attr(not(test), allow(dead_code, reason = "read by the generator's tests"))]
    pub(crate) free: Vec<bool>,
    pub(crate) reached: Vec<bool>,
}

/// Where a disc starting at `from_m` in `world` can go (see the module
/// documentation); nothing when it cannot stand at `from_m`.
///
/// # Errors
/// As [`Grid::covering`] for a world too large to rasterise.
pub(crate) fn reach(world: &World, from_m: [f64; 2]) -> Result<Reach> {
    let robot = Robot::new(ROBOT_RADIUS_M)?;
    let [x0, y0, x1, y1] = world.bounds_m();
    let m = 0.5;
    let grid = Grid::covering(
        x0.min(from_m[0]) - m,
        y0.min(from_m[1]) - m,
        x1.max(from_m[0]) + m,
        y1.max(from_m[1]) + m,
        RESOLUTION_M,
    )?;
    let clearance = clearances(world, &grid, &robot);
    let free: Vec<bool> = clearance.iter().map(|&c| c >= 0.0).collect();
    let mut reached = vec![false; grid.len()];
    if let Some(cell) = grid.world_to_cell(from_m[0], from_m[1]) {
        let start = grid.index(cell)?;
        if let Some(region) = free_regions(&grid, &free)
            .into_iter()
            .find(|r| r.binary_search(&start).is_ok())
        {
            for i in region {
                reached[i] = true;
            }
        }
    }
    Ok(Reach {
        grid,
        free,
        reached,
    })
}

/// The indices of the rooms of `rooms` that a disc of [`ROBOT_RADIUS_M`]
/// starting at `from_m` in `world` cannot reach (see the module
/// documentation); all of them when it cannot stand at `from_m`.
///
/// # Errors
/// As [`Grid::covering`] for a world too large to rasterise.
pub fn unreachable_rooms(world: &World, rooms: &[Room], from_m: [f64; 2]) -> Result<Vec<usize>> {
    let Reach { grid, reached, .. } = reach(world, from_m)?;
    Ok((0..rooms.len())
        .filter(|&r| {
            !rooms[r]
                .floor_m
                .iter()
                .any(|f| cells_in(&grid, f).any(|i| reached[i]))
        })
        .collect())
}

/// The cells whose centre lies in `floor`.
pub(crate) fn cells_in<'a>(grid: &'a Grid, floor: &[f64; 4]) -> impl Iterator<Item = usize> + 'a {
    let [gx0, gy0] = grid.origin_m();
    let r = grid.resolution_m();
    let (rows, cols) = grid.shape();
    // Cells whose centre lies in [lo, hi] along an axis: from ceil((lo -
    // origin) / r - 0.5) to floor((hi - origin) / r - 0.5), within the grid.
    let range = |lo: f64, hi: f64, origin: f64, n: usize| {
        let first = ((lo - origin) / r - 0.5).ceil().max(0.0) as usize;
        let last = ((hi - origin) / r - 0.5).floor();
        let end = if last < 0.0 {
            0
        } else {
            (last as usize + 1).min(n)
        };
        first..end.max(first)
    };
    let cs = range(floor[0], floor[2], gx0, cols);
    let rs = range(floor[1], floor[3], gy0, rows);
    rs.flat_map(move |row| cs.clone().map(move |col| row * cols + col))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::building::RoomKind;
    use crate::material::Material;
    use crate::polygon::Polygon;

    fn room(floor: [f64; 4]) -> Room {
        Room {
            name: "r".into(),
            kind: RoomKind::Room,
            floor_m: vec![floor],
        }
    }

    /// Two rooms either side of a wall with a doorway: both reachable with
    /// a doorway wider than the disc, one without it or with one too narrow.
    #[test]
    fn a_room_behind_a_narrow_door_is_unreachable() {
        let rooms = [room([0.0, 0.0, 3.0, 3.0]), room([3.2, 0.0, 6.0, 3.0])];
        let walls = |door: f64| {
            let mut p = vec![
                Polygon::rectangle([-0.1, -0.1], [6.1, 0.0], Material::Wall).unwrap(),
                Polygon::rectangle([-0.1, 3.0], [6.1, 3.1], Material::Wall).unwrap(),
                Polygon::rectangle([-0.1, 0.0], [0.0, 3.0], Material::Wall).unwrap(),
                Polygon::rectangle([6.0, 0.0], [6.1, 3.0], Material::Wall).unwrap(),
                Polygon::rectangle([3.0, 0.0], [3.2, 1.0], Material::Wall).unwrap(),
            ];
            p.push(Polygon::rectangle([3.0, 1.0 + door], [3.2, 3.0], Material::Wall).unwrap());
            World::new(p)
        };
        let from = [1.5, 1.5];
        assert!(
            unreachable_rooms(&walls(0.8), &rooms, from)
                .unwrap()
                .is_empty()
        );
        assert_eq!(unreachable_rooms(&walls(0.45), &rooms, from).unwrap(), [1]);
        // From inside a wall nothing is reachable.
        assert_eq!(
            unreachable_rooms(&walls(0.8), &rooms, [3.1, 0.5]).unwrap(),
            [0, 1]
        );
    }
}
