//! ROS map_server / nav2 map_saver files: a YAML file and the image it
//! names, read as a world and written from `nav_msgs/OccupancyGrid` data
//! (one `i8` a cell, `-1` unknown, `0..=100` percent occupied).
//!
//! # Reading
//! A YAML file gives `image` (a path relative to the YAML file),
//! `resolution`, `origin: [x, y, yaw]`, and optionally `negate` (0/1, default
//! 0), `occupied_thresh` (default 0.65), `free_thresh` (default 0.196) and
//! `mode: trinary` (the default: occupied and unknown pixels are obstacles)
//! or `mode: scale` (occupied pixels are). The YAML is read by serde (`serde_norway`, the maintained fork
//! of serde_yaml): a value of the wrong type is an error naming its line, a
//! value map_server refuses one naming its key. The image is read as
//! [`super::image`] reads occupancy images.
//!
//! The YAML's nesting is bounded before it is parsed: the parser's time
//! grows with the square of how deeply flow collections (`[...]`, `{...}`)
//! nest (thousands of levels under an ignored key take seconds), so a file
//! may hold at most [`MAX_FLOW_COLLECTIONS`] of them that hold something
//! ([`flow_collections`]: the `[` and `{` not closed at once, quoted or
//! not, which bound the depth without parsing). map_saver's files hold
//! one, the origin. Nested block collections cost the parser time in
//! proportion to the file's size (each level is a line indented further),
//! so they need no bound of their own.
//!
//! # Writing
//! Pixels as map_saver makes them: in `trinary` mode a cell at or above
//! `occupied_thresh` (in percent, rounded) is black (0), one at or below
//! `free_thresh` white (254), the rest and unknown grey (205); in `scale`
//! mode a known cell of `v` percent is `(100 - v) 255 / 100`, unknown 205.
//! Row 0 of the image is the map's top row. [`World::from_ros_map_yaml`]
//! (and map_server) read the pair back. The PGM is encoded by the `image`
//! crate (`pnm`), the YAML by serde (`serde_norway`), which quotes an image
//! name that plain YAML would misread.
//!
//! [`World::from_ros_map_yaml`]: crate::World::from_ros_map_yaml

use std::path::Path;

use covmap_core::Grid;
use image::ExtendedColorType;
use image::codecs::pnm::{PnmEncoder, PnmSubtype, SampleEncoding};

use super::image::{DEFAULT_FREE_THRESH, ImageOptions};
use super::{parse_error, read_text, write_atomic_all};
use crate::error::{Result, SimError, check_param};
use crate::world::World;

/// The most flow collections (`[...]`, `{...}`) that hold something a
/// map_server YAML file may hold ([`flow_collections`]): a bound on their
/// nesting, whose depth the YAML parser's time grows with the square of.
/// map_saver's files hold one (the origin).
pub const MAX_FLOW_COLLECTIONS: usize = 64;

/// How many flow collections that hold something `text` may open, at
/// most: its `[` and `{` not followed at once by `]` or `}` (an empty `[]`
/// nests nothing), wherever they are (a bracket in a quoted string counts
/// too, so no parsing is needed). Flow collections nest at most one deeper
/// than this count: each but the innermost of a nest holds the next.
pub fn flow_collections(text: &str) -> usize {
    let bytes = text.as_bytes();
    bytes
        .iter()
        .enumerate()
        .filter(|&(i, &b)| match b {
            b'[' => bytes.get(i + 1) != Some(&b']'),
            b'{' => bytes.get(i + 1) != Some(&b'}'),
            _ => false,
        })
        .count()
}

impl World {
    /// A world from a ROS map_server YAML file and the image it names; see
    /// [the rules](crate::load::map_server).
    pub fn from_ros_map_yaml(path: impl AsRef<Path>) -> Result<World> {
        let path = path.as_ref();
        let (image, options) = parse_ros_map_yaml(&read_text(path)?, path)?;
        let image_path = path.parent().unwrap_or(Path::new("")).join(image);
        Self::from_image_file(image_path, &options)
    }
}

/// A map_server YAML file's keys, as serde reads them (serde_norway, the
/// maintained fork of serde_yaml); other keys are ignored, as map_server
/// ignores them. A value of the wrong type is refused by serde, naming its
/// line; values of the right type that map_server refuses are refused
/// after, naming their key.
#[derive(serde::Deserialize)]
struct RosMapYaml {
    image: Option<String>,
    resolution: Option<f64>,
    origin: Option<[f64; 3]>,
    /// map_server's 0 or 1, or a YAML boolean.
    negate: Option<serde_norway::Value>,
    occupied_thresh: Option<f64>,
    free_thresh: Option<f64>,
    mode: Option<String>,
}

