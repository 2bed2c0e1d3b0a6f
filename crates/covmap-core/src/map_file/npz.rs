//! numpy's `.npz` files as far as the map file needs them: a zip archive of
//! entries stored or deflated, each a little-endian, C-ordered `.npy`
//! array. The reader takes any archive numpy writes with `np.savez` or
//! `np.savez_compressed` and refuses, with a reason, whatever it cannot
//! check: other compression methods, zip64, a CRC-32 that does not match,
//! lengths that run past the end.
//!
//! A deflated entry is inflated only up to the size its headers declare,
//! and no entry may declare more than [`MAX_INFLATION`] times its
//! compressed bytes (deflate itself reaches about 1032 at most), nor the
//! entries together more than [`MAX_MAP_FILE_BYTES`]: the work of a read
//! stays bounded by the file's size.
//!
//! Its work is bounded by the file's size: every entry's name and headers
//! are checked first (the names among those the caller knows, no name
//! twice, each entry's local header and data within the archive), and
//! entries whose bytes overlap are refused, before any CRC-32 is computed;
//! so the CRCs read each byte of the file at most once. (An archive whose
//! thousands of entries all point at the same bytes would otherwise cost
//! entries times size.)

/// One array: its `.npy` type (`<f4`, `<f8`, `<u4`), its shape and its
/// bytes, little-endian, row-major.
#[derive(Debug)]
pub(crate) struct Array<'a> {
    pub(crate) descr: String,
    pub(crate) shape: Vec<usize>,
    pub(crate) data: &'a [u8],
}

const LOCAL: u32 = 0x0403_4b50;
const CENTRAL: u32 = 0x0201_4b50;
const END: u32 = 0x0605_4b50;
/// 1980-01-01, the earliest date zip has: the archive is the same bytes
/// whenever it is written.
const DOS_DATE: u16 = 0x21;

/// The `.npy` encoding of an array of `descr` and `shape` holding `data`.
pub(crate) fn npy(descr: &str, shape: &[usize], data: &[u8]) -> Vec<u8> {
    let dims: Vec<String> = shape.iter().map(usize::to_string).collect();
    let shape = match dims.as_slice() {
        [one] => format!("({one},)"),
        _ => format!("({})", dims.join(", ")),
    };
    let mut header = format!("{{'descr': '{descr}', 'fortran_order': False, 'shape': {shape}, }}");
    // Magic, version and length take 10 bytes; the header ends in a line
    // break, and the whole is a multiple of 64 bytes.
    while (10 + header.len() + 1) % 64 != 0 {
        header.push(' ');
    }
    header.push('\n');
    let mut out = Vec::with_capacity(10 + header.len() + data.len());
    out.extend_from_slice(b"\x93NUMPY\x01\x00");
    out.extend_from_slice(&(header.len() as u16).to_le_bytes());
    out.extend_from_slice(header.as_bytes());
    out.extend_from_slice(data);
    out
}

/// The array a `.npy` entry holds.
pub(crate) fn parse_npy(bytes: &[u8]) -> Result<Array<'_>, String> {
    if bytes.len() < 10 || !bytes.starts_with(b"\x93NUMPY") {
        return Err("not a .npy array (no magic string)".into());
    }
    // Version 1 gives the header's length in 2 bytes, 2 and 3 in 4.
    let (len, start) = match bytes.get(6).copied().unwrap_or_default() {
        1 => le_bytes(bytes, 8).map(|b| (usize::from(u16::from_le_bytes(b)), 10usize)),
        2 | 3 => le_bytes(bytes, 8).map(|b| (u32::from_le_bytes(b) as usize, 12)),
        v => return Err(format!(".npy version {v} is not one numpy writes")),
    }
    .ok_or("the .npy header's length runs past the end")?;
    let (header, data) = start
        .checked_add(len)
        .and_then(|end| bytes.get(start..end).zip(bytes.get(end..)))
        .ok_or("the .npy header runs past the end")?;
    let header = std::str::from_utf8(header).map_err(|_| "the .npy header is not text")?;
    let descr = quoted_after(header, "'descr':").ok_or("the .npy header has no descr")?;
    if !header.contains("'fortran_order': False") {
        return Err("a Fortran-ordered array (covmap writes C order)".into());
    }
    let shape = shape_after(header).ok_or("the .npy header has no readable shape")?;
    let item = match descr.as_str() {
        "<f4" | "<u4" => 4,
        "<f8" => 8,
        other => return Err(format!("dtype {other} where covmap writes <f4, <f8 or <u4")),
    };
    let size = shape
        .iter()
        .try_fold(item, |n: usize, &d| n.checked_mul(d))
        .ok_or("the shape's size overflows")?;
    if data.len() != size {
        return Err(format!(
            "shape {shape:?} of {descr} needs {size} bytes, the entry holds {}",
            data.len()
        ));
    }
    Ok(Array { descr, shape, data })
}

