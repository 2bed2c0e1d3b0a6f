//! What stands in a generated building besides its walls: furniture in the
//! rooms and halls, pillars in the halls and along corridors, slanted walls
//! across rooms' back corners.
//!
//! # Nothing blocks a door or cuts a room in two
//! - Nothing stands in a door's zone: the door's span and
//!   [`DOOR_SIDE_M`] either side, [`DOOR_REACH_M`] into both rooms.
//! - Every two things in a room keep at least [`GAP_M`] apart (more than
//!   the robot's diameter), measured between their axis-aligned bounding
//!   boxes (a rotated table's box is larger than the table, so the true gap
//!   is larger still).
//! - An item against a wall stands flush with it, and either flush with
//!   the wall at its end (in the corner) or at least [`GAP_M`] from it.
//!   Free-standing items keep [`GAP_M`] from every wall.
//! - A slanted wall cuts a back corner of a room without a second door;
//!   nothing stands in the box around it.
//!
//! The generator checks the result ([`super::validity`]) and takes out a
//! room's furniture should a room still be cut off.
//!
//! Rotations are drawn from directions with rational cosines and sines
//! (Pythagorean triples) and round things are octagons of `sqrt(0.5)`: no
//! sine or cosine of the platform's maths library, so that the same seed
//! gives the same building, bit for bit, on every machine.

use rand::RngExt;

use super::building::RoomKind;
use super::layout::{Line, Plan, Side, uniform};
use super::walls::Walls;
use crate::error::Result;
use crate::material::Material;
use crate::polygon::Polygon;
use crate::rng::SimRng;

/// The least gap between two things in a room, metres: a 0.5 m disc and
/// some room.
pub(super) const GAP_M: f64 = 0.6;
/// How far either side of a door its zone reaches along the wall, metres.
pub(super) const DOOR_SIDE_M: f64 = 0.35;
/// How far into each room a door's zone reaches from the wall's centre
/// line, metres.
pub(super) const DOOR_REACH_M: f64 = 1.2;
/// The chance that a room without a second door has a slanted wall.
const P_SLANT: f64 = 0.15;
/// The chance that a building has pillars along its corridors.
const P_CORRIDOR_PILLARS: f64 = 0.4;
/// The least clear width a corridor keeps beside its pillars, metres.
const CORRIDOR_CLEAR_M: f64 = 1.0;
/// Floor area a room holds a piece of furniture for at full clutter,
/// square metres.
const AREA_PER_ITEM_M2: f64 = 2.5;
/// Tries to place one piece of furniture.
const TRIES: usize = 25;

/// Directions `(cos, sin)` with rational components.
const DIRECTIONS: [[f64; 2]; 7] = [
    [1.0, 0.0],
    [4.0 / 5.0, 3.0 / 5.0],
    [3.0 / 5.0, 4.0 / 5.0],
    [12.0 / 13.0, 5.0 / 13.0],
    [5.0 / 13.0, 12.0 / 13.0],
    [15.0 / 17.0, 8.0 / 17.0],
    [8.0 / 17.0, 15.0 / 17.0],
];

/// What an item is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum ItemKind {
    /// A desk, cabinet, table or round thing in a room or hall.
    Furniture,
    /// A pillar in a hall or against a corridor's wall.
    Pillar,
    /// A slanted wall across a room's back corner.
    SlantedWall,
}

/// An item placed, and the region it stands in.
pub(super) struct Item {
    pub(super) region: usize,
    pub(super) kind: ItemKind,
    pub(super) polygon: Polygon,
}

/// The gap between two boxes (0 where they overlap or touch).
fn gap(a: &[f64; 4], b: &[f64; 4]) -> f64 {
    let dx = (a[0] - b[2]).max(b[0] - a[2]).max(0.0);
    let dy = (a[1] - b[3]).max(b[1] - a[3]).max(0.0);
    (dx * dx + dy * dy).sqrt()
}

/// Whether two boxes overlap with positive area.
fn overlap(a: &[f64; 4], b: &[f64; 4]) -> bool {
    a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3]
}

/// `rect` grown by `by` on every side.
fn grow(rect: &[f64; 4], by: f64) -> [f64; 4] {
    [rect[0] - by, rect[1] - by, rect[2] + by, rect[3] + by]
}

/// A region's floor: its rectangle within its walls' faces.
pub(super) fn floor(rect: &[f64; 4], wall_m: f64) -> [f64; 4] {
    grow(rect, -0.5 * wall_m)
}

fn rectangle(b: [f64; 4]) -> Result<Polygon> {
    Polygon::rectangle([b[0], b[1]], [b[2], b[3]], Material::Wall)
}

