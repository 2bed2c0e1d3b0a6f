//! Simulating scans along a path.

use covmap_core::{Bearings, Log, Pose};
use rand::Rng;

use crate::error::{Result, check_bearings, check_param};
use crate::rng::sim_rng_stream;
use crate::scan::Scan;
use crate::world::World;

/// A beam to read: where it starts (world metres) and its absolute
/// direction (radians).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Beam {
    /// Where the beam starts, world metres.
    pub origin_m: [f64; 2],
    /// Its direction in the world, radians.
    pub direction_rad: f64,
}

/// A simulated range sensor ([`crate::SonarRing`], [`crate::Laser`]).
pub trait RangeSensor {
    /// The bearing of each reading relative to the heading, radians, and
    /// the range at or beyond which a reading is "no echo", metres.
    fn layout(&self) -> (&[f64], f64);
    /// Errors unless every parameter of the sensor's own (besides its
    /// bearings and maximum range) lies in its valid range.
    fn check_own(&self) -> Result<()>;
    /// One reading along `beam`, every random draw from `rng`. A sensor
    /// takes the same draws for every reading, whatever the reading turns
    /// out to be, so that a change of one reading never shifts the samples
    /// of the next. The parameters are taken as valid:
    /// [`RangeSensor::scan`] checks them first.
    fn read_beam<R: Rng + ?Sized>(&self, world: &World, beam: Beam, rng: &mut R) -> f64;

    /// The bearing of each reading relative to the heading, radians.
    fn bearings_rad(&self) -> &[f64] {
        self.layout().0
    }
    /// Readings at or beyond this are "no echo", metres.
    fn max_range_m(&self) -> f64 {
        self.layout().1
    }
    /// Errors unless every parameter lies in its valid range: from 1 to
    /// 65 536 finite bearings, a positive maximum range, and the sensor's
    /// own ([`RangeSensor::check_own`]).
    fn validate(&self) -> Result<()> {
        let (bearings_rad, max_range_m) = self.layout();
        check_bearings(bearings_rad, "bearing")?;
        check_param(
            "max_range_m",
            max_range_m,
            max_range_m > 0.0,
            "a positive distance",
        )?;
        self.check_own()
    }

    /// One scan taken from `pose`, a reading per bearing in bearing order,
    /// every random draw from `rng`. Errors on invalid parameters or a
    /// non-finite pose.
    fn scan<R: Rng + ?Sized>(&self, world: &World, pose: &Pose, rng: &mut R) -> Result<Scan> {
        self.validate()?;
        check_pose(pose, self.bearings_rad())?;
        let origin_m = [pose.x_m, pose.y_m];
        let ranges_m = self
            .bearings_rad()
            .iter()
            .map(|&bearing| {
                let direction_rad = pose.theta_rad + bearing;
                self.read_beam(
                    world,
                    Beam {
                        origin_m,
                        direction_rad,
                    },
                    rng,
                )
            })
            .collect();
        Ok(Scan {
            pose: *pose,
            ranges_m,
            bearings_rad: self.bearings_rad().to_vec(),
        })
    }
}

/// One scan from each pose. Scan `i` draws from its own stream `i` of a
/// generator seeded with `seed` ([`crate::sim_rng_stream`]), so the result
/// depends on the seed alone, never on threads: with the `parallel` feature the
/// poses run on rayon.
///
/// # Example
/// ```
/// use covmap_core::Pose;
/// use covmap_sim::{simulate, SonarRing, World};
/// let world = World::builtin("corridor").unwrap();
/// let poses: Vec<Pose> = (0..10).map(|i| Pose::new(1.0 + 0.2 * i as f64, 1.3, 0.0)).collect();
/// let scans = simulate(&SonarRing::default(), &world, &poses, 42).unwrap();
/// assert_eq!(scans.len(), 10);
/// assert_eq!(scans, simulate(&SonarRing::default(), &world, &poses, 42).unwrap());
/// ```
pub fn simulate<S: RangeSensor + Sync>(
    sensor: &S,
    world: &World,
    poses: &[Pose],
    seed: u64,
) -> Result<Vec<Scan>> {
    sensor.validate()?;
    for p in poses {
        check_pose(p, sensor.bearings_rad())?;
    }
    let one =
        |(i, pose): (usize, &Pose)| sensor.scan(world, pose, &mut sim_rng_stream(seed, i as u64));
    covmap_core::parallel::map(poses.iter().enumerate().collect(), one)
        .into_iter()
        .collect()
}