fn quoted_after(header: &str, key: &str) -> Option<String> {
    let rest = &header[header.find(key)? + key.len()..];
    let rest = rest.trim_start().strip_prefix('\'')?;
    Some(rest[..rest.find('\'')?].to_string())
}

fn shape_after(header: &str) -> Option<Vec<usize>> {
    let rest = &header[header.find("'shape':")? + 8..];
    let rest = rest.trim_start().strip_prefix('(')?;
    let inner = &rest[..rest.find(')')?];
    inner
        .split(',')
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .map(|s| s.parse().ok())
        .collect()
}

/// The largest map file written, and so the largest a reader of map files
/// must take, bytes: 4 GiB - 1, the most a zip archive without zip64 spans
/// (its offsets and sizes are 32-bit).
pub const MAX_MAP_FILE_BYTES: u64 = u32::MAX as u64;

/// The most bytes a deflated entry may declare for each of its compressed
/// bytes: deflate's own limit (about 1032) with room to spare.
pub const MAX_INFLATION: u64 = 1100;

/// zip's compression methods that covmap reads: stored and deflated.
const STORED: u16 = 0;
const DEFLATED: u16 = 8;

/// A zip archive of `entries`, each stored as it is.
///
/// # Errors
/// As [`zip_with`].
#[cfg(test)]
pub(crate) fn zip(entries: &[(&str, Vec<u8>)]) -> Result<Vec<u8>, String> {
    zip_with(entries, false)
}

/// A zip archive of `entries`, each deflated (`deflate`) or stored as it
/// is.
///
/// # Errors
/// If an entry or the archive would pass [`MAX_MAP_FILE_BYTES`] (zip64 is
/// not written).
pub(crate) fn zip_with(entries: &[(&str, Vec<u8>)], deflate: bool) -> Result<Vec<u8>, String> {
    let too_big = || "the archive would pass 4 GiB, more than a zip file without zip64 holds";
    let mut out = Vec::new();
    let mut central = Vec::new();
    for (name, data) in entries {
        let offset = u32::try_from(out.len()).map_err(|_| too_big())?;
        let size = u32::try_from(data.len()).map_err(|_| too_big())?;
        let crc = crc32fast::hash(data);
        let (method, packed) = if deflate {
            (DEFLATED, std::borrow::Cow::Owned(deflated(data)?))
        } else {
            (STORED, std::borrow::Cow::Borrowed(&data[..]))
        };
        let packed_size = u32::try_from(packed.len()).map_err(|_| too_big())?;
        let head = |sig: u32, out: &mut Vec<u8>, central_entry: bool| {
            out.extend_from_slice(&sig.to_le_bytes());
            if central_entry {
                out.extend_from_slice(&20u16.to_le_bytes()); // made by
            }
            for v in [20u16, 0, method, 0, DOS_DATE] {
                out.extend_from_slice(&v.to_le_bytes());
            }
            for v in [crc, packed_size, size] {
                out.extend_from_slice(&v.to_le_bytes());
            }
            out.extend_from_slice(&(name.len() as u16).to_le_bytes());
            out.extend_from_slice(&0u16.to_le_bytes()); // extra
        };
        head(LOCAL, &mut out, false);
        out.extend_from_slice(name.as_bytes());
        out.extend_from_slice(&packed);
        head(CENTRAL, &mut central, true);
        for v in [0u16, 0, 0] {
            central.extend_from_slice(&v.to_le_bytes()); // comment, disk, internal
        }
        central.extend_from_slice(&0u32.to_le_bytes()); // external attributes
        central.extend_from_slice(&offset.to_le_bytes());
        central.extend_from_slice(name.as_bytes());
    }
    let cd_offset = u32::try_from(out.len()).map_err(|_| too_big())?;
    let cd_size = u32::try_from(central.len()).map_err(|_| too_big())?;
    out.extend_from_slice(&central);
    let n = entries.len() as u16;
    out.extend_from_slice(&END.to_le_bytes());
    for v in [0u16, 0, n, n] {
        out.extend_from_slice(&v.to_le_bytes());
    }
    out.extend_from_slice(&cd_size.to_le_bytes());
    out.extend_from_slice(&cd_offset.to_le_bytes());
    out.extend_from_slice(&0u16.to_le_bytes());
    if out.len() as u64 > MAX_MAP_FILE_BYTES {
        return Err(too_big().into());
    }
    Ok(out)
}

