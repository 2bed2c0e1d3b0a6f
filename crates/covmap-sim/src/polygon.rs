//! Obstacle polygons: validated rings of vertices with a material.

use crate::error::{Result, SimError};
use crate::material::Material;

/// One obstacle: a simple polygon, optionally with holes, and its material.
///
/// Rings may be given in either orientation; a closing vertex equal to the first
/// and repeated consecutive vertices are dropped. Validation rejects rings with
/// fewer than three distinct vertices, non-finite coordinates, zero area, and
/// rings whose edges cross or touch each other or another ring's (the polygon
/// must be simple). Holes must lie inside the exterior ring. The inside is the
/// even-odd interior of all rings, so a hole removes its area.
///
/// # Example
/// ```
/// use covmap_sim::{Material, Polygon};
/// let tri = Polygon::new(vec![[0.0, 0.0], [0.0, 2.0], [2.0, 0.0]], Material::Wall).unwrap();
/// assert_eq!(tri.area_m2(), 2.0);
/// assert!(tri.contains([0.5, 0.5]));
/// // The part inside the unit square: the square minus the corner beyond x + y = 2.
/// assert!((tri.area_in_rect_m2([0.0, 0.0, 1.0, 1.0]) - 1.0).abs() < 1e-15);
/// assert!(Polygon::new(vec![[0.0, 0.0], [1.0, 1.0], [2.0, 2.0]], Material::Wall).is_err());
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Polygon {
    /// `rings[0]` is the exterior, the rest are holes.
    rings: Vec<Vec<[f64; 2]>>,
    material: Material,
    bounds_m: [f64; 4],
}

impl Polygon {
    /// A polygon without holes.
    pub fn new(vertices: Vec<[f64; 2]>, material: Material) -> Result<Self> {
        Self::with_holes(vertices, Vec::new(), material)
    }

    /// A polygon with holes. The rings must be simple, no two edges may
    /// cross or touch, every hole must lie inside the exterior, and no hole
    /// inside another (an island in a hole is a polygon of its own).
    pub fn with_holes(
        exterior: Vec<[f64; 2]>,
        holes: Vec<Vec<[f64; 2]>>,
        material: Material,
    ) -> Result<Self> {
        let invalid = |reason: String| SimError::InvalidPolygon { index: 0, reason };
        let mut rings = Vec::with_capacity(1 + holes.len());
        for (k, ring) in std::iter::once(exterior).chain(holes).enumerate() {
            let name = if k == 0 {
                "exterior ring".to_string()
            } else {
                format!("hole {}", k - 1)
            };
            rings.push(clean_ring(ring).map_err(|e| invalid(format!("{name}: {e}")))?);
        }
        if let Some((a, b)) = first_crossing(&rings) {
            return Err(invalid(format!(
                "edges cross or touch ({}, {}) (the polygon must be simple)",
                describe_edge(&rings, a),
                describe_edge(&rings, b)
            )));
        }
        for (k, hole) in rings.iter().enumerate().skip(1) {
            if !ring_contains(&rings[0], hole[0]) {
                return Err(invalid(format!(
                    "hole {} lies outside the exterior ring",
                    k - 1
                )));
            }
        }
        // No edges cross, so a hole lies wholly inside another or apart from
        // it: one vertex tells, and only a hole whose bounds hold it can.
        let bounds: Vec<[f64; 4]> = rings.iter().map(|r| ring_bounds(r)).collect();
        for outer in 1..rings.len() {
            for inner in 1..rings.len() {
                let (o, i) = (bounds[outer], bounds[inner]);
                let within = o[0] <= i[0] && o[1] <= i[1] && i[2] <= o[2] && i[3] <= o[3];
                if outer != inner && within && ring_contains(&rings[outer], rings[inner][0]) {
                    return Err(invalid(format!(
                        "hole {} lies inside hole {} (an island in a hole is a polygon of its own)",
                        inner - 1,
                        outer - 1
                    )));
                }
            }
        }
        let bounds_m = ring_bounds(&rings[0]);
        Ok(Self {
            rings,
            material,
            bounds_m,
        })
    }

