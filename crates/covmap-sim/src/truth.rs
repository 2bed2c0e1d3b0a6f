//! Ground truth: the exact fraction of every grid cell covered by obstacles.
//!
//! # Method
//! Overlapping polygons must count once, so clipping each polygon against each
//! cell (Sutherland–Hodgman) and adding would double-count overlaps. Instead the
//! union is measured directly by a vertical sweep, one grid column at a time:
//!
//! 1. every non-vertical ring edge is bucketed into the columns its x-range
//!    crosses (vertical edges bound no area in a vertical sweep);
//! 2. inside a column, the x-coordinates of edge ends and of pairwise edge
//!    crossings split it into slabs where no two edges cross, so the edges
//!    crossing a slab have a fixed bottom-to-top order;
//! 3. walking up a slab, each edge flips its polygon's even-odd parity; the
//!    union is inside wherever at least one polygon's parity is odd, which gives
//!    trapezoids bounded below and above by two edges;
//! 4. each trapezoid's area inside each cell row is the integral of the clamped
//!    difference of two linear functions, computed exactly piece by piece.
//!
//! Everything is `f64`; the only approximation is rounding. Work is
//! proportional to the edges per column and the cells the union touches; cells
//! outside every polygon's box cost nothing. Columns are independent, so with
//! the `parallel` feature they run on rayon and are gathered in column order
//! (the result does not depend on scheduling). Shared edges (a run of pixels
//! above another) and coincident or overlapping polygons are handled by the
//! parity walk without special cases.

use covmap_core::{CovmapError, Grid, memory};

use crate::polygon::Polygon;
use crate::world::World;

impl World {
    /// The exact coverage of every cell of `grid`: the fraction of the cell's
    /// area inside the union of the obstacles, in `[0, 1]`, row-major like the
    /// core's maps. See the [module documentation](crate::truth) for the method.
    ///
    /// # Example
    /// ```
    /// use covmap_core::Grid;
    /// use covmap_sim::{Material, Polygon, World};
    /// // A triangle over the lower-right half of a 2 x 2 grid of unit cells.
    /// let world = World::from_vertex_lists(vec![vec![[0.0, 0.0], [2.0, 0.0], [2.0, 2.0]]], Material::Wall).unwrap();
    /// let grid = Grid::new([0.0, 0.0], 1.0, 2, 2).unwrap();
    /// let c = world.coverage(&grid);
    /// assert_eq!(c, vec![0.5, 1.0, 0.0, 0.5]);
    /// ```
    ///
    /// # Panics
    /// If the result (8 bytes a cell) or the edges' column buckets cannot be
    /// allocated ([`World::try_coverage`] returns an error instead).
    pub fn coverage(&self, grid: &Grid) -> Vec<f64> {
        self.try_coverage(grid).unwrap_or_else(|e| panic!("{e}"))
    }

    /// [`World::coverage`], or [`CovmapError::OutOfMemory`] (as
    /// [`crate::SimError::Core`]) where the result (8 bytes a cell) or the
    /// edges' column buckets (4 bytes for each column an edge spans) cannot
    /// be allocated.
    pub fn try_coverage(&self, grid: &Grid) -> crate::Result<Vec<f64>> {
        Ok(coverage(self.polygons(), grid, cfg!(feature = "parallel"))?)
    }

    /// [`World::coverage`] on one thread (the reference the parallel path is
    /// tested against).
    ///
    /// # Panics
    /// As [`World::coverage`].
    pub fn coverage_sequential(&self, grid: &Grid) -> Vec<f64> {
        coverage(self.polygons(), grid, false).unwrap_or_else(|e| panic!("{e}"))
    }
}

/// A non-vertical edge, left end first.
#[derive(Clone, Copy, Debug)]
struct Edge {
    x0: f64,
    y0: f64,
    x1: f64,
    y1: f64,
    polygon: u32,
}

impl Edge {
    #[inline]
    fn y_at(&self, x: f64) -> f64 {
        // Interpolate from the nearer end: exact at both ends.
        let t = (x - self.x0) / (self.x1 - self.x0);
        if t <= 0.5 {
            self.y0 + t * (self.y1 - self.y0)
        } else {
            self.y1 + (1.0 - t) * (self.y0 - self.y1)
        }
    }
}

/// An edge clipped to one column.
#[derive(Clone, Copy, Debug)]
struct Local {
    xl: f64,
    xr: f64,
    yl: f64,
    yr: f64,
    edge: u32,
    /// Index of the edge's polygon among the column's polygons.
    polygon: u32,
}

