//! Worlds built into the library, by name.

use crate::error::{Result, SimError};
use crate::material::Material::{Glass, Wall};
use crate::polygon::Polygon;
use crate::world::World;

const NAMES: [&str; 3] = ["corridor", "office", "partial"];

impl World {
    /// The names of the built-in worlds: `corridor`, `office`, `partial`.
    pub fn builtin_names() -> &'static [&'static str] {
        &NAMES
    }

    /// A built-in world:
    ///
    /// - `corridor`: the setting of the paper's Fig. 3. A corridor 17 m long
    ///   (inner faces `x = 0` to the slanted east wall, which crosses `y = 1.3`
    ///   at `x = 17`) and 2.6 m wide (`y` in `[0, 2.6]`), 12 cm walls; three
    ///   rooms to the north (`y` up to 6.2) through 0.9 m doorways; narrow
    ///   pillars against both walls; a glass pane in the south wall (`x` in
    ///   `[6, 9]`) and a glass front to the middle room (`x` in `[8.4, 10]`);
    ///   a desk, a round column and a rotated box in the rooms. The centre
    ///   line `y = 1.3` is free from `x = 0.3` to `x = 16.5`.
    /// - `office`: a 30 m x 20 m floor: a 2.5 m corridor (`y` in `[8.5, 11]`)
    ///   between five rooms to the south and four to the north, one of them
    ///   a meeting room with a glass front; desks, cabinets, round columns and
    ///   rotated tables; pillars along the corridor.
    /// - `partial`: the arrangement of the paper's Fig. 1: a wall block whose
    ///   face is the line `x = 2.04` (`y` in `[-1, 1]`, block up to `x = 2.5`),
    ///   so on any grid with cell boundaries at multiples of 5 cm the cells of
    ///   `x` in `[2.00, 2.05)` are 20 % covered, in their far part as seen from
    ///   a robot at the origin.
    pub fn builtin(name: &str) -> Result<World> {
        let polygons = match name {
            "corridor" => corridor()?,
            "office" => office()?,
            "partial" => vec![Polygon::rectangle([2.04, -1.0], [2.5, 1.0], Wall)?],
            _ => {
                return Err(SimError::UnknownWorld {
                    name: covmap_core::quoted(name),
                    available: NAMES.join(", "),
                });
            }
        };
        Ok(World::new(polygons))
    }
}

fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Result<Polygon> {
    Polygon::rectangle([x0, y0], [x1, y1], Wall)
}

fn glass(x0: f64, y0: f64, x1: f64, y1: f64) -> Result<Polygon> {
    Polygon::rectangle([x0, y0], [x1, y1], Glass)
}

/// A `w x h` box centred on `c`, rotated by `angle_deg`.
fn rotated_box(c: [f64; 2], w: f64, h: f64, angle_deg: f64) -> Result<Polygon> {
    let (s, co) = angle_deg.to_radians().sin_cos();
    let corners = [[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]];
    Polygon::new(
        corners
            .iter()
            .map(|[u, v]| {
                let (x, y) = (u * w, v * h);
                [c[0] + co * x - s * y, c[1] + s * x + co * y]
            })
            .collect(),
        Wall,
    )
}

fn column(c: [f64; 2], radius: f64) -> Result<Polygon> {
    Polygon::regular(c, radius, 12, 0.1, Wall)
}

