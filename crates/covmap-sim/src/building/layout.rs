//! The floor plan of a generated building: corridors, the blocks of rooms
//! along them, rooms, halls and the openings between them, as axis-aligned
//! rectangles between the walls' centre lines (the walls come after, in
//! [`super::walls`]).
//!
//! # Shapes
//! A building is one wing (a straight corridor with rooms on one or both
//! sides) or two: an L (a second wing at one end of the first, its
//! corridor meeting the first's) or a T (a second wing from the middle of
//! the first). Every corridor runs to the outer walls; the blocks beside it
//! are cut into rooms of widths drawn from the room range. A block deeper
//! than the largest room holds rooms behind rooms, reached through the
//! room in front. One block may hold an open hall (6 to 12 m wide, at least
//! 4.5 m deep), open to its corridor through a wide opening. Every room
//! has a door to its corridor (or to the room in front), at least
//! [`JAMB_M`] from the walls that meet its wall; some neighbours share a
//! second door.

use rand::RngExt;

use super::building::RoomKind;
use super::options::{BuildingOptions, JAMB_M};
use crate::rng::SimRng;

/// The chance that a wing's block is deep enough for rooms behind rooms.
const P_DEEP: f64 = 0.25;
/// The chance that a building of at least [`HALL_MIN_AREA_M2`] has a hall.
const P_HALL: f64 = 0.4;
/// The least floor area of a building with a hall, square metres.
const HALL_MIN_AREA_M2: f64 = 120.0;
/// The least depth of a hall, metres.
const HALL_MIN_DEPTH_M: f64 = 4.5;
/// The least and the most width of a hall, metres.
const HALL_WIDTH_M: [f64; 2] = [6.0, 12.0];
/// The least and the most width of a hall's opening, metres.
const HALL_OPENING_M: [f64; 2] = [2.0, 3.5];
/// The chance that two neighbouring rooms share a second door.
const P_CONNECT: f64 = 0.15;

/// A side of a rectangle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Side {
    South,
    North,
    West,
    East,
}

impl Side {
    /// The four sides.
    pub(super) const ALL: [Side; 4] = [Side::South, Side::North, Side::West, Side::East];

    pub(super) fn opposite(self) -> Side {
        match self {
            Side::South => Side::North,
            Side::North => Side::South,
            Side::West => Side::East,
            Side::East => Side::West,
        }
    }

    /// The edge of `rect` on this side: its line and its span along it.
    pub(super) fn edge(self, rect: &[f64; 4]) -> (Line, [f64; 2]) {
        let [x0, y0, x1, y1] = *rect;
        match self {
            Side::South => (Line::horizontal(y0), [x0, x1]),
            Side::North => (Line::horizontal(y1), [x0, x1]),
            Side::West => (Line::vertical(x0), [y0, y1]),
            Side::East => (Line::vertical(x1), [y0, y1]),
        }
    }
}

/// A horizontal (`y = at_m`) or vertical (`x = at_m`) line.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Line {
    pub(super) horizontal: bool,
    pub(super) at_m: f64,
}

impl Line {
    pub(super) fn horizontal(y_m: f64) -> Self {
        Self {
            horizontal: true,
            at_m: y_m,
        }
    }
    pub(super) fn vertical(x_m: f64) -> Self {
        Self {
            horizontal: false,
            at_m: x_m,
        }
    }
    /// The point at `s` along the line (x on a horizontal line, y on a
    /// vertical one).
    pub(super) fn point(&self, s_m: f64) -> [f64; 2] {
        if self.horizontal {
            [s_m, self.at_m]
        } else {
            [self.at_m, s_m]
        }
    }
    /// Whether two lines are the same (to a nanometre).
    pub(super) fn same(&self, other: &Line) -> bool {
        self.horizontal == other.horizontal && (self.at_m - other.at_m).abs() < 1e-9
    }
}

/// A room, corridor or hall of the plan: its rectangle between the walls'
/// centre lines.
#[derive(Clone, Debug)]
pub(super) struct Region {
    pub(super) rect: [f64; 4],
    pub(super) kind: RoomKind,
    /// The side its door (or opening) is on: the side facing its corridor,
    /// or the room in front. Corridors: unused.
    pub(super) door_side: Side,
    /// Whether its wall on `door_side` is glass.
    pub(super) glass: bool,
    /// Whether it has a door on a side other than `door_side` (a second
    /// door to a neighbour, or the door to the room behind it).
    pub(super) side_door: bool,
}