fn coverage(polygons: &[Polygon], grid: &Grid, parallel: bool) -> Result<Vec<f64>, CovmapError> {
    let (rows, cols) = grid.shape();
    // The result first: a grid too large for it fails before any work.
    let mut out = memory::try_filled(0.0f64, rows * cols, "the ground truth")?;
    let [gx0, gy0, gx1, gy1] = grid.bounds_m();
    let col_x = |c: usize| grid.origin_m()[0] + c as f64 * grid.resolution_m();

    let mut edges = Vec::new();
    for (pi, p) in polygons.iter().enumerate() {
        let [x0, y0, x1, y1] = p.bounds_m();
        if x1 <= gx0 || x0 >= gx1 || y1 <= gy0 || y0 >= gy1 {
            continue;
        }
        for ring in p.rings() {
            for i in 0..ring.len() {
                let (a, b) = (ring[i], ring[(i + 1) % ring.len()]);
                if a[0] == b[0] {
                    continue;
                }
                let (l, r) = if a[0] < b[0] { (a, b) } else { (b, a) };
                edges.push(Edge {
                    x0: l[0],
                    y0: l[1],
                    x1: r[0],
                    y1: r[1],
                    polygon: pi as u32,
                });
            }
        }
    }

    // Bucket edges into columns (compressed rows: `start[c]..start[c + 1]`).
    let column_range = |e: &Edge| -> Option<(usize, usize)> {
        if e.x1 <= gx0 || e.x0 >= gx1 {
            return None;
        }
        let r = grid.resolution_m();
        let guess = |x: f64| (((x - gx0) / r).floor().max(0.0) as usize).min(cols - 1);
        // First column whose right boundary lies beyond x0.
        let mut first = guess(e.x0);
        while first > 0 && col_x(first) > e.x0 {
            first -= 1;
        }
        while first + 1 < cols && col_x(first + 1) <= e.x0 {
            first += 1;
        }
        // Last column whose left boundary lies before x1.
        let mut last = guess(e.x1);
        while last + 1 < cols && col_x(last + 1) < e.x1 {
            last += 1;
        }
        while last > first && col_x(last) >= e.x1 {
            last -= 1;
        }
        Some((first, last))
    };
    let mut start = vec![0usize; cols + 1];
    let ranges: Vec<Option<(usize, usize)>> = edges.iter().map(column_range).collect();
    for &(first, last) in ranges.iter().flatten() {
        for n in &mut start[first..=last] {
            *n += 1;
        }
    }
    let mut acc = 0;
    for s in start.iter_mut() {
        let n = *s;
        *s = acc;
        acc += n;
    }
    let mut bucket = memory::try_filled(0u32, acc, "the ground truth's column buckets")?;
    let mut fill = start.clone();
    for (i, range) in ranges.iter().enumerate() {
        if let Some((first, last)) = *range {
            for f in &mut fill[first..=last] {
                bucket[*f] = i as u32;
                *f += 1;
            }
        }
    }

    let column = |c: usize| column_areas(&edges, &bucket[start[c]..start[c + 1]], grid, c);
    let per_column: Vec<Vec<(u32, f64)>> = if parallel {
        covmap_core::parallel::map((0..cols).collect(), column)
    } else {
        (0..cols).map(column).collect()
    };

    let cell_area = grid.resolution_m() * grid.resolution_m();
    for (c, entries) in per_column.into_iter().enumerate() {
        for (row, area) in entries {
            out[row as usize * cols + c] = (area / cell_area).clamp(0.0, 1.0);
        }
    }
    Ok(out)
}

