//! Tests of the image and map_server loaders.

use super::*;
use crate::load::map_server::parse_ros_map_yaml;
use covmap_core::Grid;
use image::codecs::png::PngEncoder;
use image::{ExtendedColorType, ImageEncoder};

fn pgm_p5(width: usize, height: usize, pixels: &[u8]) -> Vec<u8> {
    let mut b = format!("P5\n# a comment\n{width} {height}\n255\n").into_bytes();
    b.extend_from_slice(pixels);
    b
}

#[test]
fn runs_merge_into_rectangles_with_exact_coverage() {
    // 0 = dark. An L of pixels: rows 0-1 columns 1-2, row 2 columns 1-3.
    #[rustfmt::skip]
    let px = [
        255, 0, 0, 255,
        255, 0, 0, 255,
        255, 0, 0, 0,
        255, 255, 255, 255,
    ];
    let w = World::from_image_bytes(&pgm_p5(4, 4, &px), "l.pgm", &ImageOptions::new(0.1)).unwrap();
    // Rows 0-1 merge; row 2 differs: two rectangles.
    assert_eq!(w.len(), 2);
    // Coverage on the pixel grid reproduces the image (row 0 of the grid is
    // the image's bottom row).
    let g = Grid::new([0.0, 0.0], 0.1, 4, 4).unwrap();
    let cov = w.coverage(&g);
    for row in 0..4 {
        for col in 0..4 {
            let dark = px[(3 - row) * 4 + col] == 0;
            let expect = if dark { 1.0 } else { 0.0 };
            assert!(
                (cov[row * 4 + col] - expect).abs() < 1e-12,
                "({row}, {col})"
            );
        }
    }
}

/// In scale mode a pixel is an obstacle when its occupancy is above
/// `occupied_thresh`.
#[test]
fn thresholds_negate_and_sixteen_bits() {
    // Values 100/255 -> p = 0.61 (free at 0.65, occupied at 0.5).
    let px = [100u8, 255];
    let scale = ImageOptions {
        free_thresh: None,
        ..ImageOptions::new(1.0)
    };
    assert!(World::from_image_bytes(&pgm_p5(2, 1, &px), "t.pgm", &scale).is_err());
    let mut o = scale;
    o.occupied_thresh = 0.5;
    assert_eq!(
        World::from_image_bytes(&pgm_p5(2, 1, &px), "t.pgm", &o)
            .unwrap()
            .len(),
        1
    );
    o.negate = true;
    let w = World::from_image_bytes(&pgm_p5(2, 1, &px), "t.pgm", &o).unwrap();
    assert_eq!(w.polygons()[0].bounds_m(), [1.0, 0.0, 2.0, 1.0]);
    // 16-bit: maxval 1000, big-endian samples 0 and 1000.
    let mut b = b"P5 2 1 1000\n".to_vec();
    b.extend_from_slice(&[0, 0, 0x03, 0xE8]);
    let w = World::from_image_bytes(&b, "w.pgm", &ImageOptions::new(1.0)).unwrap();
    assert_eq!(w.polygons()[0].bounds_m(), [0.0, 0.0, 1.0, 1.0]);
}

#[test]
fn malformed_images_name_the_place() {
    let e =
        World::from_image_bytes(b"P5\n4 x\n255\n", "h.pgm", &ImageOptions::new(1.0)).unwrap_err();
    assert!(e.to_string().starts_with("h.pgm, PGM header: "), "{e}");
    assert!(e.to_string().contains("digit"), "{e}");
    let e = World::from_image_bytes(&pgm_p5(4, 4, &[0; 9]), "s.pgm", &ImageOptions::new(1.0))
        .unwrap_err();
    assert!(
        e.to_string()
            .starts_with("s.pgm, PGM data: the file ends inside the pixel data"),
        "{e}"
    );
    let e =
        World::from_image_bytes(b"P2 2 1 10 3 x", "a.pgm", &ImageOptions::new(1.0)).unwrap_err();
    assert!(e.to_string().starts_with("a.pgm, PGM data: "), "{e}");
    assert!(e.to_string().contains("sample"), "{e}");
    // The Netpbm format has comments in the header only.
    let e = World::from_image_bytes(b"P2 2 1 255\n0 # c\n255", "c.pgm", &ImageOptions::new(1.0))
        .unwrap_err();
    assert!(e.to_string().starts_with("c.pgm, PGM data: "), "{e}");
    let e = World::from_image_bytes(b"P5 0 3 255\n", "z.pgm", &ImageOptions::new(1.0)).unwrap_err();
    assert!(
        e.to_string().starts_with("z.pgm, PGM header: ") && e.to_string().contains("0 x 3"),
        "{e}"
    );
    assert!(World::from_image_bytes(b"GIF89a", "x.gif", &ImageOptions::new(1.0)).is_err());
    assert!(
        World::from_image_bytes(&pgm_p5(1, 1, &[0]), "r.pgm", &ImageOptions::new(-1.0)).is_err()
    );
    let e = World::from_image_bytes(
        b"\x89PNG\r\n\x1a\nrubbish",
        "p.png",
        &ImageOptions::new(1.0),
    )
    .unwrap_err();
    assert!(e.to_string().starts_with("p.png, PNG header: "), "{e}");
}