    /// The axis-aligned rectangle `[min, max]`.
    pub fn rectangle(min_m: [f64; 2], max_m: [f64; 2], material: Material) -> Result<Self> {
        let [x0, y0] = min_m;
        let [x1, y1] = max_m;
        if !(x1 > x0 && y1 > y0) {
            return Err(SimError::InvalidPolygon {
                index: 0,
                reason: format!("empty rectangle [{x0}, {x1}] x [{y0}, {y1}]"),
            });
        }
        Self::new(vec![[x0, y0], [x1, y0], [x1, y1], [x0, y1]], material)
    }

    /// A wall along the segment `a`-`b`: a rectangle `thickness_m` wide centred
    /// on the segment and extended by half the thickness beyond both ends, so
    /// that walls meeting at a corner close it.
    pub fn wall(
        a_m: [f64; 2],
        b_m: [f64; 2],
        thickness_m: f64,
        material: Material,
    ) -> Result<Self> {
        let (dx, dy) = (b_m[0] - a_m[0], b_m[1] - a_m[1]);
        let len = dx.hypot(dy);
        if !(thickness_m.is_finite() && thickness_m > 0.0) {
            return Err(SimError::InvalidParameter {
                name: "thickness_m",
                value: thickness_m,
                expected: "a positive, finite wall thickness",
            });
        }
        if !(len.is_finite() && len > 0.0) {
            return Err(SimError::InvalidPolygon {
                index: 0,
                reason: format!(
                    "wall from ({}, {}) to ({}, {}) has no length",
                    a_m[0], a_m[1], b_m[0], b_m[1]
                ),
            });
        }
        let h = 0.5 * thickness_m;
        let (ux, uy) = (dx / len * h, dy / len * h);
        let (nx, ny) = (-uy, ux);
        let a = [a_m[0] - ux, a_m[1] - uy];
        let b = [b_m[0] + ux, b_m[1] + uy];
        Self::new(
            vec![
                [a[0] - nx, a[1] - ny],
                [b[0] - nx, b[1] - ny],
                [b[0] + nx, b[1] + ny],
                [a[0] + nx, a[1] + ny],
            ],
            material,
        )
    }

    /// A regular polygon of `sides` vertices at `radius_m` from `center_m`, the
    /// first at angle `rotation_rad` (a round column is a regular polygon).
    pub fn regular(
        center_m: [f64; 2],
        radius_m: f64,
        sides: usize,
        rotation_rad: f64,
        material: Material,
    ) -> Result<Self> {
        if !(radius_m.is_finite() && radius_m > 0.0) {
            return Err(SimError::InvalidParameter {
                name: "radius_m",
                value: radius_m,
                expected: "a positive, finite radius",
            });
        }
        if sides < 3 {
            return Err(SimError::InvalidParameter {
                name: "sides",
                value: sides as f64,
                expected: "at least 3 sides",
            });
        }
        let step = std::f64::consts::TAU / sides as f64;
        let vertices = (0..sides)
            .map(|i| {
                let a = rotation_rad + i as f64 * step;
                [
                    center_m[0] + radius_m * a.cos(),
                    center_m[1] + radius_m * a.sin(),
                ]
            })
            .collect();
        Self::new(vertices, material)
    }

    /// The exterior ring (without a closing vertex).
    pub fn exterior(&self) -> &[[f64; 2]] {
        &self.rings[0]
    }
    /// The holes.
    pub fn holes(&self) -> &[Vec<[f64; 2]>] {
        &self.rings[1..]
    }
    /// All rings, the exterior first.
    pub fn rings(&self) -> &[Vec<[f64; 2]>] {
        &self.rings
    }
    /// The surface material.
    pub fn material(&self) -> Material {
        self.material
    }
    /// `[x_min, y_min, x_max, y_max]`, metres.
    pub fn bounds_m(&self) -> [f64; 4] {
        self.bounds_m
    }

    /// The area inside the polygon, square metres (exterior minus holes).
    pub fn area_m2(&self) -> f64 {
        let ext = ring_area(&self.rings[0]).abs();
        ext - self.rings[1..]
            .iter()
            .map(|r| ring_area(r).abs())
            .sum::<f64>()
    }

    /// Whether the point lies inside (even-odd rule over all rings; points on
    /// the boundary may go either way).
    pub fn contains(&self, p: [f64; 2]) -> bool {
        let [x0, y0, x1, y1] = self.bounds_m;
        if !(p[0] >= x0 && p[0] <= x1 && p[1] >= y0 && p[1] <= y1) {
            return false;
        }
        self.rings.iter().filter(|r| ring_contains(r, p)).count() % 2 == 1
    }

