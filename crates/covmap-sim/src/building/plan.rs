//! The rooms of a plan that does not list them (a real floor plan, a
//! map_server pair, a built-in world): [`Building::from_world`].
//!
//! # The rule
//! A room is a part of the free space that narrow passages separate from
//! the rest. On a grid of [`RESOLUTION_M`] over the world:
//!
//! 1. the *start region*: the cells where the robot's disc
//!    ([`ROBOT_RADIUS_M`]) fits, the region of them a seeded start is
//!    drawn from ([`start_region`]: the largest the world encloses);
//! 2. its *core*: the enclosed cells of the start region ([`enclosed_cells`]:
//!    not the outside of a building) whose centre lies at least half of
//!    [`PASSAGE_M`] from every obstacle. A doorway narrower than
//!    [`PASSAGE_M`] (every generated door, and the doors of real plans) has
//!    no core cell, so it separates the cores of the rooms either side;
//!    corridors and rooms wider than it keep a core;
//! 3. the rooms: the connected parts of the core (8-connected, no corner
//!    cut) of at least [`MIN_CORE_M2`], in the order of their first cell,
//!    named `"region 1"`, `"region 2"`, ...; a room's floor is its core
//!    cells, merged into rectangles.
//!
//! [`enclosed_cells`]: crate::exploration::cells::enclosed_cells
//!
//! A run entered a room when the robot's centre crossed a cell of its core:
//! a robot that only looked in from the doorway did not. Every region
//! counts, corridors among them (a plan does not say which is which).
//! Doors are not listed.

use covmap_core::Grid;

use super::building::{Building, Room, RoomKind};
use super::options::ROBOT_RADIUS_M;
use crate::error::Result;
use crate::exploration::{clearances, free_regions, start_region};
use crate::robot::Robot;
use crate::world::World;

/// The cell size of the rule, metres.
pub const RESOLUTION_M: f64 = 0.1;
/// The widest passage that separates two rooms, metres: wider than the
/// widest door the generator makes (1.2 m), narrower than its narrowest
/// corridor (1.5 m).
pub const PASSAGE_M: f64 = 1.3;
/// The least core area of a room, square metres (a room of about 1.8 m
/// by 1.8 m).
pub const MIN_CORE_M2: f64 = 0.25;

impl Building {
    /// `world` as a building named `name`, its rooms found by [the
    /// rule](crate::building::plan).
    ///
    /// # Errors
    /// As [`Grid::covering`] for a world too large to rasterise at
    /// [`RESOLUTION_M`].
    pub fn from_world(world: World, name: impl Into<String>) -> Result<Building> {
        let rooms = plan_rooms(&world)?;
        Building::new(name, world, rooms, Vec::new())
    }
}

/// The rooms of `world` by the rule.
fn plan_rooms(world: &World) -> Result<Vec<Room>> {
    if world.is_empty() {
        return Ok(Vec::new());
    }
    let [x0, y0, x1, y1] = world.bounds_m();
    let m = 0.5;
    let grid = Grid::covering(x0 - m, y0 - m, x1 + m, y1 + m, RESOLUTION_M)?;
    let robot = Robot::new(ROBOT_RADIUS_M)?;
    let clearance = clearances(world, &grid, &robot);
    let (region, enclosed) = start_region(&grid, &clearance);
    let mut core = vec![false; grid.len()];
    let reach = 0.5 * PASSAGE_M - ROBOT_RADIUS_M;
    for &i in &region {
        core[i] = enclosed[i] && clearance[i] >= reach;
    }
    let cell_area = RESOLUTION_M * RESOLUTION_M;
    Ok(free_regions(&grid, &core)
        .into_iter()
        .filter(|r| r.len() as f64 * cell_area >= MIN_CORE_M2)
        .enumerate()
        .map(|(k, cells)| Room {
            name: format!("region {}", k + 1),
            kind: RoomKind::Room,
            floor_m: rectangles(&grid, &cells),
        })
        .collect())
}