/// The covered area of every cell of column `c`, as `(row, m^2)` pairs.
fn column_areas(edges: &[Edge], ids: &[u32], grid: &Grid, c: usize) -> Vec<(u32, f64)> {
    if ids.is_empty() {
        return Vec::new();
    }
    let r = grid.resolution_m();
    let [ox, oy] = grid.origin_m();
    let rows = grid.rows();
    let (xa, xb) = (ox + c as f64 * r, ox + (c + 1) as f64 * r);

    // Clip the column's edges and number their polygons locally.
    let mut polys: Vec<u32> = ids.iter().map(|&i| edges[i as usize].polygon).collect();
    polys.sort_unstable();
    polys.dedup();
    let mut local: Vec<Local> = Vec::with_capacity(ids.len());
    for &i in ids {
        let e = &edges[i as usize];
        let (xl, xr) = (e.x0.max(xa), e.x1.min(xb));
        if xl >= xr {
            continue;
        }
        let polygon = polys.binary_search(&e.polygon).unwrap_or(0) as u32;
        local.push(Local {
            xl,
            xr,
            yl: e.y_at(xl),
            yr: e.y_at(xr),
            edge: i,
            polygon,
        });
    }

    // Slab boundaries: the column's sides, edge ends, edge crossings.
    let mut events = Vec::with_capacity(2 * local.len() + 2);
    events.extend([xa, xb]);
    for l in &local {
        events.extend([l.xl, l.xr]);
    }
    let mut by_low: Vec<usize> = (0..local.len()).collect();
    let low = |l: &Local| l.yl.min(l.yr);
    let high = |l: &Local| l.yl.max(l.yr);
    by_low.sort_by(|&a, &b| low(&local[a]).total_cmp(&low(&local[b])));
    for (k, &i) in by_low.iter().enumerate() {
        let a = &local[i];
        for &j in &by_low[k + 1..] {
            let b = &local[j];
            if low(b) > high(a) {
                break;
            }
            let (xs, xe) = (a.xl.max(b.xl), a.xr.min(b.xr));
            if xs >= xe {
                continue;
            }
            let (ea, eb) = (&edges[a.edge as usize], &edges[b.edge as usize]);
            let ds = ea.y_at(xs) - eb.y_at(xs);
            let de = ea.y_at(xe) - eb.y_at(xe);
            if (ds < 0.0 && de > 0.0) || (ds > 0.0 && de < 0.0) {
                events.push(xs + (xe - xs) * (ds / (ds - de)));
            }
        }
    }
    events.retain(|x| *x >= xa && *x <= xb);
    events.sort_by(f64::total_cmp);
    events.dedup();

    let mut area = vec![0.0f64; rows];
    let mut touched = Vec::new();
    let mut parity = vec![false; polys.len()];
    let mut active: Vec<(f64, usize)> = Vec::new();
    for w in events.windows(2) {
        let (u, v) = (w[0], w[1]);
        if v <= u {
            continue;
        }
        let m = 0.5 * (u + v);
        active.clear();
        for (k, l) in local.iter().enumerate() {
            if l.xl < m && m < l.xr {
                active.push((edges[l.edge as usize].y_at(m), k));
            }
        }
        active.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        let mut inside = 0usize;
        let mut lower = 0usize;
        for &(_, k) in &active {
            let p = local[k].polygon as usize;
            parity[p] = !parity[p];
            let was = inside;
            if parity[p] {
                inside += 1;
            } else {
                inside -= 1;
            }
            if was == 0 && inside > 0 {
                lower = k;
            } else if was > 0 && inside == 0 {
                let (lo, hi) = (
                    &edges[local[lower].edge as usize],
                    &edges[local[k].edge as usize],
                );
                let (lu, lv, hu, hv) = (lo.y_at(u), lo.y_at(v), hi.y_at(u), hi.y_at(v));
                add_trapezoid(&mut area, &mut touched, oy, r, v - u, [lu, lv], [hu, hv]);
            }
        }
        // Parities cancel for closed rings; reset in case rounding split a pair.
        for &(_, k) in &active {
            parity[local[k].polygon as usize] = false;
        }
    }
    touched.sort_unstable();
    touched.dedup();
    touched
        .into_iter()
        .filter(|&j| area[j as usize] > 0.0)
        .map(|j| (j, area[j as usize]))
        .collect()
}

/// Add the area between the lines `lo` and `hi` (values at the slab's two
/// sides) over a slab of `width`, split among the cell rows it crosses.
fn add_trapezoid(
    area: &mut [f64],
    touched: &mut Vec<u32>,
    oy: f64,
    r: f64,
    width: f64,
    lo: [f64; 2],
    hi: [f64; 2],
) {
    let rows = area.len();
    let bottom = lo[0].min(lo[1]);
    let top = hi[0].max(hi[1]);
    if top <= oy || bottom >= oy + rows as f64 * r {
        return;
    }
    let first = (((bottom - oy) / r).floor().max(0.0) as usize).min(rows - 1);
    let last = (((top - oy) / r).ceil().max(1.0) as usize).min(rows);
    for (j, cell) in area.iter_mut().enumerate().take(last).skip(first) {
        let y0 = oy + j as f64 * r;
        let a = width
            * (clamped_mean(hi[0] - y0, hi[1] - y0, r) - clamped_mean(lo[0] - y0, lo[1] - y0, r));
        if a > 0.0 {
            *cell += a;
            touched.push(j as u32);
        }
    }
}