/// An octagon of circumradius `r` about `c`.
fn octagon(c: [f64; 2], r: f64) -> Result<Polygon> {
    let s = 0.5f64.sqrt() * r;
    let v = [
        [r, 0.0],
        [s, s],
        [0.0, r],
        [-s, s],
        [-r, 0.0],
        [-s, -s],
        [0.0, -r],
        [s, -s],
    ];
    Polygon::new(
        v.iter().map(|d| [c[0] + d[0], c[1] + d[1]]).collect(),
        Material::Wall,
    )
}

/// Furniture, pillars and slanted walls for `plan`, drawn from `rng`.
pub(super) fn furnish(
    rng: &mut SimRng,
    plan: &Plan,
    walls: &Walls,
    clutter: f64,
) -> Result<Vec<Item>> {
    let t = plan.wall_m;
    let zones: Vec<[f64; 4]> = plan
        .openings
        .iter()
        .map(|o| {
            let [a, b] = o.span_m;
            let (lo, hi) = (o.line.at_m - DOOR_REACH_M, o.line.at_m + DOOR_REACH_M);
            if o.line.horizontal {
                [a - DOOR_SIDE_M, lo, b + DOOR_SIDE_M, hi]
            } else {
                [lo, a - DOOR_SIDE_M, hi, b + DOOR_SIDE_M]
            }
        })
        .collect();
    let clear = |b: &[f64; 4]| !zones.iter().any(|z| overlap(z, b));
    let mut items = Vec::new();
    let mut boxes: Vec<Vec<[f64; 4]>> = vec![Vec::new(); plan.regions.len()];
    for (i, region) in plan.regions.iter().enumerate() {
        let f = floor(&region.rect, t);
        match region.kind {
            RoomKind::Corridor => continue,
            RoomKind::Room => {
                if !region.side_door && rng.random_bool(P_SLANT) {
                    let (polygon, b) = slanted_wall(rng, &f, region.door_side.opposite(), t)?;
                    boxes[i].push(b);
                    items.push(Item {
                        region: i,
                        kind: ItemKind::SlantedWall,
                        polygon,
                    });
                }
            }
            RoomKind::Hall => {
                let (sx, sy) = (uniform(rng, [2.8, 4.0]), uniform(rng, [2.8, 4.0]));
                let round = rng.random_bool(0.5);
                let half = uniform(rng, [0.15, 0.23]);
                let mut y = f[1] + 1.3;
                while y <= f[3] - 1.3 {
                    let mut x = f[0] + 1.3;
                    while x <= f[2] - 1.3 {
                        let b = [x - half, y - half, x + half, y + half];
                        if clear(&b) {
                            let polygon = if round {
                                octagon([x, y], half)?
                            } else {
                                rectangle(b)?
                            };
                            boxes[i].push(b);
                            items.push(Item {
                                region: i,
                                kind: ItemKind::Pillar,
                                polygon,
                            });
                        }
                        x += sx;
                    }
                    y += sy;
                }
            }
        }
        let area = (f[2] - f[0]) * (f[3] - f[1]);
        let count = (clutter * area / AREA_PER_ITEM_M2 * uniform(rng, [0.6, 1.4])).round() as usize;
        for _ in 0..count {
            let kind = rng.random_range(0..20u32);
            for _ in 0..TRIES {
                let placed = match kind {
                    0..=8 => against_wall(rng, &f, [1.2, 1.8], [0.6, 0.8]),
                    9..=13 => against_wall(rng, &f, [0.6, 1.2], [0.35, 0.6]),
                    14..=17 => table(rng, &f)?,
                    _ => round_thing(rng, &f)?,
                };
                let Some((polygon, b)) = placed else {
                    continue;
                };
                if clear(&b) && boxes[i].iter().all(|o| gap(o, &b) >= GAP_M) {
                    boxes[i].push(b);
                    items.push(Item {
                        region: i,
                        kind: ItemKind::Furniture,
                        polygon,
                    });
                    break;
                }
            }
        }
    }
    if rng.random_bool(P_CORRIDOR_PILLARS) {
        corridor_pillars(rng, plan, walls, &mut items)?;
    }
    Ok(items)
}