    /// The area of the polygon inside the rectangle `[x_min, y_min, x_max,
    /// y_max]`, square metres: each ring clipped by Sutherland–Hodgman (exact
    /// for any simple ring against a convex window: the degenerate edges it may
    /// leave carry no area), holes subtracted.
    pub fn area_in_rect_m2(&self, rect: [f64; 4]) -> f64 {
        let [x0, y0, x1, y1] = self.bounds_m;
        if x1 <= rect[0] || x0 >= rect[2] || y1 <= rect[1] || y0 >= rect[3] {
            return 0.0;
        }
        let mut area = 0.0;
        for (k, ring) in self.rings.iter().enumerate() {
            let a = ring_area(&clip_ring_to_rect(ring, rect)).abs();
            area += if k == 0 { a } else { -a };
        }
        area
    }
}

/// Signed area of a ring (counter-clockwise positive), by the shoelace formula
/// about the first vertex (which keeps the products small far from the origin).
pub(crate) fn ring_area(ring: &[[f64; 2]]) -> f64 {
    if ring.len() < 3 {
        return 0.0;
    }
    let o = ring[0];
    let mut twice = 0.0;
    for w in ring[1..].windows(2) {
        let (a, b) = (w[0], w[1]);
        twice += (a[0] - o[0]) * (b[1] - o[1]) - (b[0] - o[0]) * (a[1] - o[1]);
    }
    0.5 * twice
}

fn ring_bounds(ring: &[[f64; 2]]) -> [f64; 4] {
    ring.iter().fold(
        [
            f64::INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NEG_INFINITY,
        ],
        |b, p| {
            [
                b[0].min(p[0]),
                b[1].min(p[1]),
                b[2].max(p[0]),
                b[3].max(p[1]),
            ]
        },
    )
}

/// Even-odd point-in-ring test (crossings of a ray towards +x).
pub(crate) fn ring_contains(ring: &[[f64; 2]], p: [f64; 2]) -> bool {
    let mut inside = false;
    let n = ring.len();
    let mut j = n - 1;
    for i in 0..n {
        let (a, b) = (ring[i], ring[j]);
        if (a[1] > p[1]) != (b[1] > p[1]) {
            let x = a[0] + (p[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0]);
            if p[0] < x {
                inside = !inside;
            }
        }
        j = i;
    }
    inside
}

/// Drop a closing vertex and repeated vertices; check the rest.
fn clean_ring(ring: Vec<[f64; 2]>) -> std::result::Result<Vec<[f64; 2]>, String> {
    if let Some((i, p)) = ring
        .iter()
        .enumerate()
        .find(|(_, p)| !(p[0].is_finite() && p[1].is_finite()))
    {
        return Err(format!("vertex {i} ({}, {}) is not finite", p[0], p[1]));
    }
    let mut out: Vec<[f64; 2]> = Vec::with_capacity(ring.len());
    for p in ring {
        if out.last() != Some(&p) {
            out.push(p);
        }
    }
    while out.len() > 1 && out.first() == out.last() {
        out.pop();
    }
    if out.len() < 3 {
        return Err(format!(
            "{} distinct vertices (at least 3 are needed)",
            out.len()
        ));
    }
    let area = ring_area(&out);
    let [x0, y0, x1, y1] = ring_bounds(&out);
    let scale = (x1 - x0).max(y1 - y0);
    if !(area.abs() > 1e-12 * scale * scale) {
        return Err(format!(
            "zero area: {area:.3e} m^2, negligible against its {scale:.3e} m extent (at most 1e-12 of its square)"
        ));
    }
    Ok(out)
}

/// Edges are addressed as (ring, index of the first vertex).
type EdgeRef = (usize, usize);

fn describe_edge(rings: &[Vec<[f64; 2]>], (r, i): EdgeRef) -> String {
    let ring = &rings[r];
    let (a, b) = (ring[i], ring[(i + 1) % ring.len()]);
    format!(
        "ring {r} edge {i} ({}, {})-({}, {})",
        a[0], a[1], b[0], b[1]
    )
}

