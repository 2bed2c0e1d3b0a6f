//! Ray casting against the world's surfaces.

use crate::error::{Result, SimError, check_param};
use crate::material::Material;
use crate::ray_tree::{Ray, RayStack, RayTree};
use crate::world::World;

/// Batches at least this long are split over rayon's threads.
#[cfg(feature = "parallel")]
const PARALLEL_MIN_RAYS: usize = 4096;

/// What one ray met first.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RayHit {
    /// Distance to the first surface, metres; the maximum range when nothing
    /// was hit before it.
    pub distance_m: f64,
    /// Angle between the ray and the surface normal, radians in `[0, pi/2]`
    /// (0 is head-on); NaN when nothing was hit.
    pub incidence_rad: f64,
    /// Unit normal of the surface, on the side the ray came from; `[0, 0]`
    /// when nothing was hit.
    pub normal: [f64; 2],
    /// The hit surface's material; `None` when nothing was hit.
    pub material: Option<Material>,
}

impl RayHit {
    /// A miss at `max_range_m`.
    pub fn miss(max_range_m: f64) -> Self {
        Self {
            distance_m: max_range_m,
            incidence_rad: f64::NAN,
            normal: [0.0, 0.0],
            material: None,
        }
    }
    /// Whether a surface was hit within the maximum range.
    pub fn is_hit(&self) -> bool {
        self.material.is_some()
    }
}

impl World {
    /// Cast one ray from `origin_m` along `angle_rad` (radians, counter-clockwise
    /// from +x) up to `max_range_m`.
    ///
    /// The first surface met is reported, whichever polygon it belongs to: from
    /// free space that is always a surface of the union. A ray starting inside
    /// an obstacle reports the obstacle's boundary from inside. Inputs are not
    /// validated here (see [`World::cast_batch`]); a NaN gives a miss.
    ///
    /// # Example
    /// ```
    /// use covmap_sim::{Material, World};
    /// // A wall whose face runs from (2, -5) to (2, 5).
    /// let world = World::from_vertex_lists(vec![vec![[2.0, -5.0], [3.0, -5.0], [3.0, 5.0], [2.0, 5.0]]], Material::Wall).unwrap();
    /// let hit = world.cast([0.0, 0.0], std::f64::consts::FRAC_PI_4, 10.0);
    /// assert!((hit.distance_m - 2.0 * 2f64.sqrt()).abs() < 1e-12);
    /// assert!((hit.incidence_rad - std::f64::consts::FRAC_PI_4).abs() < 1e-12);
    /// assert_eq!(hit.normal, [-1.0, 0.0]);
    /// assert!(!world.cast([0.0, 0.0], std::f64::consts::PI, 10.0).is_hit());
    /// ```
    pub fn cast(&self, origin_m: [f64; 2], angle_rad: f64, max_range_m: f64) -> RayHit {
        self.cast_with(origin_m, angle_rad, max_range_m, |tree, ray| {
            tree.first_hit(ray, max_range_m)
        })
    }

    /// [`World::cast`] finding the first hit with `first_hit`, which lets a
    /// batch lend every ray the same stack.
    #[inline(always)]
    fn cast_with(
        &self,
        origin_m: [f64; 2],
        angle_rad: f64,
        max_range_m: f64,
        first_hit: impl FnOnce(&RayTree, &Ray) -> Option<(u32, f64)>,
    ) -> RayHit {
        let Some(g) = self.geometry() else {
            return RayHit::miss(max_range_m);
        };
        let (s, c) = angle_rad.sin_cos();
        let d = [c, s];
        match first_hit(&g.rays, &Ray::new(origin_m, d)) {
            Some((piece, t)) if t < max_range_m => {
                let p = g.rays.face(piece);
                let mut n = p.n;
                let mut cos = n[0] * d[0] + n[1] * d[1];
                if cos > 0.0 {
                    n = [-n[0], -n[1]];
                    cos = -cos;
                }
                RayHit {
                    distance_m: t,
                    incidence_rad: (-cos).min(1.0).acos(),
                    normal: n,
                    material: Some(p.material),
                }
            }
            _ => RayHit::miss(max_range_m),
        }
    }

