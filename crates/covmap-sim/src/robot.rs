//! The robot's body: a disc, and whether it fits.

use covmap_core::Pose;
use parry2d_f64::math::{Pose as ParryPose, Vector};
use parry2d_f64::query::{self, ShapeCastOptions};
use parry2d_f64::shape::Ball;

use crate::error::{Result, check_param};
use crate::world::{World, vector};

/// A disc-shaped robot (the B21r is a disc about 0.26 m in radius).
///
/// # Example
/// ```
/// use covmap_core::Pose;
/// use covmap_sim::{Robot, World};
/// let world = World::builtin("corridor").unwrap();
/// let robot = Robot::new(0.25).unwrap();
/// assert!(!robot.collides(&world, &Pose::new(2.0, 1.3, 0.0)));
/// assert!(robot.collides(&world, &Pose::new(2.0, 0.1, 0.0))); // against the wall
/// // Driving into the west end wall (inner face x = 0) stops 0.25 m short of it.
/// let free = robot.free_travel_m(&world, [2.0, 1.3], [-1.0, 1.3]);
/// assert!((free - 1.75).abs() < 1e-6);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Robot {
    radius_m: f64,
}

impl Robot {
    /// A disc of `radius_m` (positive, finite).
    pub fn new(radius_m: f64) -> Result<Self> {
        check_param(
            "radius_m",
            radius_m,
            radius_m > 0.0,
            "a positive, finite radius",
        )?;
        Ok(Self { radius_m })
    }

    /// The disc's radius, metres.
    pub fn radius_m(&self) -> f64 {
        self.radius_m
    }

    /// The gap between the disc at `position_m` and the nearest obstacle,
    /// metres: negative when they overlap (the centre inside an obstacle gives
    /// at most `-radius_m`).
    pub fn clearance_m(&self, world: &World, position_m: [f64; 2]) -> f64 {
        let d = world.distance_to_boundary_m(position_m);
        if world.contains_point(position_m) {
            -d - self.radius_m
        } else {
            d - self.radius_m
        }
    }

    /// Whether the disc at the pose overlaps (or touches) an obstacle. A
    /// non-finite pose collides.
    pub fn collides(&self, world: &World, pose: &Pose) -> bool {
        let p = [pose.x_m, pose.y_m];
        if !(p[0].is_finite() && p[1].is_finite()) {
            return true;
        }
        self.clearance_m(world, p) <= 0.0
    }

    /// How far the disc can drive in a straight line from `from_m` towards
    /// `to_m` before it touches an obstacle, metres: the whole length when the
    /// way is free, 0 when it starts in contact (or an input is not finite).
    /// A parry2d shape cast of the disc against the world's boundary segments.
    pub fn free_travel_m(&self, world: &World, from_m: [f64; 2], to_m: [f64; 2]) -> f64 {
        let delta = [to_m[0] - from_m[0], to_m[1] - from_m[1]];
        let length = delta[0].hypot(delta[1]);
        if !(length.is_finite() && from_m[0].is_finite() && from_m[1].is_finite()) {
            return 0.0;
        }
        if self.clearance_m(world, from_m) <= 0.0 {
            return 0.0;
        }
        let Some(g) = world.geometry() else {
            return length;
        };
        if length == 0.0 {
            return 0.0;
        }
        // Nothing lies farther than the world's far corner: a longer move
        // is cast only that far (plus the disc), which keeps the cast's
        // arithmetic in range however far the goal is.
        let [x0, y0, x1, y1] = world.bounds_m();
        let out = (from_m[0] - x0)
            .abs()
            .max((x1 - from_m[0]).abs())
            .hypot((from_m[1] - y0).abs().max((y1 - from_m[1]).abs()))
            + self.radius_m
            + 1.0;
        let cast = length.min(out);
        let delta = [delta[0] / length * cast, delta[1] / length * cast];
        let ball = Ball::new(self.radius_m);
        let options = ShapeCastOptions {
            max_time_of_impact: 1.0,
            ..ShapeCastOptions::default()
        };
        let hit = query::cast_shapes(
            &ParryPose::from_translation(vector(from_m)),
            Vector::new(delta[0], delta[1]),
            &ball,
            &ParryPose::identity(),
            Vector::ZERO,
            &g.boundary,
            options,
        );
        match hit {
            Ok(Some(h)) => h.time_of_impact.clamp(0.0, 1.0) * cast,
            Ok(None) => length,
            // parry's dispatcher supports a ball against a polyline (the tests
            // exercise it); were it ever not to, not moving is the safe answer.
            Err(_) => 0.0,
        }
    }

