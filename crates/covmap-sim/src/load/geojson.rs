//! GeoJSON worlds.
//!
//! A world file is a GeoJSON (RFC 7946) `FeatureCollection` whose features are
//! `Polygon` or `MultiPolygon` geometries with coordinates in **metres** (not
//! longitude and latitude). Each polygon is one obstacle: its first ring the
//! exterior, further rings holes; rings in either orientation, closed (first
//! position repeated, as the RFC asks) or not; positions `[x, y]` (a third
//! element is ignored). A feature's `properties.material` is `"wall"`
//! (default) or `"glass"`. A lone `Feature`, `Polygon` or `MultiPolygon` is
//! accepted as the top-level object too.
//!
//! ```json
//! {"type": "FeatureCollection", "features": [
//!   {"type": "Feature", "properties": {"material": "glass"},
//!    "geometry": {"type": "Polygon",
//!                 "coordinates": [[[0, 0], [4, 0], [4, 0.05], [0, 0.05], [0, 0]]]}}
//! ]}
//! ```
#![cfg_attr(not(test), warn(clippy::indexing_slicing))]

use std::path::Path;

use serde_json::{Value, json};

use super::{parse_error, read_text, write_atomic};
use crate::error::{Result, SimError};
use crate::material::Material;
use crate::polygon::Polygon;
use crate::world::World;

impl World {
    /// A world from a GeoJSON file (see [the format](crate::load::geojson)).
    pub fn from_geojson_file(path: impl AsRef<Path>) -> Result<World> {
        let path = path.as_ref();
        Self::from_geojson_str(&read_text(path)?, path)
    }

    /// A world from GeoJSON text; `name` is the file name errors report.
    ///
    /// # Example
    /// ```
    /// use covmap_sim::{Material, World};
    /// let text = r#"{"type": "FeatureCollection", "features": [
    ///   {"type": "Feature", "properties": {"material": "glass"},
    ///    "geometry": {"type": "Polygon", "coordinates": [[[0,0],[4,0],[4,1],[0,1],[0,0]]]}}]}"#;
    /// let world = World::from_geojson_str(text, "inline.geojson").unwrap();
    /// assert_eq!(world.polygons()[0].material(), Material::Glass);
    /// assert_eq!(World::from_geojson_str(&world.to_geojson(), "again").unwrap().polygons(), world.polygons());
    /// let err = World::from_geojson_str(r#"{"type": "Polygon", "coordinates": [[[0,0],[1,1]]]}"#, "bad.json").unwrap_err();
    /// assert!(err.to_string().starts_with("bad.json, polygon 0"), "{err}");
    /// ```
    pub fn from_geojson_str(text: &str, name: impl AsRef<Path>) -> Result<World> {
        let path = name.as_ref();
        let root: Value = serde_json::from_str(text).map_err(|e| {
            parse_error(
                path,
                format!("line {}, column {}", e.line(), e.column()),
                format!("not valid JSON: {e}"),
            )
        })?;
        let mut polygons = Vec::new();
        match type_of(&root) {
            Some("FeatureCollection") => {
                let features = root
                    .get("features")
                    .and_then(Value::as_array)
                    .ok_or_else(|| {
                        parse_error(
                            path,
                            "top level",
                            "a FeatureCollection needs a `features` array",
                        )
                    })?;
                for (i, f) in features.iter().enumerate() {
                    feature(f, &format!("feature {i}"), path, &mut polygons)?;
                }
            }
            Some("Feature") => feature(&root, "feature 0", path, &mut polygons)?,
            Some("Polygon") | Some("MultiPolygon") => {
                geometry(&root, Material::Wall, "", path, &mut polygons)?
            }
            other => {
                return Err(parse_error(
                    path,
                    "top level",
                    format!(
                        "expected a FeatureCollection, Feature, Polygon or MultiPolygon, found {}",
                        other.map_or("no `type`".to_string(), |t| format!("type {t:?}"))
                    ),
                ));
            }
        }
        if polygons.is_empty() {
            return Err(parse_error(
                path,
                "top level",
                "no polygon: the world would be empty",
            ));
        }
        Ok(World::new(polygons))
    }