fn corridor() -> Result<Vec<Polygon>> {
    const T: f64 = 0.12;
    const W: f64 = 2.6; // corridor width
    const N: f64 = 6.2; // inner face of the rooms' north wall
    Ok(vec![
        // South wall with a glass pane, open to the outside behind it.
        rect(-T, -T, 6.0, 0.0)?,
        glass(6.0, -0.03, 9.0, 0.0)?,
        rect(9.0, -T, 17.4, 0.0)?,
        // West end wall, up to the rooms' north wall.
        rect(-T, -T, 0.0, N + T)?,
        // East end: a wall that is not axis-aligned, crossing y = 1.3 at x = 17.
        Polygon::wall([16.75, -0.2], [17.25, W + 0.2], T, Wall)?,
        // North corridor wall: doorways at [1.8, 2.7], [7.0, 7.9], [12.6, 13.5];
        // the middle room's front is glass from 8.4 to 10.
        rect(-T, W, 1.8, W + T)?,
        rect(2.7, W, 7.0, W + T)?,
        rect(7.9, W, 8.4, W + T)?,
        glass(8.4, W, 10.0, W + 0.03)?,
        rect(10.0, W, 12.6, W + T)?,
        rect(13.5, W, 17.5, W + T)?,
        // Room partitions and the rooms' north wall.
        rect(5.0, W, 5.0 + T, N)?,
        rect(10.5, W, 10.5 + T, N)?,
        rect(16.0, W, 16.0 + T, N)?,
        rect(-T, N, 16.0 + T, N + T)?,
        // Narrow pillars against the walls.
        rect(3.0, 0.0, 3.16, 0.22)?,
        rect(11.5, 0.0, 11.66, 0.22)?,
        rect(14.8, 0.0, 14.96, 0.22)?,
        rect(4.2, W - 0.22, 4.36, W)?,
        rect(9.6, W - 0.22 - 0.03, 9.76, W)?,
        // Furniture.
        rect(0.4, 5.4, 2.0, N)?,
        column([7.5, 4.6], 0.25)?,
        rotated_box([14.0, 4.5], 1.2, 0.6, 30.0)?,
    ])
}

fn office() -> Result<Vec<Polygon>> {
    const T: f64 = 0.15;
    const X: f64 = 30.0;
    const Y: f64 = 20.0;
    const S: f64 = 8.5; // corridor's south face
    const C: f64 = 11.0; // corridor's north face
    let mut p = vec![
        rect(-T, -T, X + T, 0.0)?,
        rect(-T, Y, X + T, Y + T)?,
        rect(-T, 0.0, 0.0, Y)?,
        rect(X, 0.0, X + T, Y)?,
    ];
    // South rooms: five, 6 m wide, 1 m doors in the corridor wall.
    for k in 0..5 {
        let x0 = 6.0 * k as f64;
        let door = x0 + 2.5;
        p.push(rect(x0, S - T, door, S)?);
        p.push(rect(door + 1.0, S - T, x0 + 6.0, S)?);
        if k > 0 {
            p.push(rect(x0 - 0.5 * T, 0.0, x0 + 0.5 * T, S - T)?);
        }
        // Desks along the south wall, a cabinet by the door.
        p.push(rect(x0 + 0.6, 0.0, x0 + 2.2, 0.8)?);
        p.push(rect(x0 + 3.4, 0.0, x0 + 5.0, 0.8)?);
        p.push(rect(x0 + 4.8, S - T - 0.5, x0 + 5.7, S - T)?);
        match k {
            1 => p.push(column([x0 + 3.0, 4.0], 0.3)?),
            2 => p.push(rotated_box([x0 + 3.0, 4.2], 2.0, 1.0, 25.0)?),
            3 => {
                p.push(rect(x0 + 1.0, 3.0, x0 + 1.6, 5.5)?);
                p.push(column([x0 + 4.0, 5.0], 0.2)?);
            }
            4 => p.push(rotated_box([x0 + 3.5, 3.5], 1.4, 0.7, -40.0)?),
            _ => p.push(rect(x0 + 2.0, 3.5, x0 + 4.0, 4.5)?),
        }
    }
    // North rooms: four, 7.5 m wide; room 1 is a meeting room with a glass front.
    for k in 0..4 {
        let x0 = 7.5 * k as f64;
        let door = x0 + 1.0;
        if k == 1 {
            p.push(rect(x0, C, door, C + T)?);
            p.push(glass(door + 1.0, C, x0 + 7.5, C + 0.04)?);
        } else {
            p.push(rect(x0, C, door, C + T)?);
            p.push(rect(door + 1.0, C, x0 + 7.5, C + T)?);
        }
        if k > 0 {
            p.push(rect(x0 - 0.5 * T, C + T, x0 + 0.5 * T, Y)?);
        }
        match k {
            1 => {
                // A long table with chairs.
                p.push(rect(x0 + 2.0, 14.5, x0 + 5.5, 15.7)?);
                for i in 0..4 {
                    let cx = x0 + 2.3 + 0.9 * i as f64;
                    p.push(rect(cx, 14.0, cx + 0.4, 14.4)?);
                    p.push(rect(cx, 15.8, cx + 0.4, 16.2)?);
                }
            }
            _ => {
                p.push(rect(x0 + 0.5, Y - 0.8, x0 + 2.5, Y)?);
                p.push(rect(x0 + 4.5, Y - 0.8, x0 + 6.5, Y)?);
                p.push(rect(
                    x0 + 6.7,
                    C + T + 1.5,
                    x0 + 7.5 - 0.5 * T,
                    C + T + 3.5,
                )?);
                p.push(rotated_box(
                    [x0 + 3.5, 15.0],
                    1.6,
                    0.8,
                    15.0 * (k as f64 - 1.0),
                )?);
                p.push(column([x0 + 1.5, 14.0], 0.25)?);
            }
        }
    }
    // Pillars along the corridor walls, clear of the doors.
    for i in 0..5 {
        let x = 5.0 + 6.0 * i as f64;
        p.push(rect(x, S, x + 0.3, S + 0.3)?);
    }
    for i in 0..4 {
        let x = 6.0 + 7.5 * i as f64;
        p.push(rect(x, C - 0.3, x + 0.3, C)?);
    }
    Ok(p)
}

