//! Which arrays a map file holds, and their checks.

use super::npz::{self, Array};
use crate::coverage_map::{CoverageMap, HistoryState, STAGNATION_MEASUREMENTS};
use crate::error::{CovmapError, Result};
use crate::grid::Grid;

/// The version of the map file this covmap writes (and the newest it
/// reads): the `covmap_version` array of every map file.
pub const MAP_FILE_VERSION: u32 = 1;

fn bytes_of<T: Copy, const N: usize>(values: &[T], to: fn(T) -> [u8; N]) -> Vec<u8> {
    values.iter().flat_map(|&v| to(v)).collect()
}

fn invalid(reason: impl Into<String>) -> CovmapError {
    CovmapError::InvalidMapFile(reason.into())
}

impl CoverageMap {
    /// The whole posterior as a map file: a `.npz` archive (numpy's
    /// `np.load` opens it) of deflated `.npy` arrays (as `np.savez_compressed`
    /// writes them):
    ///
    /// | entry | dtype, shape | holds |
    /// | --- | --- | --- |
    /// | `covmap_version.npy` | uint32 `(1,)` | [`MAP_FILE_VERSION`] |
    /// | `grid.npy` | float64 `(3,)` | origin x, origin y (metres), resolution (metres) |
    /// | `histograms.npy` | float32 `(rows, cols, bins)` | every cell's histogram |
    /// | `history_entropies.npy` | float32 `(rows, cols, STAGNATION_MEASUREMENTS + 1)` | the entropy history, if tracked |
    /// | `history_counts.npy` | uint32 `(rows, cols)` | measurements of each cell, if tracked |
    ///
    /// Every entry carries zip's CRC-32, which [`CoverageMap::from_file_bytes`]
    /// checks.
    ///
    /// # Errors
    /// [`CovmapError::InvalidMapFile`] for a map whose file would pass
    /// [`MAX_MAP_FILE_BYTES`](crate::MAX_MAP_FILE_BYTES) (4 GiB - 1).
    ///
    /// # Example
    /// ```
    /// use covmap_core::{CoverageMap, Grid, LaserModel, Pose, ScanMap};
    /// let mut map = CoverageMap::new(Grid::new([0.0, 0.0], 0.1, 20, 30).unwrap());
    /// map.integrate(&Pose::new(1.0, 1.0, 0.0), &[1.2], &[0.0], &LaserModel::default()).unwrap();
    /// let bytes = map.to_file_bytes().unwrap();
    /// let back = CoverageMap::from_file_bytes(&bytes).unwrap();
    /// assert_eq!(back.histograms(), map.histograms());
    /// let mut flipped = bytes.clone();
    /// flipped[bytes.len() / 2] ^= 1;
    /// assert!(CoverageMap::from_file_bytes(&flipped).is_err());
    /// ```
    pub fn to_file_bytes(&self) -> Result<Vec<u8>> {
        self.to_file_bytes_with(true)
    }

    /// The map file of [`CoverageMap::to_file_bytes`], its entries deflated
    /// (`compress`) or stored as they are (larger, quicker to write and
    /// read).
    ///
    /// # Errors
    /// As [`CoverageMap::to_file_bytes`].
    pub fn to_file_bytes_with(&self, compress: bool) -> Result<Vec<u8>> {
        let g = self.grid();
        let (rows, cols, bins) = (g.rows(), g.cols(), self.bins());
        let [ox, oy] = g.origin_m();
        let mut entries = vec![
            (
                "covmap_version.npy",
                npz::npy("<u4", &[1], &MAP_FILE_VERSION.to_le_bytes()),
            ),
            (
                "grid.npy",
                npz::npy(
                    "<f8",
                    &[3],
                    &bytes_of(&[ox, oy, g.resolution_m()], f64::to_le_bytes),
                ),
            ),
            (
                "histograms.npy",
                npz::npy(
                    "<f4",
                    &[rows, cols, bins],
                    &bytes_of(self.histograms(), f32::to_le_bytes),
                ),
            ),
        ];
        if let Some(h) = self.history_state() {
            let depth = STAGNATION_MEASUREMENTS + 1;
            entries.push((
                "history_entropies.npy",
                npz::npy(
                    "<f4",
                    &[rows, cols, depth],
                    &bytes_of(&h.entropies, f32::to_le_bytes),
                ),
            ));
            entries.push((
                "history_counts.npy",
                npz::npy("<u4", &[rows, cols], &bytes_of(&h.count, u32::to_le_bytes)),
            ));
        }
        npz::zip_with(&entries, compress).map_err(invalid)
    }