/// The cells (sorted indices) as rectangles: each row's runs, merged with
/// the same run of the rows above.
fn rectangles(grid: &Grid, cells: &[usize]) -> Vec<[f64; 4]> {
    let cols = grid.cols();
    // Runs (row, first col, end col), in row order.
    let mut runs: Vec<(usize, usize, usize)> = Vec::new();
    for &i in cells {
        let (row, col) = (i / cols, i % cols);
        match runs.last_mut() {
            Some((r, _, end)) if *r == row && *end == col => *end = col + 1,
            _ => runs.push((row, col, col + 1)),
        }
    }
    // Open rectangles: (first col, end col) -> (first row, last row).
    let mut open: Vec<(usize, usize, usize, usize)> = Vec::new();
    let mut done: Vec<(usize, usize, usize, usize)> = Vec::new();
    let mut at = 0;
    while at < runs.len() {
        let row = runs[at].0;
        let mut next = Vec::new();
        while at < runs.len() && runs[at].0 == row {
            let (_, c0, c1) = runs[at];
            match open
                .iter()
                .position(|&(a, b, _, last)| a == c0 && b == c1 && last + 1 == row)
            {
                Some(k) => {
                    let (a, b, first, _) = open.swap_remove(k);
                    next.push((a, b, first, row));
                }
                None => next.push((c0, c1, row, row)),
            }
            at += 1;
        }
        done.append(&mut open);
        open = next;
    }
    done.append(&mut open);
    let [gx, gy] = grid.origin_m();
    let r = grid.resolution_m();
    let mut rects: Vec<[f64; 4]> = done
        .into_iter()
        .map(|(c0, c1, r0, r1)| {
            [
                gx + c0 as f64 * r,
                gy + r0 as f64 * r,
                gx + c1 as f64 * r,
                gy + (r1 + 1) as f64 * r,
            ]
        })
        .collect();
    rects.sort_by(|a, b| a[1].total_cmp(&b[1]).then(a[0].total_cmp(&b[0])));
    rects
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The built-in corridor: three rooms behind 0.9 m doors and the
    /// corridor; the east room's rotated box leaves passages narrower than
    /// 1.3 m either side of it, so the room is two regions: five in all. A
    /// drive along the corridor enters only it, one into the first room
    /// enters that too.
    #[test]
    fn the_corridor_has_its_rooms_and_itself() {
        let b = Building::from_world(World::builtin("corridor").unwrap(), "corridor").unwrap();
        assert_eq!(b.rooms().len(), 5, "{:?}", b.rooms());
        let along = [[1.0, 1.3], [16.0, 1.3]];
        let entered = b.rooms_entered(&along);
        assert_eq!(entered.iter().filter(|&&e| e).count(), 1, "{entered:?}");
        let into = [[1.0, 1.3], [2.25, 1.3], [2.25, 4.5]];
        assert_eq!(b.rooms_entered(&into).iter().filter(|&&e| e).count(), 2);
        let area: f64 = b.rooms().iter().map(Room::area_m2).sum();
        assert!(area > 20.0 && area < 100.0, "{area}");
    }

    /// The rectangles of a set of cells cover exactly those cells.
    #[test]
    fn rectangles_cover_the_cells() {
        let grid = Grid::new([0.0, 0.0], 1.0, 4, 5).unwrap();
        let cells = [0, 1, 2, 5, 6, 7, 9, 13, 14, 19];
        let rects = rectangles(&grid, &cells);
        let area: f64 = rects.iter().map(|r| (r[2] - r[0]) * (r[3] - r[1])).sum();
        assert_eq!(area, cells.len() as f64);
        for i in 0..20 {
            let c = grid.cell_center(grid.cell(i));
            let inside = rects
                .iter()
                .any(|r| r[0] < c[0] && c[0] < r[2] && r[1] < c[1] && c[1] < r[3]);
            assert_eq!(inside, cells.contains(&i), "cell {i}");
        }
        assert_eq!(rects.len(), 4, "{rects:?}");
    }
}
