//! A simulated ring of ultrasound sensors.

use std::f64::consts::{PI, TAU};

use covmap_core::SonarModel;
use rand::{Rng, RngExt};
use rand_distr::StandardNormal;

use crate::error::{Result, check_param};
use crate::material::Material;
use crate::raycast::RayHit;
use crate::simulate::{Beam, RangeSensor};
use crate::world::World;

/// The most rays a sonar cone is simulated by.
pub const MAX_RAYS_PER_CONE: usize = 4096;

/// A ring of sonars and how they err.
///
/// Each sensor sits at the robot's centre (so readings are measured from the
/// pose, as [`covmap_core::ScanMap::integrate`] expects) and looks along
/// `pose.theta_rad + bearings_rad[i]`. One reading is simulated as follows:
///
/// 1. `rays_per_cone` rays spread evenly across the cone (`opening_angle_rad`)
///    are cast up to `max_range_m`. A ray echoes if the surface it hits is met
///    at an angle of incidence no larger than the material's critical angle
///    (`critical_angle_wall_rad`, `critical_angle_glass_rad`); beyond it the
///    sound is reflected away (a specular miss). The reading is the nearest
///    echo in the cone.
/// 2. If no ray echoes but some ray was reflected away, with probability
///    `multipath_probability` the reflected sound comes back over a second
///    surface: the reflected ray is traced, and the reading is half the path
///    out, across and straight back (never shorter than the first leg);
///    otherwise, or if the second leg meets nothing in range, there is no echo.
/// 3. An echo gets Gaussian noise of standard deviation `noise_std_m +
///    noise_std_per_m * range`, and is kept at least `min_range_m`.
/// 4. With probability `outlier_probability` the reading is replaced by a
///    short outlier, uniform between `min_range_m` and the reading (crosstalk,
///    a passing person).
///
/// A reading that ends at or beyond `max_range_m` is reported as exactly
/// `max_range_m`: no echo, as the core's models read it. Every reading takes
/// the same four samples from the generator (three uniform, one normal),
/// in sensor order, whatever the parameters and whether or not it uses
/// them, so changing a probability does not shift the samples of the other
/// sensors.
///
/// `Default` is 24 sensors 15 degrees apart, first straight ahead, with the cone
/// and maximum range of [`SonarModel::default`] (use [`SonarRing::with_model`]
/// to match another model).
///
/// # Example
/// ```
/// use covmap_core::{CoverageMap, Grid, Pose, ScanMap, SonarModel};
/// use covmap_sim::{sim_rng, RangeSensor, SonarRing, World};
/// let world = World::builtin("corridor").unwrap();
/// let sonar = SonarRing::default();
/// let pose = Pose::new(2.0, 1.3, 0.0);
/// let scan = sonar.scan(&world, &pose, &mut sim_rng(7)).unwrap();
/// assert_eq!(scan, sonar.scan(&world, &pose, &mut sim_rng(7)).unwrap());
/// let mut map = CoverageMap::new(Grid::covering(-0.5, -0.5, 17.5, 6.5, 0.05).unwrap());
/// map.integrate(&pose, &scan.ranges_m, &scan.bearings_rad, &SonarModel::default()).unwrap();
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct SonarRing {
    /// Mounting bearing of each sensor relative to the heading, radians.
    pub bearings_rad: Vec<f64>,
    /// Full opening angle of each cone, radians, in `(0, pi)`.
    pub opening_angle_rad: f64,
    /// Readings at or beyond this are "no echo", metres.
    pub max_range_m: f64,
    /// The shortest reading the sensor produces, metres, in `[0, max_range_m)`.
    pub min_range_m: f64,
    /// Rays cast across each cone (1 casts along the axis only).
    pub rays_per_cone: usize,
    /// Standard deviation of the range noise at zero range, metres.
    pub noise_std_m: f64,
    /// Growth of that standard deviation per metre of range.
    pub noise_std_per_m: f64,
    /// Probability that a reading is replaced by a short outlier.
    pub outlier_probability: f64,
    /// Probability that a specular miss returns a longer multipath reading.
    pub multipath_probability: f64,
    /// Largest angle of incidence at which a wall still echoes, radians, in `[0, pi/2]`.
    pub critical_angle_wall_rad: f64,
    /// Largest angle of incidence at which glass still echoes, radians, in `[0, pi/2]`.
    pub critical_angle_glass_rad: f64,
}

