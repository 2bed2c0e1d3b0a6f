//! Maps out as ROS map_server / nav2 map_saver write them: a PGM image and
//! the YAML file that names it, from `nav_msgs/OccupancyGrid` data (one
//! `i8` a cell, `-1` unknown, `0..=100` percent occupied).
//!
//! Pixels as map_saver makes them: in `trinary` mode a cell at or above
//! `occupied_thresh` (in percent, rounded) is black (0), one at or below
//! `free_thresh` white (254), the rest and unknown grey (205); in `scale`
//! mode a known cell of `v` percent is `(100 - v) 255 / 100`, unknown 205.
//! Row 0 of the image is the map's top row. [`World::from_ros_map_yaml`]
//! (and map_server) read the pair back.
//!
//! [`World::from_ros_map_yaml`]: crate::World::from_ros_map_yaml

use std::path::Path;

use covmap_core::Grid;

use super::write_atomic;
use crate::error::{Result, SimError};

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
/// PGM of the same name, each atomically (the PGM first, so that the YAML
/// never names a missing image).
///
/// # Errors
/// [`SimError::InvalidParameter`] unless `0 <= free_thresh <
/// occupied_thresh <= 1`; [`SimError::LengthMismatch`] unless there is one
/// value a cell; [`SimError::InvalidValue`] for a value outside `-1..=100`;
/// [`SimError::Io`] if a file cannot be written. Nothing is written then.
pub fn write_ros_map(
    yaml_path: &Path,
    grid: &Grid,
    occupancy: &[i8],
    mode: RosMapMode,
    occupied_thresh: f64,
    free_thresh: f64,
) -> Result<()> {
    let ordered = (0.0..=1.0).contains(&occupied_thresh)
        && free_thresh >= 0.0
        && free_thresh < occupied_thresh;
    if !ordered {
        return Err(SimError::InvalidParameter {
            name: "free_thresh",
            value: free_thresh,
            expected: "0 <= free_thresh < occupied_thresh <= 1",
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
    let mut pgm = format!("P5\n# covmap map\n{cols} {rows}\n255\n").into_bytes();
    for row in (0..rows).rev() {
        pgm.extend(
            occupancy[row * cols..(row + 1) * cols]
                .iter()
                .map(|&v| pixel(v)),
        );
    }
    let image_path = yaml_path.with_extension("pgm");
    let image_name = image_path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let [x, y] = grid.origin_m();
    let yaml = format!(
        "image: {image_name}\nmode: {}\nresolution: {}\norigin: [{x}, {y}, 0.0]\nnegate: 0\noccupied_thresh: {occupied_thresh}\nfree_thresh: {free_thresh}\n",
        mode.name(),
        grid.resolution_m()
    );
    write_atomic(&image_path, &pgm)?;
    write_atomic(yaml_path, yaml.as_bytes())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::World;

    #[test]
    fn the_pair_reads_back_as_the_occupied_cells() {
        let dir = std::env::temp_dir().join(format!("covmap-ros-map-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let grid = Grid::new([-1.0, 2.0], 0.5, 4, 6).unwrap();
        let occupancy: Vec<i8> = (0..24).map(|i| [100, 0, -1, 70, 30, 64][i % 6]).collect();
        for mode in [RosMapMode::Trinary, RosMapMode::Scale] {
            let yaml = dir.join(format!("{}.yaml", mode.name()));
            write_ros_map(&yaml, &grid, &occupancy, mode, 0.65, 0.196).unwrap();
            let world = World::from_ros_map_yaml(&yaml).unwrap();
            let truth = world.coverage(&grid);
            for (i, (&v, &c)) in occupancy.iter().zip(&truth).enumerate() {
                // Scale: 70 % is grey 76, darker than the 0.65 threshold;
                // trinary: 70 % is at least 65, black.
                assert_eq!(c > 0.5, v >= 65, "{mode:?} cell {i}: {v} read as {c}");
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
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