/// The image path (relative to the YAML file) and the options of the
/// map_server YAML `text`, read from `path` (which errors name); see [the
/// rules](crate::load::map_server).
///
/// # Errors
/// [`SimError::Parse`] naming `path` and the place: more than
/// [`MAX_FLOW_COLLECTIONS`] flow collections, malformed YAML, a key of the
/// wrong type or a value map_server refuses, a key missing.
pub fn parse_ros_map_yaml(text: &str, path: &Path) -> Result<(String, ImageOptions)> {
    let brackets = flow_collections(text);
    if brackets > MAX_FLOW_COLLECTIONS {
        return Err(parse_error(
            path,
            "whole file",
            format!(
                "{brackets} flow collections (`[` or `{{`), more than the {MAX_FLOW_COLLECTIONS} a \
                 map_server YAML may hold (a bound on their nesting; map_saver writes one)"
            ),
        ));
    }
    let yaml: RosMapYaml = serde_norway::from_str(text).map_err(|e| {
        let place = e.location().map_or_else(
            || "whole file".to_string(),
            |l| format!("line {}", l.line()),
        );
        parse_error(path, place, e.to_string())
    })?;
    let at = |key: &str, reason: String| parse_error(path, format!("key `{key}`"), reason);
    let numbers = [
        ("resolution", yaml.resolution),
        ("occupied_thresh", yaml.occupied_thresh),
        ("free_thresh", yaml.free_thresh),
    ];
    for (key, v) in numbers
        .into_iter()
        .chain(yaml.origin.iter().flatten().map(|&v| ("origin", Some(v))))
    {
        if let Some(v) = v.filter(|v| !v.is_finite()) {
            return Err(at(
                key,
                format!("`{key}` must be a finite number, found {v}"),
            ));
        }
    }
    let negate = match &yaml.negate {
        None => false,
        Some(serde_norway::Value::Bool(b)) => *b,
        Some(serde_norway::Value::Number(n)) if matches!(n.as_u64(), Some(0 | 1)) => {
            n.as_u64() == Some(1)
        }
        Some(other) => {
            return Err(at(
                "negate",
                format!("negate must be 0 or 1, found {other:?}"),
            ));
        }
    };
    if let Some(mode) = yaml
        .mode
        .as_ref()
        .filter(|m| !matches!(m.as_str(), "trinary" | "scale"))
    {
        return Err(at(
            "mode",
            format!("only `mode: trinary` or `mode: scale` is supported, found {mode:?}"),
        ));
    }
    let missing = |key| parse_error(path, "whole file", format!("missing key `{key}`"));
    let image = yaml.image.ok_or_else(|| missing("image"))?;
    let mut options = ImageOptions::new(yaml.resolution.ok_or_else(|| missing("resolution"))?);
    let [x, y, yaw] = yaml.origin.ok_or_else(|| missing("origin"))?;
    options.origin_m = [x, y];
    options.yaw_rad = yaw;
    options.negate = negate;
    options.occupied_thresh = yaml.occupied_thresh.unwrap_or(options.occupied_thresh);
    // `free_thresh` is checked below, naming its key.
    options.free_thresh = None;
    options
        .validate()
        .map_err(|e| parse_error(path, "whole file", e.to_string()))?;
    // A map whose free cells would be more likely occupied than its
    // obstacles is a wrong file, in either mode.
    if let Some(free) = yaml.free_thresh
        && !((0.0..options.occupied_thresh).contains(&free))
    {
        return Err(at(
            "free_thresh",
            format!(
                "free_thresh must be at least 0 and below occupied_thresh ({}), found {free}",
                options.occupied_thresh
            ),
        ));
    }
    options.free_thresh = match yaml.mode.as_deref() {
        Some("scale") => None,
        _ => Some(
            yaml.free_thresh
                .unwrap_or(DEFAULT_FREE_THRESH)
                .min(options.occupied_thresh),
        ),
    };
    Ok((image, options))
}

/// How map_saver turns occupancy into grey values.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RosMapMode {
    /// Black, white or grey by the thresholds.
    Trinary,
    /// Grey in proportion to the occupancy.
    Scale,
}

impl RosMapMode {
    /// The mode's name in a YAML file.
    pub fn name(self) -> &'static str {
        match self {
            Self::Trinary => "trinary",
            Self::Scale => "scale",
        }
    }
}