/// `data` deflated (raw deflate, as zip holds it), at zlib's default level.
fn deflated(data: &[u8]) -> Result<Vec<u8>, String> {
    use std::io::Write as _;
    let mut encoder = flate2::write::DeflateEncoder::new(
        Vec::with_capacity(data.len() / 4),
        flate2::Compression::default(),
    );
    encoder
        .write_all(data)
        .and_then(|()| encoder.finish())
        .map_err(|e| format!("deflating an entry failed: {e}"))
}

/// A deflated entry's bytes inflated, exactly `size` of them, else why
/// not; never more than `size` bytes are produced.
fn inflated(packed: &[u8], size: usize, name: &str) -> Result<Vec<u8>, String> {
    use std::io::Read as _;
    let mut out = Vec::with_capacity(size.min(packed.len().saturating_mul(8)));
    let mut decoder = flate2::read::DeflateDecoder::new(packed).take(size as u64 + 1);
    decoder
        .read_to_end(&mut out)
        .map_err(|e| format!("entry {name}: its deflated bytes do not inflate ({e})"))?;
    if out.len() != size {
        return Err(format!(
            "entry {name}: inflates to {}{} bytes where its headers say {size}",
            out.len().min(size),
            if out.len() > size { " or more" } else { "" }
        ));
    }
    Ok(out)
}

/// The `N` bytes of `b` from `at`, if it holds them.
fn le_bytes<const N: usize>(b: &[u8], at: usize) -> Option<[u8; N]> {
    b.get(at..at.checked_add(N)?)?.try_into().ok()
}

fn u16_at(b: &[u8], at: usize) -> Result<u16, String> {
    le_bytes(b, at)
        .map(u16::from_le_bytes)
        .ok_or_else(|| format!("the archive ends at byte {} inside a record", b.len()))
}

fn u32_at(b: &[u8], at: usize) -> Result<u32, String> {
    le_bytes(b, at)
        .map(u32::from_le_bytes)
        .ok_or_else(|| format!("the archive ends at byte {} inside a record", b.len()))
}

/// An archive's entries, each by name: stored data borrowed from the
/// archive, deflated data inflated.
pub(crate) type Entries<'a> = Vec<(String, std::borrow::Cow<'a, [u8]>)>;

/// One entry of a zip archive's central directory, its headers checked.
struct Entry {
    name: String,
    crc: u32,
    /// Where its local header starts.
    local: usize,
    /// Its data as the archive holds it.
    data: std::ops::Range<usize>,
    /// Whether the data is deflated.
    deflated: bool,
    /// The size of its data once inflated.
    size: usize,
}

