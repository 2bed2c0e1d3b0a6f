//! The generator's parameters, their defaults and their checks.

use crate::error::{Result, SimError, check_param};

/// The radius of the disc every room of a generated building is reachable
/// by, metres: the exploration loop's robot.
pub const ROBOT_RADIUS_M: f64 = 0.25;

/// The least wall beside a door, between the door and the next wall that
/// meets its wall, metres.
pub const JAMB_M: f64 = 0.3;

/// The largest floor area a building may be generated with, square metres
/// (a floor of 70 x 70 m; the validity check rasterises it at 5 cm).
pub const MAX_AREA_M2: f64 = 5000.0;

/// How a building is generated ([`Building::generate`]): its size, its
/// clutter, its materials, and the ranges its doors, corridors, rooms and
/// walls are drawn from. Every range is `[least, most]`, metres.
///
/// [`Building::generate`]: super::Building::generate
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BuildingOptions {
    /// The floor area, walls included, square metres (default 200: a
    /// corridor and some ten rooms; 550 is the size of the AMROffice plan).
    pub area_m2: f64,
    /// How full the rooms are, from 0 (empty) to 1 (a desk, cabinet or
    /// table for every 2.5 square metres of floor); default 0.5.
    pub clutter: f64,
    /// The share of rooms whose front to the corridor is glass, from 0 to 1
    /// (default 0.2).
    pub glass: f64,
    /// Door widths (default 0.8 to 1.2 m): more than the robot's diameter.
    pub door_width_m: [f64; 2],
    /// Corridor widths between the walls' centre lines (default 1.5 to 3 m).
    pub corridor_width_m: [f64; 2],
    /// Room sides between the walls' centre lines (default 2.5 to 6 m): the
    /// least must hold the widest door with [`JAMB_M`] and a wall either side.
    pub room_size_m: [f64; 2],
    /// Wall thicknesses (default 0.1 to 0.2 m), one drawn for the building.
    pub wall_thickness_m: [f64; 2],
}

impl Default for BuildingOptions {
    fn default() -> Self {
        Self {
            area_m2: 200.0,
            clutter: 0.5,
            glass: 0.2,
            door_width_m: [0.8, 1.2],
            corridor_width_m: [1.5, 3.0],
            room_size_m: [2.5, 6.0],
            wall_thickness_m: [0.1, 0.2],
        }
    }
}

impl BuildingOptions {
    /// The least floor area these ranges fit: a corridor of the least width
    /// with two rooms of the least size along one side.
    pub fn min_area_m2(&self) -> f64 {
        (self.corridor_width_m[0] + self.room_size_m[0]) * 2.0 * self.room_size_m[0]
    }

