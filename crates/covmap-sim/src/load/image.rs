//! Occupancy images: PGM (P5 binary, P2 ASCII) or PNG, plus a resolution
//! (a ROS map_server YAML file names such an image and gives the rest:
//! [`super::map_server`]).
//!
//! A pixel's darkness `1 - v` (`v` its grey value scaled to `[0, 1]`; colour
//! channels are averaged and alpha is ignored, as map_server does) is its
//! probability `p` of being occupied, or `v` itself with `negate`.
//! map_server's trinary rule makes a pixel occupied where `p` exceeds
//! `occupied_thresh`, free where it is below `free_thresh`, and unknown
//! between. **Unknown pixels are obstacles here**: a map says nothing of what
//! lies in them, and as free space they would give a robot voids to drive in
//! that the map never saw (the unmapped interior of a building, the outside
//! of a mapped one), with walls where there are none; as obstacles they
//! bound the world to what its map knows, and the seeded start lies in the
//! largest free region that the known free pixels enclose
//! ([`crate::exploration::cells`]). So in trinary mode (the default,
//! [`ImageOptions::free_thresh`] `Some`) a pixel is an obstacle unless it is
//! free. In scale mode (`free_thresh` `None`, a map_server YAML file's `mode:
//! scale`) a grey pixel is a known partial occupancy rather than unknown,
//! and a pixel is an obstacle when `p` exceeds `occupied_thresh`.
//!
//! Each horizontal run of obstacle pixels becomes one rectangle, and runs
//! spanning the same columns in consecutive rows are merged into one taller
//! rectangle: the union is exactly the set of obstacle pixels, with far fewer
//! edges than one square per pixel.
//!
//! Placement follows map_server: the image's lower-left pixel's lower-left
//! corner sits at `origin_m`, row 0 of the file is the top, and the image is
//! rotated by `yaw_rad` about the origin (zero yaw keeps rectangles
//! axis-aligned).
//!
//! Both formats are decoded by the `image` crate (its `png` and `pnm`
//! codecs only): PNG of any colour type and depth (palettes expanded, 16-bit
//! samples kept whole), PGM binary (P5) or ASCII (P2) of any maxval up to
//! 65535. The header is read first and what it declares is bounded before
//! anything of its size is allocated: at most [`MAX_IMAGE_PIXELS`] pixels,
//! no more pixels than a PGM file has bytes, no more decoded bytes than
//! deflate can expand a PNG file's bytes into; the decoders get the same
//! bounds as `image::Limits`. Errors name the file, the part of it (`PGM
//! header`, `PNG data`, ...) and the decoder's reason. A PGM value above
//! its maxval reads as maxval, as the `pnm` decoder clamps it.

use std::io::Cursor;
use std::path::Path;

use covmap_core::memory;
use image::codecs::png::PngDecoder;
use image::codecs::pnm::PnmDecoder;
use image::error::LimitErrorKind;
use image::{ImageDecoder, ImageError, Limits};

use super::{parse_error, read_bytes};
use crate::error::{Result, SimError, check_param};
use crate::material::Material;
use crate::polygon::Polygon;
use crate::world::World;

/// map_server's default `free_thresh`: a pixel less likely occupied than
/// this is free.
pub const DEFAULT_FREE_THRESH: f64 = 0.196;

/// How to read an occupancy image.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ImageOptions {
    /// Side of a pixel, metres.
    pub resolution_m: f64,
    /// World position of the lower-left corner of the lower-left pixel, metres.
    pub origin_m: [f64; 2],
    /// Rotation of the image about `origin_m`, radians.
    pub yaw_rad: f64,
    /// Whether light pixels are the occupied ones.
    pub negate: bool,
    /// Probability of occupancy above which a pixel is occupied, in `[0, 1)`.
    pub occupied_thresh: f64,
    /// Trinary mode: the probability of occupancy below which a pixel is
    /// free, in `[0, occupied_thresh)`; every other pixel (occupied or
    /// unknown) is an obstacle. `None`: scale mode, where a pixel is an
    /// obstacle when it is occupied and free space otherwise.
    pub free_thresh: Option<f64>,
}

impl ImageOptions {
    /// At `resolution_m` per pixel, origin at zero, no yaw, dark = occupied,
    /// trinary with thresholds 0.65 and 0.196 (map_server's defaults).
    pub fn new(resolution_m: f64) -> Self {
        Self {
            resolution_m,
            origin_m: [0.0, 0.0],
            yaw_rad: 0.0,
            negate: false,
            occupied_thresh: 0.65,
            free_thresh: Some(DEFAULT_FREE_THRESH),
        }
    }

