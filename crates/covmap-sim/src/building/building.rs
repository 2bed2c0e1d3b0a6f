//! A building: its world, its rooms and its doors.

use serde::{Deserialize, Serialize};

use crate::error::{Result, SimError};
use crate::world::World;

/// What a room of a building is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum RoomKind {
    /// A room behind a door: an office, a room behind another.
    Room,
    /// A corridor: the way between rooms.
    Corridor,
    /// An open hall: a large room with pillars, open to a corridor.
    Hall,
}

impl RoomKind {
    /// The lowercase name (`"room"`, `"corridor"`, `"hall"`).
    pub fn as_str(self) -> &'static str {
        match self {
            Self::Room => "room",
            Self::Corridor => "corridor",
            Self::Hall => "hall",
        }
    }

    /// Whether a run is judged on entering rooms of this kind: rooms and
    /// halls are, corridors (the way to them) are not.
    pub fn judged(self) -> bool {
        !matches!(self, Self::Corridor)
    }
}

/// A room of a building: its floor, axis-aligned rectangles that do not
/// overlap, between the inner faces of its walls.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Room {
    /// Its name, unique in the building (`"room 3"`, `"corridor 1"`).
    pub name: String,
    /// What it is.
    pub kind: RoomKind,
    /// The floor: `[x_min, y_min, x_max, y_max]` rectangles, metres.
    pub floor_m: Vec<[f64; 4]>,
}

impl Room {
    /// The floor's area, square metres.
    pub fn area_m2(&self) -> f64 {
        self.floor_m
            .iter()
            .map(|r| (r[2] - r[0]) * (r[3] - r[1]))
            .sum()
    }

    /// Whether the point lies on the floor (edges included).
    pub fn contains(&self, p_m: [f64; 2]) -> bool {
        self.floor_m
            .iter()
            .any(|r| r[0] <= p_m[0] && p_m[0] <= r[2] && r[1] <= p_m[1] && p_m[1] <= r[3])
    }

    /// Whether the straight segment from `a_m` to `b_m` touches the floor.
    pub fn crossed_by(&self, a_m: [f64; 2], b_m: [f64; 2]) -> bool {
        self.floor_m.iter().any(|r| segment_meets_rect(a_m, b_m, r))
    }
}

/// Whether the closed segment `a`-`b` meets the closed rectangle `r`
/// (Liang-Barsky clipping).
fn segment_meets_rect(a: [f64; 2], b: [f64; 2], r: &[f64; 4]) -> bool {
    let d = [b[0] - a[0], b[1] - a[1]];
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for axis in 0..2 {
        let (lo, hi) = (r[axis], r[axis + 2]);
        if d[axis] == 0.0 {
            if a[axis] < lo || a[axis] > hi {
                return false;
            }
            continue;
        }
        let (mut u, mut v) = ((lo - a[axis]) / d[axis], (hi - a[axis]) / d[axis]);
        if u > v {
            std::mem::swap(&mut u, &mut v);
        }
        t0 = t0.max(u);
        t1 = t1.min(v);
        if t0 > t1 {
            return false;
        }
    }
    true
}

/// A door: an opening in a wall between two rooms.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Door {
    /// The middle of the opening, metres.
    pub center_m: [f64; 2],
    /// The clear width of the opening, metres.
    pub width_m: f64,
    /// The direction of the wall the door is in, radians (0: along x).
    pub wall_angle_rad: f64,
    /// The indices of the two rooms it joins.
    pub rooms: [usize; 2],
}

/// A world with its rooms and doors.
///
/// # Example
/// ```
/// use covmap_sim::building::{Building, BuildingOptions};
/// let building = Building::generate(7, &BuildingOptions::default()).unwrap();
/// assert_eq!(building.name(), "generated:7");
/// assert!(building.rooms().len() >= 3 && !building.doors().is_empty());
/// // The same seed gives the same building.
/// let again = Building::generate(7, &BuildingOptions::default()).unwrap();
/// assert_eq!(building.to_json(), again.to_json());
/// // A run that never leaves the first corridor enters no room.
/// let corridor = &building.rooms()[0].floor_m[0];
/// let here = [0.5 * (corridor[0] + corridor[2]), 0.5 * (corridor[1] + corridor[3])];
/// let entered = building.rooms_entered(&[here]);
/// assert!(entered[0] && !entered[1..].iter().any(|&e| e));
/// ```
#[derive(Clone, Debug)]
pub struct Building {
    name: String,
    world: World,
    rooms: Vec<Room>,
    doors: Vec<Door>,
}