impl Default for SonarRing {
    fn default() -> Self {
        Self::ring(24)
    }
}

impl SonarRing {
    /// `count` sensors evenly spaced around the robot, the first straight
    /// ahead, with the default error model. A count of 0 or above
    /// [`MAX_BEAMS`](crate::MAX_BEAMS) makes a ring that validation rejects
    /// (and allocates no more than one bearing past the limit).
    pub fn ring(count: usize) -> Self {
        let count = count.min(crate::MAX_BEAMS + 1);
        let bearings = (0..count).map(|i| i as f64 * TAU / count as f64).collect();
        Self::with_bearings(bearings)
    }

    /// Sensors at the given bearings (radians), with the default error model.
    pub fn with_bearings(bearings_rad: Vec<f64>) -> Self {
        let model = SonarModel::default();
        Self {
            bearings_rad,
            opening_angle_rad: model.opening_angle_rad,
            max_range_m: model.range.max_range_m,
            min_range_m: 0.15,
            rays_per_cone: 7,
            noise_std_m: 0.01,
            noise_std_per_m: 0.01,
            outlier_probability: 0.01,
            multipath_probability: 0.25,
            critical_angle_wall_rad: 50f64.to_radians(),
            critical_angle_glass_rad: 10f64.to_radians(),
        }
    }

    /// The eight-sonar front array of the `sonar-8ring` data set: -90, -37.5,
    /// -22.5, -7.5, 7.5, 22.5, 37.5 and 90 degrees.
    pub fn front_eight() -> Self {
        Self::with_bearings(
            [-90.0, -37.5, -22.5, -7.5, 7.5, 22.5, 37.5, 90.0]
                .iter()
                .map(|d: &f64| d.to_radians())
                .collect(),
        )
    }

    /// The same ring with the opening angle and maximum range of `model`, so
    /// that the simulated cone is the one the map assumes.
    pub fn with_model(mut self, model: &SonarModel) -> Self {
        self.opening_angle_rad = model.opening_angle_rad;
        self.max_range_m = model.range.max_range_m;
        self
    }

    /// The critical angle of incidence of a material.
    pub fn critical_angle_rad(&self, material: Material) -> f64 {
        match material {
            Material::Wall => self.critical_angle_wall_rad,
            Material::Glass => self.critical_angle_glass_rad,
        }
    }

    /// One reading of a sensor looking along `axis_rad` from `origin`, with
    /// the four uniform/normal draws already taken.
    fn reading(&self, world: &World, origin: [f64; 2], axis_rad: f64, draws: [f64; 4]) -> f64 {
        let [u_outlier, u_short, u_multipath, z] = draws;
        let max = self.max_range_m;
        let n = self.rays_per_cone;
        let mut echo = f64::INFINITY;
        let mut specular: Option<(f64, RayHit)> = None;
        for k in 0..n {
            let offset = if n == 1 {
                0.0
            } else {
                self.opening_angle_rad * (k as f64 / (n - 1) as f64 - 0.5)
            };
            let angle = axis_rad + offset;
            let hit = world.cast(origin, angle, max);
            let Some(material) = hit.material else {
                continue;
            };
            if hit.incidence_rad <= self.critical_angle_rad(material) {
                echo = echo.min(hit.distance_m);
            } else if specular.is_none_or(|(_, s)| hit.distance_m < s.distance_m) {
                specular = Some((angle, hit));
            }
        }
        let mut range = if echo.is_finite() {
            echo
        } else if let (Some((angle, hit)), true) =
            (specular, u_multipath < self.multipath_probability)
        {
            self.multipath(world, origin, angle, &hit)
        } else {
            max
        };
        if range < max {
            range += z * (self.noise_std_m + self.noise_std_per_m * range);
            range = range.max(self.min_range_m);
            if range >= max {
                range = max;
            }
        }
        if u_outlier < self.outlier_probability {
            range = self.min_range_m + u_short * (range - self.min_range_m);
        }
        range
    }