    /// The world as GeoJSON text (a `FeatureCollection`, closed rings,
    /// `properties.material`), readable by [`World::from_geojson_str`].
    pub fn to_geojson(&self) -> String {
        let features: Vec<Value> = self
            .polygons()
            .iter()
            .map(|p| {
                let rings: Vec<Vec<[f64; 2]>> = p
                    .rings()
                    .iter()
                    .map(|r| {
                        let mut closed = r.clone();
                        closed.extend(r.first());
                        closed
                    })
                    .collect();
                json!({
                    "type": "Feature",
                    "properties": {"material": p.material().as_str()},
                    "geometry": {"type": "Polygon", "coordinates": rings},
                })
            })
            .collect();
        let doc = json!({"type": "FeatureCollection", "features": features});
        // A Value of plain numbers and strings always serialises.
        serde_json::to_string_pretty(&doc).unwrap_or_default()
    }

    /// Write [`World::to_geojson`] to `path` atomically.
    pub fn save_geojson(&self, path: impl AsRef<Path>) -> Result<()> {
        write_atomic(path.as_ref(), self.to_geojson().as_bytes())
    }
}

fn type_of(v: &Value) -> Option<&str> {
    v.get("type").and_then(Value::as_str)
}

fn feature(f: &Value, place: &str, path: &Path, out: &mut Vec<Polygon>) -> Result<()> {
    if type_of(f) != Some("Feature") {
        return Err(parse_error(
            path,
            place,
            "expected an object of type \"Feature\"",
        ));
    }
    let material = match f.get("properties").and_then(|p| p.get("material")) {
        None | Some(Value::Null) => Material::Wall,
        Some(Value::String(s)) => Material::from_name(s).ok_or_else(|| {
            parse_error(
                path,
                place,
                format!("unknown material {s:?} (expected \"wall\" or \"glass\")"),
            )
        })?,
        Some(other) => {
            return Err(parse_error(
                path,
                place,
                format!("material must be a string, found {other}"),
            ));
        }
    };
    let g = f
        .get("geometry")
        .filter(|g| !g.is_null())
        .ok_or_else(|| parse_error(path, place, "the feature has no geometry"))?;
    geometry(g, material, &format!("{place}, "), path, out)
}

fn geometry(
    g: &Value,
    material: Material,
    prefix: &str,
    path: &Path,
    out: &mut Vec<Polygon>,
) -> Result<()> {
    let coords = g.get("coordinates");
    match type_of(g) {
        Some("Polygon") => {
            let place = format!("{prefix}polygon 0");
            out.push(polygon(coords, material, &place, path)?);
        }
        Some("MultiPolygon") => {
            let polys = coords.and_then(Value::as_array).ok_or_else(|| {
                parse_error(
                    path,
                    prefix.trim_end_matches(", "),
                    "MultiPolygon coordinates must be an array",
                )
            })?;
            for (k, p) in polys.iter().enumerate() {
                out.push(polygon(
                    Some(p),
                    material,
                    &format!("{prefix}polygon {k}"),
                    path,
                )?);
            }
        }
        other => {
            return Err(parse_error(
                path,
                prefix.trim_end_matches(", "),
                format!("expected a Polygon or MultiPolygon geometry, found {other:?}"),
            ));
        }
    }
    Ok(())
}