/// A PGM value above the file's maxval reads as maxval (the `pnm` decoder
/// clamps it): white, or occupied when negated.
#[test]
fn a_pgm_value_above_maxval_reads_as_maxval() {
    let o = ImageOptions {
        free_thresh: None,
        ..ImageOptions::new(1.0)
    };
    let w = World::from_image_bytes(b"P2 2 1 10 3 11", "v.pgm", &o).unwrap();
    assert_eq!(w.len(), 1);
    assert_eq!(w.polygons()[0].bounds_m(), [0.0, 0.0, 1.0, 1.0]);
    let negated = ImageOptions { negate: true, ..o };
    let w = World::from_image_bytes(b"P2 2 1 10 3 11", "v.pgm", &negated).unwrap();
    assert_eq!(w.polygons()[0].bounds_m(), [1.0, 0.0, 2.0, 1.0]);
}

/// Grey values are the file's values over its maxval, exactly as before the
/// decoder stretched them: every value of every 8-bit maxval, every value of
/// maxval 1000 (16-bit, binary and ASCII), the top of 16 bits within a step.
#[test]
fn pgm_grey_values_are_the_files_values_over_maxval() {
    let check = |bytes: &[u8], maxval: u32, tolerance: f64| {
        let grey = decode_pgm(bytes, Path::new("g.pgm")).unwrap();
        assert_eq!(grey.values.len(), maxval as usize + 1);
        for (v, &g) in grey.values.iter().enumerate() {
            let exact = v as f64 * (1.0 / f64::from(maxval));
            assert!(
                (g - exact).abs() <= tolerance,
                "maxval {maxval}, value {v}: {g} (expected {exact})"
            );
        }
    };
    for maxval in 1..=255u32 {
        let mut b = format!("P5 {} 1 {maxval}\n", maxval + 1).into_bytes();
        b.extend((0..=maxval).map(|v| v as u8));
        check(&b, maxval, 0.0);
    }
    for maxval in [256u32, 1000, 4095, 64849, 65535] {
        let mut b = format!("P5 {} 1 {maxval}\n", maxval + 1).into_bytes();
        b.extend((0..=maxval).flat_map(|v| (v as u16).to_be_bytes()));
        check(&b, maxval, 0.0);
    }
    let text: Vec<String> = (0..=1000).map(|v| v.to_string()).collect();
    check(
        format!("P2 1001 1 1000\n{}\n", text.join(" ")).as_bytes(),
        1000,
        0.0,
    );
    let mut b = b"P5 65535 1 65534\n".to_vec();
    b.extend((0..=65534u16).flat_map(|v| v.to_be_bytes()));
    check(&b, 65534, 1.0 / 65534.0);
    // A value on the threshold stays on it: 35 of 100 is an occupancy of
    // exactly 0.65, not above it (stretched to 89 of 255 it would be).
    let scale = ImageOptions {
        free_thresh: None,
        ..ImageOptions::new(1.0)
    };
    let w = World::from_image_bytes(b"P2 2 1 100 35 0", "t.pgm", &scale).unwrap();
    assert_eq!(w.polygons()[0].bounds_m(), [1.0, 0.0, 2.0, 1.0]);
}

/// Trinary mode (the default): a pixel is an obstacle unless it is free
/// (occupancy below `free_thresh`): unknown grey is an obstacle, as the
/// occupied black is; a bad `free_thresh` is named.
#[test]
fn unknown_pixels_are_obstacles() {
    // 0 occupied, 205 unknown (p = 0.196...), 206 free (p = 0.192), 255 free.
    let px = [0u8, 205, 206, 255];
    let w = World::from_image_bytes(&pgm_p5(4, 1, &px), "u.pgm", &ImageOptions::new(1.0)).unwrap();
    assert_eq!(w.len(), 1);
    assert_eq!(w.polygons()[0].bounds_m(), [0.0, 0.0, 2.0, 1.0]);
    for free in [f64::NAN, -0.1, 0.65, 0.9] {
        let o = ImageOptions {
            free_thresh: Some(free),
            ..ImageOptions::new(1.0)
        };
        let e = World::from_image_bytes(&pgm_p5(4, 1, &px), "u.pgm", &o).unwrap_err();
        assert!(
            matches!(
                e,
                SimError::InvalidParameter {
                    name: "free_thresh",
                    ..
                }
            ),
            "{free}: {e}"
        );
    }
}

