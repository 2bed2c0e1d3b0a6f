//! The seeded building generator: [`Building::generate`].
//!
//! One stream of random numbers, seeded by the seed alone, draws in order:
//! the plan (wall thickness, corridor width, block depths, shape, rooms,
//! doors, hall, glass fronts; `layout.rs`), the furniture, pillars
//! and slanted walls (`furniture.rs`), and the building's placement
//! (mirrored in x or not, x and y swapped or not). Only additions,
//! multiplications, divisions and square roots of floating-point numbers
//! make the geometry, so the same seed and options give the same building,
//! bit for bit, on every machine.
//!
//! The walls (`walls.rs`) are `wall_m` thick, centred on the plan's
//! edges; a room's floor is its rectangle within its walls' faces.
//!
//! Every building returned is valid ([`super::validity`]): every room is
//! reachable by the robot's disc from the first corridor. Should
//! furniture cut a room off despite the placement rules (none of thousands
//! of seeds tested does), the furniture of the rooms cut off is taken
//! out, then all furniture; a building still invalid is an error
//! ([`SimError::UnreachableRooms`]), never returned.

use rand::RngExt;

use super::building::{Building, Door, Room};
use super::furniture::{self, ItemKind, floor};
use super::layout::{self, Plan};
use super::options::BuildingOptions;
use super::validity::unreachable_rooms;
use super::walls;
use crate::error::{Result, SimError};
use crate::polygon::Polygon;
use crate::rng::sim_rng;
use crate::world::World;

/// Where the plan is placed: mirrored in x about its width, x and y swapped.
struct Placement {
    mirror: bool,
    transpose: bool,
    width_m: f64,
}

impl Placement {
    fn point(&self, p: [f64; 2]) -> [f64; 2] {
        let x = if self.mirror {
            self.width_m - p[0]
        } else {
            p[0]
        };
        if self.transpose { [p[1], x] } else { [x, p[1]] }
    }
    fn rect(&self, r: &[f64; 4]) -> [f64; 4] {
        let [a, b] = [self.point([r[0], r[1]]), self.point([r[2], r[3]])];
        [
            a[0].min(b[0]),
            a[1].min(b[1]),
            a[0].max(b[0]),
            a[1].max(b[1]),
        ]
    }
    fn polygon(&self, p: &Polygon) -> Result<Polygon> {
        Polygon::new(
            p.exterior().iter().map(|&v| self.point(v)).collect(),
            p.material(),
        )
    }
    fn door(&self, d: &Door) -> Door {
        let angle = if self.transpose {
            std::f64::consts::FRAC_PI_2 - d.wall_angle_rad
        } else {
            d.wall_angle_rad
        };
        Door {
            center_m: self.point(d.center_m),
            wall_angle_rad: angle,
            ..d.clone()
        }
    }
}

/// The name of the building of `seed` and `options`.
fn name(seed: u64, options: &BuildingOptions) -> String {
    if options.area_m2 == BuildingOptions::default().area_m2 {
        format!("generated:{seed}")
    } else {
        format!("generated:{seed}:{}", options.area_m2)
    }
}

/// The rooms of `plan`, named by kind and number (`"corridor 1"`, `"room
/// 3"`, `"hall 1"`).
fn rooms(plan: &Plan, placement: &Placement) -> Vec<Room> {
    let mut counts = [0usize; 3];
    plan.regions
        .iter()
        .map(|r| {
            let k = r.kind as usize;
            counts[k] += 1;
            Room {
                name: format!("{} {}", r.kind.as_str(), counts[k]),
                kind: r.kind,
                floor_m: vec![placement.rect(&floor(&r.rect, plan.wall_m))],
            }
        })
        .collect()
}

/// A generated building in its parts, placed: walls (and glass), the items
/// with their regions and kinds, rooms, doors.
struct Parts {
    name: String,
    walls: Vec<Polygon>,
    items: Vec<(usize, ItemKind, Polygon)>,
    rooms: Vec<Room>,
    doors: Vec<Door>,
}

impl Parts {
    /// The parts of the building of `seed` (`options` checked).
    fn new(seed: u64, options: &BuildingOptions) -> Result<Self> {
        let mut rng = sim_rng(seed);
        let plan = layout::plan(&mut rng, options);
        let walls = walls::walls(&plan)?;
        let items = furniture::furnish(&mut rng, &plan, &walls, options.clutter)?;
        let placement = Placement {
            mirror: rng.random_bool(0.5),
            transpose: rng.random_bool(0.5),
            width_m: plan.regions.iter().map(|r| r.rect[2]).fold(0.0, f64::max),
        };
        Ok(Self {
            name: name(seed, options),
            walls: walls
                .polygons
                .iter()
                .map(|p| placement.polygon(p))
                .collect::<Result<Vec<_>>>()?,
            items: items
                .iter()
                .map(|i| Ok((i.region, i.kind, placement.polygon(&i.polygon)?)))
                .collect::<Result<Vec<_>>>()?,
            rooms: rooms(&plan, &placement),
            doors: walls.doors.iter().map(|d| placement.door(d)).collect(),
        })
    }