/// The first pair of edges that cross or touch, other than neighbours sharing
/// their common vertex. A sweep over the edges sorted by their left end keeps
/// it near-linear for ordinary polygons.
fn first_crossing(rings: &[Vec<[f64; 2]>]) -> Option<(EdgeRef, EdgeRef)> {
    let mut edges: Vec<(f64, f64, EdgeRef)> = Vec::new();
    for (r, ring) in rings.iter().enumerate() {
        for i in 0..ring.len() {
            let (a, b) = (ring[i], ring[(i + 1) % ring.len()]);
            edges.push((a[0].min(b[0]), a[0].max(b[0]), (r, i)));
        }
    }
    edges.sort_by(|p, q| p.0.total_cmp(&q.0));
    let seg = |(r, i): EdgeRef| {
        let ring = &rings[r];
        (ring[i], ring[(i + 1) % ring.len()])
    };
    for (k, &(_, x_max, e)) in edges.iter().enumerate() {
        let (a, b) = seg(e);
        for &(x_min2, _, f) in &edges[k + 1..] {
            if x_min2 > x_max {
                break;
            }
            let (c, d) = seg(f);
            let neighbours = e.0 == f.0 && {
                let n = rings[e.0].len();
                (e.1 + 1) % n == f.1 || (f.1 + 1) % n == e.1
            };
            if neighbours {
                // Sharing one vertex is fine; folding back onto each other is not.
                let n = rings[e.0].len();
                let (first, second) = if (e.1 + 1) % n == f.1 { (e, f) } else { (f, e) };
                let (p, q) = seg(first);
                let (_, s) = seg(second);
                let (u, v) = ([q[0] - p[0], q[1] - p[1]], [s[0] - q[0], s[1] - q[1]]);
                let cross = u[0] * v[1] - u[1] * v[0];
                let dot = u[0] * v[0] + u[1] * v[1];
                if cross == 0.0 && dot < 0.0 {
                    return Some((first, second));
                }
                continue;
            }
            if segments_touch(a, b, c, d) {
                return Some((e, f));
            }
        }
    }
    None
}

fn orient(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

fn on_segment(a: [f64; 2], b: [f64; 2], p: [f64; 2]) -> bool {
    p[0] >= a[0].min(b[0])
        && p[0] <= a[0].max(b[0])
        && p[1] >= a[1].min(b[1])
        && p[1] <= a[1].max(b[1])
}

/// Whether closed segments `ab` and `cd` share a point.
pub(crate) fn segments_touch(a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> bool {
    let (d1, d2) = (orient(c, d, a), orient(c, d, b));
    let (d3, d4) = (orient(a, b, c), orient(a, b, d));
    if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0))
        && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0))
    {
        return true;
    }
    (d1 == 0.0 && on_segment(c, d, a))
        || (d2 == 0.0 && on_segment(c, d, b))
        || (d3 == 0.0 && on_segment(a, b, c))
        || (d4 == 0.0 && on_segment(a, b, d))
}