/// A PGM header that declares more pixels than the file has bytes, or more
/// than 2^30, is refused from the header, naming the file.
#[test]
fn a_pgm_header_claiming_a_huge_image_is_refused_before_decoding() {
    let opts = ImageOptions::new(0.05);
    for (header, says) in [
        ("P5\n100000 100000\n255\n", "the 2^30 an image may have"),
        ("P5\n30000 30000\n255\n", "a PGM file of 35 bytes can hold"),
        ("P5\n3000 3000\n65535\n", "a PGM file of 35 bytes can hold"),
        ("P2\n30000 30000\n255\n", "a PGM file of 35 bytes can hold"),
    ] {
        let mut bytes = header.as_bytes().to_vec();
        bytes.extend([0u8; 16]);
        let err = World::from_image_bytes(&bytes, "huge.pgm", &opts).unwrap_err();
        let text = err.to_string();
        assert!(
            text.starts_with("huge.pgm, PGM header: "),
            "{header}: {text}"
        );
        assert!(text.contains(says), "{header}: {text}");
    }
    let e = World::from_image_bytes(b"P5\n18446744073709551617 3\n255\n\0\0\0", "h.pgm", &opts)
        .unwrap_err();
    assert!(e.to_string().starts_with("h.pgm, PGM header: "), "{e}");
}

/// A 16-bit PNG's samples are read whole, out of 65535.
#[test]
fn sixteen_bit_png_samples_are_read_whole() {
    let mut data = Vec::new();
    let px: Vec<u8> = [0x8000u16, 0x5FFF, 0xFFFF]
        .iter()
        .flat_map(|v| v.to_ne_bytes())
        .collect();
    PngEncoder::new(&mut data)
        .write_image(&px, 3, 1, ExtendedColorType::L16)
        .unwrap();
    let grey = decode_png(&data, Path::new("w.png")).unwrap();
    assert_eq!(
        grey.values,
        [32768.0 / 65535.0, 24575.0 / 65535.0, 1.0],
        "{:?}",
        grey.values
    );
}

#[test]
fn png_rgb_and_yaml() {
    // Encode a 3 x 2 RGB PNG: one dark pixel at the top left.
    let mut data = Vec::new();
    let mut px = vec![255u8; 18];
    px[..3].copy_from_slice(&[10, 20, 30]);
    PngEncoder::new(&mut data)
        .write_image(&px, 3, 2, ExtendedColorType::Rgb8)
        .unwrap();
    let mut o = ImageOptions::new(0.5);
    o.origin_m = [10.0, 20.0];
    let w = World::from_image_bytes(&data, "a.png", &o).unwrap();
    assert_eq!(w.polygons()[0].bounds_m(), [10.0, 20.5, 10.5, 21.0]);
    // A half turn of yaw puts it on the other side of the origin.
    o.yaw_rad = std::f64::consts::PI;
    let w = World::from_image_bytes(&data, "a.png", &o).unwrap();
    let b = w.polygons()[0].bounds_m();
    for (x, e) in b.iter().zip([9.5, 19.0, 10.0, 19.5]) {
        assert!((x - e).abs() < 1e-12, "{b:?}");
    }

    let yaml = "image: map.png\nresolution: 0.05 # metres\norigin: [1.0, -2.0, 0.0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n";
    let (image, opts) = parse_ros_map_yaml(yaml, Path::new("m.yaml")).unwrap();
    assert_eq!(image, "map.png");
    assert_eq!(
        (opts.resolution_m, opts.origin_m, opts.yaw_rad, opts.negate),
        (0.05, [1.0, -2.0], 0.0, false)
    );
    let e = parse_ros_map_yaml(
        "image: m.png\norigin: [1, 2]\nresolution: 1\n",
        Path::new("m.yaml"),
    )
    .unwrap_err();
    assert!(e.to_string().starts_with("m.yaml, line 2"), "{e}");
    let e =
        parse_ros_map_yaml("image: m.png\norigin: [1, 2, 0]\n", Path::new("m.yaml")).unwrap_err();
    assert!(e.to_string().contains("missing key `resolution`"), "{e}");
    let e = parse_ros_map_yaml("image: m.png\nresolution: abc\n", Path::new("m.yaml")).unwrap_err();
    assert!(e.to_string().starts_with("m.yaml, line 2"), "{e}");
}