/// Write `occupancy` (one value a cell of `grid`, row-major from the
/// origin's cell) as the map_server pair `yaml_path` and, beside it, the
/// PGM of the same name, together: both are written whole to temporary
/// files first and renamed into place only when both are complete, and if
/// the YAML cannot be put in place the old PGM is put back, so that the
/// pair is never half new (see `write_atomic_all`).
///
/// # Errors
/// [`SimError::InvalidParameter`] naming the threshold at fault unless
/// `0 <= free_thresh < occupied_thresh <= 1`, and unless the grid has fewer than 2^32 rows and columns; [`SimError::LengthMismatch`] unless there is one
/// value a cell; [`SimError::InvalidValue`] for a value outside `-1..=100`;
/// [`SimError::Io`] if `yaml_path` ends in `.pgm` (its image would be the
/// same file), or if a file cannot be written. Nothing is written then.
pub fn write_ros_map(
    yaml_path: &Path,
    grid: &Grid,
    occupancy: &[i8],
    mode: RosMapMode,
    occupied_thresh: f64,
    free_thresh: f64,
) -> Result<()> {
    // Each threshold on its own first, so that the error names the bad one.
    check_param(
        "occupied_thresh",
        occupied_thresh,
        (0.0..=1.0).contains(&occupied_thresh),
        "a number from 0 to 1",
    )?;
    check_param(
        "free_thresh",
        free_thresh,
        (0.0..=1.0).contains(&free_thresh),
        "a number from 0 to 1",
    )?;
    check_param(
        "free_thresh",
        free_thresh,
        free_thresh < occupied_thresh,
        "less than occupied_thresh",
    )?;
    // The image takes the YAML's name with `.pgm`: a YAML named `.pgm`
    // (in any case, for file systems that ignore it) would overwrite it.
    if yaml_path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("pgm"))
    {
        return Err(SimError::Io {
            path: yaml_path.to_path_buf(),
            source: std::io::Error::new(
                std::io::ErrorKind::InvalidInput,
                "the YAML file would be written over its own image (the YAML's name with `.pgm`); \
                 name the YAML `.yaml`",
            ),
        });
    }
    if occupancy.len() != grid.len() {
        return Err(SimError::LengthMismatch {
            what: "occupancy values and grid cells",
            left: occupancy.len(),
            right: grid.len(),
        });
    }
    if let Some(i) = occupancy.iter().position(|v| !(-1..=100).contains(v)) {
        // Neither -1 (unknown) nor a percent.
        return Err(SimError::InvalidValue {
            what: "occupancy (-1 or 0..=100)",
            index: i,
            value: f64::from(occupancy[i]),
        });
    }
    let (occupied, free) = (
        (occupied_thresh * 100.0).round() as i8,
        (free_thresh * 100.0).round() as i8,
    );
    let pixel = |v: i8| -> u8 {
        match (mode, v) {
            (_, -1) => 205,
            (RosMapMode::Trinary, v) if v >= occupied => 0,
            (RosMapMode::Trinary, v) if v <= free => 254,
            (RosMapMode::Trinary, _) => 205,
            (RosMapMode::Scale, v) => ((100 - i32::from(v)) * 255 / 100) as u8,
        }
    };
    let (rows, cols) = grid.shape();
    let (width, height) =
        crate::picture::image_size(grid, "at most 2^32 - 1 rows and columns for a PGM")?;
    let mut pixels = Vec::with_capacity(occupancy.len());
    for row in (0..rows).rev() {
        pixels.extend(
            occupancy[row * cols..(row + 1) * cols]
                .iter()
                .map(|&v| pixel(v)),
        );
    }
    let image_path = yaml_path.with_extension("pgm");
    let mut pgm = Vec::new();
    PnmEncoder::new(&mut pgm)
        .with_subtype(PnmSubtype::Graymap(SampleEncoding::Binary))
        .encode(pixels.as_slice(), width, height, ExtendedColorType::L8)
        .map_err(|e| SimError::Io {
            path: image_path.clone(),
            source: std::io::Error::other(e.to_string()),
        })?;
    let image_name = image_path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let [x, y] = grid.origin_m();
    let yaml = serde_norway::to_string(&RosMapYamlOut {
        image: &image_name,
        mode: mode.name(),
        resolution: grid.resolution_m(),
        origin: [x, y, 0.0],
        negate: 0,
        occupied_thresh,
        free_thresh,
    })
    .map_err(|e| SimError::Io {
        path: yaml_path.to_path_buf(),
        source: std::io::Error::other(e.to_string()),
    })?;
    write_atomic_all(&[(&image_path, &pgm), (yaml_path, yaml.as_bytes())])
}

