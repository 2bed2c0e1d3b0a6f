//! ARIA `.map` worlds (MobileRobots / Adept MobileSim).
//!
//! The file starts with a `2D-Map` line and header lines (`MinPos:`,
//! `NumLines:`, `Cairn:` annotations, ...). The `LINES` line opens the wall
//! section: one segment `x1 y1 x2 y2` per line, in millimetres, up to the
//! `DATA` line (scan points, ignored) or the end of the file. Each segment
//! becomes a [`Polygon::wall`] of the given thickness (centred on the segment,
//! extended by half the thickness at both ends so that corners close). A
//! `NumLines:` header, when present, must match the number of segments.
#![cfg_attr(not(test), warn(clippy::indexing_slicing))]

use std::path::Path;

use super::{parse_error, read_text};
use crate::error::{Result, SimError, check_param};
use crate::material::Material;
use crate::polygon::Polygon;
use crate::world::World;

/// The thickest wall an ARIA map's segments may be drawn as, metres.
pub const MAX_WALL_THICKNESS_M: f64 = 100.0;

impl World {
    /// A world from the wall segments of an ARIA `.map` file, each a wall
    /// `wall_thickness_m` thick (see [the format](crate::load::aria)), at most
    /// [`MAX_WALL_THICKNESS_M`].
    pub fn from_aria_map_file(path: impl AsRef<Path>, wall_thickness_m: f64) -> Result<World> {
        let path = path.as_ref();
        Self::from_aria_map_str(&read_text(path)?, path, wall_thickness_m)
    }

