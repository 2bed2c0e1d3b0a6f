//! The exploration loop over scan sources and motions of its own: a robot in
//! a world of segments, some of which its sensor cannot see (glass to a
//! sonar), must not be trapped by them, nor pass through them.

use covmap::exploration::{
    AnySensorModel, Exploration, ExplorationSetup, Motion, ScanSource, Strategy, Termination,
    Travel,
};
use covmap::{CovmapError, Grid, Pose, Result};

type Segment = ([f64; 2], [f64; 2]);

/// Where the ray from `origin` along `angle` first meets `segment`, metres.
fn hit(origin: [f64; 2], angle: f64, (a, b): Segment) -> Option<f64> {
    let (dx, dy) = (angle.cos(), angle.sin());
    let (ex, ey) = (b[0] - a[0], b[1] - a[1]);
    let denominator = dx * ey - dy * ex;
    if denominator.abs() < 1e-12 {
        return None;
    }
    let (wx, wy) = (a[0] - origin[0], a[1] - origin[1]);
    let t = (wx * ey - wy * ex) / denominator;
    let u = (wx * dy - wy * dx) / denominator;
    (t >= 0.0 && (0.0..=1.0).contains(&u)).then_some(t)
}

/// Distance from `p` to `segment`.
fn distance((a, b): Segment, p: [f64; 2]) -> f64 {
    let (ex, ey) = (b[0] - a[0], b[1] - a[1]);
    let t = (((p[0] - a[0]) * ex + (p[1] - a[1]) * ey) / (ex * ex + ey * ey)).clamp(0.0, 1.0);
    (p[0] - a[0] - t * ex).hypot(p[1] - a[1] - t * ey)
}

/// A 6 m x 4 m room of segments, split at `x = 3` by a wall with a doorway
/// from `y = 2.8` to `3.8`; the wall is `visible` to the sensor or not.
struct Room {
    walls: Vec<Segment>,
    split: Vec<Segment>,
    visible: bool,
}

impl Room {
    fn new(visible: bool) -> Self {
        let corners = [[0.0, 0.0], [6.0, 0.0], [6.0, 4.0], [0.0, 4.0]];
        Self {
            walls: (0..4).map(|k| (corners[k], corners[(k + 1) % 4])).collect(),
            split: vec![([3.0, 0.0], [3.0, 2.8]), ([3.0, 3.8], [3.0, 4.0])],
            visible,
        }
    }
    fn solid(&self) -> impl Iterator<Item = &Segment> {
        self.walls.iter().chain(&self.split)
    }
}

/// A ring of 360 laser beams, exact, out to 30 m.
struct Beams<'w> {
    room: &'w Room,
    bearings: Vec<f64>,
}

impl ScanSource for Beams<'_> {
    fn bearings(&self) -> &[f64] {
        &self.bearings
    }
    fn scan(&mut self, pose: &Pose) -> Result<Vec<f64>> {
        let seen: Vec<&Segment> = if self.room.visible {
            self.room.solid().collect()
        } else {
            self.room.walls.iter().collect()
        };
        Ok(self
            .bearings
            .iter()
            .map(|b| {
                seen.iter()
                    .filter_map(|&&s| hit([pose.x_m, pose.y_m], pose.theta_rad + b, s))
                    .fold(30.0, f64::min)
            })
            .collect())
    }
}

/// A disc of 0.25 m driving in millimetre steps until it would touch a wall.
struct Disc<'w> {
    room: &'w Room,
    /// Whether the robot got past the splitting wall (through the doorway).
    far_side: bool,
}