/// An opening in the wall on `line` from `span_m[0]` to `span_m[1]`: a door
/// or a hall's opening, between two regions.
#[derive(Clone, Debug)]
pub(super) struct Opening {
    pub(super) line: Line,
    pub(super) span_m: [f64; 2],
    pub(super) regions: [usize; 2],
}

/// A building's plan.
#[derive(Clone, Debug)]
pub(super) struct Plan {
    /// The corridors first, then the rooms and halls.
    pub(super) regions: Vec<Region>,
    pub(super) openings: Vec<Opening>,
    /// The wall thickness, metres.
    pub(super) wall_m: f64,
}

/// A block of rooms: its rectangle and the side facing its corridor.
struct Block {
    rect: [f64; 4],
    side: Side,
    /// The corridor it faces.
    corridor: usize,
}

impl Block {
    /// Along its corridor side: `[start, end]`.
    fn span(&self) -> [f64; 2] {
        self.side.edge(&self.rect).1
    }
    /// Away from its corridor side.
    fn depth_m(&self) -> f64 {
        let [x0, y0, x1, y1] = self.rect;
        match self.side {
            Side::South | Side::North => y1 - y0,
            Side::West | Side::East => x1 - x0,
        }
    }
    /// The part from `u` to `v` along the corridor side, from depth `a` to
    /// `b` away from it.
    fn slab(&self, [u, v]: [f64; 2], [a, b]: [f64; 2]) -> [f64; 4] {
        let [x0, y0, x1, y1] = self.rect;
        match self.side {
            Side::South => [u, y0 + a, v, y0 + b],
            Side::North => [u, y1 - b, v, y1 - a],
            Side::West => [x0 + a, u, x0 + b, v],
            Side::East => [x1 - b, u, x1 - a, v],
        }
    }
    /// The line at depth `d` from the corridor side (parallel to it).
    fn line_at_depth(&self, d: f64) -> Line {
        let [x0, y0, x1, y1] = self.rect;
        match self.side {
            Side::South => Line::horizontal(y0 + d),
            Side::North => Line::horizontal(y1 - d),
            Side::West => Line::vertical(x0 + d),
            Side::East => Line::vertical(x1 - d),
        }
    }
    /// The line across the block at `u` along the corridor side, and the
    /// span on it of depths `a` to `b`.
    fn line_across(&self, u: f64, [a, b]: [f64; 2]) -> (Line, [f64; 2]) {
        let [x0, y0, x1, y1] = self.rect;
        match self.side {
            Side::South => (Line::vertical(u), [y0 + a, y0 + b]),
            Side::North => (Line::vertical(u), [y1 - b, y1 - a]),
            Side::West => (Line::horizontal(u), [x0 + a, x0 + b]),
            Side::East => (Line::horizontal(u), [x1 - b, x1 - a]),
        }
    }
}

/// A draw from `[lo, hi]` (`lo` when the range is empty).
pub(super) fn uniform(rng: &mut SimRng, [lo, hi]: [f64; 2]) -> f64 {
    if hi > lo {
        rng.random_range(lo..hi)
    } else {
        lo
    }
}

