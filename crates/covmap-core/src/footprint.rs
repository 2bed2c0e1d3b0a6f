//! Which cells one reading covers: cone and ray traversal.
//!
//! Both walk only the cells they report (no per-cell membership test over a
//! bounding box): a cone is cut row by row into column intervals, a ray is
//! followed cell by cell (Amanatides and Woo).

use crate::grid::Grid;
use crate::sensor::Footprint;

/// What to do with each cell of a footprint.
///
/// A trait rather than a closure so that a hot visitor can be marked
/// `#[inline(always)]` (closures cannot be on stable Rust); any
/// `FnMut(usize, f64)` is a visitor too.
pub(crate) trait CellVisitor {
    /// Visit the cell at row-major `index`, `d_l` metres from the sensor. The
    /// footprint reaches the cell at `enter_m`: the cell belongs to the
    /// footprint of every reach `>= enter_m` (the centre distance for a cone,
    /// where the ray enters the cell for a ray).
    fn cell(&mut self, index: usize, d_l: f64, enter_m: f64);

    /// Visit the cells `first .. first + n` of one row of a cone, at
    /// distances `d[..n]` (which are also where the cone reaches them), those
    /// within `reach_m` only (`d[n..]` lie past the row's end: finite, but no
    /// cells'). `near` and `far` are the least and the greatest of `d[..n]`.
    /// A visitor may take the block at once.
    #[inline(always)]
    fn row_block(
        &mut self,
        first: usize,
        d: &[f64; ROW_BLOCK],
        n: usize,
        _bounds: [f64; 2],
        reach_m: f64,
    ) {
        cells_of_block(self, first, d, n, reach_m);
    }

    /// Whether the visitor wants no more cells: a ray's walk stops after the
    /// cell that made it so (a cone's walk does not ask). A visitor that
    /// stops must do nothing with any later cell, so that stopping changes
    /// nothing but the time taken.
    #[inline(always)]
    fn done(&self) -> bool {
        false
    }
}

/// Visit the cells of a row block ([`CellVisitor::row_block`]) one by one,
/// those within `reach_m`: what a visitor does that does not take the block
/// at once.
#[inline(always)]
pub(crate) fn cells_of_block<V: CellVisitor + ?Sized>(
    visitor: &mut V,
    first: usize,
    d: &[f64; ROW_BLOCK],
    n: usize,
    reach_m: f64,
) {
    for (k, &d) in d[..n].iter().enumerate() {
        if d <= reach_m {
            visitor.cell(first + k, d, d);
        }
    }
}

impl<F: FnMut(usize, f64)> CellVisitor for F {
    #[inline(always)]
    fn cell(&mut self, index: usize, d_l: f64, _enter_m: f64) {
        self(index, d_l)
    }
}

/// Call `f.cell(index, d_l, enter_m)` for every cell of `grid` in the footprint
/// of a beam from `origin` (inside the grid) along `angle_rad`, out to
/// `reach_m`. `d_l` is the cell's distance from the origin as the footprint
/// defines it. A cell is visited exactly when `enter_m <= reach_m`, so the
/// footprints of one beam for growing reaches are nested, and a caller can tell
/// which of them a cell belongs to from `enter_m` alone.
#[inline(always)]
pub(crate) fn visit(
    grid: &Grid,
    origin: [f64; 2],
    angle_rad: f64,
    reach_m: f64,
    footprint: Footprint,
    f: &mut impl CellVisitor,
) {
    match footprint {
        Footprint::Cone { half_angle_rad } => {
            visit_cone(grid, origin, angle_rad, half_angle_rad, reach_m, f)
        }
        Footprint::Ray => visit_ray(grid, origin, angle_rad, reach_m, f),
    }
}

/// Whether `angle` lies within `half` of `axis` (all radians).
fn within(angle: f64, axis: f64, half: f64) -> bool {
    let d = (angle - axis).rem_euclid(std::f64::consts::TAU);
    d <= half || d >= std::f64::consts::TAU - half
}

/// Index range `[lo, hi]` of cells whose centres `(i + 0.5) r` lie in
/// `[a, b]` (in grid-relative metres), clamped to `0..n`.
#[inline(always)]
fn centre_range(a: f64, b: f64, r: f64, n: usize) -> Option<(usize, usize)> {
    let lo = (a / r - 0.5).ceil().max(0.0);
    let hi = (b / r - 0.5).floor().min(n as f64 - 1.0);
    (lo <= hi).then_some((lo as usize, hi as usize))
}