impl Motion for Disc<'_> {
    fn drive(&mut self, from: [f64; 2], to: [f64; 2]) -> Result<Travel> {
        let length = (to[0] - from[0]).hypot(to[1] - from[1]);
        if !(length.is_finite()) {
            return Err(CovmapError::Robot("a drive to nowhere".into()));
        }
        let steps = (length / 0.001).ceil().max(1.0) as usize;
        let at = |k: usize| {
            let f = (k as f64 / steps as f64).min(1.0);
            [
                from[0] + f * (to[0] - from[0]),
                from[1] + f * (to[1] - from[1]),
            ]
        };
        for k in 1..=steps {
            let p = at(k);
            if let Some(&touched) = self.room.solid().find(|&&s| distance(s, p) < 0.25) {
                let back = at(k.saturating_sub(2));
                let travelled = (back[0] - from[0]).hypot(back[1] - from[1]);
                let (a, b) = touched;
                let t = (((p[0] - a[0]) * (b[0] - a[0]) + (p[1] - a[1]) * (b[1] - a[1]))
                    / ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)))
                .clamp(0.0, 1.0);
                let contact = [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])];
                return Ok(Travel {
                    travelled_m: travelled,
                    contact_m: Some(contact),
                });
            }
            self.far_side |= p[0] > 3.3;
        }
        Ok(Travel {
            travelled_m: length,
            contact_m: None,
        })
    }
}

fn run(visible: bool, strategy: Strategy) -> (Termination, usize, bool, f64, Vec<[f64; 2]>) {
    let room = Room::new(visible);
    let grid = Grid::covering(-0.5, -0.5, 6.5, 4.5, 0.05).unwrap();
    let mut setup = ExplorationSetup::new(grid, Pose::new(1.0, 1.0, 0.0), strategy);
    setup.model = AnySensorModel::laser();
    setup.config.max_steps = 400;
    let bearings = (0..360)
        .map(|i| i as f64 * std::f64::consts::TAU / 360.0)
        .collect();
    let source = Beams {
        room: &room,
        bearings,
    };
    let mut motion = Disc {
        room: &room,
        far_side: false,
    };
    let mut exploration = Exploration::new(setup, source, &mut motion).unwrap();
    let mut goals = Vec::new();
    while let Some(step) = exploration.step().unwrap() {
        goals.push([step.goal.x_m, step.goal.y_m]);
    }
    let termination = exploration.termination().unwrap();
    let result = exploration.into_result();
    assert!(
        (result.path_length_m - result.trajectory.length_m()).abs() < 1e-9,
        "path and trajectory"
    );
    (
        termination,
        result.contacts,
        motion.far_side,
        result.path_length_m,
        goals,
    )
}

impl Motion for &mut Disc<'_> {
    fn drive(&mut self, from: [f64; 2], to: [f64; 2]) -> Result<Travel> {
        (**self).drive(from, to)
    }
}

/// A wall the sensor cannot see: the robot runs into it, the contact is
/// evidence, and the run still ends by its rule, never sent to the goal it
/// has just reached.
#[test]
fn an_invisible_wall_traps_no_strategy() {
    let mut contacts_seen = 0;
    for strategy in [
        Strategy::coverage(0.5).unwrap(),
        Strategy::counting(1, None).unwrap(),
        Strategy::frontier(),
    ] {
        let (termination, contacts, far_side, path_m, goals) = run(false, strategy);
        let figures = format!(
            "{strategy:?}: {termination}, {contacts} contacts, {path_m:.1} m, {} goals, far side {far_side}",
            goals.len()
        );
        assert!(termination.by_rule(), "{figures}");
        contacts_seen += contacts;
        assert!(
            goals.windows(2).all(|w| w[0] != w[1]),
            "{figures}: a goal chosen twice in a row"
        );
    }
    assert!(
        contacts_seen > 0,
        "the robot never ran into the invisible wall"
    );
}

/// With the wall in sight the robot never touches it.
#[test]
fn a_visible_wall_is_never_touched() {
    let (termination, contacts, far_side, path_m, _) = run(true, Strategy::coverage(0.5).unwrap());
    eprintln!("visible: {termination}, {contacts} contacts, {path_m:.1} m, far side {far_side}");
    assert!(termination.by_rule(), "{termination}");
    assert_eq!(contacts, 0);
    assert!(far_side, "the robot never went through the doorway");
}
