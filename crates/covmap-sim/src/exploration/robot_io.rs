//! The simulated robot the exploration loop drives: its sensor and its
//! drive in the true world ([`covmap_core::exploration::ScanSource`] and
//! [`covmap_core::exploration::Motion`]).

use std::sync::Arc;

use covmap_core::exploration::{Motion, ScanSource, Travel};
use covmap_core::{CovmapError, Pose};
use parry2d_f64::query::PointQuery;

use super::sensor::SimSensor;
use crate::rng::sim_rng_stream;
use crate::robot::Robot;
use crate::world::{World, vector};

/// How far short of a contact the robot stops, metres: its last free point,
/// from which it can drive away again (a disc touching an obstacle cannot
/// move at all in [`Robot::free_travel_m`]).
pub const STANDOFF_M: f64 = 0.005;

/// The simulated sensor in the true world: scan `k` of a run (counting from
/// 0) draws its noise from stream `k` of the run's seed
/// ([`sim_rng_stream`]), so a run depends on its seed alone.
#[derive(Clone, Debug)]
pub struct WorldScans {
    world: Arc<World>,
    sensor: SimSensor,
    seed: u64,
    next: u64,
}

impl WorldScans {
    /// The sensor in `world`, its first scan drawing from stream 0 of `seed`.
    pub fn new(world: Arc<World>, sensor: SimSensor, seed: u64) -> Self {
        Self {
            world,
            sensor,
            seed,
            next: 0,
        }
    }
    /// The sensor.
    pub fn sensor(&self) -> &SimSensor {
        &self.sensor
    }
}

impl ScanSource for WorldScans {
    fn bearings(&self) -> &[f64] {
        self.sensor.bearings_rad()
    }

    fn scan(&mut self, pose: &Pose) -> covmap_core::Result<Vec<f64>> {
        let mut rng = sim_rng_stream(self.seed, self.next);
        self.next += 1;
        self.sensor
            .ranges(&self.world, pose, &mut rng)
            .map_err(|e| CovmapError::Robot(e.to_string()))
    }
}

/// The disc robot driving in the true world: a straight drive goes as far
/// as [`Robot::free_travel_m`] lets it, and stops [`STANDOFF_M`] short of a
/// contact (a target itself closer than that to an obstacle ahead is a
/// contact too); the contact point is the point of the world's boundary
/// nearest to the disc's centre where it touched.
#[derive(Clone, Debug)]
pub struct WorldMotion {
    world: Arc<World>,
    robot: Robot,
}

impl WorldMotion {
    /// `robot` in `world`.
    pub fn new(world: Arc<World>, robot: Robot) -> Self {
        Self { world, robot }
    }
    /// The robot's body.
    pub fn robot(&self) -> &Robot {
        &self.robot
    }
}

impl Motion for WorldMotion {
    fn drive(&mut self, from_m: [f64; 2], to_m: [f64; 2]) -> covmap_core::Result<Travel> {
        let length = (to_m[0] - from_m[0]).hypot(to_m[1] - from_m[1]);
        if !(length > 0.0) {
            return Ok(Travel {
                travelled_m: 0.0,
                contact_m: None,
            });
        }
        let direction = [
            (to_m[0] - from_m[0]) / length,
            (to_m[1] - from_m[1]) / length,
        ];
        // A target closer than the stand-off to an obstacle ahead is a
        // contact too: the robot never stops touching (it could not move off
        // again).
        let beyond = [
            to_m[0] + direction[0] * STANDOFF_M,
            to_m[1] + direction[1] * STANDOFF_M,
        ];
        let free = self.robot.free_travel_m(&self.world, from_m, beyond);
        // The whole way is free when the cast returns its whole length,
        // which it computes as this does: `length + STANDOFF_M` may differ
        // from it in the last bit, and a free drive would end in a phantom
        // contact.
        let cast_m = (beyond[0] - from_m[0]).hypot(beyond[1] - from_m[1]);
        if free >= cast_m {
            return Ok(Travel {
                travelled_m: length,
                contact_m: None,
            });
        }
        let touching = [
            from_m[0] + direction[0] * free,
            from_m[1] + direction[1] * free,
        ];
        let contact_m = match self.world.geometry() {
            Some(g) => {
                let p = g
                    .boundary
                    .project_local_point(vector(touching), false)
                    .point;
                [p.x, p.y]
            }
            // Nothing to touch: unreachable, as the whole way is free then.
            None => touching,
        };
        Ok(Travel {
            travelled_m: (free - STANDOFF_M).clamp(0.0, length),
            contact_m: Some(contact_m),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::RngExt;

    /// Drives through open space end without a contact and cover their
    /// whole length, whatever the rounding of their length; a drive into a
    /// wall ends in a contact on the wall, a radius (and the stand-off)
    /// from where the robot stopped.
    #[test]
    fn contacts_are_where_the_disc_touched_and_nowhere_else() {
        let world = Arc::new(World::builtin("corridor").unwrap());
        let mut motion = WorldMotion::new(Arc::clone(&world), Robot::new(0.25).unwrap());
        let mut rng = sim_rng_stream(7, 0);
        // Along the corridor's centre line, in short hops of every length
        // and direction, well clear of its walls (1.3 m either side).
        for _ in 0..2000 {
            let from = [rng.random_range(2.0..15.0), rng.random_range(1.0..1.6)];
            let angle: f64 = rng.random_range(-std::f64::consts::PI..std::f64::consts::PI);
            let length: f64 = rng.random_range(0.01..0.5);
            let to = [
                from[0] + length * angle.cos(),
                from[1] + length * angle.sin(),
            ];
            let travel = motion.drive(from, to).unwrap();
            assert_eq!(
                travel.contact_m, None,
                "phantom contact from {from:?} to {to:?}"
            );
            assert_eq!(travel.travelled_m, (to[0] - from[0]).hypot(to[1] - from[1]));
        }
        // Straight into the south wall (its face is y = 0) from y = 1.
        let travel = motion.drive([2.0, 1.0], [2.0, -0.5]).unwrap();
        let contact = travel.contact_m.expect("the wall is touched");
        assert!(
            (contact[0] - 2.0).abs() < 1e-9 && contact[1].abs() < 1e-9,
            "{contact:?}"
        );
        let stopped = 1.0 - travel.travelled_m;
        assert!(
            (stopped - 0.25 - STANDOFF_M).abs() < 1e-6,
            "stopped at y = {stopped}"
        );
    }
}
