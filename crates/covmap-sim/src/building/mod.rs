//! Buildings: a [`World`](crate::World) with its rooms and doors, so that an
//! exploration can be judged room by room.
//!
//! - [`Building::generate`]: a seeded floor plan ([`generate`]): corridors
//!   (straight, L or T), rooms along them with doors 0.8 to 1.2 m wide,
//!   rooms behind rooms, open halls with pillars, furniture, pillars along
//!   corridors, slanted walls, glass fronts; sized and cluttered by
//!   [`BuildingOptions`]. Every generated building is valid: every room is
//!   reachable by a disc of [`ROBOT_RADIUS_M`] from every other through its
//!   doors ([`validity`]).
//! - [`Building::from_world`]: any world (a real plan, a map_server pair, a
//!   built-in world), its rooms found by the rule of [`plan`].
//! - [`Building::rooms_entered`]: which rooms a trajectory entered.
//!
//! A building's coordinates are metres; rooms are floors of axis-aligned
//! rectangles, doors openings in walls.

#[allow(
    clippy::module_inception,
    reason = "the concept's own file, as parry's `query/ray/ray.rs`"
)]
mod building;
mod furniture;
pub mod generate;
mod layout;
mod options;
pub mod plan;
pub mod validity;
mod walls;

pub use building::{Building, Door, Room, RoomKind};
pub use options::{BuildingOptions, JAMB_M, MAX_AREA_M2, ROBOT_RADIUS_M};
