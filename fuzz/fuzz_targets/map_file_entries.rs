//! The zip entry table of the map file: a valid map file's local entries
//! (its headers and arrays), behind a central directory the fuzzer writes:
//! up to 64 entries of any name (the map file's five, others, one twice),
//! any method, pointing anywhere, of any size and CRC. A map or an error,
//! never a panic; every entry's name and headers are checked, and entries
//! that overlap refused, before any CRC is computed, so the work is
//! bounded by the file's size (libFuzzer's time limit holds it to that).
#![no_main]

use std::sync::OnceLock;

use covmap::{CoverageMap, Grid, LaserModel, Pose, ScanMap};
use libfuzzer_sys::fuzz_target;

/// The names an entry may have: the map file's, and others.
const NAMES: [&str; 8] = [
    "covmap_version.npy",
    "grid.npy",
    "histograms.npy",
    "history_entropies.npy",
    "history_counts.npy",
    "other.npy",
    "",
    "grid.npy\0",
];

/// The local part of a small map's file (everything before its central
/// directory), made once.
fn local_part() -> &'static [u8] {
    static PART: OnceLock<Vec<u8>> = OnceLock::new();
    PART.get_or_init(|| {
        let mut map = CoverageMap::new(Grid::new([0.0, 0.0], 0.1, 4, 5).unwrap());
        map.track_history(true);
        map.integrate(&Pose::new(0.2, 0.2, 0.0), &[0.3], &[0.0], &LaserModel::default())
            .unwrap();
        let bytes = map.to_file_bytes().unwrap();
        let end = bytes.len() - 22;
        let cd_offset = u32::from_le_bytes(bytes[end + 16..end + 20].try_into().unwrap());
        bytes[..cd_offset as usize].to_vec()
    })
}

fuzz_target!(|data: &[u8]| {
    let local = local_part();
    let mut central = Vec::new();
    let mut count = 0u16;
    // 14 bytes an entry: name, method, local offset, size, CRC (4 each).
    for e in data.chunks_exact(14).take(64) {
        let name = NAMES[usize::from(e[0]) % NAMES.len()].as_bytes();
        let four = |b: &[u8]| u32::from_le_bytes([b[0], b[1], b[2], b[3]]);
        let (offset, size, crc) = (four(&e[2..6]), four(&e[6..10]), four(&e[10..14]));
        central.extend_from_slice(&0x0201_4b50u32.to_le_bytes());
        for v in [20u16, 20, 0, u16::from(e[1] % 2) * 8, 0, 0x21] {
            central.extend_from_slice(&v.to_le_bytes());
        }
        for v in [crc, size, size] {
            central.extend_from_slice(&v.to_le_bytes());
        }
        for v in [name.len() as u16, 0, 0, 0, 0] {
            central.extend_from_slice(&v.to_le_bytes());
        }
        central.extend_from_slice(&0u32.to_le_bytes());
        central.extend_from_slice(&(offset % (local.len() as u32 + 1)).to_le_bytes());
        central.extend_from_slice(name);
        count += 1;
    }
    let mut archive = local.to_vec();
    archive.extend_from_slice(&central);
    archive.extend_from_slice(&0x0605_4b50u32.to_le_bytes());
    for v in [0u16, 0, count, count] {
        archive.extend_from_slice(&v.to_le_bytes());
    }
    archive.extend_from_slice(&(central.len() as u32).to_le_bytes());
    archive.extend_from_slice(&(local.len() as u32).to_le_bytes());
    archive.extend_from_slice(&0u16.to_le_bytes());
    if let Ok(map) = CoverageMap::from_file_bytes(&archive) {
        assert_eq!(map.grid().shape(), (4, 5));
    }
});