    /// The middle of the first corridor's floor: where the validity check
    /// starts.
    fn start_m(&self) -> [f64; 2] {
        let corridor = self.rooms[0].floor_m[0];
        [
            0.5 * (corridor[0] + corridor[2]),
            0.5 * (corridor[1] + corridor[3]),
        ]
    }

    /// The world of the walls and the items `kept`.
    fn world(&self, kept: impl Fn(usize, ItemKind) -> bool) -> World {
        let mut polygons = self.walls.clone();
        polygons.extend(
            self.items
                .iter()
                .enumerate()
                .filter(|(i, (_, kind, _))| kept(*i, *kind))
                .map(|(_, (_, _, p))| p.clone()),
        );
        World::new(polygons)
    }
}

impl Building {
    /// The building of `seed` (see [the module](crate::building::generate)):
    /// named `"generated:SEED"`, or `"generated:SEED:AREA"` when
    /// `options.area_m2` is not the default.
    ///
    /// # Errors
    /// [`SimError::InvalidParameter`] naming the first option out of its
    /// range ([`BuildingOptions::validate`]), before anything is drawn.
    pub fn generate(seed: u64, options: &BuildingOptions) -> Result<Building> {
        options.validate()?;
        let parts = Parts::new(seed, options)?;
        let from = parts.start_m();
        let mut kept = vec![true; parts.items.len()];
        loop {
            let world = parts.world(|i, _| kept[i]);
            let cut_off = unreachable_rooms(&world, &parts.rooms, from)?;
            if cut_off.is_empty() {
                return Building::new(parts.name, world, parts.rooms, parts.doors);
            }
            let before = kept.clone();
            for (k, (region, _, _)) in kept.iter_mut().zip(&parts.items) {
                if cut_off.contains(region) {
                    *k = false;
                }
            }
            if kept == before {
                if kept.iter().any(|&k| k) {
                    kept.fill(false);
                } else {
                    let names: Vec<&str> = cut_off
                        .iter()
                        .map(|&r| parts.rooms[r].name.as_str())
                        .collect();
                    return Err(SimError::UnreachableRooms {
                        building: parts.name,
                        rooms: names.join(", "),
                    });
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::building::RoomKind;
    use crate::material::Material;
    use proptest::prelude::*;

    fn options(area_m2: f64) -> BuildingOptions {
        BuildingOptions {
            area_m2,
            ..BuildingOptions::default()
        }
    }

    /// The same seed gives the same building (the same polygons, bit for
    /// bit, the same rooms and doors); another seed another one.
    #[test]
    fn the_same_seed_gives_the_same_building() {
        for seed in [0, 1, 17, 1_000_003] {
            let a = Building::generate(seed, &options(200.0)).unwrap();
            let b = Building::generate(seed, &options(200.0)).unwrap();
            assert_eq!(a.world().polygons(), b.world().polygons(), "{seed}");
            assert_eq!(a.rooms(), b.rooms());
            assert_eq!(a.doors(), b.doors());
            assert_eq!(a.to_json(), b.to_json());
            let c = Building::generate(seed + 1, &options(200.0)).unwrap();
            assert_ne!(a.to_json(), c.to_json());
        }
    }

    /// A digest of the building of seed 1, written down: a change that
    /// makes another building of the same seed (on this machine or any
    /// other) fails here. (Update it when the generator is changed on
    /// purpose: the split's buildings change with it.)
    #[test]
    fn seed_one_gives_the_building_it_always_gave() {
        let b = Building::generate(1, &BuildingOptions::default()).unwrap();
        let digest = b
            .world()
            .polygons()
            .iter()
            .flat_map(|p| p.exterior().iter().flatten())
            .fold(0u64, |h, v| h.rotate_left(5) ^ v.to_bits());
        assert_eq!(
            (b.world().len(), b.rooms().len(), b.doors().len(), digest),
            SEED_ONE
        );
    }
    const SEED_ONE: (usize, usize, usize, u64) = (67, 12, 12, 15731758301978113238);

    /// Properties of every building, over seeds and sizes: doors of the
    /// options' widths (hall openings 2 to 3.5 m), walls within the
    /// options' thickness, rooms whose floors lie inside the building and
    /// do not overlap, and every room reachable by the robot's disc from
    /// the first corridor.
    #[test]
    fn buildings_are_valid_over_many_seeds() {
        for seed in 0..60u64 {
            let area = [40.0, 120.0, 200.0, 550.0][seed as usize % 4];
            let b = Building::generate(seed, &options(area)).unwrap();
            check(&b, &options(area));
        }
    }

    fn check(b: &Building, o: &BuildingOptions) {
        let name = b.name();
        assert!(
            b.rooms().iter().any(|r| r.kind == RoomKind::Corridor),
            "{name}"
        );
        assert!(b.rooms().iter().any(|r| r.kind.judged()), "{name}");
        for d in b.doors() {
            let hall = d.rooms.iter().any(|&r| b.rooms()[r].kind == RoomKind::Hall);
            let [lo, hi] = if hall { [2.0, 3.5] } else { o.door_width_m };
            assert!(
                (lo - 1e-9..=hi + 1e-9).contains(&d.width_m),
                "{name}: door of {} m",
                d.width_m
            );
        }
        let area: f64 = b.rooms().iter().map(Room::area_m2).sum();
        assert!(area < o.area_m2 && area > 0.6 * o.area_m2, "{name}: {area}");
        for (i, r) in b.rooms().iter().enumerate() {
            for s in &b.rooms()[i + 1..] {
                let [f, g] = [r.floor_m[0], s.floor_m[0]];
                let w = f[2].min(g[2]) - f[0].max(g[0]);
                let h = f[3].min(g[3]) - f[1].max(g[1]);
                assert!(w <= 1e-9 || h <= 1e-9, "{name}: {} and {}", r.name, s.name);
            }
        }
        let glass = b
            .world()
            .polygons()
            .iter()
            .filter(|p| p.material() == Material::Glass)
            .count();
        // At most two panes a room, either side of its door.
        assert!(glass <= 2 * b.rooms().len(), "{name}");
        let corridor = b.rooms()[0].floor_m[0];
        let from = [
            0.5 * (corridor[0] + corridor[2]),
            0.5 * (corridor[1] + corridor[3]),
        ];
        let cut_off = unreachable_rooms(b.world(), b.rooms(), from).unwrap();
        assert!(cut_off.is_empty(), "{name}: rooms {cut_off:?} cut off");
    }

    /// Furniture and pillars never cut off a part of a room: every cell
    /// of a room's floor where the robot's disc fits, and which it reaches
    /// from the first corridor with walls and slanted walls alone (not the
    /// pocket behind a slanted wall), it still reaches with everything
    /// placed; over seeds and sizes, the rooms as full as the options let
    /// them be.
    #[test]
    fn furniture_never_cuts_off_a_part_of_a_room() {
        use crate::building::validity::{cells_in, reach};
        for seed in 0..24u64 {
            let o = BuildingOptions {
                area_m2: [120.0, 250.0, 550.0][seed as usize % 3],
                clutter: 1.0,
                ..BuildingOptions::default()
            };
            let parts = Parts::new(seed, &o).unwrap();
            let bare = reach(
                &parts.world(|_, kind| kind == ItemKind::SlantedWall),
                parts.start_m(),
            )
            .unwrap();
            let full = reach(&parts.world(|_, _| true), parts.start_m()).unwrap();
            assert_eq!(bare.grid, full.grid);
            for room in &parts.rooms {
                for floor in &room.floor_m {
                    for i in cells_in(&full.grid, floor) {
                        if full.free[i] && bare.reached[i] {
                            assert!(
                                full.reached[i],
                                "{}: {} cut off at {:?}",
                                parts.name,
                                room.name,
                                full.grid.cell_center(full.grid.cell(i))
                            );
                        }
                    }
                }
            }
            // The building returned keeps every item.
            let b = Building::generate(seed, &o).unwrap();
            assert_eq!(b.world().len(), parts.walls.len() + parts.items.len());
        }
    }

    #[test]
    fn bad_options_are_refused_before_anything_is_drawn() {
        let bad = BuildingOptions {
            door_width_m: [0.3, 1.0],
            ..BuildingOptions::default()
        };
        let e = Building::generate(0, &bad).unwrap_err();
        assert!(e.to_string().contains("door_width_m[0]"), "{e}");
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(24))]
        /// Any seed, any size and clutter within the defaults' ranges:
        /// a valid building, the same twice.
        #[test]
        fn any_seed_gives_a_valid_building(
            seed in any::<u64>(),
            area in 40.0f64..400.0,
            clutter in 0.0f64..=1.0,
            glass in 0.0f64..=1.0,
        ) {
            let o = BuildingOptions { area_m2: area, clutter, glass, ..BuildingOptions::default() };
            let a = Building::generate(seed, &o).unwrap();
            check(&a, &o);
            let b = Building::generate(seed, &o).unwrap();
            prop_assert_eq!(a.to_json(), b.to_json());
        }
    }
}