    /// Errors, naming the value, unless every parameter is finite and in
    /// its range: shares in `[0, 1]`; each range `[least, most]` with `0 <
    /// least <= most`; doors wider than the robot's diameter
    /// (2 [`ROBOT_RADIUS_M`]) and at most 3 m; walls from 0.02 to 0.5 m;
    /// corridors wider than the robot's diameter plus the thickest wall,
    /// at most 10 m; rooms whose least side holds the widest door
    /// (`door_width_m[1] + 2 (wall_thickness_m[1] + JAMB_M)`), at most 30
    /// m; an area from [`BuildingOptions::min_area_m2`] to [`MAX_AREA_M2`].
    pub fn validate(&self) -> Result<()> {
        check_param(
            "clutter",
            self.clutter,
            (0.0..=1.0).contains(&self.clutter),
            "a share from 0 to 1",
        )?;
        check_param(
            "glass",
            self.glass,
            (0.0..=1.0).contains(&self.glass),
            "a share from 0 to 1",
        )?;
        let ranges = [
            (
                ["wall_thickness_m[0]", "wall_thickness_m[1]"],
                self.wall_thickness_m,
                0.02,
                0.5,
                "a wall thickness from 0.02 to 0.5 m, the least first",
            ),
            (
                ["door_width_m[0]", "door_width_m[1]"],
                self.door_width_m,
                2.0 * ROBOT_RADIUS_M,
                3.0,
                "a door wider than the robot's diameter (0.5 m) and at most 3 m, the least first",
            ),
            (
                ["corridor_width_m[0]", "corridor_width_m[1]"],
                self.corridor_width_m,
                2.0 * ROBOT_RADIUS_M,
                10.0,
                "a corridor wider than the robot's diameter (0.5 m) and at most 10 m, the least first",
            ),
            (
                ["room_size_m[0]", "room_size_m[1]"],
                self.room_size_m,
                0.0,
                30.0,
                "a room side above 0 and at most 30 m, the least first",
            ),
        ];
        for ([lo_name, hi_name], [lo, hi], least, most, expected) in ranges {
            check_param(lo_name, lo, lo > least && lo <= most, expected)?;
            check_param(hi_name, hi, hi >= lo && hi <= most, expected)?;
        }
        let [_, thickest] = self.wall_thickness_m;
        check_param(
            "corridor_width_m[0]",
            self.corridor_width_m[0],
            self.corridor_width_m[0] > 2.0 * ROBOT_RADIUS_M + thickest,
            "a corridor wider than the robot's diameter (0.5 m) plus the thickest wall",
        )?;
        let door_room = self.door_width_m[1] + 2.0 * (thickest + JAMB_M);
        check_param(
            "room_size_m[0]",
            self.room_size_m[0],
            self.room_size_m[0] >= door_room,
            "rooms that fit the widest door with 0.3 m of wall either side and the thickest walls: \
             at least door_width_m[1] + 2 (wall_thickness_m[1] + 0.3)",
        )?;
        if !(self.area_m2 >= self.min_area_m2() && self.area_m2 <= MAX_AREA_M2) {
            return Err(SimError::InvalidParameter {
                name: "area_m2",
                value: self.area_m2,
                expected: "a floor area that fits a corridor and two rooms \
                           ((corridor_width_m[0] + room_size_m[0]) 2 room_size_m[0]) and at most 5000 m^2",
            });
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn name_of(options: BuildingOptions) -> &'static str {
        match options.validate() {
            Err(SimError::InvalidParameter { name, .. }) => name,
            other => panic!("{options:?}: {other:?}"),
        }
    }

    #[test]
    fn bad_parameters_are_named() {
        let d = BuildingOptions::default();
        d.validate().unwrap();
        assert!(d.min_area_m2() < d.area_m2);
        for (options, name) in [
            (
                BuildingOptions {
                    area_m2: f64::NAN,
                    ..d
                },
                "area_m2",
            ),
            (BuildingOptions { area_m2: -5.0, ..d }, "area_m2"),
            (BuildingOptions { area_m2: 10.0, ..d }, "area_m2"),
            (BuildingOptions { area_m2: 1e9, ..d }, "area_m2"),
            (BuildingOptions { clutter: 1.5, ..d }, "clutter"),
            (
                BuildingOptions {
                    glass: f64::NAN,
                    ..d
                },
                "glass",
            ),
            (
                BuildingOptions {
                    door_width_m: [0.4, 1.0],
                    ..d
                },
                "door_width_m[0]",
            ),
            (
                BuildingOptions {
                    door_width_m: [1.0, 0.9],
                    ..d
                },
                "door_width_m[1]",
            ),
            (
                BuildingOptions {
                    corridor_width_m: [-1.0, 2.0],
                    ..d
                },
                "corridor_width_m[0]",
            ),
            (
                BuildingOptions {
                    corridor_width_m: [0.6, 2.0],
                    ..d
                },
                "corridor_width_m[0]",
            ),
            (
                BuildingOptions {
                    room_size_m: [1.5, 6.0],
                    ..d
                },
                "room_size_m[0]",
            ),
            (
                BuildingOptions {
                    room_size_m: [3.0, f64::INFINITY],
                    ..d
                },
                "room_size_m[1]",
            ),
            (
                BuildingOptions {
                    wall_thickness_m: [0.0, 0.1],
                    ..d
                },
                "wall_thickness_m[0]",
            ),
        ] {
            assert_eq!(name_of(options), name, "{options:?}");
        }
    }
}