/// CRC-32 (ISO-HDLC, as PNG chunks use it), bit by bit.
fn crc32(bytes: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &b in bytes {
        crc ^= b as u32;
        for _ in 0..8 {
            crc = if crc & 1 != 0 {
                (crc >> 1) ^ 0xEDB8_8320
            } else {
                crc >> 1
            };
        }
    }
    !crc
}

/// A valid one-pixel grey PNG whose header then claims `width` x `height`
/// (its chunk checksum mended, so only the size is a lie).
fn png_claiming(width: u32, height: u32) -> Vec<u8> {
    let mut data = Vec::new();
    PngEncoder::new(&mut data)
        .write_image(&[0], 1, 1, ExtendedColorType::L8)
        .unwrap();
    // Signature (8 bytes), IHDR length (4), "IHDR" (4), width, height, ...
    data[16..20].copy_from_slice(&width.to_be_bytes());
    data[20..24].copy_from_slice(&height.to_be_bytes());
    let crc = crc32(&data[12..29]);
    data[29..33].copy_from_slice(&crc.to_be_bytes());
    data
}

/// A short PNG whose header claims 100000 x 100000 pixels is refused from its
/// header, before anything of that size is allocated (it would need 10 GB).
#[test]
fn a_png_header_claiming_a_huge_image_is_refused_before_decoding() {
    let opts = ImageOptions::new(0.05);
    let small = World::from_image_bytes(&png_claiming(1, 1), "one.png", &opts);
    assert!(small.is_ok(), "{small:?}");
    for (width, height) in [(100_000, 100_000), (1_000_000, 1), (1 << 31, 1 << 31)] {
        let bytes = png_claiming(width, height);
        let err = World::from_image_bytes(&bytes, "huge.png", &opts).unwrap_err();
        let text = err.to_string();
        assert!(
            text.contains("huge.png") && text.contains("PNG header") && text.contains("pixels"),
            "{width} x {height}: {text}"
        );
    }
}

#[test]
fn yaml_values_map_server_refuses_name_their_line() {
    let base = "image: m.png\nresolution: 0.5\norigin: [0, 0, 0]\n";
    for (extra, place, says) in [
        (
            "free_thresh: [1]\n",
            "line 4",
            "invalid type: sequence, expected f64",
        ),
        ("negate: 2\n", "key `negate`", "negate must be 0 or 1"),
        ("negate: yes\n", "key `negate`", "negate must be 0 or 1"),
        (
            "mode: raw\n",
            "key `mode`",
            "only `mode: trinary` or `mode: scale`",
        ),
        (
            "occupied_thresh: .nan\n",
            "key `occupied_thresh`",
            "must be a finite number",
        ),
        (
            "occupied_thresh: 0.3\nfree_thresh: 0.6\n",
            "key `free_thresh`",
            "below occupied_thresh (0.3), found 0.6",
        ),
        ("free_thresh: -0.1\n", "key `free_thresh`", "at least 0"),
    ] {
        let e = parse_ros_map_yaml(&format!("{base}{extra}"), Path::new("m.yaml")).unwrap_err();
        let text = e.to_string();
        assert!(
            text.starts_with(&format!("m.yaml, {place}")),
            "{extra}: {text}"
        );
        assert!(text.contains(says), "{extra}: {text}");
    }
    // Quoted values, flow mappings and unknown keys read as map_server reads them.
    let (image, o) = parse_ros_map_yaml(
        "{image: \"a b.pgm\", resolution: 0.1, origin: [1, 2, 0.5], negate: true, unknown: 3}",
        Path::new("m.yaml"),
    )
    .unwrap();
    assert_eq!(
        (image.as_str(), o.origin_m, o.yaw_rad, o.negate),
        ("a b.pgm", [1.0, 2.0], 0.5, true)
    );
    let e = parse_ros_map_yaml("- a list\n", Path::new("m.yaml")).unwrap_err();
    assert!(e.to_string().starts_with("m.yaml, line 1"), "{e}");
}

#[test]
fn a_checkerboard_of_more_rectangles_than_the_bound_is_refused() {
    // 1450 x 1450 pixels, every other one occupied: 1,051,250 rectangles.
    let side = 1450;
    let pixels: Vec<u8> = (0..side * side)
        .map(|i| {
            if (i % side + i / side) % 2 == 0 {
                0
            } else {
                255
            }
        })
        .collect();
    let bytes = pgm_p5(side, side, &pixels);
    let err = World::from_image_bytes(&bytes, Path::new("board.pgm"), &ImageOptions::new(0.05))
        .unwrap_err();
    assert!(err.to_string().contains("rectangles"), "{err}");
    assert!(err.to_string().contains("board.pgm"), "{err}");
}