/// The entries of a zip archive, in the order of its central directory,
/// each named in `known` (at most once) and checked against its CRC-32.
/// Names and headers are checked for every entry before any CRC is
/// computed, and entries whose bytes overlap are refused.
pub(crate) fn unzip<'a>(b: &'a [u8], known: &[&str]) -> Result<Entries<'a>, String> {
    if b.is_empty() {
        return Err("the file is empty".into());
    }
    // No archive comment: the end record is the last 22 bytes.
    let end = b
        .len()
        .checked_sub(22)
        .filter(|&e| u32_at(b, e) == Ok(END))
        .ok_or("not a zip archive, or one cut short (no end record)")?;
    let count = usize::from(u16_at(b, end + 10)?);
    let cd_size = u32_at(b, end + 12)? as usize;
    let cd_offset = u32_at(b, end + 16)? as usize;
    if cd_offset.checked_add(cd_size) != Some(end) {
        return Err("the central directory does not end where the end record begins".into());
    }
    if count > known.len() {
        return Err(format!(
            "{count} entries, more than the {} a map file holds",
            known.len()
        ));
    }
    let mut entries: Vec<Entry> = Vec::with_capacity(count);
    let mut declared = 0u64;
    let mut at = cd_offset;
    for _ in 0..count {
        if u32_at(b, at)? != CENTRAL {
            return Err(format!("no central directory entry at byte {at}"));
        }
        let method = u16_at(b, at + 10)?;
        let crc = u32_at(b, at + 16)?;
        let (csize, usize_) = (u32_at(b, at + 20)?, u32_at(b, at + 24)?);
        let name_len = usize::from(u16_at(b, at + 28)?);
        let skip = usize::from(u16_at(b, at + 30)?) + usize::from(u16_at(b, at + 32)?);
        let local = u32_at(b, at + 42)? as usize;
        let name = b
            .get(at + 46..at + 46 + name_len)
            .and_then(|n| std::str::from_utf8(n).ok())
            .ok_or("an entry's name runs past the end or is not text")?
            .to_string();
        if !known.contains(&name.as_str()) {
            let shown: String = name.chars().take(60).collect();
            return Err(format!("unknown entry {shown}"));
        }
        if entries.iter().any(|e| e.name == name) {
            return Err(format!("entry {name} appears twice"));
        }
        match method {
            STORED if csize == usize_ => {}
            STORED => return Err(format!("entry {name} is stored, but its sizes differ")),
            DEFLATED => {
                if u64::from(usize_) > MAX_INFLATION * u64::from(csize) + 1024 {
                    return Err(format!(
                        "entry {name} declares {usize_} bytes from {csize} deflated ones, more than \
                         deflate gives"
                    ));
                }
                declared += u64::from(usize_);
                if declared > MAX_MAP_FILE_BYTES {
                    return Err(format!(
                        "the entries declare more than {MAX_MAP_FILE_BYTES} bytes in all"
                    ));
                }
            }
            _ => {
                return Err(format!(
                    "entry {name} is compressed by method {method} (covmap reads stored and \
                     deflated entries)"
                ));
            }
        }
        if u32_at(b, local)? != LOCAL {
            return Err(format!("entry {name}: no local header at byte {local}"));
        }
        let local_name = usize::from(u16_at(b, local + 26)?);
        let local_extra = usize::from(u16_at(b, local + 28)?);
        let start = local + 30 + local_name + local_extra;
        let data = start..start + csize as usize;
        if data.end > cd_offset {
            return Err(format!("entry {name} runs past the archive's data"));
        }
        if b.get(local + 30..local + 30 + local_name) != Some(name.as_bytes()) {
            return Err(format!(
                "entry {name}: its local header names another entry"
            ));
        }
        entries.push(Entry {
            name,
            crc,
            local,
            data,
            deflated: method == DEFLATED,
            size: usize_ as usize,
        });
        at += 46 + name_len + skip;
    }
    if at != end {
        return Err("the central directory holds more than its entries".into());
    }
    // Each entry's bytes, its local header to the end of its data, apart.
    let mut spans: Vec<(usize, usize, &str)> = entries
        .iter()
        .map(|e| (e.local, e.data.end, e.name.as_str()))
        .collect();
    spans.sort_unstable();
    let neighbours = spans.iter().zip(spans.iter().skip(1));
    if let Some((a, b)) = neighbours.clone().find(|(a, b)| b.0 < a.1) {
        return Err(format!(
            "entries {} and {} overlap (bytes {} to {} and {} to {})",
            a.2, b.2, a.0, a.1, b.0, b.1
        ));
    }
    let mut checked = Vec::with_capacity(entries.len());
    for e in entries {
        let held = b
            .get(e.data)
            .ok_or_else(|| format!("entry {} runs past the end", e.name))?;
        let data = if e.deflated {
            std::borrow::Cow::Owned(inflated(held, e.size, &e.name)?)
        } else {
            std::borrow::Cow::Borrowed(held)
        };
        if crc32fast::hash(&data) != e.crc {
            return Err(format!(
                "entry {}: CRC-32 mismatch, the bytes changed",
                e.name
            ));
        }
        checked.push((e.name, data));
    }
    Ok(checked)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arrays_round_trip_through_an_archive() {
        let values: Vec<u8> = [1.5f32, -2.0, 3.25]
            .iter()
            .flat_map(|v| v.to_le_bytes())
            .collect();
        let entries = vec![
            ("a.npy", npy("<f4", &[3], &values)),
            ("b.npy", npy("<u4", &[1, 1], &7u32.to_le_bytes())),
        ];
        let archive = zip(&entries).unwrap();
        let back = unzip(&archive, &["a.npy", "b.npy"]).unwrap();
        assert_eq!(back.len(), 2);
        let a = parse_npy(&back[0].1).unwrap();
        assert_eq!(
            (a.descr.as_str(), &a.shape[..], a.data),
            ("<f4", &[3][..], &values[..])
        );
        assert_eq!(parse_npy(&back[1].1).unwrap().shape, vec![1, 1]);
        assert_eq!(
            entries[0].1.len() % 64,
            values.len() % 64,
            "the header is a multiple of 64 bytes"
        );
    }

    #[test]
    fn every_flipped_byte_and_every_cut_is_refused() {
        let data: Vec<u8> = (0..40u8).collect();
        let archive = zip(&[("x.npy", npy("<f4", &[10], &data))]).unwrap();
        for i in 0..archive.len() {
            let mut bad = archive.clone();
            bad[i] ^= 0x10;
            let ok =
                unzip(&bad, &["x.npy"]).and_then(|e| parse_npy(&e[0].1).map(|a| a.data.to_vec()));
            // A flip may land where zip keeps nothing checked (the version a
            // tool needs, a date): the data then still read intact.
            if let Ok(read) = ok {
                assert_eq!(read, data, "byte {i} flipped, wrong data read");
            }
        }
        for cut in 0..archive.len() {
            assert!(unzip(&archive[..cut], &["x.npy"]).is_err(), "cut at {cut}");
        }
    }

    #[test]
    fn deflated_archives_round_trip_and_every_flip_and_cut_is_refused() {
        let data: Vec<u8> = (0..4000u32).flat_map(|v| (v % 7).to_le_bytes()).collect();
        let entries = vec![("x.npy", npy("<u4", &[1000], &data))];
        let archive = zip_with(&entries, true).unwrap();
        assert!(archive.len() < data.len() / 4, "{} bytes", archive.len());
        let back = unzip(&archive, &["x.npy"]).unwrap();
        assert_eq!(&back[0].1[..], &entries[0].1[..]);
        for i in 0..archive.len() {
            let mut bad = archive.clone();
            bad[i] ^= 0x10;
            if let Ok(read) = unzip(&bad, &["x.npy"]) {
                assert_eq!(
                    &read[0].1[..],
                    &entries[0].1[..],
                    "byte {i} flipped, wrong data read"
                );
            }
        }
        for cut in 0..archive.len() {
            assert!(unzip(&archive[..cut], &["x.npy"]).is_err(), "cut at {cut}");
        }
    }

    #[test]
    fn a_deflated_entry_that_claims_more_than_deflate_gives_is_refused_unread() {
        let archive = zip_with(&[("x.npy", vec![0u8; 1 << 20])], true).unwrap();
        let (packed, size) = (u32_at(&archive, 18).unwrap(), u32_at(&archive, 22).unwrap());
        assert!(u64::from(size) <= MAX_INFLATION * u64::from(packed));
        // The central directory's sizes claimed 4000 times the bytes held.
        let mut bomb = archive.clone();
        let central = archive.len() - 22 - (46 + 5);
        bomb[central + 24..central + 28].copy_from_slice(&(packed * 4000).to_le_bytes());
        let error = unzip(&bomb, &["x.npy"]).unwrap_err();
        assert!(error.contains("more than deflate gives"), "{error}");
        // A size within the bound but not the real one: refused after at
        // most that many bytes.
        let mut short = archive.clone();
        short[central + 24..central + 28].copy_from_slice(&(size / 2).to_le_bytes());
        let error = unzip(&short, &["x.npy"]).unwrap_err();
        assert!(error.contains("inflates to"), "{error}");
    }

    /// An archive of `entries` as `zip` writes it, but each local header
    /// at the given offset of the data that precedes it: `(name, data,
    /// offset)`, the offset `None` for the next free byte. Entries may so
    /// overlap.
    fn archive_with_offsets(entries: &[(&str, Vec<u8>, Option<usize>)]) -> Vec<u8> {
        let mut out = Vec::new();
        let mut central = Vec::new();
        for (name, data, offset) in entries {
            let offset = offset.unwrap_or(out.len());
            let one = zip(&[(name, data.clone())]).unwrap();
            let local_len = 30 + name.len() + data.len();
            if offset == out.len() {
                out.extend_from_slice(&one[..local_len]);
            }
            let mut entry = one[local_len..one.len() - 22].to_vec();
            entry[42..46].copy_from_slice(&(offset as u32).to_le_bytes());
            central.extend_from_slice(&entry);
        }
        let cd_offset = out.len() as u32;
        out.extend_from_slice(&central);
        out.extend_from_slice(&END.to_le_bytes());
        let n = entries.len() as u16;
        for v in [0u16, 0, n, n] {
            out.extend_from_slice(&v.to_le_bytes());
        }
        out.extend_from_slice(&(central.len() as u32).to_le_bytes());
        out.extend_from_slice(&cd_offset.to_le_bytes());
        out.extend_from_slice(&0u16.to_le_bytes());
        out
    }

    /// Entries whose bytes overlap (here one's local header and data lie
    /// inside the other's data) are refused before any CRC is computed; an
    /// unknown name, a name twice, or more entries than the names known,
    /// before too: the errors are those, not the CRC mismatch that the
    /// changed bytes also give.
    #[test]
    fn names_headers_and_overlaps_are_checked_before_contents() {
        let inner_data: Vec<u8> = (0..40u8).collect();
        let inner = zip(&[("b.npy", inner_data.clone())]).unwrap();
        let outer_data = inner[..30 + 5 + inner_data.len()].to_vec();
        let entries = [
            ("a.npy", outer_data, None),
            ("b.npy", inner_data, Some(30 + 5)),
        ];
        let overlapping = archive_with_offsets(&entries);
        assert!(
            unzip(&overlapping, &["a.npy", "b.npy"])
                .unwrap_err()
                .contains("overlap")
        );
        let mut changed = overlapping.clone();
        changed[30 + 5 + 30 + 5 + 10] ^= 0xff; // inside both entries' data
        let err = unzip(&changed, &["a.npy", "b.npy"]).unwrap_err();
        assert!(err.contains("entries a.npy and b.npy overlap"), "{err}");
        let err = unzip(&changed, &["a.npy"]).unwrap_err();
        assert!(err.contains("more than the 1"), "{err}");
        let err = unzip(&changed, &["a.npy", "c.npy"]).unwrap_err();
        assert!(err.contains("unknown entry b.npy"), "{err}");
        let same = [
            ("a.npy", vec![1u8; 8], None),
            ("a.npy", vec![1u8; 8], Some(0)),
        ];
        let err = unzip(&archive_with_offsets(&same), &["a.npy", "b.npy"]).unwrap_err();
        assert!(err.contains("appears twice"), "{err}");
    }

    #[test]
    fn bad_npy_headers_say_why() {
        assert!(parse_npy(b"").unwrap_err().contains("magic"));
        let f = npy("<f4", &[2], &[0; 8]).into_iter().collect::<Vec<_>>();
        assert!(
            parse_npy(&f[..f.len() - 1])
                .unwrap_err()
                .contains("needs 8 bytes")
        );
        let huge = npy("<f8", &[usize::MAX / 2, 4], &[]);
        assert!(parse_npy(&huge).unwrap_err().contains("overflows"));
        let other = npy("<i8", &[1], &[0; 8]);
        assert!(parse_npy(&other).unwrap_err().contains("<i8"));
        // Version 2 keeps the header's length in 4 bytes: 2 of them missing.
        let cut = b"\x93NUMPY\x02\x00\x10\x00";
        assert!(
            parse_npy(cut)
                .unwrap_err()
                .contains("length runs past the end")
        );
        assert!(
            parse_npy(b"\x93NUMPY\x07\x00\x10\x00")
                .unwrap_err()
                .contains("version 7")
        );
    }
}
