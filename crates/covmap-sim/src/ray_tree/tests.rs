//! Tests of the ray caster's hierarchy.

use super::*;
use crate::World;
use crate::rng::sim_rng;
use rand::RngExt;

/// Both descents (inline and borrowed stack) against testing every piece:
/// the same hit or miss, at the same distance.
fn assert_matches_brute_force(tree: &RayTree, ray: &Ray, max_t: f64, stack: &mut RayStack) {
    let expected = tree.first_hit_brute_force(ray, max_t);
    for got in [
        tree.first_hit(ray, max_t),
        tree.first_hit_with(ray, max_t, stack),
    ] {
        match (got, expected) {
            (None, None) => {}
            (Some((_, t)), Some((_, t_expected))) => {
                assert!(
                    (t - t_expected).abs() <= 1e-9,
                    "{ray:?} up to {max_t}: {t} against {t_expected}"
                )
            }
            _ => panic!("{ray:?} up to {max_t}: {got:?} against {expected:?}"),
        }
    }
}

fn random_rays(tree: &RayTree, bounds: [f64; 4], seed: u64, n: usize) -> usize {
    let mut rng = sim_rng(seed);
    let [x0, y0, x1, y1] = bounds;
    let (w, h) = (x1 - x0, y1 - y0);
    let mut stack = RayStack::default();
    let mut hits = 0;
    for i in 0..n {
        // Origins also outside the world and inside obstacles.
        let o = [
            x0 - 0.2 * w + 1.4 * w * rng.random::<f64>(),
            y0 - 0.2 * h + 1.4 * h * rng.random::<f64>(),
        ];
        let (s, c) = (rng.random::<f64>() * std::f64::consts::TAU).sin_cos();
        let max_t = [0.5, 5.0, 30.0, f64::INFINITY][i % 4];
        let ray = Ray::new(o, [c, s]);
        assert_matches_brute_force(tree, &ray, max_t, &mut stack);
        hits += usize::from(tree.first_hit(&ray, max_t).is_some());
    }
    hits
}

fn edges(world: &World) -> Vec<([f64; 2], [f64; 2], Material)> {
    let mut edges = Vec::new();
    for p in world.polygons() {
        for ring in p.rings() {
            for (i, &a) in ring.iter().enumerate() {
                edges.push((a, ring[(i + 1) % ring.len()], p.material()));
            }
        }
    }
    edges
}

#[test]
fn descent_matches_brute_force_on_every_builtin_world() {
    for (i, name) in World::builtin_names().iter().enumerate() {
        let world = World::builtin(name).unwrap();
        let tree = RayTree::new(edges(&world));
        let hits = random_rays(&tree, world.bounds_m(), 11 + i as u64, 20_000);
        assert!(
            hits > 5_000,
            "{name}: only {hits} hits, the test is too weak"
        );
    }
}

#[test]
fn office_descends_on_an_inline_stack() {
    let tree = RayTree::new(edges(&World::builtin("office").unwrap()));
    assert!(tree.stack_len <= INLINE_STACK, "{}", tree.stack_len);
}

#[test]
fn descent_matches_brute_force_in_random_clutter() {
    // Thousands of short segments at random: a deep tree, boxes of every
    // shape, rays starting in between.
    let mut rng = sim_rng(5);
    let edges: Vec<_> = (0..3000)
        .map(|_| {
            let a = [100.0 * rng.random::<f64>(), 60.0 * rng.random::<f64>()];
            let (s, c) = (rng.random::<f64>() * std::f64::consts::TAU).sin_cos();
            let len = 0.05 + 3.0 * rng.random::<f64>();
            (a, [a[0] + len * c, a[1] + len * s], Material::Wall)
        })
        .collect();
    let tree = RayTree::new(edges);
    let hits = random_rays(&tree, [0.0, 0.0, 100.0, 60.0], 6, 20_000);
    assert!(hits > 5_000, "only {hits} hits");
}