/// The plan of a building drawn from `rng` (`options` checked).
pub(super) fn plan(rng: &mut SimRng, options: &BuildingOptions) -> Plan {
    let wall_m = uniform(rng, options.wall_thickness_m);
    let [lo, hi] = options.room_size_m;
    let area = options.area_m2;
    let depth = |rng: &mut SimRng| {
        if rng.random_bool(P_DEEP) && 2.0 * lo <= lo + hi {
            uniform(rng, [2.0 * lo, lo + hi])
        } else {
            uniform(rng, [lo, hi])
        }
    };
    let corridor_m = uniform(rng, options.corridor_width_m);
    let (ds, dn, dl, dr) = (depth(rng), depth(rng), depth(rng), depth(rng));
    let shape = rng.random_range(0..10u32);
    let mut corridors = Vec::new();
    let mut blocks = Vec::new();
    let two_wings = match shape {
        0..=3 if area >= 150.0 => wings(
            rng,
            area,
            corridor_m,
            [ds, dn, dl, dr],
            lo,
            false,
            &mut corridors,
            &mut blocks,
        ),
        4..=7 if area >= 150.0 => wings(
            rng,
            area,
            corridor_m,
            [ds, dn, dl, dr],
            lo,
            true,
            &mut corridors,
            &mut blocks,
        ),
        _ => false,
    };
    if !two_wings {
        straight(
            area,
            [corridor_m, options.corridor_width_m[0]],
            [ds, dn],
            lo,
            &mut corridors,
            &mut blocks,
        );
    }
    let mut regions: Vec<Region> = corridors
        .iter()
        .map(|&rect| Region {
            rect,
            kind: RoomKind::Corridor,
            door_side: Side::South,
            glass: false,
            side_door: false,
        })
        .collect();
    let mut openings = Vec::new();
    let hall_block = choose_hall(rng, area, &blocks);
    let half = 0.5 * wall_m;
    for (b, block) in blocks.iter().enumerate() {
        let [u0, u1] = block.span();
        let depth_m = block.depth_m();
        let mut segments = vec![[u0, u1]];
        if hall_block == Some(b) {
            let width = uniform(rng, [HALL_WIDTH_M[0], HALL_WIDTH_M[1].min(u1 - u0)]);
            let mut start = uniform(rng, [u0, u1 - width]);
            let mut end = start + width;
            if start - u0 < lo {
                start = u0;
            }
            if u1 - end < lo {
                end = u1;
            }
            segments = [[u0, start], [end, u1]]
                .into_iter()
                .filter(|s| s[1] > s[0])
                .collect();
            let hall = regions.len();
            regions.push(Region {
                rect: block.slab([start, end], [0.0, depth_m]),
                kind: RoomKind::Hall,
                door_side: block.side,
                glass: false,
                side_door: false,
            });
            let room_for = end - start - 2.0 * (half + JAMB_M);
            let opening = uniform(rng, [HALL_OPENING_M[0], HALL_OPENING_M[1].min(room_for)]);
            let from = uniform(rng, [start + half + JAMB_M, end - half - JAMB_M - opening]);
            openings.push(Opening {
                line: block.side.edge(&block.rect).0,
                span_m: [from, from + opening],
                regions: [block.corridor, hall],
            });
        }
        for segment in segments {
            let bounds = split_length(rng, segment, lo, hi);
            let mut fronts: Vec<(usize, f64)> = Vec::new();
            for column in bounds.windows(2) {
                let column = [column[0], column[1]];
                let split =
                    (depth_m > hi && depth_m >= 2.0 * lo).then(|| uniform(rng, [lo, depth_m - lo]));
                let front_depth = split.unwrap_or(depth_m);
                let front = regions.len();
                regions.push(room(block.slab(column, [0.0, front_depth]), block.side));
                regions[front].glass = rng.random_bool(options.glass);
                let door = door_span(rng, column, half, options.door_width_m);
                openings.push(Opening {
                    line: block.side.edge(&block.rect).0,
                    span_m: door,
                    regions: [block.corridor, front],
                });
                if let Some(split) = split {
                    // The room in front has a second door, on its back side.
                    regions[front].side_door = true;
                    let back = regions.len();
                    regions.push(room(block.slab(column, [split, depth_m]), block.side));
                    let door = door_span(rng, column, half, options.door_width_m);
                    openings.push(Opening {
                        line: block.line_at_depth(split),
                        span_m: door,
                        regions: [front, back],
                    });
                }
                fronts.push((front, front_depth));
            }
            // A second door between some neighbouring front rooms, on the
            // wall between them.
            for pair in bounds[1..bounds.len() - 1].iter().zip(fronts.windows(2)) {
                let (&u, [(a, da), (b, db)]) = pair else {
                    continue;
                };
                if !rng.random_bool(P_CONNECT) {
                    continue;
                }
                let dmin = da.min(*db);
                let (line, span) =
                    block.line_across(u, door_span(rng, [0.0, dmin], half, options.door_width_m));
                openings.push(Opening {
                    line,
                    span_m: span,
                    regions: [*a, *b],
                });
                regions[*a].side_door = true;
                regions[*b].side_door = true;
            }
        }
    }
    Plan {
        regions,
        openings,
        wall_m,
    }
}