/// The mean over `t` in `[0, 1]` of `clamp(a + t (b - a), 0, h)`: exact, by
/// splitting where the line crosses 0 and `h` (between the kinks the clamped
/// function is linear, so the trapezoid rule is exact).
fn clamped_mean(a: f64, b: f64, h: f64) -> f64 {
    let g = |t: f64| (a + t * (b - a)).clamp(0.0, h);
    if a == b {
        return a.clamp(0.0, h);
    }
    let mut ts = [0.0, -a / (b - a), (h - a) / (b - a), 1.0];
    for t in &mut ts[1..3] {
        *t = t.clamp(0.0, 1.0);
    }
    if ts[1] > ts[2] {
        ts.swap(1, 2);
    }
    let mut sum = 0.0;
    let mut prev = (ts[0], g(ts[0]));
    for &t in &ts[1..] {
        let gt = g(t);
        sum += (t - prev.0) * 0.5 * (prev.1 + gt);
        prev = (t, gt);
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::Material;
    use proptest::prelude::*;

    fn world(lists: Vec<Vec<[f64; 2]>>) -> World {
        World::from_vertex_lists(lists, Material::Wall).unwrap()
    }

    #[test]
    fn clamped_mean_cases() {
        assert_eq!(clamped_mean(-1.0, -2.0, 1.0), 0.0);
        assert_eq!(clamped_mean(2.0, 3.0, 1.0), 1.0);
        assert!((clamped_mean(0.0, 1.0, 1.0) - 0.5).abs() < 1e-15);
        // From -1 to 2 over h = 1: 1/3 below, 1/3 rising, 1/3 at the top.
        assert!((clamped_mean(-1.0, 2.0, 1.0) - 0.5).abs() < 1e-15);
        assert!((clamped_mean(2.0, -1.0, 1.0) - 0.5).abs() < 1e-15);
        assert_eq!(clamped_mean(0.25, 0.25, 1.0), 0.25);
    }

    #[test]
    fn unit_square_on_cell_boundaries() {
        let w = world(vec![vec![[1.0, 1.0], [2.0, 1.0], [2.0, 2.0], [1.0, 2.0]]]);
        let g = Grid::new([0.0, 0.0], 1.0, 3, 3).unwrap();
        let c = w.coverage(&g);
        let mut expect = vec![0.0; 9];
        expect[4] = 1.0;
        assert_eq!(c, expect);
    }

    #[test]
    fn overlaps_count_once() {
        // Two unit-offset 2 x 2 squares: union area 7 on a grid of unit cells.
        let w = world(vec![
            vec![[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]],
            vec![[1.0, 1.0], [3.0, 1.0], [3.0, 3.0], [1.0, 3.0]],
        ]);
        let g = Grid::new([0.0, 0.0], 1.0, 3, 3).unwrap();
        let c = w.coverage(&g);
        assert_eq!(c, vec![1.0, 1.0, 0.0, 1.0, 1.0, 1.0, 0.0, 1.0, 1.0]);
        // Identical polygons twice, off the cell boundaries.
        let tri = vec![[0.1, 0.2], [2.7, 0.4], [1.3, 2.9]];
        let once = world(vec![tri.clone()]).coverage(&g);
        let twice = world(vec![tri.clone(), tri]).coverage(&g);
        for (a, b) in once.iter().zip(&twice) {
            assert!((a - b).abs() < 1e-12);
        }
    }

    #[test]
    fn fig1_partial_cell() {
        // A wall face at x = 2.04 fills the far 20 % of the cell [2.00, 2.05).
        let w = world(vec![vec![
            [2.04, -1.0],
            [2.5, -1.0],
            [2.5, 1.0],
            [2.04, 1.0],
        ]]);
        let g = Grid::new([1.0, -0.5], 0.05, 20, 40).unwrap();
        let c = w.coverage(&g);
        let i = g.index(g.world_to_cell(2.025, 0.0).unwrap()).unwrap();
        assert!((c[i] - 0.2).abs() < 1e-9, "{}", c[i]);
        assert_eq!(c[i + 1], 1.0);
        assert_eq!(c[i - 1], 0.0);
    }

    #[test]
    fn polygon_beyond_the_grid() {
        // A polygon reaching far below and left of the grid still fills it.
        let w = world(vec![vec![
            [-10.0, -10.0],
            [10.0, -10.0],
            [10.0, 0.5],
            [-10.0, 0.5],
        ]]);
        let g = Grid::new([0.0, 0.0], 0.25, 4, 4).unwrap();
        let c = w.coverage(&g);
        assert_eq!(&c[..8], &[1.0; 8]);
        assert_eq!(&c[8..], &[0.0; 8]);
    }

    /// The area of each cell by clipping the single polygon against it
    /// (Sutherland–Hodgman): an independent reference for one polygon.
    fn clipped(p: &Polygon, g: &Grid) -> Vec<f64> {
        let r = g.resolution_m();
        (0..g.len())
            .map(|i| {
                let [cx, cy] = g.cell_center(g.cell(i));
                p.area_in_rect_m2([cx - 0.5 * r, cy - 0.5 * r, cx + 0.5 * r, cy + 0.5 * r])
                    / (r * r)
            })
            .collect()
    }

    /// A star-shaped (hence simple) polygon around `c`: `n` vertices at sorted
    /// angles and radii in `[0.3, 1] * radius`.
    fn star(rng: &mut crate::rng::SimRng, c: [f64; 2], radius: f64, n: usize) -> Vec<[f64; 2]> {
        use rand::RngExt;
        let mut angles: Vec<f64> = (0..n)
            .map(|_| rng.random::<f64>() * std::f64::consts::TAU)
            .collect();
        angles.sort_by(f64::total_cmp);
        angles.dedup();
        angles
            .into_iter()
            .map(|a| {
                let rr = radius * (0.3 + 0.7 * rng.random::<f64>());
                [c[0] + rr * a.cos(), c[1] + rr * a.sin()]
            })
            .collect()
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(48))]

        #[test]
        fn axis_aligned_rectangles_match_interval_products(
            x0 in -1.0f64..1.0, y0 in -1.0f64..1.0, w in 0.01f64..1.5, h in 0.01f64..1.5,
            ox in -0.5f64..0.0, oy in -0.5f64..0.0, r in 0.03f64..0.3,
        ) {
            let world = world(vec![vec![[x0, y0], [x0 + w, y0], [x0 + w, y0 + h], [x0, y0 + h]]]);
            let g = Grid::covering(ox - 1.0, oy - 1.0, 1.8, 1.9, r).unwrap();
            let c = world.coverage(&g);
            let overlap = |a0: f64, a1: f64, b0: f64, b1: f64| (a1.min(b1) - a0.max(b0)).max(0.0);
            for (i, &v) in c.iter().enumerate() {
                let [cx, cy] = g.cell_center(g.cell(i));
                let expect = overlap(x0, x0 + w, cx - r / 2.0, cx + r / 2.0)
                    * overlap(y0, y0 + h, cy - r / 2.0, cy + r / 2.0) / (r * r);
                prop_assert!((v - expect).abs() < 1e-9, "cell {} {} vs {}", i, v, expect);
            }
        }

        #[test]
        fn rotated_squares_and_triangles_match_analytic_areas(
            cx in -0.3f64..0.3, cy in -0.3f64..0.3, side in 0.05f64..1.2, angle in 0.0f64..6.3,
            t in prop::array::uniform6(-1.0f64..1.0), r in 0.04f64..0.25,
        ) {
            let g = Grid::covering(-1.3, -1.2, 1.4, 1.3, r).unwrap();
            let (s, co) = angle.sin_cos();
            let sq: Vec<[f64; 2]> = [[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]]
                .iter()
                .map(|[u, v]| [cx + side * (co * u - s * v), cy + side * (s * u + co * v)])
                .collect();
            let tri = vec![[t[0], t[1]], [t[2], t[3]], [t[4], t[5]]];
            let twice = (t[2] - t[0]) * (t[5] - t[1]) - (t[4] - t[0]) * (t[3] - t[1]);
            prop_assume!(twice.abs() > 1e-3);
            for (shape, area) in [(sq, side * side), (tri, 0.5 * twice.abs())] {
                let p = Polygon::new(shape.clone(), Material::Wall).unwrap();
                let c = world(vec![shape]).coverage(&g);
                let cell = g.resolution_m() * g.resolution_m();
                let total: f64 = c.iter().sum::<f64>() * cell;
                // Entirely inside the grid: the coverage adds up to the area.
                prop_assert!((total - area).abs() <= 1e-9 * area, "{} vs {}", total, area);
                for (v, e) in c.iter().zip(clipped(&p, &g)) {
                    prop_assert!((0.0..=1.0).contains(v));
                    prop_assert!((v - e).abs() < 1e-9, "{} vs clipped {}", v, e);
                }
            }
        }

        #[test]
        fn coverage_adds_up_to_the_area_inside_the_grid(
            seed in any::<u64>(), ox in -2.0f64..0.0, oy in -2.0f64..0.0, r in 0.05f64..0.4,
            cols in 5usize..60, rows in 5usize..60,
        ) {
            // Disjoint star polygons on a lattice of 2 m boxes; the grid cuts some.
            let mut rng = crate::rng::sim_rng(seed);
            let polys: Vec<Vec<[f64; 2]>> = (0..16)
                .map(|k| star(&mut rng, [-3.0 + 2.0 * (k % 4) as f64, -3.0 + 2.0 * (k / 4) as f64], 0.95, 3 + k % 9))
                .filter(|v| v.len() >= 3)
                .collect();
            let world = World::from_vertex_lists(polys, Material::Wall);
            prop_assume!(world.is_ok());
            let world = world.unwrap();
            let g = Grid::new([ox, oy], r, rows, cols).unwrap();
            let c = world.coverage(&g);
            prop_assert!(c.iter().all(|v| (0.0..=1.0).contains(v)));
            let inside: f64 = world.polygons().iter().map(|p| p.area_in_rect_m2(g.bounds_m())).sum();
            let total: f64 = c.iter().sum::<f64>() * r * r;
            prop_assert!((total - inside).abs() <= 1e-9 * inside.max(1e-12), "{} vs {}", total, inside);
        }

        #[test]
        fn overlapping_random_polygons_match_supersampling(seed in any::<u64>()) {
            // Overlapping stars: the union, against 48 x 48 samples per cell.
            let mut rng = crate::rng::sim_rng(seed);
            use rand::RngExt;
            let polys: Vec<Vec<[f64; 2]>> = (0..5)
                .map(|_| {
                    let c = [rng.random::<f64>() * 1.2 - 0.6, rng.random::<f64>() * 1.2 - 0.6];
                    let n = 3 + (rng.random::<u32>() % 10) as usize;
                    star(&mut rng, c, 0.7, n)
                })
                .filter(|v| v.len() >= 3)
                .collect();
            let world = World::from_vertex_lists(polys, Material::Wall);
            prop_assume!(world.is_ok());
            let world = world.unwrap();
            let g = Grid::new([-1.05, -1.0], 0.25, 8, 8).unwrap();
            let c = world.coverage(&g);
            let n = 48;
            let r = g.resolution_m();
            let mut total_err = 0.0;
            for (i, &v) in c.iter().enumerate() {
                let [cx, cy] = g.cell_center(g.cell(i));
                let mut hits = 0;
                for a in 0..n {
                    for b in 0..n {
                        let x = cx - r / 2.0 + (a as f64 + 0.5) * r / n as f64;
                        let y = cy - r / 2.0 + (b as f64 + 0.5) * r / n as f64;
                        hits += world.contains_point([x, y]) as usize;
                    }
                }
                let sampled = hits as f64 / (n * n) as f64;
                // Midpoint sampling errs by at most about one row of samples per
                // boundary crossing the cell (1/48 each); the stars' boundaries
                // cross a cell a few times at most.
                prop_assert!((v - sampled).abs() < 0.1, "cell {}: {} vs sampled {}", i, v, sampled);
                total_err += v - sampled;
            }
            // Errors of opposite sign cancel over the grid.
            prop_assert!(total_err.abs() / 64.0 < 0.01, "mean error {}", total_err / 64.0);
        }
    }

    #[test]
    fn parallel_equals_sequential() {
        let w = World::builtin("office").unwrap();
        let [x0, y0, x1, y1] = w.bounds_m();
        let g = Grid::covering(x0 - 0.3, y0 - 0.3, x1 + 0.3, y1 + 0.3, 0.1).unwrap();
        assert_eq!(
            coverage(w.polygons(), &g, true),
            coverage(w.polygons(), &g, false)
        );
    }
}