/// Beyond this magnitude (radians) a cone's axis is reduced to (-pi, pi]
/// before its cells are found; below it, differences of angles keep 13 or
/// more significant digits.
const LARGE_ANGLE: f64 = 1e3;

/// Cells of a cone's row whose distances are computed together.
pub(crate) const ROW_BLOCK: usize = 8;

/// Cells whose centres lie in the sector of radius `reach` and half-angle
/// `half` (< pi/2) around `axis`: the disk cut by the two boundary half-planes.
#[inline(always)]
fn visit_cone(
    grid: &Grid,
    [sx, sy]: [f64; 2],
    axis: f64,
    half: f64,
    reach: f64,
    f: &mut impl CellVisitor,
) {
    // `within` compares angles by their difference, which a large axis
    // would swamp: such an axis is brought to (-pi, pi] first, through the
    // direction its sine and cosine give (exactly reduced, as every other
    // use of the angle is).
    let axis = if axis.abs() <= LARGE_ANGLE {
        axis
    } else {
        let (s, c) = axis.sin_cos();
        s.atan2(c)
    };
    let r = grid.resolution_m();
    let [ox, oy] = grid.origin_m();
    let cols = grid.cols();
    let (right_sin, right_cos) = (axis - half).sin_cos();
    let (left_sin, left_cos) = (axis + half).sin_cos();

    // Interval ends are widened by `slack` and every cell checked against
    // `d_l <= reach` itself: membership of the disk is decided by that one
    // comparison, never by the rounding of the interval arithmetic.
    let slack = 1e-9 * r;
    // The sector's vertical extent: the apex, the two boundary ends, and the
    // top and bottom of the circle where they lie inside the cone.
    let mut y_lo = 0.0f64.min(reach * right_sin).min(reach * left_sin);
    let mut y_hi = 0.0f64.max(reach * right_sin).max(reach * left_sin);
    if within(std::f64::consts::FRAC_PI_2, axis, half) {
        y_hi = reach;
    }
    if within(-std::f64::consts::FRAC_PI_2, axis, half) {
        y_lo = -reach;
    }
    let Some((row_lo, row_hi)) = centre_range(
        sy + y_lo - slack - oy,
        sy + y_hi + slack - oy,
        r,
        grid.rows(),
    ) else {
        return;
    };
    let reach2 = reach * reach;
    for row in row_lo..=row_hi {
        let py = oy + (row as f64 + 0.5) * r - sy;
        let w2 = reach2 - py * py;
        if w2 < -slack {
            continue;
        }
        let w = w2.max(0.0).sqrt() + slack;
        let (mut lo, mut hi) = (-w, w);
        // Left of the right boundary: cross(b, p) >= 0, i.e. b_y px <= b_x py.
        if right_sin > 0.0 {
            hi = hi.min(right_cos * py / right_sin);
        } else if right_sin < 0.0 {
            lo = lo.max(right_cos * py / right_sin);
        } else if right_cos * py < 0.0 {
            continue;
        }
        // Right of the left boundary: cross(a, p) <= 0, i.e. a_y px >= a_x py.
        if left_sin > 0.0 {
            lo = lo.max(left_cos * py / left_sin);
        } else if left_sin < 0.0 {
            hi = hi.min(left_cos * py / left_sin);
        } else if left_cos * py > 0.0 {
            continue;
        }
        if lo > hi {
            continue;
        }
        let Some((col_lo, col_hi)) = centre_range(sx + lo - ox, sx + hi - ox, r, cols) else {
            continue;
        };
        let base = row * cols;
        let py2 = py * py;
        // The distances of a block of cells first (vector square roots), then
        // the visits.
        let mut col = col_lo;
        let mut next = ox + (col_lo as f64 + 0.5) * r - sx;
        while col <= col_hi {
            let n = (col_hi + 1 - col).min(ROW_BLOCK);
            let mut px = [0.0f64; ROW_BLOCK];
            for x in px.iter_mut() {
                *x = next;
                next += r;
            }
            let mut d = [0.0f64; ROW_BLOCK];
            for (d, &x) in d.iter_mut().zip(&px) {
                *d = (x * x + py2).sqrt();
            }
            // The distance falls towards the sensor's column and grows away
            // from it (every step rounds monotonically), so the extremes lie
            // at the block's ends unless the block spans that column.
            let (first, last) = (px[0], px[n - 1]);
            let far = d[0].max(d[n - 1]);
            let near = if first >= 0.0 {
                d[0]
            } else if last <= 0.0 {
                d[n - 1]
            } else {
                d[..n]
                    .iter()
                    .fold(f64::INFINITY, |lo, &x| if x < lo { x } else { lo })
            };
            f.row_block(base + col, &d, n, [near, far], reach);
            // Only the row's last block is short, so `next` runs past the
            // row's end only when the row is done; past it, `px` and `d` are
            // finite but name no cells.
            col += n;
        }
    }
}

