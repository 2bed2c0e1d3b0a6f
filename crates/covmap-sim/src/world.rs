//! A world: obstacle polygons and the parry2d structures that query them.

use parry2d_f64::bounding_volume::Aabb;
use parry2d_f64::math::Vector;
use parry2d_f64::partitioning::{Bvh, BvhBuildStrategy};
use parry2d_f64::query::PointQuery;
use parry2d_f64::shape::Polyline;

use crate::error::{Result, SimError};
use crate::material::Material;
use crate::polygon::Polygon;
use crate::ray_tree::RayTree;

/// A set of obstacle polygons; overlapping polygons are their union.
///
/// Everything outside the polygons is free space. Beside the polygons the
/// world keeps three parry2d structures, built once: every ring edge in one
/// [`Polyline`] (distance queries and the robot's shape casts), a bounding-volume
/// hierarchy over the polygons' boxes (point-inside queries), and one over the
/// edges cut into pieces of at most 2 m (ray casts: long walls would otherwise
/// give boxes that most rays have to open), which the ray caster descends as a
/// copy with four children a node. parry types stay inside the crate: the API
/// speaks `[f64; 2]` in metres.
///
/// Build one from polygons ([`World::new`], [`World::from_vertex_lists`]), from
/// files (see [`crate::load`]) or by name ([`World::builtin`]).
///
/// # Example
/// ```
/// use covmap_sim::{Material, Polygon, World};
/// let world = World::from_vertex_lists(
///     vec![vec![[1.0, -1.0], [2.0, -1.0], [2.0, 1.0], [1.0, 1.0]]],
///     Material::Wall,
/// )
/// .unwrap();
/// assert!(world.contains_point([1.5, 0.0]));
/// assert_eq!(world.distance_to_obstacle_m([0.0, 0.0]), 1.0);
/// let hit = world.cast([0.0, 0.0], 0.0, 10.0);
/// assert!((hit.distance_m - 1.0).abs() < 1e-12);
/// ```
#[derive(Clone, Debug)]
pub struct World {
    polygons: Vec<Polygon>,
    bounds_m: [f64; 4],
    geometry: Option<Geometry>,
}

/// The query structures, absent for an empty world.
#[derive(Clone, Debug)]
pub(crate) struct Geometry {
    /// Every ring edge of every polygon, one segment each (distance queries
    /// and shape casts).
    pub(crate) boundary: Polyline,
    /// The material of each segment of `boundary`.
    pub(crate) segment_material: Vec<Material>,
    /// Leaf `i` is the box of polygon `i`.
    pub(crate) polygon_bvh: Bvh,
    /// The ray caster's boundary pieces and parry's hierarchy over them.
    pub(crate) rays: RayTree,
}

pub(crate) fn vector(p: [f64; 2]) -> Vector {
    Vector::new(p[0], p[1])
}

impl World {
    /// A world of already validated polygons (an empty world is all free space).
    pub fn new(polygons: Vec<Polygon>) -> Self {
        let bounds_m = polygons.iter().fold(
            [
                f64::INFINITY,
                f64::INFINITY,
                f64::NEG_INFINITY,
                f64::NEG_INFINITY,
            ],
            |b, p| {
                let q = p.bounds_m();
                [
                    b[0].min(q[0]),
                    b[1].min(q[1]),
                    b[2].max(q[2]),
                    b[3].max(q[3]),
                ]
            },
        );
        let geometry = (!polygons.is_empty()).then(|| build_geometry(&polygons));
        let bounds_m = if polygons.is_empty() {
            [0.0; 4]
        } else {
            bounds_m
        };
        Self {
            polygons,
            bounds_m,
            geometry,
        }
    }

    /// A world of polygons given as vertex lists, all of one material. An
    /// invalid polygon is an error naming its index in `lists`.
    pub fn from_vertex_lists(lists: Vec<Vec<[f64; 2]>>, material: Material) -> Result<Self> {
        let polygons = lists
            .into_iter()
            .enumerate()
            .map(|(index, v)| {
                Polygon::new(v, material).map_err(|e| match e {
                    SimError::InvalidPolygon { reason, .. } => {
                        SimError::InvalidPolygon { index, reason }
                    }
                    other => other,
                })
            })
            .collect::<Result<Vec<_>>>()?;
        Ok(Self::new(polygons))
    }