    pub(super) fn validate(&self) -> Result<()> {
        check_param(
            "resolution_m",
            self.resolution_m,
            self.resolution_m > 0.0,
            "a positive pixel size",
        )?;
        for (name, v) in [
            ("origin_m[0]", self.origin_m[0]),
            ("origin_m[1]", self.origin_m[1]),
            ("yaw_rad", self.yaw_rad),
        ] {
            check_param(name, v, true, "a finite number")?;
        }
        check_param(
            "occupied_thresh",
            self.occupied_thresh,
            (0.0..1.0).contains(&self.occupied_thresh),
            "a probability in [0, 1)",
        )?;
        if let Some(free) = self.free_thresh {
            check_param(
                "free_thresh",
                free,
                (0.0..self.occupied_thresh).contains(&free),
                "a probability at least 0 and below occupied_thresh",
            )?;
        }
        Ok(())
    }
}

/// A decoded image: grey values in `[0, 1]`, row 0 at the top.
struct Grey {
    width: usize,
    height: usize,
    values: Vec<f64>,
}

impl World {
    /// A world from a PGM or PNG occupancy image (the format is recognised by
    /// its first bytes); see [the rules](crate::load::image).
    pub fn from_image_file(path: impl AsRef<Path>, options: &ImageOptions) -> Result<World> {
        let path = path.as_ref();
        Self::from_image_bytes(&read_bytes(path)?, path, options)
    }

    /// A world from the bytes of a PGM or PNG image; `name` is the file name
    /// errors report.
    ///
    /// # Example
    /// ```
    /// use covmap_sim::{ImageOptions, World};
    /// // 4 x 2 pixels at 0.5 m: a dark run of two pixels on the top row.
    /// let pgm = b"P2\n4 2\n255\n255 0 0 255\n255 255 255 255\n";
    /// let world = World::from_image_bytes(pgm, "tiny.pgm", &ImageOptions::new(0.5)).unwrap();
    /// assert_eq!(world.len(), 1);
    /// assert_eq!(world.polygons()[0].bounds_m(), [0.5, 0.5, 1.5, 1.0]);
    /// let err = World::from_image_bytes(b"P2\n4 2\n255\n255 0 0\n", "cut.pgm", &ImageOptions::new(0.5)).unwrap_err();
    /// assert!(err.to_string().starts_with("cut.pgm, PGM data: "), "{err}");
    /// ```
    pub fn from_image_bytes(
        bytes: &[u8],
        name: impl AsRef<Path>,
        options: &ImageOptions,
    ) -> Result<World> {
        let path = name.as_ref();
        options.validate()?;
        let grey = if bytes.starts_with(b"\x89PNG") {
            decode_png(bytes, path)?
        } else if bytes.starts_with(b"P5") || bytes.starts_with(b"P2") {
            decode_pgm(bytes, path)?
        } else {
            return Err(parse_error(
                path,
                "byte 0",
                "not a PGM (P5/P2) or PNG image",
            ));
        };
        world_from_grey(&grey, options, path)
    }
}

/// The most pixels an image file may declare (2^30).
pub const MAX_IMAGE_PIXELS: usize = 1 << 30;

/// The most rectangles an occupancy image may become (2^20): each is an
/// obstacle polygon of four edges, so that a world loaded from an image
/// holds a bounded number of polygons (and its ray caster of pieces), however
/// the pixels fall. A checkerboard of 1450 x 1450 pixels passes it; real
/// occupancy maps, whose walls are runs of pixels, stay far below.
pub const MAX_IMAGE_RECTANGLES: usize = 1 << 20;

/// The longest side a decoder accepts: [`MAX_IMAGE_PIXELS`], that of an image
/// one pixel high.
const MAX_IMAGE_SIDE: u32 = 1 << 30;
const _: () = assert!(MAX_IMAGE_SIDE as usize == MAX_IMAGE_PIXELS);

/// The largest factor by which deflate (PNG's compression) expands data.
const DEFLATE_MAX_RATIO: usize = 1032;

/// What the decoders may allocate: sides of at most [`MAX_IMAGE_SIDE`]
/// pixels, and `max_bytes` bytes.
fn decoder_limits(max_bytes: usize) -> Limits {
    let mut limits = Limits::no_limits();
    limits.max_image_width = Some(MAX_IMAGE_SIDE);
    limits.max_image_height = Some(MAX_IMAGE_SIDE);
    limits.max_alloc = Some(u64::try_from(max_bytes).unwrap_or(u64::MAX));
    limits
}

/// The error for a header that declares more than `bound` allows.
fn too_large(path: &Path, place: &str, width: u32, height: u32, bound: &str) -> SimError {
    parse_error(
        path,
        place,
        format!("the declared {width} x {height} pixels are more than {bound}"),
    )
}

