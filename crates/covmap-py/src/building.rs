//! `covmap.Building`, `covmap.Room`, `covmap.Door`: a world with its rooms
//! and doors, generated from a seed or read from a plan.

use std::path::PathBuf;

use covmap::sim::World;
use covmap::sim::building::{Building, BuildingOptions, Door, Room};
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;

use crate::convert::{self, rows_array};
use crate::errors::OrRaise;
use crate::numbers::{Float, Seed};
use crate::world::PyWorld;

/// A building: a ``World`` with its rooms and doors, so that an
/// exploration can be judged room by room (``rooms_never_entered``).
///
/// Make one with a static method: ``Building.generate(seed, ...)`` (a
/// seeded floor plan), ``Building.from_file(path)`` (a real plan, a
/// map_server pair), ``Building.builtin(name)`` or
/// ``Building.from_world(world, name)``. Buildings pickle.
#[pyclass(frozen, name = "Building", module = "covmap._native")]
pub(crate) struct PyBuilding(pub(crate) Building);

/// A room, corridor or hall of a ``Building``: its name, its kind and its
/// floor (axis-aligned rectangles between its walls' faces).
#[pyclass(frozen, name = "Room", module = "covmap._native")]
pub(crate) struct PyRoom(Room);

/// A door of a ``Building``: an opening in a wall between two rooms.
#[pyclass(frozen, name = "Door", module = "covmap._native")]
pub(crate) struct PyDoor(Door);

/// A trajectory argument: ``(K, 2)`` points or ``(K, 3)`` poses.
fn trajectory(obj: &Bound<'_, PyAny>) -> PyResult<Vec<[f64; 2]>> {
    if let Ok(poses) = convert::rows::<3>(obj, "trajectory", "pose (x, y, theta)") {
        return Ok(poses.iter().map(|p| [p[0], p[1]]).collect());
    }
    convert::rows::<2>(obj, "trajectory", "point (x, y)")
}