fn room(rect: [f64; 4], door_side: Side) -> Region {
    Region {
        rect,
        kind: RoomKind::Room,
        door_side,
        glass: false,
        side_door: false,
    }
}

/// A door's span in a wall from `span[0]` to `span[1]` (between the centre
/// lines of the walls meeting it), its width drawn from `widths`, at least
/// [`JAMB_M`] from the faces of those walls.
fn door_span(rng: &mut SimRng, [a, b]: [f64; 2], half_wall_m: f64, widths: [f64; 2]) -> [f64; 2] {
    let width = uniform(rng, widths);
    let from = uniform(
        rng,
        [a + half_wall_m + JAMB_M, b - half_wall_m - JAMB_M - width],
    );
    [from, from + width]
}

/// Cut `[u0, u1]` into pieces from `lo` to `hi` long (a remainder shorter
/// than `lo` joins the last piece): the cut points, both ends included.
fn split_length(rng: &mut SimRng, [u0, u1]: [f64; 2], lo: f64, hi: f64) -> Vec<f64> {
    let mut bounds = vec![u0];
    let mut at = u0;
    while u1 - at > hi && u1 - at >= 2.0 * lo {
        let w = uniform(rng, [lo, hi.min(u1 - at - lo)]);
        at += w;
        bounds.push(at);
    }
    match bounds.len() {
        1 => bounds.push(u1),
        _ if u1 - at >= lo => bounds.push(u1),
        n => bounds[n - 1] = u1,
    }
    bounds
}

/// The block to hold a hall, if the building has one.
fn choose_hall(rng: &mut SimRng, area_m2: f64, blocks: &[Block]) -> Option<usize> {
    let eligible: Vec<usize> = (0..blocks.len())
        .filter(|&b| {
            let [u0, u1] = blocks[b].span();
            blocks[b].depth_m() >= HALL_MIN_DEPTH_M && u1 - u0 >= HALL_WIDTH_M[0]
        })
        .collect();
    if area_m2 < HALL_MIN_AREA_M2 || eligible.is_empty() || !rng.random_bool(P_HALL) {
        return None;
    }
    Some(eligible[rng.random_range(0..eligible.len())])
}

/// One wing along x: a corridor of `corridor_m[0]` (or, if the area is
/// too small for it, the least width `corridor_m[1]`) with blocks of depth
/// `ds` (south) and `dn` (north), or the north block alone, `area_m2`
/// square metres in all, at least two rooms long.
fn straight(
    area_m2: f64,
    [mut cw, least_cw]: [f64; 2],
    [ds, mut dn]: [f64; 2],
    lo: f64,
    corridors: &mut Vec<[f64; 4]>,
    blocks: &mut Vec<Block>,
) {
    let length = area_m2 / (ds + cw + dn);
    if length >= 2.0 * lo {
        let (y0, y1) = (ds, ds + cw);
        let top = y1 + dn;
        corridors.push([0.0, y0, length, y1]);
        blocks.push(Block {
            rect: [0.0, 0.0, length, y0],
            side: Side::North,
            corridor: 0,
        });
        blocks.push(Block {
            rect: [0.0, y1, length, top],
            side: Side::South,
            corridor: 0,
        });
        return;
    }
    // One side only, made shallower and the corridor narrower until two
    // rooms fit (the options' least area guarantees they do).
    if area_m2 / (cw + dn) < 2.0 * lo {
        dn = (area_m2 / (2.0 * lo) - cw).max(lo);
    }
    if area_m2 / (cw + dn) < 2.0 * lo {
        cw = least_cw;
    }
    let length = area_m2 / (cw + dn);
    corridors.push([0.0, 0.0, length, cw]);
    blocks.push(Block {
        rect: [0.0, cw, length, cw + dn],
        side: Side::South,
        corridor: 0,
    });
}