    /// The reading of sound reflected at `hit` onto a second surface and back.
    fn multipath(&self, world: &World, origin: [f64; 2], angle: f64, hit: &RayHit) -> f64 {
        let (s, c) = angle.sin_cos();
        let d1 = hit.distance_m;
        let p = [origin[0] + d1 * c, origin[1] + d1 * s];
        let [nx, ny] = hit.normal;
        let dot = c * nx + s * ny;
        let r = [c - 2.0 * dot * nx, s - 2.0 * dot * ny];
        // Start a hair off the surface so the second leg does not re-hit it.
        let eps = 1e-9;
        let start = [p[0] + eps * r[0], p[1] + eps * r[1]];
        let second = world.cast(start, r[1].atan2(r[0]), 2.0 * self.max_range_m);
        if !second.is_hit() {
            return self.max_range_m;
        }
        let d2 = second.distance_m + eps;
        let q = [p[0] + d2 * r[0], p[1] + d2 * r[1]];
        let back = (q[0] - origin[0]).hypot(q[1] - origin[1]);
        (0.5 * (d1 + d2 + back)).min(self.max_range_m)
    }
}

impl RangeSensor for SonarRing {
    fn layout(&self) -> (&[f64], f64) {
        (&self.bearings_rad, self.max_range_m)
    }

    fn check_own(&self) -> Result<()> {
        let a = self.opening_angle_rad;
        check_param(
            "opening_angle_rad",
            a,
            a > 0.0 && a < PI,
            "an angle in (0, pi) radians",
        )?;
        let max = self.max_range_m;
        let min = self.min_range_m;
        check_param(
            "min_range_m",
            min,
            min >= 0.0 && min < max,
            "a distance in [0, max_range_m)",
        )?;
        check_param(
            "rays_per_cone",
            self.rays_per_cone as f64,
            (1..=MAX_RAYS_PER_CONE).contains(&self.rays_per_cone),
            "a ray count from 1 to 4096",
        )?;
        check_param(
            "noise_std_m",
            self.noise_std_m,
            self.noise_std_m >= 0.0,
            "a non-negative standard deviation",
        )?;
        check_param(
            "noise_std_per_m",
            self.noise_std_per_m,
            self.noise_std_per_m >= 0.0,
            "a non-negative growth",
        )?;
        for (name, p) in [
            ("outlier_probability", self.outlier_probability),
            ("multipath_probability", self.multipath_probability),
        ] {
            check_param(name, p, (0.0..=1.0).contains(&p), "a probability in [0, 1]")?;
        }
        for (name, c) in [
            ("critical_angle_wall_rad", self.critical_angle_wall_rad),
            ("critical_angle_glass_rad", self.critical_angle_glass_rad),
        ] {
            check_param(
                name,
                c,
                (0.0..=PI / 2.0).contains(&c),
                "an angle in [0, pi/2] radians",
            )?;
        }
        Ok(())
    }