/// A slanted wall across the corner of floor `f` on its `back` side (one
/// of the two drawn), its legs 0.8 to 1.5 m (at most 35 % of the floor's
/// sides): the wall and the box around the corner it cuts.
fn slanted_wall(rng: &mut SimRng, f: &[f64; 4], back: Side, t: f64) -> Result<(Polygon, [f64; 4])> {
    let (w, h) = (f[2] - f[0], f[3] - f[1]);
    let first = rng.random_bool(0.5);
    // The corner, the direction along the back wall and along the side wall.
    let (corner, along_back, along_side) = match (back, first) {
        (Side::North, true) => ([f[0], f[3]], [1.0, 0.0], [0.0, -1.0]),
        (Side::North, false) => ([f[2], f[3]], [-1.0, 0.0], [0.0, -1.0]),
        (Side::South, true) => ([f[0], f[1]], [1.0, 0.0], [0.0, 1.0]),
        (Side::South, false) => ([f[2], f[1]], [-1.0, 0.0], [0.0, 1.0]),
        (Side::West, true) => ([f[0], f[1]], [0.0, 1.0], [1.0, 0.0]),
        (Side::West, false) => ([f[0], f[3]], [0.0, -1.0], [1.0, 0.0]),
        (Side::East, true) => ([f[2], f[1]], [0.0, 1.0], [-1.0, 0.0]),
        (Side::East, false) => ([f[2], f[3]], [0.0, -1.0], [-1.0, 0.0]),
    };
    let (back_len, side_len) = match back {
        Side::North | Side::South => (w, h),
        Side::West | Side::East => (h, w),
    };
    let a = uniform(rng, [0.8, 1.5]).min(0.35 * back_len);
    let b = uniform(rng, [0.8, 1.5]).min(0.35 * side_len);
    let p = [corner[0] + a * along_back[0], corner[1] + a * along_back[1]];
    let q = [corner[0] + b * along_side[0], corner[1] + b * along_side[1]];
    let (dx, dy) = (q[0] - p[0], q[1] - p[1]);
    let len = (dx * dx + dy * dy).sqrt();
    let h2 = 0.5 * t;
    let (ux, uy) = (dx / len * h2, dy / len * h2);
    let (nx, ny) = (-uy, ux);
    let (p0, q0) = ([p[0] - ux, p[1] - uy], [q[0] + ux, q[1] + uy]);
    let polygon = Polygon::new(
        vec![
            [p0[0] - nx, p0[1] - ny],
            [q0[0] - nx, q0[1] - ny],
            [q0[0] + nx, q0[1] + ny],
            [p0[0] + nx, p0[1] + ny],
        ],
        Material::Wall,
    )?;
    let xs = [corner[0], p[0], q[0]];
    let ys = [corner[1], p[1], q[1]];
    let b = [
        xs.iter().copied().fold(f64::INFINITY, f64::min) - t,
        ys.iter().copied().fold(f64::INFINITY, f64::min) - t,
        xs.iter().copied().fold(f64::NEG_INFINITY, f64::max) + t,
        ys.iter().copied().fold(f64::NEG_INFINITY, f64::max) + t,
    ];
    Ok((polygon, b))
}

/// A desk or cabinet `lengths` long and `depths` deep flush against a wall
/// of floor `f`, in the corner or [`GAP_M`] from it (None where it does
/// not fit).
fn against_wall(
    rng: &mut SimRng,
    f: &[f64; 4],
    lengths: [f64; 2],
    depths: [f64; 2],
) -> Option<(Polygon, [f64; 4])> {
    let side = Side::ALL[rng.random_range(0..4)];
    let (length, depth) = (uniform(rng, lengths), uniform(rng, depths));
    let (_, [a, b]) = side.edge(f);
    if b - a < length {
        return None;
    }
    let mut u = uniform(rng, [a, b - length]);
    if u - a < 0.5 * GAP_M {
        u = a;
    }
    if b - (u + length) < 0.5 * GAP_M {
        u = b - length;
    }
    let ends = [u - a, b - (u + length)];
    if ends.iter().any(|&e| e > 0.0 && e < GAP_M) {
        return None;
    }
    let v = u + length;
    let r = match side {
        Side::South => [u, f[1], v, f[1] + depth],
        Side::North => [u, f[3] - depth, v, f[3]],
        Side::West => [f[0], u, f[0] + depth, v],
        Side::East => [f[2] - depth, u, f[2], v],
    };
    rectangle(r).ok().map(|p| (p, r))
}

/// A free-standing item whose box has half-sides `half`: its centre, where
/// the box keeps [`GAP_M`] from the walls of floor `f` (None where it does
/// not fit).
fn free_centre(rng: &mut SimRng, f: &[f64; 4], half: [f64; 2]) -> Option<[f64; 2]> {
    let lo = [f[0] + half[0] + GAP_M, f[1] + half[1] + GAP_M];
    let hi = [f[2] - half[0] - GAP_M, f[3] - half[1] - GAP_M];
    (lo[0] <= hi[0] && lo[1] <= hi[1])
        .then(|| [uniform(rng, [lo[0], hi[0]]), uniform(rng, [lo[1], hi[1]])])
}