/// Two wings (see the module documentation): wing A along x with blocks
/// `ds` (south) and `dn` (north) deep, wing B along y from wing A's north
/// side with blocks `dl` (west) and `dr` (east) deep, its corridor running
/// down to wing A's; flush with wing A's east end (`tee` false: an L) or
/// from its middle (a T). False, and nothing added, where the area does not
/// fit two rooms along each block.
#[allow(clippy::too_many_arguments, reason = "the wings' dimensions")]
fn wings(
    rng: &mut SimRng,
    area_m2: f64,
    cw: f64,
    [ds, dn, dl, dr]: [f64; 4],
    lo: f64,
    tee: bool,
    corridors: &mut Vec<[f64; 4]>,
    blocks: &mut Vec<Block>,
) -> bool {
    let share = uniform(rng, [0.5, 0.7]);
    let la = share * area_m2 / (ds + cw + dn);
    let lb = (1.0 - share) * area_m2 / (dl + cw + dr);
    let west = dl.max(lo);
    let east = la - cw - dr.max(lo);
    if lb < 2.0 * lo || east < west {
        return false;
    }
    let xb = if tee {
        uniform(rng, [west, east])
    } else {
        la - cw - dr
    };
    if xb < west {
        return false;
    }
    let xr = xb + cw;
    let (y0, y1) = (ds, ds + cw);
    let top_a = y1 + dn;
    let top = top_a + lb;
    let right_end = if tee { xr + dr } else { la };
    corridors.push([0.0, y0, la, y1]);
    corridors.push([xb, y1, xr, top]);
    let mut add = |rect: [f64; 4], side, corridor| {
        blocks.push(Block {
            rect,
            side,
            corridor,
        })
    };
    add([0.0, 0.0, la, y0], Side::North, 0);
    add([0.0, y1, xb, top_a], Side::South, 0);
    add([xr, y1, la, top_a], Side::South, 0);
    add([xb - dl, top_a, xb, top], Side::East, 1);
    add([xr, top_a, right_end, top], Side::West, 1);
    true
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::sim_rng;

    #[test]
    fn lengths_split_into_room_widths() {
        let mut rng = sim_rng(3);
        for len in [5.0, 6.0, 7.3, 12.0, 31.7, 100.0] {
            let b = split_length(&mut rng, [1.0, 1.0 + len], 2.5, 6.0);
            assert_eq!(b[0], 1.0);
            assert_eq!(*b.last().unwrap(), 1.0 + len);
            for w in b.windows(2) {
                let width = w[1] - w[0];
                assert!((2.5 - 1e-9..=8.5 + 1e-9).contains(&width), "{len}: {b:?}");
            }
        }
    }

    /// Every room has a door, every opening lies on the edges of both its
    /// regions and within both, the regions tile the footprint without
    /// overlapping.
    #[test]
    fn plans_are_consistent() {
        for seed in 0..200 {
            let mut rng = sim_rng(seed);
            let area = [60.0, 200.0, 550.0][seed as usize % 3];
            let options = BuildingOptions {
                area_m2: area,
                ..BuildingOptions::default()
            };
            let plan = plan(&mut rng, &options);
            let total: f64 = plan
                .regions
                .iter()
                .map(|r| (r.rect[2] - r.rect[0]) * (r.rect[3] - r.rect[1]))
                .sum();
            assert!((total - area).abs() < 1e-6 * area, "{seed}: {total}");
            for (i, a) in plan.regions.iter().enumerate() {
                for b in &plan.regions[i + 1..] {
                    let w = a.rect[2].min(b.rect[2]) - a.rect[0].max(b.rect[0]);
                    let h = a.rect[3].min(b.rect[3]) - a.rect[1].max(b.rect[1]);
                    assert!(w <= 1e-9 || h <= 1e-9, "{seed}: {a:?} {b:?}");
                }
            }
            for (i, r) in plan.regions.iter().enumerate() {
                if r.kind != RoomKind::Corridor {
                    assert!(
                        plan.openings.iter().any(|o| o.regions.contains(&i)),
                        "{seed}: room {i} has no door"
                    );
                }
            }
            for o in &plan.openings {
                for &r in &o.regions {
                    let on_edge = Side::ALL.iter().any(|s| {
                        let (line, [a, b]) = s.edge(&plan.regions[r].rect);
                        line.same(&o.line) && a <= o.span_m[0] && o.span_m[1] <= b
                    });
                    assert!(on_edge, "{seed}: {o:?} not on region {r}");
                }
            }
        }
    }
}
