//! The paper's Fig. 1: a cell partly covered by an obstacle. The occupancy grid
//! calls it occupied; the coverage map recovers how much of it is covered.

use covmap::ScanMap;
use covmap::{Cell, CoverageMap, Grid, LaserModel, OccupancyGrid, Pose, SonarModel};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

const TARGET: Cell = Cell { row: 20, col: 30 };

fn grid() -> Grid {
    Grid::new([0.0, 0.0], 0.05, 40, 40).unwrap()
}

/// Gaussian noise by Box-Muller (keeps rand_distr out of the dev-dependencies).
fn gauss(rng: &mut ChaCha8Rng, sigma: f64) -> f64 {
    let u1: f64 = rng.random_range(f64::EPSILON..1.0);
    let u2: f64 = rng.random();
    sigma * (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
}

struct Outcome {
    ml: f32,
    occupancy: f32,
}

/// A wall filling `x >= x_face`, with `x_face` chosen so the wall covers the far
/// `fraction` of the target cell; `readings` laser beams from varied positions
/// and angles hitting the face inside the target cell's row.
fn laser_run(fraction: f64, readings: usize, seed: u64) -> Outcome {
    let g = grid();
    let [x_far, _] = g.cell_center(TARGET).map(|v| v + 0.025);
    let x_face = x_far - fraction * 0.05;
    let [_, y_c] = g.cell_center(TARGET);
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut map = CoverageMap::new(g);
    let mut occ = OccupancyGrid::new(g);
    let laser = LaserModel::default();
    for _ in 0..readings {
        let y_hit = y_c + rng.random_range(-0.02..0.02);
        let phi: f64 = rng.random_range(-20f64.to_radians()..20f64.to_radians());
        let l = rng.random_range(0.4..1.2);
        let pose = Pose::new(x_face - l * phi.cos(), y_hit - l * phi.sin(), phi);
        let range = [l + gauss(&mut rng, 0.005)];
        map.integrate(&pose, &range, &[0.0], &laser).unwrap();
        occ.integrate(&pose, &range, &[0.0], &laser).unwrap();
    }
    let i = g.index(TARGET).unwrap();
    Outcome {
        ml: map.ml()[i],
        occupancy: occ.probabilities()[i],
    }
}

/// The same with a sonar facing the wall head-on from varied distances.
fn sonar_run(fraction: f64, readings: usize, seed: u64) -> Outcome {
    let g = grid();
    let [x_c, y_c] = g.cell_center(TARGET);
    let x_face = x_c + 0.025 - fraction * 0.05;
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut map = CoverageMap::new(g);
    let mut occ = OccupancyGrid::new(g);
    let sonar = SonarModel::default();
    for _ in 0..readings {
        let l = rng.random_range(0.4..1.2);
        let pose = Pose::new(x_face - l, y_c, 0.0);
        let range = [l + gauss(&mut rng, 0.005)];
        map.integrate(&pose, &range, &[0.0], &sonar).unwrap();
        occ.integrate(&pose, &range, &[0.0], &sonar).unwrap();
    }
    let i = g.index(TARGET).unwrap();
    Outcome {
        ml: map.ml()[i],
        occupancy: occ.probabilities()[i],
    }
}

#[test]
fn partly_covered_cell_laser() {
    for (fraction, seed) in [0.2, 0.5, 0.8]
        .into_iter()
        .flat_map(|f| (0..5).map(move |s| (f, s)))
    {
        let o = laser_run(fraction, 200, seed);
        assert!(
            (o.ml as f64 - fraction).abs() <= 1.0 / 15.0 + 1e-6,
            "laser, fraction {fraction}, seed {seed}: ML coverage {}",
            o.ml
        );
        assert!(
            o.occupancy > 0.9,
            "laser, fraction {fraction}: occupancy {}",
            o.occupancy
        );
    }
}

#[test]
fn partly_covered_cell_sonar() {
    for (fraction, seed) in [0.2, 0.5, 0.8]
        .into_iter()
        .flat_map(|f| (0..5).map(move |s| (f, s)))
    {
        let o = sonar_run(fraction, 200, seed);
        assert!(
            (o.ml as f64 - fraction).abs() <= 1.0 / 15.0 + 1e-6,
            "sonar, fraction {fraction}, seed {seed}: ML coverage {}",
            o.ml
        );
        assert!(
            o.occupancy > 0.9,
            "sonar, fraction {fraction}: occupancy {}",
            o.occupancy
        );
    }
}