/// An error of the `image` crate at `place` (`what` says what the bytes
/// there are): a broken limit is a header declaring more than `bound`
/// allows, a cut file says so, anything else in the crate's words.
fn image_error(path: &Path, place: &str, what: &str, bound: &str, e: ImageError) -> SimError {
    match e {
        ImageError::Limits(e) => parse_error(
            path,
            place,
            match e.kind() {
                LimitErrorKind::DimensionError => {
                    format!("the declared image has a side of more than 2^30 pixels ({e})")
                }
                _ => format!("the declared pixels are more than {bound} ({e})"),
            },
        ),
        ImageError::IoError(e) if e.kind() == std::io::ErrorKind::UnexpectedEof => {
            parse_error(path, place, format!("the file ends inside the {what}"))
        }
        e => parse_error(path, place, e.to_string()),
    }
}

/// How a decoded sample becomes a level of grey.
#[derive(Clone, Copy)]
enum Samples {
    /// PNG: the sample is the level, out of 255 or 65535 by its width.
    AsDecoded,
    /// PGM: the sample is the file's value out of `maxval`, which the `pnm`
    /// decoder stretched to 255 (maxval up to 255) or 65535 (above).
    Stretched { maxval: u32 },
}

fn decode_png(bytes: &[u8], path: &Path) -> Result<Grey> {
    // No more decoded bytes than deflate can expand the file's bytes into
    // (at most 1032 to 1): a short file that claims a huge image is refused
    // from its header. The `png` decoder under the `image` crate holds its
    // own buffers to the same bound.
    let max_bytes = bytes.len().saturating_mul(DEFLATE_MAX_RATIO);
    let bound = format!("a PNG file of {} bytes can hold", bytes.len());
    let decoder = PngDecoder::with_limits(Cursor::new(bytes), decoder_limits(max_bytes))
        .map_err(|e| image_error(path, "PNG header", "PNG header", &bound, e))?;
    decode_grey(decoder, path, "PNG", max_bytes, &bound, Samples::AsDecoded)
}

fn decode_pgm(bytes: &[u8], path: &Path) -> Result<Grey> {
    let bound = format!("a PGM file of {} bytes can hold", bytes.len());
    let decoder = PnmDecoder::new(Cursor::new(bytes))
        .map_err(|e| image_error(path, "PGM header", "PGM header", &bound, e))?;
    let maxval = decoder.header().maximal_sample();
    // Every pixel takes at least a byte of the file (a binary sample one or
    // two, an ASCII one a digit): a header that promises more pixels than
    // the file has bytes is refused before anything of its size is made.
    let max_bytes = bytes
        .len()
        .saturating_mul(usize::from(decoder.color_type().bytes_per_pixel()));
    decode_grey(
        decoder,
        path,
        "PGM",
        max_bytes,
        &bound,
        Samples::Stretched { maxval },
    )
}

/// The grey values of the image `decoder` has read the header of. The
/// declared size is checked before anything of that size is allocated: at
/// most [`MAX_IMAGE_PIXELS`] pixels and `max_bytes` decoded bytes (`bound`
/// says why), the buffers asked for fallibly.
fn decode_grey(
    mut decoder: impl ImageDecoder,
    path: &Path,
    format: &str,
    max_bytes: usize,
    bound: &str,
    samples: Samples,
) -> Result<Grey> {
    let header = format!("{format} header");
    let (w, h) = decoder.dimensions();
    if w == 0 || h == 0 {
        return Err(parse_error(
            path,
            header,
            format!("the declared image of {w} x {h} pixels has none"),
        ));
    }
    let (width, height) = (w as usize, h as usize);
    let count = width
        .checked_mul(height)
        .filter(|&n| n <= MAX_IMAGE_PIXELS)
        .ok_or_else(|| too_large(path, &header, w, h, "the 2^30 an image may have"))?;
    let size = usize::try_from(decoder.total_bytes())
        .ok()
        .filter(|&size| size <= max_bytes)
        .ok_or_else(|| too_large(path, &header, w, h, bound))?;
    decoder
        .set_limits(decoder_limits(max_bytes))
        .map_err(|e| image_error(path, &header, "header", bound, e))?;
    let color = decoder.color_type();
    let mut buf = memory::try_filled(
        0u8,
        size,
        &format!("{}: the {format}'s decoded pixels", path.display()),
    )?;
    decoder
        .read_image(&mut buf)
        .map_err(|e| image_error(path, &format!("{format} data"), "pixel data", bound, e))?;
    // Colour channels averaged; alpha ignored. Samples of 16 bits are in the
    // machine's byte order (`read_image`'s contract).
    let wide = color.bytes_per_pixel() == 2 * color.channel_count();
    let colours = if color.has_color() { 3 } else { 1 };
    let full = if wide { 65535.0 } else { 255.0 };
    let mut values = memory::try_with_capacity(
        count,
        &format!("{}: the {format}'s grey values", path.display()),
    )?;
    for pixel in buf.chunks_exact(usize::from(color.bytes_per_pixel())) {
        let sum: f64 = if wide {
            let (samples, _) = pixel.as_chunks::<2>();
            samples
                .iter()
                .take(colours)
                .map(|&s| f64::from(u16::from_ne_bytes(s)))
                .sum()
        } else {
            pixel.iter().take(colours).map(|&s| f64::from(s)).sum()
        };
        values.push(match samples {
            Samples::AsDecoded => sum / (full * colours as f64),
            Samples::Stretched { maxval } => {
                // The decoder stretched the file's value v to
                // round(v * full / maxval) (in f32): rounding back gives v
                // exactly for every maxval up to 64849 (every v checked), and
                // v within one step of maxval above. A value above maxval
                // comes out as maxval.
                let maxval = f64::from(maxval);
                (sum * maxval / full).round() * (1.0 / maxval)
            }
        });
    }
    Ok(Grey {
        width,
        height,
        values,
    })
}