#[cfg(test)]
mod tests {
    use super::*;
    use covmap_core::Grid;

    #[test]
    fn every_builtin_builds() {
        for name in World::builtin_names() {
            let w = World::builtin(name).unwrap();
            assert!(!w.is_empty(), "{name}");
        }
        let e = World::builtin("nowhere").unwrap_err();
        assert!(e.to_string().contains("corridor, office, partial"), "{e}");
    }

    #[test]
    fn corridor_layout() {
        let w = World::builtin("corridor").unwrap();
        // The centre line is free, the rooms reachable through the doors.
        for i in 0..=162 {
            let x = 0.3 + 0.1 * i as f64;
            assert!(w.distance_to_obstacle_m([x, 1.3]) > 0.25, "x = {x}");
        }
        for door in [2.25, 7.45, 13.05] {
            assert!(w.distance_to_obstacle_m([door, W_MID]) >= 0.45 - 1e-9);
        }
        // Where the slanted wall crosses the centre line.
        let hit = w.cast([16.0, 1.3], 0.0, 5.0);
        assert!((hit.distance_m - (17.0 - 16.0 - 0.06 / (0.5f64.atan2(3.0)).cos())).abs() < 1e-9);
        assert!(hit.incidence_rad > 0.1);
        // Glass in the south wall.
        assert_eq!(
            w.cast([7.5, 1.3], -std::f64::consts::FRAC_PI_2, 5.0)
                .material,
            Some(Glass)
        );
    }
    const W_MID: f64 = 2.66;

    #[test]
    fn partial_is_fig1() {
        let w = World::builtin("partial").unwrap();
        let g = Grid::new([0.0, -0.5], 0.05, 20, 60).unwrap();
        let c = w.coverage(&g);
        let cell = g.index(g.world_to_cell(2.03, 0.0).unwrap()).unwrap();
        assert!((c[cell] - 0.2).abs() < 1e-9, "{}", c[cell]);
    }

    #[test]
    fn office_is_larger_and_has_glass() {
        let w = World::builtin("office").unwrap();
        let [x0, y0, x1, y1] = w.bounds_m();
        assert!(x1 - x0 > 29.0 && y1 - y0 > 19.0);
        assert!(w.polygons().iter().any(|p| p.material() == Glass));
        assert!(w.segment_count() > 300, "{}", w.segment_count());
    }
}
