//! What the loop needs from a robot: a source of scans and a motion.
//!
//! The loop ([`Exploration`](super::Exploration)) decides on the map and acts
//! through these two traits only, so that the same loop drives a simulated
//! robot (`covmap_sim`'s world-backed source and motion), a log replay or a
//! real robot.

use crate::error::Result;
use crate::pose::Pose;

/// A range sensor on the robot: where its beams point, and one scan.
pub trait ScanSource {
    /// The bearing of every beam relative to the robot's heading, radians,
    /// in the order [`ScanSource::scan`] returns the readings. The same on
    /// every call.
    fn bearings(&self) -> &[f64];

    /// One scan taken from `pose`: a range per bearing, metres; a reading at
    /// or beyond the sensor model's maximum range means "no echo". Each call
    /// is the next scan of the run (a simulated source draws scan `k`'s noise
    /// from its own stream `k`).
    ///
    /// # Errors
    /// Whatever stops the source from scanning; the loop passes it on and
    /// changes no map.
    fn scan(&mut self, pose: &Pose) -> Result<Vec<f64>>;
}

/// How far one straight drive got.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Travel {
    /// Distance driven from the start towards the target, metres, from 0 to
    /// the distance between them.
    pub travelled_m: f64,
    /// Where the robot touched an obstacle (a bumper's contact point, in
    /// world metres), or `None` when it got to the target without contact.
    /// After a contact the robot stands `travelled_m` along the way, at its
    /// last free point.
    pub contact_m: Option<[f64; 2]>,
}

/// The robot's drive: straight moves between points.
pub trait Motion {
    /// Drive straight from `from_m` towards `to_m`, stopping at `to_m` or at
    /// the last free point before a contact. The robot turns on the spot to
    /// face the way first (turning costs no path length).
    ///
    /// # Errors
    /// Whatever stops the drive from moving; the loop passes it on.
    fn drive(&mut self, from_m: [f64; 2], to_m: [f64; 2]) -> Result<Travel>;
}