    /// A world from ARIA map text; `name` is the file name errors report.
    ///
    /// # Example
    /// ```
    /// use covmap_sim::World;
    /// let text = "2D-Map\nNumLines: 2\nLINES\n0 0 4000 0\n4000 0 4000 3000\nDATA\n1 2\n";
    /// let world = World::from_aria_map_str(text, "tiny.map", 0.1).unwrap();
    /// assert_eq!(world.len(), 2);
    /// assert!(world.contains_point([2.0, 0.04]));
    /// let err = World::from_aria_map_str("2D-Map\nLINES\n0 0 10\n", "bad.map", 0.1).unwrap_err();
    /// assert!(err.to_string().starts_with("bad.map, line 3"), "{err}");
    /// ```
    pub fn from_aria_map_str(
        text: &str,
        name: impl AsRef<Path>,
        wall_thickness_m: f64,
    ) -> Result<World> {
        let path = name.as_ref();
        check_param(
            "wall_thickness_m",
            wall_thickness_m,
            wall_thickness_m > 0.0 && wall_thickness_m <= MAX_WALL_THICKNESS_M,
            "a positive wall thickness of at most 100 m",
        )?;
        let mut lines = text.lines().enumerate().map(|(i, l)| (i + 1, l.trim()));
        match lines.next() {
            Some((_, first)) if first.starts_with("2D-Map") => {}
            _ => {
                return Err(parse_error(
                    path,
                    "line 1",
                    "an ARIA map starts with a `2D-Map` line",
                ));
            }
        }
        let mut declared: Option<(usize, usize)> = None;
        let mut in_lines = false;
        let mut seen_lines = false;
        let mut polygons = Vec::new();
        for (no, line) in lines {
            if line.is_empty() {
                continue;
            }
            if in_lines {
                if line == "DATA" || line == "LINES" || line.ends_with(':') {
                    in_lines = false;
                    if line == "DATA" {
                        break;
                    }
                    continue;
                }
                let numbers: Vec<&str> = line.split_whitespace().collect();
                let parsed: Option<Vec<f64>> = numbers
                    .iter()
                    .map(|t| t.parse::<f64>().ok().filter(|v| v.is_finite()))
                    .collect();
                let [x1, y1, x2, y2] = match parsed.as_deref() {
                    Some(&[x1, y1, x2, y2]) => [x1, y1, x2, y2],
                    _ => {
                        return Err(parse_error(
                            path,
                            format!("line {no}"),
                            format!(
                                "expected a wall segment `x1 y1 x2 y2` in millimetres, found {line:?}"
                            ),
                        ));
                    }
                };
                let a = [x1 / 1000.0, y1 / 1000.0];
                let b = [x2 / 1000.0, y2 / 1000.0];
                let wall =
                    Polygon::wall(a, b, wall_thickness_m, Material::Wall).map_err(|e| match e {
                        SimError::InvalidPolygon { reason, .. } => {
                            parse_error(path, format!("line {no}"), reason)
                        }
                        other => other,
                    })?;
                polygons.push(wall);
                continue;
            }
            if line == "LINES" {
                in_lines = true;
                seen_lines = true;
            } else if line == "DATA" {
                break;
            } else if let Some(rest) = line.strip_prefix("NumLines:") {
                let n = rest.trim().parse::<usize>().map_err(|_| {
                    parse_error(
                        path,
                        format!("line {no}"),
                        format!("NumLines must be a count, found {:?}", rest.trim()),
                    )
                })?;
                declared = Some((n, no));
            }
        }
        if !seen_lines || polygons.is_empty() {
            return Err(parse_error(
                path,
                "LINES section",
                "no wall segment: the world would be empty",
            ));
        }
        if let Some((n, no)) = declared
            && n != polygons.len()
        {
            return Err(parse_error(
                path,
                format!("line {no}"),
                format!(
                    "NumLines declares {n} segments but the LINES section holds {}",
                    polygons.len()
                ),
            ));
        }
        Ok(World::new(polygons))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn errors_name_the_line() {
        let e = World::from_aria_map_str("LINES\n0 0 1 1\n", "a.map", 0.1).unwrap_err();
        assert!(e.to_string().contains("a.map, line 1"), "{e}");
        let e = World::from_aria_map_str("2D-Map\nLINES\n0 0 1000 0\n5 5 5 5\n", "a.map", 0.1)
            .unwrap_err();
        assert!(e.to_string().contains("a.map, line 4: wall from"), "{e}");
        let e = World::from_aria_map_str("2D-Map\nNumLines: 3\nLINES\n0 0 1000 0\n", "a.map", 0.1)
            .unwrap_err();
        assert!(e.to_string().contains("line 2: NumLines declares 3"), "{e}");
        let e = World::from_aria_map_str("2D-Map\nLINES\nDATA\n1 1\n", "a.map", 0.1).unwrap_err();
        assert!(e.to_string().contains("no wall segment"), "{e}");
        let e = World::from_aria_map_str("2D-Map\nLINES\n0 0 1000 x\n", "a.map", 0.1).unwrap_err();
        assert!(e.to_string().contains("line 3"), "{e}");
        assert!(World::from_aria_map_str("2D-Map\nLINES\n0 0 1000 0\n", "a.map", 0.0).is_err());
    }

    #[test]
    fn walls_have_the_thickness() {
        let w = World::from_aria_map_str("2D-Map\nLINES\n0 0 2000 0\n", "a.map", 0.1).unwrap();
        // 2 m long plus 5 cm at each end, 10 cm thick.
        assert!((w.polygon_area_m2() - 2.1 * 0.1).abs() < 1e-12);
        assert!(w.contains_point([2.04, 0.0]) && !w.contains_point([2.06, 0.0]));
        // A thickness no wall has is the parameter's fault, not the file's.
        for bad in [0.0, -0.1, 1e300, f64::NAN] {
            let e =
                World::from_aria_map_str("2D-Map\nLINES\n0 0 2000 0\n", "a.map", bad).unwrap_err();
            assert!(
                matches!(
                    e,
                    SimError::InvalidParameter {
                        name: "wall_thickness_m",
                        ..
                    }
                ),
                "{e}"
            );
        }
    }
}
