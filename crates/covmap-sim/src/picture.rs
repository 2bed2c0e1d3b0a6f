//! Writing maps as greyscale PNG pictures.

use std::path::Path;

use covmap_core::Grid;
use image::codecs::png::{CompressionType, FilterType, PngEncoder};
use image::{ExtendedColorType, ImageEncoder};

use crate::error::{Result, SimError};
use crate::load::write_atomic;

/// Write a map of values in `[0, 1]` (1 = covered / occupied) over `grid` as
/// an 8-bit greyscale PNG, atomically (a temporary file, then a rename).
///
/// One pixel per cell, north up (the grid's last row is the picture's first),
/// 1 black and 0 white; NaN is drawn mid-grey. Errors if `values` does not have
/// one value per cell or the file cannot be written.
///
/// # Example
/// ```
/// use covmap_core::Grid;
/// let grid = Grid::new([0.0, 0.0], 0.1, 2, 3).unwrap();
/// # let dir = tempfile::tempdir().unwrap();
/// # let path = dir.path().join("map.png");
/// covmap_sim::write_map_png(&path, &grid, &[0.0, 0.5, 1.0, 1.0, 0.0, f64::NAN]).unwrap();
/// assert!(std::fs::metadata(&path).unwrap().len() > 0);
/// ```
pub fn write_map_png(path: impl AsRef<Path>, grid: &Grid, values: &[f64]) -> Result<()> {
    let path = path.as_ref();
    let (rows, cols) = grid.shape();
    if values.len() != grid.len() {
        return Err(SimError::LengthMismatch {
            what: "map values and grid cells",
            left: values.len(),
            right: grid.len(),
        });
    }
    let (width, height) = image_size(grid, "at most 2^32 - 1 rows and columns for a PNG")?;
    let mut pixels = Vec::with_capacity(rows * cols);
    for row in (0..rows).rev() {
        for v in &values[row * cols..(row + 1) * cols] {
            let grey = if v.is_nan() {
                128
            } else {
                (255.0 * (1.0 - v.clamp(0.0, 1.0))).round() as u8
            };
            pixels.push(grey);
        }
    }
    let mut bytes = Vec::new();
    // Deflate's default level and adaptive filters, the `png` crate's own
    // defaults (the `image` crate's would be its fastest level).
    PngEncoder::new_with_quality(&mut bytes, CompressionType::Default, FilterType::Adaptive)
        .write_image(&pixels, width, height, ExtendedColorType::L8)
        .map_err(|e| SimError::Io {
            path: path.to_path_buf(),
            source: std::io::Error::other(e.to_string()),
        })?;
    write_atomic(path, &bytes)
}

/// The grid's width and height (columns, rows) as an image's; a grid of
/// more than `u32::MAX` rows or columns is an error that says `expected`
/// (the limit and the format).
pub(crate) fn image_size(grid: &Grid, expected: &'static str) -> Result<(u32, u32)> {
    let (rows, cols) = grid.shape();
    match (u32::try_from(cols), u32::try_from(rows)) {
        (Ok(w), Ok(h)) => Ok((w, h)),
        _ => Err(SimError::InvalidParameter {
            name: "grid size",
            value: grid.len() as f64,
            expected,
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::load::image::ImageOptions;
    use crate::world::World;

    #[test]
    fn written_picture_reads_back_as_the_same_world() {
        // Write a coverage map of a square and load the PNG as an occupancy image.
        let grid = Grid::new([0.0, 0.0], 0.1, 4, 5).unwrap();
        let mut v = vec![0.0; 20];
        v[2 * 5 + 3] = 1.0; // row 2, col 3
        let tmp = tempfile::tempdir().unwrap();
        let dir = tmp.path();
        let path = dir.join("m.png");
        write_map_png(&path, &grid, &v).unwrap();
        let w = World::from_image_file(&path, &ImageOptions::new(0.1)).unwrap();
        assert_eq!(w.len(), 1);
        let b = w.polygons()[0].bounds_m();
        for (x, e) in b.iter().zip([0.3, 0.2, 0.4, 0.3]) {
            assert!((x - e).abs() < 1e-12, "{b:?}");
        }
        assert!(write_map_png(&path, &grid, &v[..3]).is_err());
        // No temporary file is left behind.
        assert_eq!(std::fs::read_dir(dir).unwrap().count(), 1);
    }
}