#[pymethods]
impl PyBuilding {
    /// The building of ``seed`` (0 to 2**64 - 1): corridors (straight, L
    /// or T) with rooms along them, rooms behind rooms, open halls with
    /// pillars, doors ``door_width_m`` wide, furniture that never blocks a
    /// door, pillars along corridors, slanted walls and glass fronts.
    /// ``area_m2``: the floor area, walls included (550 is AMROffice's
    /// size); ``clutter``: furniture, from 0 (none) to 1 (a piece per 2.5
    /// square metres); ``glass``: the share of glass room fronts; the
    /// ranges ``(least, most)`` of door, corridor and room widths and wall
    /// thicknesses, metres. Every room is reachable by a disc of 0.25 m
    /// from the first corridor. The same seed and parameters give the same
    /// building on every machine. A parameter out of its range (NaN, a
    /// negative size, a door narrower than the robot, rooms that cannot
    /// hold the widest door, an area too small for a corridor and two
    /// rooms) raises ``InvalidParameterError`` naming it.
    #[staticmethod]
    #[pyo3(signature = (
        seed, *, area_m2=Float(200.0), clutter=Float(0.5), glass=Float(0.2), door_width_m=None,
        corridor_width_m=None, room_size_m=None, wall_thickness_m=None
    ), text_signature = "(seed, *, area_m2=200.0, clutter=0.5, glass=0.2, door_width_m=(0.8, 1.2), corridor_width_m=(1.5, 3.0), room_size_m=(2.5, 6.0), wall_thickness_m=(0.1, 0.2))")]
    #[allow(
        clippy::too_many_arguments,
        reason = "one keyword argument per parameter"
    )]
    fn generate(
        py: Python<'_>,
        seed: Seed,
        area_m2: Float,
        clutter: Float,
        glass: Float,
        door_width_m: Option<&Bound<'_, PyAny>>,
        corridor_width_m: Option<&Bound<'_, PyAny>>,
        room_size_m: Option<&Bound<'_, PyAny>>,
        wall_thickness_m: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        let defaults = BuildingOptions::default();
        let range = |obj: Option<&Bound<'_, PyAny>>, name: &str, default| {
            obj.map_or(Ok(default), |o| {
                convert::fixed_numbers::<2>(o, name, "(least, most)")
            })
        };
        let options = BuildingOptions {
            area_m2: area_m2.0,
            clutter: clutter.0,
            glass: glass.0,
            door_width_m: range(door_width_m, "door_width_m", defaults.door_width_m)?,
            corridor_width_m: range(
                corridor_width_m,
                "corridor_width_m",
                defaults.corridor_width_m,
            )?,
            room_size_m: range(room_size_m, "room_size_m", defaults.room_size_m)?,
            wall_thickness_m: range(
                wall_thickness_m,
                "wall_thickness_m",
                defaults.wall_thickness_m,
            )?,
        };
        py.detach(|| Building::generate(seed.0, &options))
            .map(Self)
            .or_raise(py)
    }

    /// ``world`` as a building named ``name``, its rooms found by the rule
    /// for plans: the parts of the free space where the robot may start
    /// that passages narrower than 1.3 m (doorways) separate, each at
    /// least 0.25 square metres beyond 0.65 m from every obstacle (its
    /// core); a run enters one when the robot's centre crosses its core.
    /// Doors are not listed.
    #[staticmethod]
    #[pyo3(signature = (world, name="world"))]
    fn from_world(py: Python<'_>, world: PyRef<'_, PyWorld>, name: &str) -> PyResult<Self> {
        let world = world.0.clone();
        py.detach(|| Building::from_world(world, name))
            .map(Self)
            .or_raise(py)
    }

    /// A built-in world as a building (``World.builtin``; rooms by the
    /// rule of ``from_world``), named by its name.
    #[staticmethod]
    fn builtin(py: Python<'_>, name: &str) -> PyResult<Self> {
        let world = World::builtin(name).or_raise(py)?;
        py.detach(|| Building::from_world(world, name))
            .map(Self)
            .or_raise(py)
    }

    /// A world file as a building (``World.from_file``, the same
    /// arguments; rooms by the rule of ``from_world``), named by the
    /// file's name.
    #[staticmethod]
    #[pyo3(signature = (path, *, wall_thickness_m=None, resolution=None, origin=None))]
    fn from_file(
        py: Python<'_>,
        path: PathBuf,
        wall_thickness_m: Option<Float>,
        resolution: Option<Float>,
        origin: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        let name = path
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_else(|| path.display().to_string());
        let world = crate::world::load(py, path, wall_thickness_m, resolution, origin)?;
        py.detach(|| Building::from_world(world, name))
            .map(Self)
            .or_raise(py)
    }

    /// Its name: ``"generated:SEED"`` (``"generated:SEED:AREA"`` for
    /// another area than the default), a plan's file name, a built-in
    /// world's name.
    #[getter]
    fn name(&self) -> &str {
        self.0.name()
    }
    /// The world: walls, furniture, pillars and glass.
    #[getter]
    fn world(&self) -> PyWorld {
        PyWorld(self.0.world().clone())
    }
    /// The rooms, corridors and halls, in order (doors name them by index).
    #[getter]
    fn rooms(&self) -> Vec<PyRoom> {
        self.0.rooms().iter().cloned().map(PyRoom).collect()
    }
    /// The doors.
    #[getter]
    fn doors(&self) -> Vec<PyDoor> {
        self.0.doors().iter().cloned().map(PyDoor).collect()
    }
    /// The area of the rooms' floors, square metres.
    #[getter]
    fn floor_area_m2(&self) -> f64 {
        self.0.rooms().iter().map(Room::area_m2).sum()
    }

    /// Whether the robot's centre, driving straight from each point of
    /// ``trajectory`` (``(K, 2)`` points or ``(K, 3)`` poses, as
    /// ``ExplorationResult.trajectory``) to the next, entered each room:
    /// a bool array, one a room.
    fn rooms_entered<'py>(
        &self,
        py: Python<'py>,
        trajectory: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArray1<bool>>> {
        let points = self::trajectory(trajectory)?;
        let b = &self.0;
        let entered = py.detach(|| b.rooms_entered(&points));
        Ok(PyArray1::from_vec(py, entered))
    }

    /// The names of the rooms and halls (not corridors) that
    /// ``trajectory`` never entered (see ``rooms_entered``).
    fn rooms_never_entered(
        &self,
        py: Python<'_>,
        trajectory: &Bound<'_, PyAny>,
    ) -> PyResult<Vec<String>> {
        let points = self::trajectory(trajectory)?;
        let b = &self.0;
        let never = py.detach(|| b.rooms_never_entered(&points));
        Ok(never
            .into_iter()
            .map(|i| b.rooms()[i].name.clone())
            .collect())
    }

    /// The building as JSON text (its world as GeoJSON, its rooms and
    /// doors); ``Building.from_json`` reads it back.
    fn to_json(&self) -> String {
        self.0.to_json()
    }
    /// A building from ``to_json``'s text; ``FileFormatError`` for text
    /// that is not one.
    #[staticmethod]
    fn from_json(py: Python<'_>, text: &str) -> PyResult<Self> {
        Building::from_json(text, "building JSON")
            .map(Self)
            .or_raise(py)
    }
    /// Pickle and copy support: rebuilt by ``Building.from_json``.
    fn __reduce__<'py>(&self, py: Python<'py>) -> PyResult<(Bound<'py, PyAny>, (String,))> {
        let rebuild = py.get_type::<Self>().getattr("from_json")?;
        Ok((rebuild, (self.0.to_json(),)))
    }

    fn __repr__(&self) -> String {
        let judged = self.0.rooms().iter().filter(|r| r.kind.judged()).count();
        format!(
            "<Building {}: {} rooms, {} doors, {} polygons>",
            self.0.name(),
            judged,
            self.0.doors().len(),
            self.0.world().len()
        )
    }
}