/// Cells the ray from `origin` crosses within `reach`, each once, in order.
#[inline(always)]
fn visit_ray(grid: &Grid, [sx, sy]: [f64; 2], angle: f64, reach: f64, f: &mut impl CellVisitor) {
    let r = grid.resolution_m();
    let [ox, oy] = grid.origin_m();
    let (dy, dx) = angle.sin_cos();
    let [gx, gy] = grid.world_to_grid(sx, sy);
    let (mut col, mut row) = (gx.floor() as i64, gy.floor() as i64);
    let (cols, rows) = (grid.cols() as i64, grid.rows() as i64);
    // Distance along the ray to the next vertical / horizontal grid line, and
    // between successive ones.
    let axis = |g: f64, cell: i64, d: f64| -> (i64, f64, f64) {
        if d > 0.0 {
            (1, ((cell + 1) as f64 - g) * r / d, r / d)
        } else if d < 0.0 {
            (-1, (g - cell as f64) * r / -d, r / -d)
        } else {
            (0, f64::INFINITY, f64::INFINITY)
        }
    };
    let (step_c, mut t_c, dt_c) = axis(gx, col, dx);
    let (step_r, mut t_r, dt_r) = axis(gy, row, dy);
    let mut enter = 0.0;
    while (0..cols).contains(&col) && (0..rows).contains(&row) {
        let cx = ox + (col as f64 + 0.5) * r - sx;
        let cy = oy + (row as f64 + 0.5) * r - sy;
        f.cell((row * cols + col) as usize, cx * dx + cy * dy, enter);
        if f.done() {
            break;
        }
        if t_c < t_r {
            if t_c > reach {
                break;
            }
            enter = t_c;
            col += step_c;
            t_c += dt_c;
        } else {
            if t_r > reach {
                break;
            }
            enter = t_r;
            row += step_r;
            t_r += dt_r;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_rng::uniform;
    use std::collections::BTreeMap;

    fn collect(
        grid: &Grid,
        o: [f64; 2],
        a: f64,
        reach: f64,
        fp: Footprint,
    ) -> BTreeMap<usize, f64> {
        let mut m = BTreeMap::new();
        visit(grid, o, a, reach, fp, &mut |i, d| {
            assert!(m.insert(i, d).is_none(), "cell {i} visited twice");
        });
        m
    }

    /// A huge axis covers the cells of the direction its sine and cosine
    /// give, as the same direction written small does.
    #[test]
    fn a_huge_axis_is_the_direction_it_names() {
        let grid = Grid::new([0.0, 0.0], 0.05, 60, 60).unwrap();
        let cone = Footprint::Cone {
            half_angle_rad: 7.5f64.to_radians(),
        };
        for axis in [2e3, -5e5, 1e12, 1e16, 1e300] {
            let (s, c) = f64::sin_cos(axis);
            let small = s.atan2(c);
            let got = collect(&grid, [1.5, 1.5], axis, 1.0, cone);
            assert!(got.len() > 50, "{axis}: {} cells", got.len());
            assert_eq!(got, collect(&grid, [1.5, 1.5], small, 1.0, cone), "{axis}");
        }
    }

    /// The row-interval cone equals a brute-force test of every cell centre.
    #[test]
    fn cone_matches_brute_force() {
        let grid = Grid::new([-3.0, -2.0], 0.1, 47, 61).unwrap();
        let mut next = uniform(0x9e37_79b9_7f4a_7c15);
        for _ in 0..300 {
            let o = [-3.0 + 6.1 * next(), -2.0 + 4.7 * next()];
            let axis = std::f64::consts::TAU * (next() - 0.5) * 2.0;
            let half = 0.01 + 1.5 * next();
            let reach = 4.0 * next();
            let got = collect(
                &grid,
                o,
                axis,
                reach,
                Footprint::Cone {
                    half_angle_rad: half,
                },
            );
            let mut want = BTreeMap::new();
            for i in 0..grid.len() {
                let [x, y] = grid.cell_center(grid.cell(i));
                let (px, py) = (x - o[0], y - o[1]);
                let d = px.hypot(py);
                if d <= reach && within(py.atan2(px), axis, half) {
                    want.insert(i, d);
                }
            }
            assert_eq!(
                got.keys().collect::<Vec<_>>(),
                want.keys().collect::<Vec<_>>()
            );
            for (k, d) in &got {
                assert!((d - want[k]).abs() < 1e-9);
            }
        }
    }

    /// A row block's `near` and `far` are the least and the greatest of its
    /// distances, on cones of every direction, inside the map and at its
    /// edges.
    #[test]
    fn row_block_bounds_are_the_extremes() {
        /// Blocks seen, short ones, and ones whose nearest cell is inside.
        #[derive(Default)]
        struct Check([usize; 3]);
        impl CellVisitor for Check {
            fn cell(&mut self, _: usize, _: f64, _: f64) {}
            fn row_block(
                &mut self,
                _: usize,
                d: &[f64; ROW_BLOCK],
                n: usize,
                [near, far]: [f64; 2],
                _: f64,
            ) {
                let lo = d[..n].iter().copied().fold(f64::INFINITY, f64::min);
                let hi = d[..n].iter().copied().fold(0.0, f64::max);
                assert_eq!((near, far), (lo, hi), "{:?}", &d[..n]);
                self.0[0] += 1;
                self.0[1] += usize::from(n < ROW_BLOCK);
                self.0[2] += usize::from(lo < d[0] && lo < d[n - 1]);
            }
        }
        let grid = Grid::new([-1.0, 0.5], 0.05, 90, 70).unwrap();
        let mut check = Check::default();
        for k in 0..720 {
            let axis = k as f64 * 0.5f64.to_radians() + 0.003;
            let origin = [
                -1.0 + 0.0117 * (k % 300) as f64,
                0.5 + 0.0093 * (k % 370) as f64,
            ];
            let cone = Footprint::Cone {
                half_angle_rad: (5.0 + (k % 40) as f64).to_radians(),
            };
            visit(&grid, origin, axis, 1.0 + (k % 5) as f64, cone, &mut check);
        }
        let [blocks, short, inside] = check.0;
        assert!(
            blocks > 10_000 && short > 1_000 && inside > 1_000,
            "{blocks} blocks, {short} short, {inside} inside"
        );
    }

    /// Every cell the ray visits intersects the segment, they are contiguous,
    /// and the projected distances grow along the ray.
    #[test]
    fn ray_visits_crossed_cells_in_order() {
        let grid = Grid::new([0.0, 0.0], 0.05, 100, 100).unwrap();
        for k in 0..720 {
            let a = k as f64 * 0.5f64.to_radians() + 0.001;
            let o = [2.512, 2.487];
            let reach = 1.7;
            let mut cells = Vec::new();
            visit(&grid, o, a, reach, Footprint::Ray, &mut |i, d| {
                cells.push((grid.cell(i), d))
            });
            // Cells are 4-connected neighbours, distances increase.
            for w in cells.windows(2) {
                let (c0, d0) = w[0];
                let (c1, d1) = w[1];
                assert_eq!(c0.row.abs_diff(c1.row) + c0.col.abs_diff(c1.col), 1);
                assert!(d1 > d0);
            }
            // The end point's cell is the last one or just before it.
            let end = [o[0] + reach * a.cos(), o[1] + reach * a.sin()];
            let end_cell = grid.world_to_cell(end[0], end[1]).unwrap();
            let pos = cells
                .iter()
                .position(|(c, _)| *c == end_cell)
                .expect("end cell visited");
            assert!(cells.len() - pos <= 2, "walked past the end");
            // Dense sampling of the segment finds no cell the walk missed.
            for s in 0..2000 {
                let t = reach * s as f64 / 2000.0;
                let c = grid
                    .world_to_cell(o[0] + t * a.cos(), o[1] + t * a.sin())
                    .unwrap();
                assert!(
                    cells.iter().any(|(x, _)| *x == c),
                    "missed {c:?} at angle {a}"
                );
            }
        }
    }

    #[test]
    fn ray_stops_at_map_edge() {
        let grid = Grid::new([0.0, 0.0], 1.0, 3, 3).unwrap();
        let mut n = 0;
        visit(
            &grid,
            [0.5, 1.5],
            0.0,
            100.0,
            Footprint::Ray,
            &mut |_, _| n += 1,
        );
        assert_eq!(n, 3);
    }
}