/// Sutherland–Hodgman clipping of a ring against an axis-aligned rectangle.
pub(crate) fn clip_ring_to_rect(ring: &[[f64; 2]], rect: [f64; 4]) -> Vec<[f64; 2]> {
    // (axis, bound, keep the side >= bound?)
    let planes = [
        (0, rect[0], true),
        (0, rect[2], false),
        (1, rect[1], true),
        (1, rect[3], false),
    ];
    let mut poly = ring.to_vec();
    for (axis, bound, keep_above) in planes {
        if poly.is_empty() {
            break;
        }
        let inside = |p: &[f64; 2]| {
            if keep_above {
                p[axis] >= bound
            } else {
                p[axis] <= bound
            }
        };
        let mut out = Vec::with_capacity(poly.len() + 4);
        let mut prev = poly[poly.len() - 1];
        for &cur in &poly {
            let (ci, pi) = (inside(&cur), inside(&prev));
            if ci != pi {
                let t = (bound - prev[axis]) / (cur[axis] - prev[axis]);
                let mut x = [
                    prev[0] + t * (cur[0] - prev[0]),
                    prev[1] + t * (cur[1] - prev[1]),
                ];
                x[axis] = bound;
                out.push(x);
            }
            if ci {
                out.push(cur);
            }
            prev = cur;
        }
        poly = out;
    }
    poly
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rejects_degenerate_rings() {
        let w = Material::Wall;
        assert!(Polygon::new(vec![[0.0, 0.0], [1.0, 0.0]], w).is_err());
        assert!(Polygon::new(vec![[0.0, 0.0], [1.0, 0.0], [1.0, 0.0], [0.0, 0.0]], w).is_err());
        assert!(Polygon::new(vec![[0.0, 0.0], [1.0, 0.0], [f64::NAN, 1.0]], w).is_err());
        // A bow tie crosses itself.
        let e = Polygon::new(vec![[0.0, 0.0], [2.0, 2.0], [2.0, 0.0], [0.0, 1.0]], w).unwrap_err();
        assert!(e.to_string().contains("cross"), "{e}");
        // A spike folds back onto its neighbour.
        assert!(Polygon::new(vec![[0.0, 0.0], [2.0, 0.0], [1.0, 0.0], [1.0, 1.0]], w).is_err());
        // A hole outside the exterior.
        let sq = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        let far = vec![[2.0, 2.0], [3.0, 2.0], [3.0, 3.0]];
        assert!(Polygon::with_holes(sq.clone(), vec![far], w).is_err());
        // A hole crossing the exterior.
        let cross = vec![[0.5, 0.5], [1.5, 0.5], [1.5, 0.7]];
        assert!(Polygon::with_holes(sq, vec![cross], w).is_err());
        // A hole inside another: the even-odd rule would fill the inner one,
        // the area would subtract it.
        let square = |lo: f64, hi: f64| vec![[lo, lo], [hi, lo], [hi, hi], [lo, hi]];
        for holes in [
            vec![square(2.0, 8.0), square(4.0, 6.0)],
            vec![square(4.0, 6.0), square(2.0, 8.0)],
        ] {
            let e = Polygon::with_holes(square(0.0, 10.0), holes, w).unwrap_err();
            assert!(e.to_string().contains("lies inside hole"), "{e}");
        }
        assert!(
            Polygon::with_holes(
                square(0.0, 10.0),
                vec![square(1.0, 3.0), square(5.0, 8.0)],
                w
            )
            .is_ok()
        );
    }

    #[test]
    fn closing_vertex_and_orientation_do_not_matter() {
        let ccw = vec![[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [0.0, 1.0], [0.0, 0.0]];
        let mut cw = ccw.clone();
        cw.reverse();
        let a = Polygon::new(ccw, Material::Wall).unwrap();
        let b = Polygon::new(cw, Material::Wall).unwrap();
        assert_eq!(a.exterior().len(), 4);
        assert_eq!(a.area_m2(), 2.0);
        assert_eq!(b.area_m2(), 2.0);
    }

    #[test]
    fn holes_subtract() {
        let sq = vec![[0.0, 0.0], [4.0, 0.0], [4.0, 4.0], [0.0, 4.0]];
        let hole = vec![[1.0, 1.0], [1.0, 3.0], [3.0, 3.0], [3.0, 1.0]];
        let p = Polygon::with_holes(sq, vec![hole], Material::Glass).unwrap();
        assert_eq!(p.area_m2(), 12.0);
        assert!(!p.contains([2.0, 2.0]));
        assert!(p.contains([0.5, 2.0]));
        assert!((p.area_in_rect_m2([0.0, 0.0, 2.0, 2.0]) - 3.0).abs() < 1e-12);
    }

    #[test]
    fn wall_and_regular_shapes() {
        let w = Polygon::wall([0.0, 0.0], [3.0, 4.0], 0.2, Material::Wall).unwrap();
        assert!((w.area_m2() - 0.2 * 5.2).abs() < 1e-12);
        assert!(Polygon::wall([1.0, 1.0], [1.0, 1.0], 0.1, Material::Wall).is_err());
        let hex = Polygon::regular([1.0, 1.0], 1.0, 6, 0.0, Material::Wall).unwrap();
        assert!((hex.area_m2() - 1.5 * 3f64.sqrt()).abs() < 1e-12);
    }

    #[test]
    fn concave_clip_area() {
        // An L: the unit square [0,2]^2 minus [1,2]^2.
        let l = Polygon::new(
            vec![
                [0.0, 0.0],
                [2.0, 0.0],
                [2.0, 1.0],
                [1.0, 1.0],
                [1.0, 2.0],
                [0.0, 2.0],
            ],
            Material::Wall,
        )
        .unwrap();
        assert_eq!(l.area_m2(), 3.0);
        assert!((l.area_in_rect_m2([0.5, 0.5, 1.5, 1.5]) - 0.75).abs() < 1e-12);
        assert_eq!(l.area_in_rect_m2([1.0, 1.0, 2.0, 2.0]), 0.0);
    }
}
