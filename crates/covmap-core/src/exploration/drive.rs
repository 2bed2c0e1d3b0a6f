//! The robot's drive: along a planned path through the world with the
//! [`Motion`], a scan every `scan_spacing_m` and at the goal, every scan
//! into the maps, and what happens at a contact (see the [loop's
//! documentation](super::exploration)).

use std::time::Instant;

use super::exploration::Exploration;
use super::source::{Motion, ScanSource, Travel};
use super::strategy::{sees_all_around, widest_gap_rad};
use crate::error::Result;
use crate::pose::Pose;
use crate::scan_map::{ScanBeams, ScanMap};

/// How far a contact point is moved into the obstacle to find the cell it
/// lies in, metres (a point on a cell's edge belongs to one of two cells).
const INTO_CONTACT_M: f64 = 1e-3;

/// How one drive along a path went.
pub(super) struct Drive {
    pub reached: bool,
    pub travelled_m: f64,
    /// Distance driven towards the goal (without backing off a contact).
    pub headway_m: f64,
    pub scans: usize,
    pub contact_m: Option<[f64; 2]>,
}

impl<S: ScanSource, M: Motion> Exploration<S, M> {
    /// Drive along `path` (cell centres, from the robot's cell) to `goal`:
    /// straight legs, a scan every `scan_spacing_m`, a stop at a contact or
    /// at the path limit, a turn to the goal's heading and a scan at the goal.
    pub(super) fn follow(&mut self, path: &[[f64; 2]], goal: &Pose) -> Result<Drive> {
        let resolution_m = self.map.grid().resolution_m();
        let mut drive = Drive {
            reached: false,
            travelled_m: 0.0,
            headway_m: 0.0,
            scans: self.totals.scans,
            contact_m: None,
        };
        // The path starts at the centre of the robot's cell: the robot heads
        // for the next corner straight away (a detour to its own cell's
        // centre could run into what it has just touched).
        let corners = straight_runs(path, resolution_m);
        for waypoint in corners.into_iter().skip(usize::from(path.len() > 1)) {
            loop {
                let here = [self.pose.x_m, self.pose.y_m];
                let left_m = (waypoint[0] - here[0]).hypot(waypoint[1] - here[1]);
                if left_m <= 1e-9 {
                    break;
                }
                let budget_m = self.config.max_path_m - self.totals.path_length_m;
                let leg_m = left_m
                    .min(self.config.scan_spacing_m - self.since_scan_m)
                    .min(budget_m);
                let direction = [
                    (waypoint[0] - here[0]) / left_m,
                    (waypoint[1] - here[1]) / left_m,
                ];
                let to = if leg_m >= left_m {
                    waypoint
                } else {
                    [
                        here[0] + direction[0] * leg_m,
                        here[1] + direction[1] * leg_m,
                    ]
                };
                let heading = direction[1].atan2(direction[0]);
                let travel = self.drive_straight(to, direction, leg_m, heading)?;
                drive.travelled_m += travel.travelled_m;

                if let Some(contact_m) = travel.contact_m {
                    self.scan_here()?;
                    self.integrate_contact(contact_m)?;
                    drive.headway_m = drive.travelled_m;
                    drive.travelled_m += self.back_off(contact_m)?;
                    drive.contact_m = Some(contact_m);
                    drive.scans = self.totals.scans - drive.scans;
                    return Ok(drive);
                }
                if self.since_scan_m >= self.config.scan_spacing_m - 1e-9 {
                    self.scan_here()?;
                }
                if self.at_path_limit() {
                    if self.since_scan_m > 0.0 {
                        self.scan_here()?;
                    }
                    drive.headway_m = drive.travelled_m;
                    drive.scans = self.totals.scans - drive.scans;
                    return Ok(drive);
                }
            }
        }
        // At the goal: face the goal's heading and scan.
        let turned = self.pose.theta_rad != goal.theta_rad;
        if turned {
            self.pose.theta_rad = goal.theta_rad;
            self.trajectory.push(self.pose, false);
        }
        if turned || self.since_scan_m > 0.0 || drive.travelled_m == 0.0 {
            self.scan_here()?;
        }
        drive.reached = true;
        drive.headway_m = drive.travelled_m;
        drive.scans = self.totals.scans - drive.scans;
        Ok(drive)
    }

