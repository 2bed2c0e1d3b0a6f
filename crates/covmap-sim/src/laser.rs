//! A simulated laser range finder.

use std::f64::consts::PI;

use covmap_core::LaserModel;
use rand::{Rng, RngExt};
use rand_distr::StandardNormal;

use crate::error::{Result, check_param};
use crate::simulate::{Beam, RangeSensor};
use crate::world::World;

/// A laser scanner: thin beams, small Gaussian noise.
///
/// Each beam is one ray from the pose; a hit at distance `d` reads
/// `d + noise_std_m * z` (z standard normal, one draw per beam in beam order),
/// kept non-negative; a beam that meets nothing before `max_range_m`, or whose
/// noisy reading reaches it, reads exactly `max_range_m` ("no echo"). Every
/// surface, glass included, reflects the laser.
///
/// # Example
/// ```
/// use covmap_core::Pose;
/// use covmap_sim::{sim_rng, Laser, RangeSensor, World};
/// let laser = Laser::sick_361();
/// assert_eq!(laser.bearings_rad.len(), 361);
/// let world = World::builtin("office").unwrap();
/// let scan = laser.scan(&world, &Pose::new(2.0, 10.0, 0.0), &mut sim_rng(1)).unwrap();
/// assert!(scan.ranges_m.iter().all(|&r| r > 0.0 && r <= laser.max_range_m));
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Laser {
    /// Bearing of each beam relative to the heading, radians.
    pub bearings_rad: Vec<f64>,
    /// Readings at or beyond this are "no echo", metres.
    pub max_range_m: f64,
    /// Standard deviation of the range noise, metres.
    pub noise_std_m: f64,
}

impl Laser {
    /// `beams` beams spread evenly over `fov_rad` centred on the heading, the
    /// first at `-fov_rad / 2` and the last at `+fov_rad / 2`; maximum range
    /// from [`LaserModel::default`], 1 cm noise.
    pub fn new(beams: usize, fov_rad: f64) -> Result<Self> {
        check_param(
            "beams",
            beams as f64,
            (2..=crate::MAX_BEAMS).contains(&beams),
            "from 2 to 65536 beams",
        )?;
        check_param(
            "fov_rad",
            fov_rad,
            fov_rad > 0.0 && fov_rad <= 2.0 * PI,
            "an angle in (0, 2 pi] radians",
        )?;
        let step = fov_rad / (beams - 1) as f64;
        Ok(Self::with_bearings(
            (0..beams)
                .map(|i| -0.5 * fov_rad + i as f64 * step)
                .collect(),
        ))
    }

    /// Beams at the given bearings (radians), with the default range and noise.
    pub fn with_bearings(bearings_rad: Vec<f64>) -> Self {
        Self {
            bearings_rad,
            max_range_m: LaserModel::default().range.max_range_m,
            noise_std_m: 0.01,
        }
    }

    /// 180 beams one degree apart from -90 degrees (to +89), the layout of
    /// the 180-beam CARMEN logs.
    pub fn sick_180() -> Self {
        Self::with_bearings((0..180).map(|i| (i as f64 - 90.0).to_radians()).collect())
    }

    /// 361 beams half a degree apart from -90 to +90 degrees.
    pub fn sick_361() -> Self {
        Self::with_bearings(
            (0..361)
                .map(|i| (0.5 * i as f64 - 90.0).to_radians())
                .collect(),
        )
    }
}

impl RangeSensor for Laser {
    fn layout(&self) -> (&[f64], f64) {
        (&self.bearings_rad, self.max_range_m)
    }

    fn check_own(&self) -> Result<()> {
        check_param(
            "noise_std_m",
            self.noise_std_m,
            self.noise_std_m >= 0.0,
            "a non-negative standard deviation",
        )
    }

    fn read_beam<R: Rng + ?Sized>(&self, world: &World, beam: Beam, rng: &mut R) -> f64 {
        let z: f64 = rng.sample(StandardNormal);
        let max = self.max_range_m;
        let hit = world.cast(beam.origin_m, beam.direction_rad, max);
        if !hit.is_hit() {
            return max;
        }
        let r = (hit.distance_m + self.noise_std_m * z).max(0.0);
        if r >= max { max } else { r }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::Material;
    use crate::polygon::Polygon;
    use crate::rng::sim_rng;
    use covmap_core::Pose;

    #[test]
    fn layouts() {
        let l = Laser::sick_361();
        assert!((l.bearings_rad[0] + PI / 2.0).abs() < 1e-15);
        assert!((l.bearings_rad[360] - PI / 2.0).abs() < 1e-15);
        let l = Laser::sick_180();
        assert!((l.bearings_rad[179] - 89f64.to_radians()).abs() < 1e-15);
        let l = Laser::new(361, PI).unwrap();
        assert!((l.bearings_rad[1] - l.bearings_rad[0] - 0.5f64.to_radians()).abs() < 1e-12);
        assert!(Laser::new(1, PI).is_err());
        assert!(Laser::new(10, 0.0).is_err());
    }

    #[test]
    fn readings_against_geometry_and_noise() {
        // A wall face on x = 3 spanning y in [-10, 10].
        let w = World::new(vec![
            Polygon::rectangle([3.0, -10.0], [4.0, 10.0], Material::Glass).unwrap(),
        ]);
        let mut l = Laser::sick_361();
        l.noise_std_m = 0.0;
        let s = l
            .scan(&w, &Pose::new(0.0, 0.0, 0.0), &mut sim_rng(2))
            .unwrap();
        for (r, b) in s.ranges_m.iter().zip(&s.bearings_rad) {
            let expect = if b.cos() > 1e-9 {
                (3.0 / b.cos()).min(30.0)
            } else {
                30.0
            };
            // Beyond |y| = 10 the beam passes the wall's end.
            let expect = if (3.0 * b.tan()).abs() > 10.0 {
                30.0
            } else {
                expect
            };
            assert!((r - expect).abs() < 1e-9, "bearing {b}: {r} vs {expect}");
        }
        l.noise_std_m = 0.02;
        let mut rng = sim_rng(11);
        let v: Vec<f64> = (0..5000)
            .map(|_| {
                l.scan(&w, &Pose::new(0.0, 0.0, 0.0), &mut rng)
                    .unwrap()
                    .ranges_m[180]
            })
            .collect();
        let m = v.iter().sum::<f64>() / v.len() as f64;
        let sd = (v.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (v.len() - 1) as f64).sqrt();
        // 5 standard errors: 0.02 / sqrt(5000) = 2.8e-4 for the mean, 1 % for the sd.
        assert!((m - 3.0).abs() < 1.5e-3, "{m}");
        assert!((sd - 0.02).abs() < 0.02 * 0.05, "{sd}");
    }

    #[test]
    fn same_seed_same_scan() {
        let w = World::builtin("office").unwrap();
        let l = Laser::sick_180();
        let p = Pose::new(2.0, 10.0, 0.3);
        let a = l.scan(&w, &p, &mut sim_rng(4)).unwrap();
        assert_eq!(a, l.scan(&w, &p, &mut sim_rng(4)).unwrap());
        assert_ne!(a, l.scan(&w, &p, &mut sim_rng(5)).unwrap());
        let mut bad = l.clone();
        bad.noise_std_m = -1.0;
        assert!(bad.scan(&w, &p, &mut sim_rng(4)).is_err());
    }
}