fn polygon(
    coords: Option<&Value>,
    material: Material,
    place: &str,
    path: &Path,
) -> Result<Polygon> {
    let rings = coords
        .and_then(Value::as_array)
        .filter(|r| !r.is_empty())
        .ok_or_else(|| {
            parse_error(
                path,
                place,
                "polygon coordinates must be a non-empty array of rings",
            )
        })?;
    let mut parsed = Vec::with_capacity(rings.len());
    for (r, ring) in rings.iter().enumerate() {
        let positions = ring.as_array().ok_or_else(|| {
            parse_error(
                path,
                format!("{place}, ring {r}"),
                "a ring must be an array of positions",
            )
        })?;
        let mut pts = Vec::with_capacity(positions.len());
        for (i, p) in positions.iter().enumerate() {
            let xy = p.as_array().and_then(|a| {
                let x = a.first()?.as_f64()?;
                let y = a.get(1)?.as_f64()?;
                Some([x, y])
            });
            let xy = xy.ok_or_else(|| {
                parse_error(
                    path,
                    format!("{place}, ring {r}, position {i}"),
                    format!("expected [x, y] in metres, found {p}"),
                )
            })?;
            pts.push(xy);
        }
        parsed.push(pts);
    }
    let exterior = parsed.remove(0);
    Polygon::with_holes(exterior, parsed, material).map_err(|e| match e {
        SimError::InvalidPolygon { reason, .. } => parse_error(path, place, reason),
        other => other,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn errors_name_the_place() {
        let e = World::from_geojson_str("{\"type\": \n [", "w.json").unwrap_err();
        assert!(e.to_string().starts_with("w.json, line 2"), "{e}");
        let fc = |features: &str| {
            format!(r#"{{"type": "FeatureCollection", "features": [{features}]}}"#)
        };
        let ok = r#"{"type": "Feature", "geometry": {"type": "Polygon", "coordinates": [[[0,0],[1,0],[1,1]]]}}"#;
        let bad_pos = r#"{"type": "Feature", "geometry": {"type": "Polygon", "coordinates": [[[0,0],[1,"a"],[1,1]]]}}"#;
        let e = World::from_geojson_str(&fc(&format!("{ok}, {bad_pos}")), "w.json").unwrap_err();
        assert!(
            e.to_string()
                .contains("feature 1, polygon 0, ring 0, position 1"),
            "{e}"
        );
        let glassy = r#"{"type": "Feature", "properties": {"material": "steel"}, "geometry": {"type": "Polygon", "coordinates": [[[0,0],[1,0],[1,1]]]}}"#;
        let e = World::from_geojson_str(&fc(glassy), "w.json").unwrap_err();
        assert!(
            e.to_string()
                .contains("feature 0: unknown material \"steel\""),
            "{e}"
        );
        let point = r#"{"type": "Feature", "geometry": {"type": "Point", "coordinates": [0, 0]}}"#;
        assert!(World::from_geojson_str(&fc(point), "w.json").is_err());
        let degenerate = r#"{"type": "Feature", "geometry": {"type": "MultiPolygon", "coordinates": [[[[0,0],[1,0],[1,1]]], [[[0,0],[1,1],[2,2]]]]}}"#;
        let e = World::from_geojson_str(&fc(degenerate), "w.json").unwrap_err();
        assert!(
            e.to_string()
                .contains("feature 0, polygon 1: exterior ring: zero area"),
            "{e}"
        );
        assert!(World::from_geojson_str(&fc(""), "w.json").is_err());
    }

    #[test]
    fn round_trip_keeps_holes_and_materials() {
        let w = World::builtin("corridor").unwrap();
        let back = World::from_geojson_str(&w.to_geojson(), "x").unwrap();
        assert_eq!(back.polygons(), w.polygons());
        let holed = Polygon::with_holes(
            vec![[0.0, 0.0], [3.0, 0.0], [3.0, 3.0], [0.0, 3.0]],
            vec![vec![[1.0, 1.0], [2.0, 1.0], [2.0, 2.0], [1.0, 2.0]]],
            Material::Glass,
        )
        .unwrap();
        let w = World::new(vec![holed]);
        let back = World::from_geojson_str(&w.to_geojson(), "x").unwrap();
        assert_eq!(back.polygons(), w.polygons());
        assert_eq!(back.polygons()[0].area_m2(), 8.0);
    }
}