    /// The obstacles.
    pub fn polygons(&self) -> &[Polygon] {
        &self.polygons
    }
    /// Number of obstacles.
    pub fn len(&self) -> usize {
        self.polygons.len()
    }
    /// Whether the world has no obstacle.
    pub fn is_empty(&self) -> bool {
        self.polygons.is_empty()
    }
    /// `[x_min, y_min, x_max, y_max]` of all obstacles, metres (all zero when empty).
    pub fn bounds_m(&self) -> [f64; 4] {
        self.bounds_m
    }
    /// Number of boundary segments (ring edges) the ray caster tests.
    pub fn segment_count(&self) -> usize {
        self.geometry
            .as_ref()
            .map_or(0, |g| g.segment_material.len())
    }
    /// The sum of the polygons' areas, square metres (overlaps counted twice;
    /// the exact union inside a region is [`World::coverage`] times the cell area).
    pub fn polygon_area_m2(&self) -> f64 {
        self.polygons.iter().map(Polygon::area_m2).sum()
    }

    pub(crate) fn geometry(&self) -> Option<&Geometry> {
        self.geometry.as_ref()
    }

    /// Whether the point lies inside an obstacle.
    pub fn contains_point(&self, p_m: [f64; 2]) -> bool {
        let Some(g) = &self.geometry else {
            return false;
        };
        let q = vector(p_m);
        let aabb = Aabb::new(q, q);
        g.polygon_bvh
            .intersect_aabb(&aabb)
            .any(|i| self.polygons[i as usize].contains(p_m))
    }

    /// Distance from the point to the nearest obstacle boundary, metres
    /// (infinite in an empty world; also measured from inside an obstacle).
    pub fn distance_to_boundary_m(&self, p_m: [f64; 2]) -> f64 {
        match &self.geometry {
            Some(g) => g.boundary.distance_to_local_point(vector(p_m), false),
            None => f64::INFINITY,
        }
    }

    /// Distance from the point to the nearest obstacle, metres: 0 inside one.
    pub fn distance_to_obstacle_m(&self, p_m: [f64; 2]) -> f64 {
        if self.contains_point(p_m) {
            0.0
        } else {
            self.distance_to_boundary_m(p_m)
        }
    }
}

fn build_geometry(polygons: &[Polygon]) -> Geometry {
    let mut vertices = Vec::new();
    let mut indices = Vec::new();
    let mut segment_material = Vec::new();
    for p in polygons {
        for ring in p.rings() {
            let first = vertices.len() as u32;
            let n = ring.len() as u32;
            vertices.extend(ring.iter().map(|&v| vector(v)));
            for i in 0..n {
                indices.push([first + i, first + (i + 1) % n]);
                segment_material.push(p.material());
            }
        }
    }
    let edges = indices.iter().zip(&segment_material).map(|([i, j], &m)| {
        let (a, b) = (vertices[*i as usize], vertices[*j as usize]);
        ([a.x, a.y], [b.x, b.y], m)
    });
    let rays = RayTree::new(edges);
    let boxes: Vec<Aabb> = polygons
        .iter()
        .map(|p| {
            let [x0, y0, x1, y1] = p.bounds_m();
            Aabb::new(Vector::new(x0, y0), Vector::new(x1, y1))
        })
        .collect();
    Geometry {
        boundary: Polyline::new(vertices, Some(indices)),
        segment_material,
        polygon_bvh: Bvh::from_leaves(BvhBuildStrategy::Binned, &boxes),
        rays,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn empty_world_is_free() {
        let w = World::new(Vec::new());
        assert!(w.is_empty());
        assert!(!w.contains_point([0.0, 0.0]));
        assert_eq!(w.distance_to_obstacle_m([0.0, 0.0]), f64::INFINITY);
        assert_eq!(w.segment_count(), 0);
    }

    #[test]
    fn invalid_polygon_is_named_by_index() {
        let good = vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
        let bad = vec![[0.0, 0.0], [1.0, 0.0]];
        let e = World::from_vertex_lists(vec![good, bad], Material::Wall).unwrap_err();
        assert!(
            matches!(e, SimError::InvalidPolygon { index: 1, .. }),
            "{e}"
        );
    }

    #[test]
    fn union_queries() {
        let w = World::from_vertex_lists(
            vec![
                vec![[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]],
                vec![[1.0, 1.0], [3.0, 1.0], [3.0, 3.0], [1.0, 3.0]],
            ],
            Material::Wall,
        )
        .unwrap();
        assert_eq!(w.segment_count(), 8);
        assert_eq!(w.bounds_m(), [0.0, 0.0, 3.0, 3.0]);
        assert!(w.contains_point([1.5, 1.5]));
        assert!(w.contains_point([2.5, 2.5]));
        assert!(!w.contains_point([2.5, 0.5]));
        assert!((w.distance_to_obstacle_m([2.5, 0.5]) - 0.5).abs() < 1e-12);
        assert_eq!(w.distance_to_obstacle_m([0.5, 0.5]), 0.0);
    }
}