    /// Cast a batch of rays: ray `i` from `origins_m[i]` along `angles_rad[i]`,
    /// up to `max_range_m`. With the `parallel` feature, batches of 4096 rays or
    /// more run on rayon's threads; the result is the same either way.
    ///
    /// Errors on mismatched lengths, a non-finite origin or angle, or a maximum
    /// range that is not positive and finite.
    pub fn cast_batch(
        &self,
        origins_m: &[[f64; 2]],
        angles_rad: &[f64],
        max_range_m: f64,
    ) -> Result<Vec<RayHit>> {
        #[cfg(feature = "parallel")]
        if origins_m.len() >= PARALLEL_MIN_RAYS {
            use rayon::prelude::*;
            validate_rays(origins_m, angles_rad, max_range_m)?;
            return Ok(origins_m
                .par_iter()
                .zip(angles_rad.par_iter())
                .with_min_len(1024)
                .map_init(RayStack::default, |stack, (&o, &a)| {
                    self.cast_batched(o, a, max_range_m, stack)
                })
                .collect());
        }
        self.cast_batch_sequential(origins_m, angles_rad, max_range_m)
    }

    /// [`World::cast_batch`] on the calling thread only.
    pub fn cast_batch_sequential(
        &self,
        origins_m: &[[f64; 2]],
        angles_rad: &[f64],
        max_range_m: f64,
    ) -> Result<Vec<RayHit>> {
        validate_rays(origins_m, angles_rad, max_range_m)?;
        Ok(self.cast_sequential(origins_m, angles_rad, max_range_m))
    }

    fn cast_sequential(
        &self,
        origins_m: &[[f64; 2]],
        angles_rad: &[f64],
        max_range_m: f64,
    ) -> Vec<RayHit> {
        let mut stack = RayStack::default();
        origins_m
            .iter()
            .zip(angles_rad)
            .map(|(&o, &a)| self.cast_batched(o, a, max_range_m, &mut stack))
            .collect()
    }

    /// One ray of a batch, on the batch's stack.
    fn cast_batched(
        &self,
        origin_m: [f64; 2],
        angle_rad: f64,
        max_range_m: f64,
        stack: &mut RayStack,
    ) -> RayHit {
        self.cast_with(origin_m, angle_rad, max_range_m, |tree, ray| {
            tree.first_hit_with(ray, max_range_m, stack)
        })
    }
}