/// A table, 1 to 2 m by 0.6 to 1 m, rotated.
fn table(rng: &mut SimRng, f: &[f64; 4]) -> Result<Option<(Polygon, [f64; 4])>> {
    let (length, depth) = (uniform(rng, [1.0, 2.0]), uniform(rng, [0.6, 1.0]));
    let [c, s] = DIRECTIONS[rng.random_range(0..DIRECTIONS.len())];
    let s = if rng.random_bool(0.5) { s } else { -s };
    let half = [
        0.5 * (c.abs() * length + s.abs() * depth),
        0.5 * (s.abs() * length + c.abs() * depth),
    ];
    let Some(m) = free_centre(rng, f, half) else {
        return Ok(None);
    };
    let corners = [[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]];
    let polygon = Polygon::new(
        corners
            .iter()
            .map(|[u, v]| {
                let (x, y) = (u * length, v * depth);
                [m[0] + c * x - s * y, m[1] + s * x + c * y]
            })
            .collect(),
        Material::Wall,
    )?;
    let b = [
        m[0] - half[0],
        m[1] - half[1],
        m[0] + half[0],
        m[1] + half[1],
    ];
    Ok(Some((polygon, b)))
}

/// A round table, plant or column: an octagon of radius 0.2 to 0.45 m.
fn round_thing(rng: &mut SimRng, f: &[f64; 4]) -> Result<Option<(Polygon, [f64; 4])>> {
    let r = uniform(rng, [0.2, 0.45]);
    let Some(m) = free_centre(rng, f, [r, r]) else {
        return Ok(None);
    };
    Ok(Some((
        octagon(m, r)?,
        [m[0] - r, m[1] - r, m[0] + r, m[1] + r],
    )))
}

/// Pillars along the long walls of the corridors, against their faces,
/// 3.5 to 6 m apart, on solid wall only and at least 0.4 m from its ends
/// (doors, openings, glass), on one side where the corridor is too narrow
/// for both to leave [`CORRIDOR_CLEAR_M`].
fn corridor_pillars(
    rng: &mut SimRng,
    plan: &Plan,
    walls: &Walls,
    items: &mut Vec<Item>,
) -> Result<()> {
    let t = plan.wall_m;
    let spacing = uniform(rng, [3.5, 6.0]);
    let (width, depth) = (uniform(rng, [0.2, 0.35]), uniform(rng, [0.12, 0.22]));
    for (i, region) in plan.regions.iter().enumerate() {
        if region.kind != RoomKind::Corridor {
            continue;
        }
        let r = region.rect;
        let along_x = r[2] - r[0] >= r[3] - r[1];
        let clear_width = if along_x { r[3] - r[1] } else { r[2] - r[0] } - t;
        let sides: &[Side] = match (along_x, clear_width - 2.0 * depth >= CORRIDOR_CLEAR_M) {
            (true, true) => &[Side::South, Side::North],
            (true, false) => &[Side::South],
            (false, true) => &[Side::West, Side::East],
            (false, false) => &[Side::West],
        };
        if clear_width - depth < CORRIDOR_CLEAR_M {
            continue;
        }
        let f = floor(&r, t);
        for &side in sides {
            let (line, [a, b]) = side.edge(&r);
            let Some((_, solid)) = walls.solid.iter().find(|(l, _)| l.same(&line)) else {
                continue;
            };
            let mut u = a + 0.5 * spacing;
            while u + width <= b - 0.5 {
                let fits = solid
                    .iter()
                    .any(|s| s[0] + 0.4 <= u && u + width <= s[1] - 0.4);
                if fits {
                    let rect = pillar(&line, side, &f, [u, u + width], depth);
                    items.push(Item {
                        region: i,
                        kind: ItemKind::Pillar,
                        polygon: rectangle(rect)?,
                    });
                }
                u += spacing;
            }
        }
    }
    Ok(())
}

/// A pillar spanning `span` along `line`, `depth` deep from the face of
/// the wall on the corridor's `side` (its floor `f`).
fn pillar(line: &Line, side: Side, f: &[f64; 4], [u, v]: [f64; 2], depth: f64) -> [f64; 4] {
    debug_assert!(line.horizontal == matches!(side, Side::South | Side::North));
    match side {
        Side::South => [u, f[1], v, f[1] + depth],
        Side::North => [u, f[3] - depth, v, f[3]],
        Side::West => [f[0], u, f[0] + depth, v],
        Side::East => [f[2] - depth, u, f[2], v],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gaps_between_boxes() {
        let a = [0.0, 0.0, 1.0, 1.0];
        assert_eq!(gap(&a, &[2.0, 0.5, 3.0, 2.0]), 1.0);
        assert_eq!(gap(&a, &[4.0, 5.0, 5.0, 6.0]), 5.0);
        assert_eq!(gap(&a, &[0.5, 0.5, 2.0, 2.0]), 0.0);
        assert!(overlap(&a, &[0.5, 0.5, 2.0, 2.0]));
        assert!(!overlap(&a, &[1.0, 0.0, 2.0, 1.0]));
    }
}