    /// The map a map file holds ([`CoverageMap::to_file_bytes`]), bit for
    /// bit the map that was saved.
    ///
    /// # Errors
    /// [`CovmapError::InvalidMapFile`] for bytes that are not a whole,
    /// unchanged map file of a version this covmap reads (empty, cut short,
    /// a byte changed, an entry missing, unknown or of the wrong dtype or
    /// shape); the grid's, the histograms' and the history's own errors
    /// for values no map can hold.
    pub fn from_file_bytes(bytes: &[u8]) -> Result<CoverageMap> {
        let known = [
            "covmap_version.npy",
            "grid.npy",
            "histograms.npy",
            "history_entropies.npy",
            "history_counts.npy",
        ];
        let entries = npz::unzip(bytes, &known).map_err(invalid)?;
        let get = |name: &str| -> Result<Option<Array<'_>>> {
            match entries.iter().find(|(n, _)| n == name) {
                Some((_, data)) => npz::parse_npy(data)
                    .map(Some)
                    .map_err(|e| invalid(format!("{name}: {e}"))),
                None => Ok(None),
            }
        };
        let need = |name: &str| get(name)?.ok_or_else(|| invalid(format!("no {name}")));
        let version = need("covmap_version.npy")?;
        let version = expect(&version, "covmap_version.npy", "<u4", &[1])?;
        let [version] = exactly(all(version.data, u32::from_le_bytes), "covmap_version.npy")?;
        if version != MAP_FILE_VERSION {
            return Err(invalid(format!(
                "version {version}, where this covmap reads version {MAP_FILE_VERSION}"
            )));
        }
        let grid = need("grid.npy")?;
        let grid = expect(&grid, "grid.npy", "<f8", &[3])?;
        let [x, y, resolution] = exactly(all(grid.data, f64::from_le_bytes), "grid.npy")?;
        let hist = need("histograms.npy")?;
        let (&[rows, cols, bins], "<f4") = (hist.shape.as_slice(), hist.descr.as_str()) else {
            return Err(invalid(format!(
                "histograms.npy is {} of shape {:?}, not float32 (rows, cols, bins)",
                hist.descr, hist.shape
            )));
        };
        let grid = Grid::new([x, y], resolution, rows, cols)?;
        let mut map = CoverageMap::from_histograms(grid, bins, all(hist.data, f32::from_le_bytes))?;
        match (get("history_entropies.npy")?, get("history_counts.npy")?) {
            (None, None) => {}
            (Some(e), Some(c)) => {
                let depth = STAGNATION_MEASUREMENTS + 1;
                let e = expect(&e, "history_entropies.npy", "<f4", &[rows, cols, depth])?;
                let c = expect(&c, "history_counts.npy", "<u4", &[rows, cols])?;
                map.restore_history(HistoryState {
                    entropies: all(e.data, f32::from_le_bytes),
                    count: all(c.data, u32::from_le_bytes),
                })?;
            }
            _ => {
                return Err(invalid(
                    "one of history_entropies.npy and history_counts.npy without the other",
                ));
            }
        }
        Ok(map)
    }
}

fn expect<'a, 'b>(
    a: &'a Array<'b>,
    name: &str,
    descr: &str,
    shape: &[usize],
) -> Result<&'a Array<'b>> {
    if a.descr == descr && a.shape == shape {
        Ok(a)
    } else {
        Err(invalid(format!(
            "{name} is {} of shape {:?}, not {descr} of shape {shape:?}",
            a.descr, a.shape
        )))
    }
}

/// The values of an array's little-endian `data`, `B` bytes each.
fn all<T, const B: usize>(data: &[u8], from_le_bytes: fn([u8; B]) -> T) -> Vec<T> {
    data.as_chunks::<B>()
        .0
        .iter()
        .map(|&c| from_le_bytes(c))
        .collect()
}