fn validate_rays(origins_m: &[[f64; 2]], angles_rad: &[f64], max_range_m: f64) -> Result<()> {
    check_param(
        "max_range_m",
        max_range_m,
        max_range_m > 0.0,
        "a positive, finite distance",
    )?;
    if origins_m.len() != angles_rad.len() {
        return Err(SimError::LengthMismatch {
            what: "ray origins and angles",
            left: origins_m.len(),
            right: angles_rad.len(),
        });
    }
    for (index, o) in origins_m.iter().enumerate() {
        for (what, value) in [("ray origin x", o[0]), ("ray origin y", o[1])] {
            if !value.is_finite() {
                return Err(SimError::InvalidValue { what, index, value });
            }
        }
    }
    if let Some((index, &value)) = angles_rad.iter().enumerate().find(|(_, a)| !a.is_finite()) {
        return Err(SimError::InvalidValue {
            what: "ray angle",
            index,
            value,
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::polygon::Polygon;
    use std::f64::consts::{FRAC_PI_2, FRAC_PI_6, PI};

    fn room() -> World {
        // A 4 x 2 room (inner faces x = 0, 4 and y = 0, 2) of 0.1 m walls, a
        // glass pane on the right wall, a diamond in the middle.
        let w = Material::Wall;
        World::new(vec![
            Polygon::rectangle([-0.1, -0.1], [4.1, 0.0], w).unwrap(),
            Polygon::rectangle([-0.1, 2.0], [4.1, 2.1], w).unwrap(),
            Polygon::rectangle([-0.1, 0.0], [0.0, 2.0], w).unwrap(),
            Polygon::rectangle([4.0, 0.0], [4.05, 2.0], Material::Glass).unwrap(),
            Polygon::new(vec![[2.0, 0.8], [2.2, 1.0], [2.0, 1.2], [1.8, 1.0]], w).unwrap(),
        ])
    }

    #[test]
    fn hand_computed_hits() {
        let w = room();
        // Straight up from (1, 1): the ceiling at 1 m, head-on.
        let h = w.cast([1.0, 1.0], FRAC_PI_2, 10.0);
        assert!((h.distance_m - 1.0).abs() < 1e-12);
        assert!(h.incidence_rad.abs() < 1e-7);
        assert_eq!(h.material, Some(Material::Wall));
        assert_eq!(h.normal, [0.0, -1.0]);
        // Along +x from (1, 1.1): the diamond's upper-left face y = x - 0.8
        // at x = 1.9, at 45 degrees.
        let h = w.cast([1.0, 1.1], 0.0, 10.0);
        assert!((h.distance_m - 0.9).abs() < 1e-12, "{h:?}");
        assert!((h.incidence_rad - std::f64::consts::FRAC_PI_4).abs() < 1e-12);
        // 30 degrees above +x from (3, 0.5): reaches x = 4 (glass) at y = 0.5 + tan 30.
        let h = w.cast([3.0, 0.5], FRAC_PI_6, 10.0);
        assert!((h.distance_m - 1.0 / FRAC_PI_6.cos()).abs() < 1e-12);
        assert!((h.incidence_rad - FRAC_PI_6).abs() < 1e-12);
        assert_eq!(h.material, Some(Material::Glass));
        // Beyond the range: a miss at the maximum range.
        let h = w.cast([1.0, 1.0], FRAC_PI_2, 0.5);
        assert!(!h.is_hit());
        assert_eq!((h.distance_m, h.normal), (0.5, [0.0, 0.0]));
        assert!(h.incidence_rad.is_nan());
        // To the left, the inner face of the left wall at 1 m.
        let h = w.cast([1.0, 1.0], PI, 10.0);
        assert!((h.distance_m - 1.0).abs() < 1e-12);
    }

    #[test]
    fn axis_aligned_rays_along_piece_boundaries() {
        // A wall face on x = 3 cut into 2 m pieces at y = ..., -2, 0, 2, ...:
        // rays exactly along y = 0 and y = 2 (piece ends) must hit it.
        let w = World::new(vec![
            Polygon::rectangle([3.0, -10.0], [4.0, 10.0], Material::Wall).unwrap(),
            Polygon::rectangle([-3.0, -1.0], [-2.0, 0.0], Material::Wall).unwrap(),
        ]);
        for y in [-2.0, 0.0, 2.0, 10.0, -10.0] {
            let h = w.cast([0.0, y], 0.0, 30.0);
            assert!((h.distance_m - 3.0).abs() < 1e-12, "y = {y}: {h:?}");
        }
        let h = w.cast([0.0, -0.5], PI, 30.0);
        assert!((h.distance_m - 2.0).abs() < 1e-12, "{h:?}");
        let h = w.cast([3.5, -20.0], FRAC_PI_2, 30.0);
        assert!((h.distance_m - 10.0).abs() < 1e-12, "{h:?}");
    }

    #[test]
    fn batch_validates_and_matches_single_casts() {
        let w = room();
        assert!(w.cast_batch(&[[0.5, 0.5]], &[0.0, 1.0], 5.0).is_err());
        assert!(matches!(
            w.cast_batch(&[[0.5, f64::NAN]], &[0.0], 5.0),
            Err(SimError::InvalidValue { index: 0, .. })
        ));
        assert!(w.cast_batch(&[[0.5, 0.5]], &[f64::INFINITY], 5.0).is_err());
        assert!(w.cast_batch(&[[0.5, 0.5]], &[0.0], 0.0).is_err());
        let n = 10_000;
        let origins: Vec<[f64; 2]> = (0..n)
            .map(|i| {
                [
                    0.2 + 3.6 * (i as f64 * 0.618).fract(),
                    0.1 + 1.8 * (i as f64 * 0.414).fract(),
                ]
            })
            .collect();
        let angles: Vec<f64> = (0..n).map(|i| i as f64 * 0.01).collect();
        let par = w.cast_batch(&origins, &angles, 6.0).unwrap();
        let seq = w.cast_batch_sequential(&origins, &angles, 6.0).unwrap();
        assert_eq!(par.len(), n);
        for (i, (a, b)) in par.iter().zip(&seq).enumerate() {
            assert_eq!(a.distance_m, b.distance_m, "ray {i}");
            assert_eq!(a.material, b.material);
            assert_eq!(a.normal, w.cast(origins[i], angles[i], 6.0).normal);
            // Inside a closed room (the diamond aside) every ray hits something.
            assert!(a.is_hit() && a.distance_m < 4.5);
        }
    }

    /// The first crossing of the ray with any polygon edge, written
    /// independently of the ray caster (no pieces, no hierarchy).
    fn brute_force_distance(w: &World, o: [f64; 2], angle: f64, max: f64) -> Option<f64> {
        let d = [angle.cos(), angle.sin()];
        let mut best: Option<f64> = None;
        for p in w.polygons() {
            for ring in p.rings() {
                for (i, &a) in ring.iter().enumerate() {
                    let b = ring[(i + 1) % ring.len()];
                    let e = [b[0] - a[0], b[1] - a[1]];
                    let denom = d[0] * e[1] - d[1] * e[0];
                    if denom == 0.0 {
                        continue;
                    }
                    let w = [a[0] - o[0], a[1] - o[1]];
                    let t = (w[0] * e[1] - w[1] * e[0]) / denom;
                    let u = (w[0] * d[1] - w[1] * d[0]) / denom;
                    if t >= 0.0 && t < max && (0.0..=1.0).contains(&u) && best.is_none_or(|b| t < b)
                    {
                        best = Some(t);
                    }
                }
            }
        }
        best
    }

    #[test]
    fn casts_match_brute_force_over_polygon_edges() {
        use rand::RngExt;
        let w = World::builtin("office").unwrap();
        let [x0, y0, x1, y1] = w.bounds_m();
        let mut rng = crate::rng::sim_rng(3);
        let n = 10_000;
        let origins: Vec<[f64; 2]> = (0..n)
            .map(|_| {
                [
                    x0 + (x1 - x0) * rng.random::<f64>(),
                    y0 + (y1 - y0) * rng.random::<f64>(),
                ]
            })
            .collect();
        let angles: Vec<f64> = (0..n)
            .map(|_| rng.random::<f64>() * std::f64::consts::TAU)
            .collect();
        for max in [5.0, 30.0] {
            let batch = w.cast_batch(&origins, &angles, max).unwrap();
            let mut hits = 0;
            for (i, hit) in batch.iter().enumerate() {
                let one = w.cast(origins[i], angles[i], max);
                assert_eq!(
                    (hit.distance_m, hit.normal, hit.material),
                    (one.distance_m, one.normal, one.material)
                );
                match brute_force_distance(&w, origins[i], angles[i], max) {
                    Some(t) => {
                        assert!(
                            hit.is_hit() && (hit.distance_m - t).abs() <= 1e-9,
                            "ray {i}: {hit:?}, expected {t}"
                        );
                        hits += 1;
                    }
                    None => assert!(!hit.is_hit(), "ray {i}: {hit:?}, expected a miss"),
                }
            }
            assert!(hits > n / 2, "only {hits} hits up to {max} m");
        }
    }
}