/// A building as JSON ([`Building::to_json`]).
#[derive(Serialize, Deserialize)]
struct BuildingJson {
    name: String,
    world: serde_json::Value,
    rooms: Vec<Room>,
    doors: Vec<Door>,
}

impl Building {
    /// A building of `world` with the rooms and doors given (no check that
    /// they match the world: [`crate::building::validity`] checks that).
    ///
    /// # Errors
    /// [`SimError::InvalidValue`] for a room floor or a door that is not
    /// finite or is empty, or a door naming a room that does not exist.
    pub fn new(
        name: impl Into<String>,
        world: World,
        rooms: Vec<Room>,
        doors: Vec<Door>,
    ) -> Result<Self> {
        for (index, room) in rooms.iter().enumerate() {
            for r in &room.floor_m {
                if !(r.iter().all(|v| v.is_finite()) && r[0] < r[2] && r[1] < r[3]) {
                    return Err(SimError::InvalidValue {
                        what: "room floor rectangle (finite, non-empty)",
                        index,
                        value: r.iter().copied().find(|v| !v.is_finite()).unwrap_or(0.0),
                    });
                }
            }
        }
        for (index, door) in doors.iter().enumerate() {
            let values = [
                door.center_m[0],
                door.center_m[1],
                door.width_m,
                door.wall_angle_rad,
            ];
            if let Some(&value) = values.iter().find(|v| !v.is_finite()) {
                return Err(SimError::InvalidValue {
                    what: "door (finite centre, width and angle)",
                    index,
                    value,
                });
            }
            if let Some(&room) = door.rooms.iter().find(|&&r| r >= rooms.len()) {
                return Err(SimError::InvalidValue {
                    what: "door's room index",
                    index,
                    value: room as f64,
                });
            }
        }
        Ok(Self {
            name: name.into(),
            world,
            rooms,
            doors,
        })
    }

    /// Its name: a generated building's `"generated:SEED"` (with
    /// `":AREA"` when its area is not the default), a plan's file name, a
    /// built-in world's name.
    pub fn name(&self) -> &str {
        &self.name
    }
    /// The world: walls, furniture, pillars, glass.
    pub fn world(&self) -> &World {
        &self.world
    }
    /// The rooms, corridors and halls.
    pub fn rooms(&self) -> &[Room] {
        &self.rooms
    }
    /// The doors.
    pub fn doors(&self) -> &[Door] {
        &self.doors
    }

    /// Whether the robot's centre, driving straight from each point of
    /// `trajectory_m` to the next, touched each room's floor (one flag a
    /// room, in the rooms' order).
    pub fn rooms_entered(&self, trajectory_m: &[[f64; 2]]) -> Vec<bool> {
        self.rooms
            .iter()
            .map(|room| match trajectory_m {
                [] => false,
                [p] => room.contains(*p),
                _ => trajectory_m.windows(2).any(|w| room.crossed_by(w[0], w[1])),
            })
            .collect()
    }

    /// The indices of the rooms a run is judged on ([`RoomKind::judged`])
    /// that `trajectory_m` never entered ([`Building::rooms_entered`]).
    pub fn rooms_never_entered(&self, trajectory_m: &[[f64; 2]]) -> Vec<usize> {
        self.rooms_entered(trajectory_m)
            .into_iter()
            .enumerate()
            .filter(|&(i, entered)| !entered && self.rooms[i].kind.judged())
            .map(|(i, _)| i)
            .collect()
    }