    /// The first scans: one at the start and, for a sensor that does not see
    /// all around, one after each turn on the spot by the arc its bearings
    /// span, until the turns have come full circle (a 180-degree laser scans
    /// twice, facing both ways): a robot knows nothing of what lies behind
    /// it, and planning on cells still unknown around its own disc would
    /// find no way out.
    pub(super) fn look_around(&mut self) -> Result<()> {
        use std::f64::consts::TAU;
        self.scan_here()?;
        if sees_all_around(&self.bearings) {
            return Ok(());
        }
        // The arc the bearings span (at least one beam's worth: a single
        // bearing turns by 45 degrees).
        let arc_rad = (TAU - widest_gap_rad(&self.bearings)).max(TAU / 8.0);
        let turns = (TAU / arc_rad).ceil() as usize - 1;
        let start = self.pose.theta_rad;
        for k in 1..=turns {
            let theta = (start + k as f64 * arc_rad + std::f64::consts::PI).rem_euclid(TAU)
                - std::f64::consts::PI;
            self.pose = Pose::new(self.pose.x_m, self.pose.y_m, theta);
            self.scan_here()?;
        }
        Ok(())
    }

    /// Scan from the robot's pose and integrate the scan into every map.
    fn scan_here(&mut self) -> Result<()> {
        let started = Instant::now();
        let ranges = self.source.scan(&self.pose)?;
        let integrating = Instant::now();
        self.totals.timing.sensing_s += (integrating - started).as_secs_f64();
        let (pose, bearings, model) = (&self.pose, &self.bearings[..], self.model.as_dyn());
        // No-echo readings stopped before what the map is certain of, and
        // echoes attributed to it (see the module documentation of
        // `crate::exploration`).
        let epsilon = self.config.epsilon;
        let reading = self
            .config
            .occlude_no_echo
            .then(|| self.map.read_scan(pose, &ranges, bearings, model, epsilon));
        let scan = ScanBeams::new(pose, &ranges, bearings);
        let scan = reading.as_ref().map_or(scan, |r| r.beams(scan));
        // The coverage map checks the scan first: an invalid one changes no map.
        self.map.integrate_scan(scan, model)?;
        self.occupancy.integrate_scan(scan, model)?;
        // The robot remembers what it ran into, whatever the readings say.
        self.map.pin_covered(&self.contact_cells)?;
        self.totals.timing.integration_s += integrating.elapsed().as_secs_f64();
        self.totals.scans += 1;
        self.since_scan_m = 0.0;
        match (
            self.trajectory.poses.last(),
            self.trajectory.scanned.last_mut(),
        ) {
            (Some(last), Some(scanned)) if *last == self.pose && !*scanned => *scanned = true,
            _ => self.trajectory.push(self.pose, true),
        }
        Ok(())
    }

    /// Integrate a contact at `contact_m` (world metres) into the coverage
    /// map (pinned certainly covered) and the occupancy grid (occupied):
    /// the cell the robot ran into, and its
    /// neighbours along the surface there, one cell either side (the
    /// surface is taken to go on that far: a wall, a pane, a column's
    /// flank; a flat bumper learns no more).
    fn integrate_contact(&mut self, contact_m: [f64; 2]) -> Result<()> {
        let started = Instant::now();
        let resolution_m = self.map.grid().resolution_m();
        let (dx, dy) = (contact_m[0] - self.pose.x_m, contact_m[1] - self.pose.y_m);
        let length = dx.hypot(dy).max(f64::MIN_POSITIVE);
        let (normal, tangent) = ([dx / length, dy / length], [-dy / length, dx / length]);
        let mut cells = Vec::new();
        for along in [-1.0, 0.0, 1.0] {
            let x = contact_m[0] + INTO_CONTACT_M * normal[0] + along * resolution_m * tangent[0];
            let y = contact_m[1] + INTO_CONTACT_M * normal[1] + along * resolution_m * tangent[1];
            if let Some(cell) = self.map.grid().world_to_cell(x, y)
                && !cells.contains(&cell)
            {
                cells.push(cell);
            }
        }
        if cells.is_empty() {
            // The contact lies off the map: the map's error, named.
            self.map.grid().check_inside(contact_m[0], contact_m[1])?;
        }
        for cell in cells {
            self.occupancy.integrate_contact(cell)?;
            if !self.contact_cells.contains(&cell) {
                self.contact_cells.push(cell);
            }
        }
        // Held certainly covered in the coverage map from now on: a bumper
        // is far more reliable than a sonar, and a wall no echo shows (a
        // specular surface, glass) must not lure the robot back.
        self.map.pin_covered(&self.contact_cells)?;
        self.totals.contacts += 1;
        self.totals.timing.integration_s += started.elapsed().as_secs_f64();
        Ok(())
    }