/// The YAML file of a map_server pair, as serde writes it (`serde_norway`):
/// the keys map_saver writes, in its order; the image's name quoted where
/// YAML needs it.
#[derive(serde::Serialize)]
struct RosMapYamlOut<'a> {
    image: &'a str,
    mode: &'static str,
    resolution: f64,
    origin: [f64; 3],
    negate: u8,
    occupied_thresh: f64,
    free_thresh: f64,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::World;

    #[test]
    fn the_pair_reads_back_as_the_occupied_cells() {
        let tmp = tempfile::tempdir().unwrap();
        let dir = tmp.path();
        let grid = Grid::new([-1.0, 2.0], 0.5, 4, 6).unwrap();
        let occupancy: Vec<i8> = (0..24).map(|i| [100, 0, -1, 70, 30, 64][i % 6]).collect();
        for mode in [RosMapMode::Trinary, RosMapMode::Scale] {
            let yaml = dir.join(format!("{}.yaml", mode.name()));
            write_ros_map(&yaml, &grid, &occupancy, mode, 0.65, 0.196).unwrap();
            let world = World::from_ros_map_yaml(&yaml).unwrap();
            let truth = world.coverage(&grid);
            for (i, (&v, &c)) in occupancy.iter().zip(&truth).enumerate() {
                // Scale: 70 % is grey 76, darker than the 0.65 threshold,
                // the rest lighter; trinary: only a cell at or below
                // free_thresh (20 %) is white and free, the unknown (-1)
                // and the uncertain (30 %, 64 %) are grey 205 and
                // obstacles, as the occupied black.
                let obstacle = match mode {
                    RosMapMode::Scale => v >= 65,
                    RosMapMode::Trinary => !(0..=20).contains(&v),
                };
                assert_eq!(c > 0.5, obstacle, "{mode:?} cell {i}: {v} read as {c}");
            }
        }
        let yaml = dir.join("bad.yaml");
        assert!(
            write_ros_map(
                &yaml,
                &grid,
                &occupancy[1..],
                RosMapMode::Trinary,
                0.65,
                0.2
            )
            .is_err()
        );
        assert!(write_ros_map(&yaml, &grid, &[101; 24], RosMapMode::Trinary, 0.65, 0.2).is_err());
        assert!(write_ros_map(&yaml, &grid, &occupancy, RosMapMode::Trinary, 0.2, 0.65).is_err());
        assert!(!yaml.exists() && !yaml.with_extension("pgm").exists());
    }

    /// A YAML path ending in `.pgm` would be its own image: it is refused,
    /// naming the path, and nothing is written.
    #[test]
    fn a_yaml_path_ending_in_pgm_is_refused_before_anything_is_written() {
        let tmp = tempfile::tempdir().unwrap();
        let dir = tmp.path();
        let grid = Grid::new([0.0, 0.0], 0.5, 2, 3).unwrap();
        let occupancy = [100, 0, 0, 0, 0, 100];
        for name in ["x.pgm", "x.PGM"] {
            let path = dir.join(name);
            let err = write_ros_map(&path, &grid, &occupancy, RosMapMode::Trinary, 0.65, 0.196)
                .unwrap_err();
            assert!(matches!(err, SimError::Io { .. }), "{err:?}");
            assert!(
                err.to_string().contains(&path.display().to_string()),
                "{err}"
            );
            assert_eq!(std::fs::read_dir(dir).unwrap().count(), 0, "{name}");
        }
    }

    /// A YAML path that is a directory is refused before the PGM is
    /// written: no new image beside it, the old pair unchanged.
    #[test]
    fn a_yaml_path_that_is_a_directory_leaves_no_new_image() {
        let tmp = tempfile::tempdir().unwrap();
        let dir = tmp.path();
        let yaml = dir.join("map.yaml");
        std::fs::create_dir_all(&yaml).unwrap();
        let grid = Grid::new([0.0, 0.0], 0.5, 2, 3).unwrap();
        let occupancy = [100, 0, 0, 0, 0, 100];
        let write = || write_ros_map(&yaml, &grid, &occupancy, RosMapMode::Trinary, 0.65, 0.196);
        assert!(write().is_err());
        assert_eq!(std::fs::read_dir(dir).unwrap().count(), 1);
        std::fs::write(yaml.with_extension("pgm"), b"old image").unwrap();
        assert!(write().is_err());
        assert_eq!(
            std::fs::read(yaml.with_extension("pgm")).unwrap(),
            b"old image"
        );
        assert_eq!(std::fs::read_dir(dir).unwrap().count(), 2);
    }

    /// A bad `occupied_thresh` is reported as itself, not as the
    /// `free_thresh` it was compared with; thresholds out of order blame
    /// `free_thresh`.
    #[test]
    fn a_bad_occupied_thresh_is_named_as_itself() {
        let tmp = tempfile::tempdir().unwrap();
        let dir = tmp.path();
        let yaml = dir.join("map.yaml");
        let grid = Grid::new([0.0, 0.0], 0.5, 2, 3).unwrap();
        let occupancy = [100, 0, 0, 0, 0, 100];
        let name = |occupied: f64, free: f64| match write_ros_map(
            &yaml,
            &grid,
            &occupancy,
            RosMapMode::Trinary,
            occupied,
            free,
        ) {
            Err(SimError::InvalidParameter { name, .. }) => name,
            other => panic!("({occupied}, {free}): {other:?}"),
        };
        for occupied in [f64::NAN, 1.5, -0.1, f64::INFINITY] {
            assert_eq!(name(occupied, 0.196), "occupied_thresh");
        }
        for free in [f64::NAN, -0.1, 1.5] {
            assert_eq!(name(0.65, free), "free_thresh");
        }
        assert_eq!(name(0.2, 0.65), "free_thresh");
        assert_eq!(name(0.5, 0.5), "free_thresh");
        assert_eq!(
            std::fs::read_dir(dir).unwrap().count(),
            0,
            "a refused write left a file"
        );
    }

    /// A YAML nested deeply under a key map_server ignores is refused before
    /// it is parsed (it would take seconds), with a message naming the
    /// bound; as many collections as the bound allows are parsed.
    #[test]
    fn deeply_nested_yaml_is_refused_before_it_is_parsed() {
        let path = Path::new("map.yaml");
        let valid = "image: map.pgm\nresolution: 0.05\norigin: [0.0, 0.0, 0.0]\n";
        let deep = format!(
            "ignored: {}{}\n{valid}",
            "[".repeat(100_000),
            "]".repeat(100_000)
        );
        let started = std::time::Instant::now();
        let err = parse_ros_map_yaml(&deep, path).unwrap_err().to_string();
        assert!(
            err.contains("100000 flow collections") && err.contains("64"),
            "{err}"
        );
        assert!(
            started.elapsed().as_secs_f64() < 1.0,
            "{:?}",
            started.elapsed()
        );
        // The origin holds something; the innermost `[]` of the nest nothing.
        let n = MAX_FLOW_COLLECTIONS;
        let nested = format!("ignored: {}{}\n{valid}", "[".repeat(n), "]".repeat(n));
        assert_eq!(parse_ros_map_yaml(&nested, path).unwrap().0, "map.pgm");
        let empty = format!("a: []\nb: {{}}\n{nested}");
        assert_eq!(parse_ros_map_yaml(&empty, path).unwrap().0, "map.pgm");
        let one_more = format!("other: [1]\n{nested}");
        assert!(parse_ros_map_yaml(&one_more, path).is_err());
        assert_eq!(flow_collections("a: [[1], [], {}, \"[x\"]"), 3);
    }

    /// The YAML names its image so that YAML reads the name back whole,
    /// whatever the file is called (in a plain scalar `#` would start a
    /// comment, `: ` a mapping, `- ` or `[` a sequence).
    #[test]
    fn image_names_that_plain_yaml_would_misread_are_read_back() {
        let tmp = tempfile::tempdir().unwrap();
        let dir = tmp.path();
        let grid = Grid::new([0.0, 0.0], 0.5, 2, 3).unwrap();
        let occupancy = [100, 0, 0, 0, 0, 100];
        for name in ["map #1", "a: b", "- x", "[x]", "'q", "%d", "0x10", "~"] {
            let yaml = dir.join(format!("{name}.yaml"));
            write_ros_map(&yaml, &grid, &occupancy, RosMapMode::Trinary, 0.65, 0.196).unwrap();
            let world = World::from_ros_map_yaml(&yaml).unwrap_or_else(|e| {
                panic!("{name}: {e}\n{}", std::fs::read_to_string(&yaml).unwrap())
            });
            assert_eq!(world.len(), 2, "{name}");
        }
        let text = std::fs::read_to_string(dir.join("- x.yaml")).unwrap();
        assert!(
            text.starts_with("image: '- x.pgm'\nmode: trinary\n"),
            "{text}"
        );
    }
}