fn world_from_grey(grey: &Grey, o: &ImageOptions, path: &Path) -> Result<World> {
    let occupied = |v: f64| {
        let p = if o.negate { v } else { 1.0 - v };
        match o.free_thresh {
            Some(free) => !(p < free),
            None => p > o.occupied_thresh,
        }
    };
    let (w, h, r) = (grey.width, grey.height, o.resolution_m);
    // Open rectangles: (first column, end column, top row), sorted by column.
    let mut open: Vec<(usize, usize, usize)> = Vec::new();
    let mut rects: Vec<(usize, usize, usize, usize)> = Vec::new(); // c0, c1, top row, bottom row (inclusive)
    for row in 0..=h {
        let mut runs = Vec::new();
        if row < h {
            let line = &grey.values[row * w..(row + 1) * w];
            let mut c = 0;
            while c < w {
                if occupied(line[c]) {
                    let start = c;
                    while c < w && occupied(line[c]) {
                        c += 1;
                    }
                    runs.push((start, c));
                } else {
                    c += 1;
                }
            }
        }
        let mut next = Vec::with_capacity(runs.len());
        let mut k = 0;
        for &(c0, c1, top) in &open {
            while k < runs.len() && runs[k].0 < c0 {
                next.push((runs[k].0, runs[k].1, row));
                k += 1;
            }
            if k < runs.len() && runs[k] == (c0, c1) {
                next.push((c0, c1, top));
                k += 1;
            } else {
                if rects.len() == MAX_IMAGE_RECTANGLES {
                    return Err(parse_error(
                        path,
                        format!("pixel ({c0}, {top})"),
                        format!(
                            "the occupied pixels make more than {MAX_IMAGE_RECTANGLES} rectangles, \
                             the most a world from an image may hold"
                        ),
                    ));
                }
                rects.push((c0, c1, top, row - 1));
            }
        }
        next.extend(runs[k..].iter().map(|&(c0, c1)| (c0, c1, row)));
        next.sort_unstable();
        open = next;
    }
    if rects.is_empty() {
        return Err(parse_error(
            path,
            "all pixels",
            format!(
                "no obstacle pixel (probability of occupancy {}{}): check `negate` and the thresholds",
                match o.free_thresh {
                    Some(free) => format!("at least free_thresh = {free}"),
                    None => format!("above occupied_thresh = {}", o.occupied_thresh),
                },
                if o.negate { ", negated" } else { "" }
            ),
        ));
    }
    let (s, c) = o.yaw_rad.sin_cos();
    let place = |x: f64, y: f64| [o.origin_m[0] + c * x - s * y, o.origin_m[1] + s * x + c * y];
    let polygons = rects
        .into_iter()
        .map(|(c0, c1, top, bottom)| {
            let (x0, x1) = (c0 as f64 * r, c1 as f64 * r);
            let (y0, y1) = ((h - 1 - bottom) as f64 * r, (h - top) as f64 * r);
            let vertices = if o.yaw_rad == 0.0 {
                vec![
                    [o.origin_m[0] + x0, o.origin_m[1] + y0],
                    [o.origin_m[0] + x1, o.origin_m[1] + y0],
                    [o.origin_m[0] + x1, o.origin_m[1] + y1],
                    [o.origin_m[0] + x0, o.origin_m[1] + y1],
                ]
            } else {
                vec![place(x0, y0), place(x1, y0), place(x1, y1), place(x0, y1)]
            };
            Polygon::new(vertices, Material::Wall)
                .map_err(|e| parse_error(path, format!("pixel ({c0}, {top})"), e.to_string()))
        })
        .collect::<Result<Vec<_>>>()?;
    Ok(World::new(polygons))
}

#[cfg(test)]
mod tests;
