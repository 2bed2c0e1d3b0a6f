//! The loaders against the real worlds in `../shared/data/worlds`.

use covmap::Grid;
use covmap::sim::{ImageOptions, World};

use super::shared_worlds;

#[test]
fn aria_office_walls_match_its_own_scan_points() {
    let Some(dir) = shared_worlds() else { return };
    let path = dir.join("AMROffice.map");
    let world = World::from_aria_map_file(&path, 0.1).unwrap();
    assert_eq!(world.len(), 243);
    // LineMinPos -11682 -4183, LineMaxPos 5213 26519 (mm), widened by the
    // walls' half thickness and end extensions.
    let [x0, y0, x1, y1] = world.bounds_m();
    for (got, want) in [(x0, -11.682), (y0, -4.183), (x1, 5.213), (y1, 26.519)] {
        assert!((got - want).abs() <= 0.1, "{:?}", world.bounds_m());
    }
    // The DATA section holds the laser points the walls were drawn from: most
    // must lie on a wall (this fails if millimetres or axes were mixed up).
    let text = std::fs::read_to_string(&path).unwrap();
    let points: Vec<[f64; 2]> = text
        .lines()
        .skip_while(|l| l.trim() != "DATA")
        .skip(1)
        .filter_map(|l| {
            let v: Vec<f64> = l
                .split_whitespace()
                .filter_map(|t| t.parse().ok())
                .collect();
            (v.len() == 2).then(|| [v[0] / 1000.0, v[1] / 1000.0])
        })
        .collect();
    assert!(points.len() > 20_000, "{}", points.len());
    let near = points
        .iter()
        .filter(|&&p| world.distance_to_obstacle_m(p) < 0.1)
        .count();
    let share = near as f64 / points.len() as f64;
    assert!(
        share > 0.8,
        "only {share:.3} of the scan points lie within 10 cm of a wall"
    );
    // Errors name the file.
    let e = World::from_aria_map_file(dir.join("missing.map"), 0.1).unwrap_err();
    assert!(e.to_string().contains("missing.map"), "{e}");
}

#[test]
fn willow_garage_coverage_reproduces_the_obstacle_pixels() {
    let Some(dir) = shared_worlds() else { return };
    let path = dir.join("willow-full.pgm");
    let world = World::from_image_file(&path, &ImageOptions::new(0.1)).unwrap();
    // Count the obstacle pixels independently: P5, 540 x 587, maxval 255;
    // in trinary mode every pixel that is not free is an obstacle (the
    // unknown ones too), free when (255 - v) / 255 < 0.196.
    let bytes = std::fs::read(&path).unwrap();
    let header_end = {
        let mut fields = 0;
        let mut i = 0;
        while fields < 4 {
            if bytes[i] == b'#' {
                while bytes[i] != b'\n' {
                    i += 1;
                }
            } else if !bytes[i].is_ascii_whitespace() {
                fields += 1;
                while !bytes[i].is_ascii_whitespace() {
                    i += 1;
                }
            }
            i += 1;
        }
        i
    };
    let pixels = &bytes[header_end..];
    assert_eq!(pixels.len(), 540 * 587);
    let not_free = |v: u8| (255.0 - v as f64) / 255.0 >= 0.196;
    let occupied = pixels.iter().filter(|&&v| not_free(v)).count();
    let dark = pixels
        .iter()
        .filter(|&&v| (255.0 - v as f64) / 255.0 > 0.65)
        .count();
    assert!(dark > 4000 && occupied > dark, "{dark}, {occupied}");
    // On the pixel lattice the exact coverage is the image itself.
    let grid = Grid::new([0.0, 0.0], 0.1, 587, 540).unwrap();
    let cov = world.coverage(&grid);
    let total: f64 = cov.iter().sum();
    assert!(
        (total - occupied as f64).abs() < 1e-6 * occupied as f64,
        "{total} vs {occupied}"
    );
    for (i, &v) in cov.iter().enumerate() {
        let (row, col) = (i / 540, i % 540);
        let v_px = pixels[(586 - row) * 540 + col];
        let obstacle = not_free(v_px);
        assert!(
            (v - if obstacle { 1.0 } else { 0.0 }).abs() < 1e-9,
            "cell ({row}, {col})"
        );
    }
    // Merged runs: far fewer rectangles than occupied pixels.
    assert!(world.len() < occupied / 2, "{} rectangles", world.len());
}

#[test]
fn stata_basement_yaml_places_the_rotated_image() {
    let Some(dir) = shared_worlds() else { return };
    let world = World::from_ros_map_yaml(dir.join("stata_basement.yaml")).unwrap();
    // 1730 x 1300 pixels of 0.0504 m, rotated by 3.14 rad about (25.9, 48.5):
    // the image lies to the lower left of the origin.
    let (w, h) = (1730.0 * 0.0504, 1300.0 * 0.0504);
    let [x0, y0, x1, y1] = world.bounds_m();
    assert!(
        x1 <= 25.9 + 0.2 && x0 >= 25.9 - w - 0.2,
        "{:?}",
        world.bounds_m()
    );
    assert!(
        y1 <= 48.5 + 0.2 && y0 >= 48.5 - h - 0.2,
        "{:?}",
        world.bounds_m()
    );
    // The rectangles are disjoint, so the exact coverage adds up to their areas.
    let grid = Grid::covering(x0 - 0.1, y0 - 0.1, x1 + 0.1, y1 + 0.1, 0.1).unwrap();
    let covered: f64 = world.coverage(&grid).iter().sum::<f64>() * 0.01;
    let area = world.polygon_area_m2();
    assert!((covered - area).abs() < 1e-9 * area, "{covered} vs {area}");
    // Errors name the file and line.
    let tmp = tempfile::tempdir().unwrap();
    let bad = tmp.path().join("bad.yaml");
    std::fs::write(
        &bad,
        "image: stata_basement.png\nresolution: fine\norigin: [0, 0, 0]\n",
    )
    .unwrap();
    let e = World::from_ros_map_yaml(&bad).unwrap_err();
    assert!(e.to_string().contains(".yaml, line 2"), "{e}");
}