#[test]
fn axis_parallel_rays_match_brute_force() {
    // Along the axes from every vertex and from points on the walls' lines
    // (where the origin lies on faces of boxes) of the office: the careful
    // slab test.
    let world = World::builtin("office").unwrap();
    let edges = edges(&world);
    let tree = RayTree::new(edges.iter().copied());
    let mut stack = RayStack::default();
    let mut hits = 0;
    for (a, b, _) in &edges {
        for o in [
            *a,
            [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])],
            [a[0] + 0.25, a[1]],
            [a[0], a[1] - 0.5],
        ] {
            for d in [[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [0.0, -1.0]] {
                let ray = Ray::new(o, d);
                assert_matches_brute_force(&tree, &ray, 30.0, &mut stack);
                hits += usize::from(tree.first_hit(&ray, 30.0).is_some());
            }
        }
    }
    assert!(hits > 1000, "only {hits} hits");
}

#[test]
fn one_piece_and_no_piece() {
    let tree = RayTree::new([([1.0, -1.0], [1.0, 1.0], Material::Glass)]);
    let hit = tree.first_hit(&Ray::new([0.0, 0.5], [1.0, 0.0]), 5.0);
    assert_eq!(hit, Some((0, 1.0)));
    assert_eq!(tree.face(0).material, Material::Glass);
    assert_eq!(tree.first_hit(&Ray::new([0.0, 1.5], [1.0, 0.0]), 5.0), None);
    assert_eq!(
        tree.first_hit(&Ray::new([0.0, 0.5], [1.0, 0.0]), 1.0),
        None,
        "the range is exclusive"
    );
    let empty = RayTree::new([]);
    assert_eq!(
        empty.first_hit(&Ray::new([0.0, 0.0], [1.0, 0.0]), 5.0),
        None
    );
}

/// An edge of a million kilometres is cut into at most `MAX_PIECES`,
/// and rays still find it where it is.
#[test]
fn a_very_long_edge_takes_bounded_pieces() {
    let tree = RayTree::new([
        ([0.0, 0.0], [1e9, 0.0], Material::Wall),
        ([0.0, 1.0], [1.0, 2.0], Material::Wall),
    ]);
    assert_eq!(tree.lines.len(), MAX_PIECES + 1);
    let mut stack = RayStack::default();
    let ray = Ray::new([3.5e8, 5.0], [0.0, -1.0]);
    assert_matches_brute_force(&tree, &ray, 10.0, &mut stack);
    assert!(
        tree.first_hit(&ray, 10.0)
            .is_some_and(|(_, t)| (t - 5.0).abs() < 1e-6)
    );
}

#[test]
fn nan_rays_miss() {
    let tree = RayTree::new(edges(&World::builtin("office").unwrap()));
    let mut stack = RayStack::default();
    let nan = f64::NAN;
    for (o, d) in [
        ([nan, 1.0], [0.6, 0.8]),
        ([1.0, 1.0], [nan, nan]),
        ([1.0, nan], [1.0, 0.0]),
    ] {
        assert_eq!(tree.first_hit_with(&Ray::new(o, d), 30.0, &mut stack), None);
    }
}

#[test]
fn many_long_edges_are_cut_into_a_bounded_number_of_pieces() {
    // 4096 edges of 2 km: 1024 pieces each at 2 m, 4 million in all.
    let edges: Vec<_> = (0..4096)
        .map(|i| {
            let y = f64::from(i);
            ([0.0, y], [2000.0, y], Material::Wall)
        })
        .collect();
    let tree = RayTree::new(edges.clone());
    let pieces = tree.lines.len();
    assert!(pieces <= edges.len() + MAX_EXTRA_PIECES, "{pieces}");
    assert!(pieces > MAX_EXTRA_PIECES / 4, "{pieces}");
    // One such edge alone is cut at 2 m, as before.
    assert_eq!(RayTree::new(edges[..1].to_vec()).lines.len(), 1000);
}