/// [`simulate`]'s scans as a [`Log`]: scan `i` from `poses[i]` at time
/// `i` seconds, the sensor's bearings and maximum range, the sensor at the
/// robot's pose; the same seed gives the same log.
///
/// # Example
/// ```
/// use covmap_core::Pose;
/// use covmap_sim::{record, Laser, World};
/// let world = World::builtin("corridor").unwrap();
/// let poses: Vec<Pose> = (0..5).map(|i| Pose::new(1.0 + 0.2 * i as f64, 1.3, 0.0)).collect();
/// let log = record(&Laser::sick_180(), &world, &poses, 7).unwrap();
/// assert_eq!((log.len(), log.beams()), (5, Laser::sick_180().bearings_rad.len()));
/// ```
pub fn record<S: RangeSensor + Sync>(
    sensor: &S,
    world: &World,
    poses: &[Pose],
    seed: u64,
) -> Result<Log> {
    let scans = simulate(sensor, world, poses, seed)?;
    let ranges = scans.into_iter().flat_map(|s| s.ranges_m).collect();
    Ok(Log::new(
        poses.to_vec(),
        (0..poses.len()).map(|i| i as f64).collect(),
        ranges,
        Bearings::Fixed(sensor.bearings_rad().to_vec()),
        sensor.max_range_m(),
    )?)
}

/// Errors unless every component of the pose is finite and every beam
/// direction from it (heading plus one of `bearings_rad`) is: the poses
/// and bearings a map's `integrate` refuses are refused here too.
pub(crate) fn check_pose(pose: &Pose, bearings_rad: &[f64]) -> Result<()> {
    pose.check_finite()?;
    Ok(pose.check_bearings(bearings_rad)?)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::SimError;
    use crate::laser::Laser;
    use crate::sonar::SonarRing;
    use covmap_core::CovmapError;

    #[test]
    fn a_heading_whose_beams_overflow_is_refused_as_integrate_refuses_it() {
        let world = World::builtin("corridor").unwrap();
        let laser = Laser::with_bearings(vec![1e308, 0.0]);
        let pose = Pose::new(1.0, 1.0, 1e308);
        let err = laser
            .scan(&world, &pose, &mut sim_rng_stream(1, 0))
            .unwrap_err();
        assert!(
            matches!(
                err,
                SimError::Core(CovmapError::InvalidBearing { index: 0, .. })
            ),
            "{err}"
        );
        assert!(simulate(&laser, &world, &[pose], 1).is_err());
        use covmap_core::ScanMap;
        let mut map =
            covmap_core::CoverageMap::new(covmap_core::Grid::new([0.0, 0.0], 0.1, 30, 30).unwrap());
        let model = covmap_core::LaserModel::default();
        assert!(
            map.integrate(&pose, &[1.0, 1.0], laser.bearings_rad(), &model)
                .is_err()
        );
    }

    #[test]
    fn parallel_simulation_equals_the_sequential_loop() {
        let world = World::builtin("office").unwrap();
        let poses: Vec<Pose> = (0..40)
            .map(|i| Pose::new(1.0 + 0.7 * i as f64, 9.7, 0.1 * i as f64))
            .collect();
        let sonar = SonarRing::default();
        let laser = Laser::sick_361();
        let scans = simulate(&sonar, &world, &poses, 11).unwrap();
        let lasers = simulate(&laser, &world, &poses, 11).unwrap();
        for (i, p) in poses.iter().enumerate() {
            assert_eq!(
                scans[i],
                sonar
                    .scan(&world, p, &mut sim_rng_stream(11, i as u64))
                    .unwrap()
            );
            assert_eq!(
                lasers[i],
                laser
                    .scan(&world, p, &mut sim_rng_stream(11, i as u64))
                    .unwrap()
            );
        }
        assert_ne!(scans, simulate(&sonar, &world, &poses, 12).unwrap());
        let log = record(&laser, &world, &poses, 11).unwrap();
        for (i, scan) in lasers.iter().enumerate() {
            assert_eq!(log.scan_ranges(i), &scan.ranges_m[..]);
            assert_eq!(log.poses()[i], poses[i]);
        }
        assert_eq!(log.max_range_m(), laser.max_range_m());
        let bad = [Pose::new(1.0, f64::INFINITY, 0.0)];
        assert!(simulate(&sonar, &world, &bad, 1).is_err());
    }
}