    /// The building as JSON: its name, its world as GeoJSON
    /// ([`World::to_geojson`]), its rooms and doors;
    /// [`Building::from_json`] reads it back.
    pub fn to_json(&self) -> String {
        let world = serde_json::from_str(&self.world.to_geojson()).unwrap_or_default();
        let json = BuildingJson {
            name: self.name.clone(),
            world,
            rooms: self.rooms.clone(),
            doors: self.doors.clone(),
        };
        serde_json::to_string(&json).unwrap_or_default()
    }

    /// A building from [`Building::to_json`]'s text; `source` names it in
    /// errors.
    ///
    /// # Errors
    /// [`SimError::Parse`] for text that is not such JSON, and the errors
    /// of [`World::from_geojson_str`] and [`Building::new`].
    pub fn from_json(text: &str, source: &str) -> Result<Self> {
        let json: BuildingJson = serde_json::from_str(text).map_err(|e| SimError::Parse {
            path: source.into(),
            place: format!("line {}, column {}", e.line(), e.column()),
            reason: e.to_string(),
        })?;
        let world = World::from_geojson_str(&json.world.to_string(), source)?;
        Self::new(json.name, world, json.rooms, json.doors)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn room(floor: [f64; 4]) -> Room {
        Room {
            name: "r".into(),
            kind: RoomKind::Room,
            floor_m: vec![floor],
        }
    }

    /// A segment enters a room when any part of it lies on the floor: one
    /// passing by does not, one crossing a corner does, one ending on the
    /// edge does.
    #[test]
    fn segments_meet_floors_where_they_cross_them() {
        let r = room([0.0, 0.0, 2.0, 1.0]);
        assert!(r.crossed_by([-1.0, 0.5], [3.0, 0.5]));
        assert!(!r.crossed_by([-1.0, 1.5], [3.0, 1.5]));
        assert!(r.crossed_by([1.0, 1.8], [2.5, 0.3])); // across the corner
        assert!(!r.crossed_by([1.5, 2.0], [2.5, 0.5])); // past it
        assert!(r.crossed_by([2.0, 3.0], [2.0, 1.0])); // ends on the corner
        assert!(r.crossed_by([0.5, 0.5], [0.5, 0.5])); // a point inside
        assert!(!r.crossed_by([0.5, -0.5], [0.5, -0.5]));
    }

    #[test]
    fn rooms_entered_by_a_trajectory() {
        let world = World::from_vertex_lists(
            vec![vec![[4.0, 2.0], [4.2, 2.0], [4.2, 6.0], [4.0, 6.0]]],
            crate::Material::Wall,
        )
        .unwrap();
        let rooms = vec![
            Room {
                name: "corridor".into(),
                kind: RoomKind::Corridor,
                floor_m: vec![[0.0, 0.0, 10.0, 2.0]],
            },
            room([0.0, 2.2, 4.0, 6.0]),
            room([4.2, 2.2, 10.0, 6.0]),
        ];
        let b = Building::new("b", world, rooms, Vec::new()).unwrap();
        let path = [[1.0, 1.0], [2.0, 3.0], [2.0, 1.0], [8.0, 1.0]];
        assert_eq!(b.rooms_entered(&path), [true, true, false]);
        assert_eq!(b.rooms_never_entered(&path), [2]);
        assert_eq!(b.rooms_never_entered(&[]), [1, 2]);
        let back = Building::from_json(&b.to_json(), "b.json").unwrap();
        assert_eq!(back.rooms(), b.rooms());
        assert_eq!(back.name(), "b");
        assert!(Building::from_json("{", "x.json").is_err());
    }

    #[test]
    fn bad_floors_and_doors_are_refused() {
        let world = World::new(Vec::new());
        let bad = vec![room([0.0, 0.0, f64::NAN, 1.0])];
        assert!(Building::new("b", world.clone(), bad, Vec::new()).is_err());
        let empty = vec![room([1.0, 0.0, 1.0, 1.0])];
        assert!(Building::new("b", world.clone(), empty, Vec::new()).is_err());
        let door = Door {
            center_m: [0.0, 0.0],
            width_m: 1.0,
            wall_angle_rad: 0.0,
            rooms: [0, 1],
        };
        let one = vec![room([0.0, 0.0, 1.0, 1.0])];
        assert!(Building::new("b", world, one, vec![door]).is_err());
    }
}