    /// Back off a cell straight away from the contact at `contact_m`, as
    /// far as the motion lets the robot (and the path limit); the distance
    /// driven. A robot left touching a wall could not start along it.
    fn back_off(&mut self, contact_m: [f64; 2]) -> Result<f64> {
        let (dx, dy) = (self.pose.x_m - contact_m[0], self.pose.y_m - contact_m[1]);
        let length = dx.hypot(dy);
        let distance_m = self
            .map
            .grid()
            .resolution_m()
            .min(self.config.max_path_m - self.totals.path_length_m);
        if !(length > 0.0 && distance_m > 0.0) {
            return Ok(0.0);
        }
        let away = [dx / length, dy / length];
        let to = [
            self.pose.x_m + away[0] * distance_m,
            self.pose.y_m + away[1] * distance_m,
        ];
        // Backing up: the robot keeps facing the way it came.
        let travel = self.drive_straight(to, away, distance_m, self.pose.theta_rad)?;
        Ok(travel.travelled_m)
    }

    /// Drive straight towards `to`, `distance_m` away along the unit vector
    /// `direction`, facing `theta_rad`, with the motion: the robot ends where
    /// the motion stopped it, the pose on the trajectory, the distance on
    /// the path. Returns the distance driven and the contact, if any.
    fn drive_straight(
        &mut self,
        to: [f64; 2],
        direction: [f64; 2],
        distance_m: f64,
        theta_rad: f64,
    ) -> Result<Travel> {
        let here = [self.pose.x_m, self.pose.y_m];
        let started = Instant::now();
        let travel = self.motion.drive(here, to)?;
        self.totals.timing.sensing_s += started.elapsed().as_secs_f64();
        let travelled_m = travel.travelled_m.clamp(0.0, distance_m);
        self.pose = Pose::new(
            here[0] + direction[0] * travelled_m,
            here[1] + direction[1] * travelled_m,
            theta_rad,
        );
        self.trajectory.push(self.pose, false);
        if travelled_m > 0.0 {
            let driven = &mut self.driven;
            crate::footprint::visit(
                self.map.grid(),
                here,
                direction[1].atan2(direction[0]),
                travelled_m,
                crate::sensor::Footprint::Ray,
                &mut |i: usize, _| driven[i] = true,
            );
        }
        self.totals.path_length_m += travelled_m;
        self.since_scan_m += travelled_m;
        Ok(Travel {
            travelled_m,
            contact_m: travel.contact_m,
        })
    }
}

/// The corners of `path` (cell centres, 8-connected steps): its first and
/// last points and every point where the step direction changes.
fn straight_runs(path: &[[f64; 2]], resolution_m: f64) -> Vec<[f64; 2]> {
    let step = |a: [f64; 2], b: [f64; 2]| {
        (
            ((b[0] - a[0]) / resolution_m).round() as i64,
            ((b[1] - a[1]) / resolution_m).round() as i64,
        )
    };
    let mut corners: Vec<[f64; 2]> = path.first().copied().into_iter().collect();
    for k in 1..path.len() {
        let last = k + 1 == path.len();
        if last || step(path[k - 1], path[k]) != step(path[k], path[k + 1]) {
            corners.push(path[k]);
        }
    }
    corners
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn straight_runs_keep_the_corners() {
        let p = |x: f64, y: f64| [x * 0.05, y * 0.05];
        let path = [
            p(0., 0.),
            p(1., 0.),
            p(2., 0.),
            p(3., 1.),
            p(4., 2.),
            p(4., 3.),
        ];
        assert_eq!(
            straight_runs(&path, 0.05),
            vec![p(0., 0.), p(2., 0.), p(4., 2.), p(4., 3.)]
        );
        assert_eq!(straight_runs(&path[..1], 0.05), vec![p(0., 0.)]);
        assert!(straight_runs(&[], 0.05).is_empty());
    }
}