    /// Whether driving straight from `from_m` to `to_m` touches an obstacle.
    /// A move with a non-finite end collides, as a non-finite pose does.
    pub fn move_collides(&self, world: &World, from_m: [f64; 2], to_m: [f64; 2]) -> bool {
        if !from_m.iter().chain(&to_m).all(|v| v.is_finite()) {
            return true;
        }
        let length = (to_m[0] - from_m[0]).hypot(to_m[1] - from_m[1]);
        if self.clearance_m(world, from_m) <= 0.0 || self.clearance_m(world, to_m) <= 0.0 {
            return true;
        }
        self.free_travel_m(world, from_m, to_m) < length
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::Material;
    use crate::polygon::Polygon;

    fn block() -> World {
        World::new(vec![
            Polygon::rectangle([2.0, -1.0], [4.0, 1.0], Material::Wall).unwrap(),
        ])
    }

    #[test]
    fn pose_collisions() {
        let w = block();
        let r = Robot::new(0.5).unwrap();
        assert!(!r.collides(&w, &Pose::new(1.4, 0.0, 0.0)));
        assert!(r.collides(&w, &Pose::new(1.6, 0.0, 0.0)));
        // Deep inside: far from the boundary but inside.
        assert!(r.collides(&w, &Pose::new(3.0, 0.0, 0.0)));
        assert!((r.clearance_m(&w, [3.0, 0.0]) + 1.5).abs() < 1e-12);
        assert!((r.clearance_m(&w, [0.0, 0.0]) - 1.5).abs() < 1e-12);
        // Near a corner the distance is Euclidean.
        assert!((r.clearance_m(&w, [1.0, 2.0]) - (2f64.sqrt() - 0.5)).abs() < 1e-12);
        assert!(r.collides(&w, &Pose::new(f64::NAN, 0.0, 0.0)));
        assert!(Robot::new(0.0).is_err());
    }

    #[test]
    fn move_collisions() {
        let w = block();
        let r = Robot::new(0.5).unwrap();
        // Straight at the block: contact when the centre is at x = 1.5.
        assert!((r.free_travel_m(&w, [0.0, 0.0], [5.0, 0.0]) - 1.5).abs() < 1e-6);
        assert!(r.move_collides(&w, [0.0, 0.0], [5.0, 0.0]));
        // Passing above it with 0.1 m to spare; then grazing within 0.1.
        assert!(!r.move_collides(&w, [0.0, 1.6], [6.0, 1.6]));
        assert_eq!(r.free_travel_m(&w, [0.0, 1.6], [6.0, 1.6]), 6.0);
        assert!(r.move_collides(&w, [0.0, 1.4], [6.0, 1.4]));
        // Both ends free but the block in between.
        assert!(r.move_collides(&w, [0.0, 0.0], [6.0, 0.0]));
        assert_eq!(r.free_travel_m(&w, [1.6, 0.0], [0.0, 0.0]), 0.0);
        // A non-finite end collides, as a non-finite pose does, even with
        // nothing in the way.
        let empty = World::new(Vec::new());
        for (from, to) in [
            ([f64::NAN, 1.3], [2.0, 1.3]),
            ([2.0, 1.3], [f64::NAN, 1.3]),
            ([0.0, 0.0], [f64::INFINITY, 0.0]),
        ] {
            assert!(r.move_collides(&empty, from, to), "{from:?} -> {to:?}");
        }
        // A goal far beyond the world: the wall still stops the disc, and
        // with nothing in the way the whole length is free.
        for far in [1e6, 1e155, 1e300] {
            assert!(
                (r.free_travel_m(&w, [0.0, 0.0], [far, 0.0]) - 1.5).abs() < 1e-6,
                "{far}"
            );
            assert_eq!(r.free_travel_m(&w, [0.0, 1.6], [far, 1.6]), far, "{far}");
        }
    }
}