/// `values` as an array of `N`, as [`expect`] checked the entry `name`'s
/// shape to hold.
fn exactly<T, const N: usize>(values: Vec<T>, name: &str) -> Result<[T; N]> {
    values
        .try_into()
        .map_err(|v: Vec<T>| invalid(format!("{name} holds {} values, not {N}", v.len())))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pose::Pose;
    use crate::scan_map::ScanMap;
    use crate::sensor::SonarModel;

    fn scanned(history: bool) -> CoverageMap {
        let grid = Grid::new([-1.0, 0.5], 0.1, 25, 35).unwrap();
        let mut map = CoverageMap::with_bins(grid, 8).unwrap();
        map.track_history(history);
        for i in 0..5 {
            let pose = Pose::new(0.5 + 0.1 * i as f64, 1.5, 0.3 * i as f64);
            map.integrate(
                &pose,
                &[0.8, 1.3, 5.0],
                &[-0.4, 0.0, 0.4],
                &SonarModel::default(),
            )
            .unwrap();
        }
        map
    }

    #[test]
    fn a_saved_map_loads_bit_for_bit_with_its_history() {
        for history in [false, true] {
            let map = scanned(history);
            let back = CoverageMap::from_file_bytes(&map.to_file_bytes().unwrap()).unwrap();
            assert_eq!(back.grid(), map.grid());
            assert_eq!(back.bins(), map.bins());
            let bits = |m: &CoverageMap| {
                m.histograms()
                    .iter()
                    .map(|v| v.to_bits())
                    .collect::<Vec<_>>()
            };
            assert_eq!(bits(&back), bits(&map));
            assert_eq!(back.history_state(), map.history_state());
        }
    }

    #[test]
    fn changed_cut_or_empty_files_are_errors_never_wrong_maps() {
        let map = scanned(true);
        let bytes = map.to_file_bytes().unwrap();
        assert!(matches!(
            CoverageMap::from_file_bytes(&[]),
            Err(CovmapError::InvalidMapFile(_))
        ));
        for cut in [1, 22, bytes.len() / 3, bytes.len() - 1] {
            assert!(
                CoverageMap::from_file_bytes(&bytes[..cut]).is_err(),
                "cut at {cut}"
            );
        }
        // Every 7th byte flipped in turn: an error, or (a flip in a field
        // zip leaves unchecked) the same map.
        for i in (0..bytes.len()).step_by(7) {
            let mut bad = bytes.clone();
            bad[i] ^= 0x04;
            if let Ok(m) = CoverageMap::from_file_bytes(&bad) {
                assert_eq!(m.histograms(), map.histograms(), "byte {i}");
                assert_eq!(m.grid(), map.grid(), "byte {i}");
                assert_eq!(m.history_state(), map.history_state(), "byte {i}");
            }
        }
    }

    #[test]
    fn newer_versions_and_strange_entries_are_refused() {
        let map = scanned(false);
        let entries = |version: u32, extra: bool| {
            let mut e = vec![
                (
                    "covmap_version.npy",
                    npz::npy("<u4", &[1], &version.to_le_bytes()),
                ),
                (
                    "grid.npy",
                    npz::npy("<f8", &[3], &bytes_of(&[0.0, 0.0, 0.1], f64::to_le_bytes)),
                ),
                (
                    "histograms.npy",
                    npz::npy(
                        "<f4",
                        &[25, 35, 8],
                        &bytes_of(map.histograms(), f32::to_le_bytes),
                    ),
                ),
            ];
            if extra {
                e.push(("other.npy", npz::npy("<u4", &[1], &[0; 4])));
            }
            npz::zip(&e).unwrap()
        };
        assert!(CoverageMap::from_file_bytes(&entries(1, false)).is_ok());
        let err = CoverageMap::from_file_bytes(&entries(2, false)).unwrap_err();
        assert!(err.to_string().contains("version 2"), "{err}");
        let err = CoverageMap::from_file_bytes(&entries(1, true)).unwrap_err();
        assert!(err.to_string().contains("other.npy"), "{err}");
    }
}
