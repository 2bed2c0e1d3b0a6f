//! A plan's walls: a wall along every edge between two regions and along
//! the outside, except between two corridors (where corridors meet they
//! are open to each other); openings cut out; glass fronts.
//!
//! Walls are centred on the regions' edges, [`Plan::wall_m`] thick, and
//! run half their thickness beyond the ends of their edges, so that walls
//! meeting at a corner close it. Edges on one line are merged before the
//! openings are cut, so a door's clear width is exactly its span. A glass
//! front replaces the wall of a room's door side between posts
//! ([`GLASS_POST_M`] from the walls meeting it), a pane [`GLASS_M`] thick.

use std::f64::consts::FRAC_PI_2;

use super::building::{Door, RoomKind};
use super::layout::{Line, Plan, Side};
use crate::error::Result;
use crate::material::Material;
use crate::polygon::Polygon;

/// The thickness of a glass pane, metres.
pub(super) const GLASS_M: f64 = 0.04;
/// The solid wall either side of a glass front, beyond the walls meeting
/// it, metres.
pub(super) const GLASS_POST_M: f64 = 0.1;

/// The walls of a plan.
pub(super) struct Walls {
    /// Walls and glass panes.
    pub(super) polygons: Vec<Polygon>,
    /// One door an opening of the plan, in the plan's order.
    pub(super) doors: Vec<Door>,
    /// Every line that holds wall, and its solid (not glass, not open)
    /// spans, merged and sorted.
    pub(super) solid: Vec<(Line, Vec<[f64; 2]>)>,
}

/// The spans of `spans` merged where they overlap or touch, sorted.
fn merge(mut spans: Vec<[f64; 2]>) -> Vec<[f64; 2]> {
    spans.sort_by(|a, b| a[0].total_cmp(&b[0]));
    let mut merged: Vec<[f64; 2]> = Vec::with_capacity(spans.len());
    for s in spans {
        match merged.last_mut() {
            Some(last) if s[0] <= last[1] => last[1] = last[1].max(s[1]),
            _ => merged.push(s),
        }
    }
    merged
}

/// `spans` without `[a, b]`.
fn cut(spans: &[[f64; 2]], [a, b]: [f64; 2]) -> Vec<[f64; 2]> {
    let mut out = Vec::with_capacity(spans.len() + 1);
    for &[s, e] in spans {
        if e <= a || s >= b {
            out.push([s, e]);
            continue;
        }
        if s < a {
            out.push([s, a]);
        }
        if e > b {
            out.push([b, e]);
        }
    }
    out
}

/// The line's entry in `lines`, added if new.
fn line_entry(lines: &mut Vec<(Line, Vec<[f64; 2]>)>, line: Line) -> &mut Vec<[f64; 2]> {
    let at = match lines.iter().position(|(l, _)| l.same(&line)) {
        Some(at) => at,
        None => {
            lines.push((line, Vec::new()));
            lines.len() - 1
        }
    };
    &mut lines[at].1
}

/// A band of `thickness_m` centred on `line` from `a` to `b`.
fn band(line: &Line, [a, b]: [f64; 2], thickness_m: f64, material: Material) -> Result<Polygon> {
    let h = 0.5 * thickness_m;
    let (lo, hi) = (line.at_m - h, line.at_m + h);
    if line.horizontal {
        Polygon::rectangle([a, lo], [b, hi], material)
    } else {
        Polygon::rectangle([lo, a], [hi, b], material)
    }
}

/// The walls of `plan`.
pub(super) fn walls(plan: &Plan) -> Result<Walls> {
    let half = 0.5 * plan.wall_m;
    let regions = &plan.regions;
    let mut lines: Vec<(Line, Vec<[f64; 2]>)> = Vec::new();
    for (i, region) in regions.iter().enumerate() {
        for side in Side::ALL {
            let (line, span) = side.edge(&region.rect);
            let mut walled = vec![span];
            if region.kind == RoomKind::Corridor {
                for (j, other) in regions.iter().enumerate() {
                    if i == j || other.kind != RoomKind::Corridor {
                        continue;
                    }
                    let (their, [c, d]) = side.opposite().edge(&other.rect);
                    if their.same(&line) && c < span[1] && d > span[0] {
                        walled = cut(&walled, [c.max(span[0]), d.min(span[1])]);
                    }
                }
            }
            // Half a thickness beyond each end, to close the corners.
            line_entry(&mut lines, line).extend(walled.iter().map(|&[a, b]| [a - half, b + half]));
        }
    }
    for (_, spans) in &mut lines {
        *spans = merge(std::mem::take(spans));
    }
    let mut doors = Vec::with_capacity(plan.openings.len());
    for opening in &plan.openings {
        let spans = line_entry(&mut lines, opening.line);
        *spans = cut(spans, opening.span_m);
        let [a, b] = opening.span_m;
        doors.push(Door {
            center_m: opening.line.point(0.5 * (a + b)),
            width_m: b - a,
            wall_angle_rad: if opening.line.horizontal {
                0.0
            } else {
                FRAC_PI_2
            },
            rooms: opening.regions,
        });
    }
    let mut polygons = Vec::new();
    for region in regions.iter().filter(|r| r.glass) {
        let (line, [a, b]) = region.door_side.edge(&region.rect);
        let mut panes = vec![[a + half + GLASS_POST_M, b - half - GLASS_POST_M]];
        for opening in plan.openings.iter().filter(|o| o.line.same(&line)) {
            panes = cut(&panes, opening.span_m);
        }
        let spans = line_entry(&mut lines, line);
        for pane in panes {
            *spans = cut(spans, pane);
            polygons.push(band(&line, pane, GLASS_M, Material::Glass)?);
        }
    }
    for (line, spans) in &lines {
        for &span in spans {
            // Nothing shorter than a millimetre: no sliver of a wall.
            if span[1] - span[0] > 1e-3 {
                polygons.push(band(line, span, plan.wall_m, Material::Wall)?);
            }
        }
    }
    Ok(Walls {
        polygons,
        doors,
        solid: lines,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spans_merge_and_cut() {
        assert_eq!(
            merge(vec![[3.0, 4.0], [0.0, 1.0], [0.5, 2.0], [2.0, 2.5]]),
            [[0.0, 2.5], [3.0, 4.0]]
        );
        assert_eq!(
            cut(&[[0.0, 2.0], [3.0, 4.0]], [1.0, 3.5]),
            [[0.0, 1.0], [3.5, 4.0]]
        );
        assert_eq!(cut(&[[0.0, 2.0]], [-1.0, 3.0]), Vec::<[f64; 2]>::new());
    }
}