    fn read_beam<R: Rng + ?Sized>(&self, world: &World, beam: Beam, rng: &mut R) -> f64 {
        let draws = [
            rng.random(),
            rng.random(),
            rng.random(),
            rng.sample(StandardNormal),
        ];
        self.reading(world, beam.origin_m, beam.direction_rad, draws)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::SimError;
    use crate::polygon::Polygon;
    use crate::rng::sim_rng;
    use covmap_core::Pose;

    /// A long wall whose face is the line y = 0 (obstacle below), glass from x = 10 on.
    fn wall() -> World {
        World::new(vec![
            Polygon::rectangle([-20.0, -1.0], [10.0, 0.0], Material::Wall).unwrap(),
            Polygon::rectangle([10.0, -1.0], [30.0, 0.0], Material::Glass).unwrap(),
        ])
    }

    fn quiet(bearings: Vec<f64>) -> SonarRing {
        SonarRing {
            noise_std_m: 0.0,
            noise_std_per_m: 0.0,
            outlier_probability: 0.0,
            multipath_probability: 0.0,
            ..SonarRing::with_bearings(bearings)
        }
    }

    fn mean_std(v: &[f64]) -> (f64, f64) {
        let n = v.len() as f64;
        let m = v.iter().sum::<f64>() / n;
        (
            m,
            (v.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (n - 1.0)).sqrt(),
        )
    }

    #[test]
    fn head_on_reading_is_the_distance() {
        // Looking straight down at the wall from 2 m: every ray of the cone
        // echoes, the nearest is the axis.
        let s = quiet(vec![0.0]);
        let pose = Pose::new(0.0, 2.0, -PI / 2.0);
        let scan = s.scan(&wall(), &pose, &mut sim_rng(1)).unwrap();
        assert!((scan.ranges_m[0] - 2.0).abs() < 1e-12);
    }

    #[test]
    fn nearest_echo_in_the_cone() {
        // A pillar 1.5 m ahead slightly off the axis (inside the 15 degree cone)
        // shortens the reading although the axis ray passes it.
        let world = World::new(vec![
            Polygon::rectangle([3.0, -5.0], [3.2, 5.0], Material::Wall).unwrap(),
            Polygon::rectangle([1.5, 0.12], [1.6, 0.16], Material::Wall).unwrap(),
        ]);
        let s = quiet(vec![0.0]);
        let r = s
            .scan(&world, &Pose::new(0.0, 0.0, 0.0), &mut sim_rng(1))
            .unwrap()
            .ranges_m[0];
        assert!(r > 1.5 && r < 1.51, "{r}");
        let mut axis_only = s;
        axis_only.rays_per_cone = 1;
        let r = axis_only
            .scan(&world, &Pose::new(0.0, 0.0, 0.0), &mut sim_rng(1))
            .unwrap()
            .ranges_m[0];
        assert!((r - 3.0).abs() < 1e-12);
    }

    #[test]
    fn specular_miss_past_the_critical_angle() {
        // Looking at the wall at 60 degrees from its normal: past the wall's
        // 50 degrees even at the cone's edge (52.5): no echo.
        let s = quiet(vec![0.0]);
        let w = wall();
        let looking = |x: f64, incidence_deg: f64| {
            let heading = -(90f64 - incidence_deg).to_radians();
            s.scan(&w, &Pose::new(x, 1.0, heading), &mut sim_rng(3))
                .unwrap()
                .ranges_m[0]
        };
        assert_eq!(looking(0.0, 60.0), s.max_range_m);
        // At 40 degrees the wall echoes, at the nearest ray of the cone (32.5).
        let r = looking(0.0, 40.0);
        assert!((r - 1.0 / 32.5f64.to_radians().cos()).abs() < 1e-9, "{r}");
        // Glass at 15 degrees: the cone spans 7.5 to 22.5, the glass echoes only
        // up to 10 degrees: the ray at 7.5 degrees echoes.
        let r = looking(15.0, 15.0);
        assert!((r - 1.0 / 7.5f64.to_radians().cos()).abs() < 1e-9, "{r}");
        // Glass at 25 degrees: no ray within 10 degrees, no echo; a wall would echo.
        assert_eq!(looking(15.0, 25.0), s.max_range_m);
        assert!(looking(0.0, 25.0) < 1.2);
    }

    #[test]
    fn multipath_reading_is_longer() {
        // A corner: the wall y = 0 and a wall x = 3. Looking at the floor wall
        // at 70 degrees incidence the sound glances off to the x = 3 wall.
        let world = World::new(vec![
            Polygon::rectangle([-5.0, -1.0], [5.0, 0.0], Material::Wall).unwrap(),
            Polygon::rectangle([3.0, 0.0], [4.0, 5.0], Material::Wall).unwrap(),
        ]);
        let mut s = quiet(vec![0.0]);
        s.multipath_probability = 1.0;
        s.rays_per_cone = 1;
        let heading = -(20f64).to_radians();
        let r = s
            .scan(&world, &Pose::new(0.0, 0.5, heading), &mut sim_rng(1))
            .unwrap()
            .ranges_m[0];
        let d1 = 0.5 / 20f64.to_radians().sin();
        assert!(r > d1 && r < s.max_range_m, "{r} vs first leg {d1}");
        // The mirror image of the origin in y = 0 gives the exact path.
        let p = [0.5 / 20f64.to_radians().tan(), 0.0];
        let q = [3.0, (3.0 - p[0]) * 20f64.to_radians().tan()];
        let d2 = (q[0] - p[0]).hypot(q[1]);
        let back = q[0].hypot(q[1] - 0.5);
        assert!((r - 0.5 * (d1 + d2 + back)).abs() < 1e-6, "{r}");
        s.multipath_probability = 0.0;
        let r = s
            .scan(&world, &Pose::new(0.0, 0.5, heading), &mut sim_rng(1))
            .unwrap()
            .ranges_m[0];
        assert_eq!(r, s.max_range_m);
    }

    #[test]
    fn noise_statistics() {
        // Head-on at 2 m: mean 2, spread 0.01 + 0.01 * 2 = 0.03 (a few draws
        // fall outside the clamp, none here: 0.15 is 60 sigma away).
        let mut s = quiet(vec![0.0]);
        s.noise_std_m = 0.01;
        s.noise_std_per_m = 0.01;
        s.rays_per_cone = 1;
        let w = wall();
        let pose = Pose::new(0.0, 2.0, -PI / 2.0);
        let mut rng = sim_rng(42);
        let v: Vec<f64> = (0..20_000)
            .map(|_| s.scan(&w, &pose, &mut rng).unwrap().ranges_m[0])
            .collect();
        let (m, sd) = mean_std(&v);
        // Standard error of the mean: 0.03 / sqrt(20000) = 2.1e-4; allow 5 of them.
        assert!((m - 2.0).abs() < 1.1e-3, "mean {m}");
        // The sample sd of 20000 normals is within 2 % of the truth (4 standard errors).
        assert!((sd - 0.03).abs() < 0.03 * 0.02, "sd {sd}");
        // The spread grows with range: at 4 m, 0.05.
        let far = Pose::new(0.0, 4.0, -PI / 2.0);
        let v: Vec<f64> = (0..20_000)
            .map(|_| s.scan(&w, &far, &mut rng).unwrap().ranges_m[0])
            .collect();
        let (m, sd) = mean_std(&v);
        assert!(
            (m - 4.0).abs() < 2e-3 && (sd - 0.05).abs() < 0.05 * 0.02,
            "{m} {sd}"
        );
    }

    #[test]
    fn outliers_are_short_and_as_frequent_as_asked() {
        let mut s = quiet(vec![0.0]);
        s.outlier_probability = 0.2;
        s.rays_per_cone = 1;
        let w = wall();
        let pose = Pose::new(0.0, 3.0, -PI / 2.0);
        let mut rng = sim_rng(5);
        let v: Vec<f64> = (0..10_000)
            .map(|_| s.scan(&w, &pose, &mut rng).unwrap().ranges_m[0])
            .collect();
        let short = v.iter().filter(|&&r| r < 3.0 - 1e-9).count() as f64 / v.len() as f64;
        // Binomial sd: sqrt(0.2 * 0.8 / 10000) = 0.004; allow 5 of them.
        assert!((short - 0.2).abs() < 0.02, "{short}");
        assert!(v.iter().all(|&r| (s.min_range_m..=3.0 + 1e-9).contains(&r)));
        // Uniform between 0.15 and 3: their mean is near 1.575 (standard error 0.018).
        let outl: Vec<f64> = v.into_iter().filter(|&r| r < 3.0 - 1e-9).collect();
        let (m, _) = mean_std(&outl);
        assert!((m - 1.575).abs() < 0.08, "{m}");
    }

    #[test]
    fn same_seed_same_scan_and_validation() {
        let w = World::builtin("corridor").unwrap();
        let s = SonarRing::default();
        let pose = Pose::new(3.0, 1.2, 0.4);
        let a = s.scan(&w, &pose, &mut sim_rng(9)).unwrap();
        assert_eq!(a, s.scan(&w, &pose, &mut sim_rng(9)).unwrap());
        assert_ne!(
            a.ranges_m,
            s.scan(&w, &pose, &mut sim_rng(10)).unwrap().ranges_m
        );
        assert_eq!(a.ranges_m.len(), 24);
        assert_eq!(SonarRing::front_eight().bearings_rad.len(), 8);
        let mut bad = s.clone();
        bad.outlier_probability = 1.5;
        assert!(matches!(
            bad.scan(&w, &pose, &mut sim_rng(1)),
            Err(SimError::InvalidParameter {
                name: "outlier_probability",
                ..
            })
        ));
        let mut bad = s.clone();
        bad.min_range_m = 6.0;
        assert!(bad.validate().is_err());
        let mut bad = s.clone();
        bad.bearings_rad[3] = f64::NAN;
        assert!(bad.validate().is_err());
        let mut bad = s.clone();
        bad.rays_per_cone = 0;
        assert!(bad.validate().is_err());
        assert!(
            s.scan(&w, &Pose::new(f64::NAN, 0.0, 0.0), &mut sim_rng(1))
                .is_err()
        );
    }
}