#[pymethods]
impl PyRoom {
    /// Its name, unique in the building (``"room 3"``, ``"corridor 1"``,
    /// ``"region 2"``).
    #[getter]
    fn name(&self) -> &str {
        &self.0.name
    }
    /// ``"room"``, ``"corridor"`` or ``"hall"``.
    #[getter]
    fn kind(&self) -> &'static str {
        self.0.kind.as_str()
    }
    /// The floor: ``(K, 4)`` float64 rectangles ``(x_min, y_min, x_max,
    /// y_max)``, metres.
    #[getter]
    fn floor<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        rows_array(py, &self.0.floor_m)
    }
    /// The floor's area, square metres.
    #[getter]
    fn area_m2(&self) -> f64 {
        self.0.area_m2()
    }
    fn __repr__(&self) -> String {
        format!(
            "<Room {:?}: {}, {:.1} m^2>",
            self.0.name,
            self.0.kind.as_str(),
            self.0.area_m2()
        )
    }
}

#[pymethods]
impl PyDoor {
    /// The middle of the opening, ``(x, y)``, metres.
    #[getter]
    fn center(&self) -> (f64, f64) {
        (self.0.center_m[0], self.0.center_m[1])
    }
    /// The opening's clear width, metres.
    #[getter]
    fn width_m(&self) -> f64 {
        self.0.width_m
    }
    /// The direction of the wall it is in, radians (0: along x).
    #[getter]
    fn wall_angle_rad(&self) -> f64 {
        self.0.wall_angle_rad
    }
    /// The indices in ``Building.rooms`` of the two rooms it joins.
    #[getter]
    fn rooms(&self) -> (usize, usize) {
        (self.0.rooms[0], self.0.rooms[1])
    }
    fn __repr__(&self) -> String {
        format!(
            "<Door {:.2} m at ({:.2}, {:.2}) between rooms {} and {}>",
            self.0.width_m,
            self.0.center_m[0],
            self.0.center_m[1],
            self.0.rooms[0],
            self.0.rooms[1]
        )
    }
}
