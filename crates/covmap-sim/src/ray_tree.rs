//! The ray caster's hierarchy: the world's boundary cut into short pieces,
//! boxed by parry2d's bounding-volume hierarchy, and that hierarchy laid out
//! flat for a tight front-to-back descent.
//!
//! parry2d builds the tree (binned SAH over the pieces' boxes); [`RayTree`]
//! copies it once through parry's public traversal (parry 0.31 keeps a node's
//! child link private) into nodes of four: each node of the copy holds the
//! boxes of a parry node's grandchildren (or of a child that is a leaf). A ray
//! then makes half as many decisions on its way down, each after four box
//! tests done at once, and which boxes it entered comes out as bits rather
//! than as branches no predictor can guess. Every box and every leaf is
//! parry's (the boxes widened by [`slack`]); every other level of parry's
//! boxes is left out.
//!
//! Why not parry's own query: `Bvh::find_best` (generic closures, a growable
//! stack, one binary node per step) was where the ray caster spent most of its
//! time; the copy casts about 1.5 times as many rays per second on `office`.

use parry2d_f64::bounding_volume::Aabb;
use parry2d_f64::math::Vector;
use parry2d_f64::partitioning::{Bvh, BvhBuildStrategy, BvhNodeIndex, TraversalAction};

use wide::f64x4;

use crate::material::Material;

/// The longest piece of an edge the ray caster tests as one leaf, metres
/// (for edges of up to [`MAX_PIECES`] such pieces).
pub(crate) const RAY_PIECE_M: f64 = 2.0;
/// The most pieces one edge is cut into (2 km of edge at [`RAY_PIECE_M`]).
pub(crate) const MAX_PIECES: usize = 1024;
/// The most pieces a whole world is cut into beyond one per edge: where its
/// edges at [`RAY_PIECE_M`] would make more, every piece is made longer by
/// the same factor. A world's ray caster thus holds at most its edge count
/// plus 2^20 pieces (about 150 bytes each with the hierarchy over them),
/// however long its edges are.
pub(crate) const MAX_EXTRA_PIECES: usize = 1 << 20;

/// Marks a child link as a piece index rather than a node index (a world
/// would need billions of pieces to reach it).
const LEAF: u32 = 1 << 31;

/// Trees whose descent needs no more stack entries than this (`office`
/// needs 22) use a stack on the call stack for single casts; deeper ones
/// borrow one from the heap.
const INLINE_STACK: usize = 48;

/// Where a piece of an obstacle's boundary lies: all the descent reads of it.
#[derive(Clone, Copy, Debug)]
struct Line {
    /// Start point.
    a: [f64; 2],
    /// End minus start.
    e: [f64; 2],
}

/// What a piece of an obstacle's boundary is: read once per ray that hits it.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Face {
    /// Unit normal (left of the piece's direction).
    pub(crate) n: [f64; 2],
    /// The surface's material.
    pub(crate) material: Material,
}

/// The boxes of a node's (up to) four children side by side: lane `k` is
/// child `k`, so all four are tested with the same operations. An unused lane
/// holds a box no ray enters.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(64))]
struct Node {
    /// `[x_min, x_max]` of the boxes, widened by [`slack`].
    x: [[f64; 4]; 2],
    /// `[y_min, y_max]` of the boxes, widened by [`slack`].
    y: [[f64; 4]; 2],
}

/// A box no ray enters (not even one along an axis through it).
const NO_BOX: ([f64; 2], [f64; 2]) = (
    [f64::INFINITY, f64::NEG_INFINITY],
    [f64::INFINITY, f64::NEG_INFINITY],
);

impl Node {
    /// A node of four unused lanes.
    fn empty() -> Self {
        let (x, y) = NO_BOX;
        Self {
            x: [[x[0]; 4], [x[1]; 4]],
            y: [[y[0]; 4], [y[1]; 4]],
        }
    }

    /// Lane `k` becomes parry's box `b`, widened by [`slack`].
    fn set_box(&mut self, k: usize, b: &Aabb) {
        (self.x[0][k], self.x[1][k]) = (b.mins.x - slack(b.mins.x), b.maxs.x + slack(b.maxs.x));
        (self.y[0][k], self.y[1][k]) = (b.mins.y - slack(b.mins.y), b.maxs.y + slack(b.maxs.y));
    }
}

/// How far a box is widened past a coordinate `c`, metres. The slab test
/// computes `(c - o) / d` with a relative error of a few ulp; widening by far
/// more than that (for origins closer than a million times the coordinates'
/// size) keeps every box the ray truly crosses, also the zero-width boxes of
/// pieces along an axis, and the exact piece test decides the hit.
fn slack(c: f64) -> f64 {
    1e-9 * (1.0 + c.abs())
}

/// Where a node's children lead, lane by lane.
#[derive(Clone, Copy, Debug)]
struct Links {
    /// A node index, or `LEAF | piece index`.
    child: [u32; 4],
    /// Bit `k` set: child `k` is a piece (also set for unused lanes).
    leaves: u32,
}

impl Links {
    fn new(child: [u32; 4]) -> Self {
        let leaves = (0..4).fold(0, |bits, k| bits | (u32::from(child[k] & LEAF != 0) << k));
        Self { child, leaves }
    }
}

/// A ray in the form the descent wants.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Ray {
    /// Origin.
    o: [f64; 2],
    /// Unit direction.
    d: [f64; 2],
    /// `1 / d`, per axis (infinite along an axis-parallel ray).
    inv: [f64; 2],
    /// Per axis, which side of a box the ray meets first (0: min, 1: max).
    near: [usize; 2],
}

impl Ray {
    /// The ray from `o` along the unit vector `d`.
    pub(crate) fn new(o: [f64; 2], d: [f64; 2]) -> Self {
        let near = [usize::from(d[0] < 0.0), usize::from(d[1] < 0.0)];
        Self {
            o,
            d,
            inv: [1.0 / d[0], 1.0 / d[1]],
            near,
        }
    }
}

/// The boundary pieces and parry's hierarchy over them.
#[derive(Clone, Debug)]
pub(crate) struct RayTree {
    /// Piece `i` is `lines[i]` and `faces[i]`.
    lines: Vec<Line>,
    faces: Vec<Face>,
    /// Node 0 is the root (none without pieces).
    nodes: Vec<Node>,
    /// The children of each node (apart from the boxes, so that the descent
    /// reads whole cache lines of boxes).
    links: Vec<Links>,
    /// The most entries the descent's stack can hold: three per level.
    stack_len: usize,
}

/// The pieces an edge of `length_m` is cut into at pieces of `piece_m`.
fn pieces_of(length_m: f64, piece_m: f64) -> usize {
    (length_m / piece_m).ceil().clamp(1.0, MAX_PIECES as f64) as usize
}

/// The length of the pieces edges of `lengths_m` are cut into: [`RAY_PIECE_M`],
/// or, where that would make more than [`MAX_EXTRA_PIECES`] pieces beyond
/// one an edge, the least power-of-two multiple of it that makes no more.
fn piece_length_m(lengths_m: impl Iterator<Item = f64> + Clone) -> f64 {
    let extra = |piece_m: f64| -> usize {
        lengths_m
            .clone()
            .map(|l| pieces_of(l, piece_m) - 1)
            .fold(0usize, usize::saturating_add)
    };
    let mut piece_m = RAY_PIECE_M;
    // Ends: at a piece of f64::MAX every edge is one piece.
    while extra(piece_m) > MAX_EXTRA_PIECES && piece_m < f64::MAX / 2.0 {
        piece_m *= 2.0;
    }
    piece_m
}

/// Reusable scratch space for [`RayTree::first_hit_with`]: a batch of rays
/// shares one.
#[derive(Clone, Debug, Default)]
pub(crate) struct RayStack(Vec<(u32, f64)>);

impl RayTree {
    /// The tree over `edges` (`[start, end, material]` each, non-degenerate),
    /// each cut into pieces no longer than [`RAY_PIECE_M`], but into no more
    /// than [`MAX_PIECES`] (an edge kilometres long gets longer pieces, not
    /// unbounded memory), and all together into no more than one a edge
    /// plus [`MAX_EXTRA_PIECES`] (many long edges get longer pieces too).
    pub(crate) fn new(edges: impl IntoIterator<Item = ([f64; 2], [f64; 2], Material)>) -> Self {
        let edges: Vec<_> = edges
            .into_iter()
            .map(|(a, b, material)| (Vector::new(a[0], a[1]), Vector::new(b[0], b[1]), material))
            .collect();
        let piece_m = piece_length_m(edges.iter().map(|(a, b, _)| (*b - *a).length()));
        let (mut lines, mut faces) = (Vec::new(), Vec::new());
        for (a, b, material) in edges {
            let count = pieces_of((b - a).length(), piece_m);
            for k in 0..count {
                // Cut points computed from both ends, so the pieces meet exactly.
                let at = |t: usize| {
                    if t == count {
                        b
                    } else {
                        a + (b - a) * (t as f64 / count as f64)
                    }
                };
                let (p, q) = (at(k), at(k + 1));
                let e = [q.x - p.x, q.y - p.y];
                let len = e[0].hypot(e[1]);
                lines.push(Line { a: [p.x, p.y], e });
                faces.push(Face {
                    n: [-e[1] / len, e[0] / len],
                    material,
                });
            }
        }
        let boxes: Vec<Aabb> = lines
            .iter()
            .map(|p| {
                let q = [p.a[0] + p.e[0], p.a[1] + p.e[1]];
                let lo = Vector::new(p.a[0].min(q[0]), p.a[1].min(q[1]));
                Aabb::new(lo, Vector::new(p.a[0].max(q[0]), p.a[1].max(q[1])))
            })
            .collect();
        let (nodes, links, levels) = match boxes.len() {
            0 => (Vec::new(), Vec::new(), 0),
            1 => {
                // parry keeps a lone leaf in a half-empty root.
                let mut node = Node::empty();
                node.set_box(0, &boxes[0]);
                (vec![node], vec![Links::new([LEAF; 4])], 1)
            }
            _ => collapse(&read_pairs(&Bvh::from_leaves(
                BvhBuildStrategy::Binned,
                &boxes,
            ))),
        };
        Self {
            lines,
            faces,
            nodes,
            links,
            stack_len: 3 * levels + 1,
        }
    }

    /// The surface of piece `index`.
    pub(crate) fn face(&self, index: u32) -> &Face {
        &self.faces[index as usize]
    }

    /// The first piece `ray` meets before `max_t` (exclusive) and the distance
    /// to it, front to back through the hierarchy.
    pub(crate) fn first_hit(&self, ray: &Ray, max_t: f64) -> Option<(u32, f64)> {
        if self.stack_len <= INLINE_STACK {
            self.descend(ray, max_t, &mut [(0, 0.0); INLINE_STACK])
        } else {
            self.first_hit_with(ray, max_t, &mut RayStack::default())
        }
    }

    /// [`RayTree::first_hit`] with the stack borrowed from `stack`.
    pub(crate) fn first_hit_with(
        &self,
        ray: &Ray,
        max_t: f64,
        stack: &mut RayStack,
    ) -> Option<(u32, f64)> {
        if stack.0.len() < self.stack_len {
            stack.0.resize(self.stack_len, (0, 0.0));
        }
        self.descend(ray, max_t, &mut stack.0)
    }

    /// Every piece tested, no hierarchy: the reference for the tests.
    #[cfg(test)]
    pub(crate) fn first_hit_brute_force(&self, ray: &Ray, max_t: f64) -> Option<(u32, f64)> {
        let mut best = None;
        let mut best_t = max_t;
        for (i, p) in self.lines.iter().enumerate() {
            if let Some(t) = hit_piece(p, ray, best_t) {
                (best, best_t) = (Some(i as u32), t);
            }
        }
        best.map(|i| (i, best_t))
    }

    fn descend(&self, ray: &Ray, max_t: f64, stack: &mut [(u32, f64)]) -> Option<(u32, f64)> {
        if self.nodes.is_empty() {
            return None;
        }
        // A ray parallel to an axis takes the careful slab test; every other
        // ray the quick one. Both are monomorphised: the choice is made once.
        if ray.d[0] == 0.0 || ray.d[1] == 0.0 {
            self.descend_with(ray, max_t, stack, enter_careful)
        } else {
            self.descend_with(ray, max_t, stack, enter)
        }
    }

    /// Depth first, nearest child first; a subtree or piece is skipped once
    /// its box starts beyond the best hit so far, also when popped from the
    /// stack.
    #[inline(always)]
    fn descend_with(
        &self,
        ray: &Ray,
        max_t: f64,
        stack: &mut [(u32, f64)],
        enter: impl Fn(&Node, &Ray, f64) -> Slabs,
    ) -> Option<(u32, f64)> {
        let mut best_t = max_t;
        let mut best = u32::MAX;
        let mut top = 0;
        let mut node = 0;
        loop {
            let Slabs { t_in: t, entered } = enter(&self.nodes[node as usize], ray, best_t);
            let Links { child, leaves } = self.links[node as usize];
            // Pieces first: a hit moves `best_t` in, which may spare boxes.
            let mut pieces = entered & leaves;
            while pieces != 0 {
                let k = pieces.trailing_zeros() as usize;
                pieces &= pieces - 1;
                let piece = child[k] & !LEAF;
                if t[k] < best_t
                    && let Some(t_hit) = hit_piece(&self.lines[piece as usize], ray, best_t)
                {
                    (best, best_t) = (piece, t_hit);
                }
            }
            let mut inner = entered & !leaves;
            if inner & inner.wrapping_sub(1) == 0 {
                // One child or none: no stack.
                if inner != 0 {
                    let k = inner.trailing_zeros() as usize;
                    if t[k] < best_t {
                        node = child[k];
                        continue;
                    }
                }
            } else {
                // Farthest first onto the stack, so the nearest comes off first.
                // At most four more entries, three of them left behind: the
                // stack holds at most `3 * levels + 1`.
                let start = top;
                while inner != 0 {
                    let k = inner.trailing_zeros() as usize;
                    inner &= inner - 1;
                    stack[top] = (child[k], t[k]);
                    top += 1;
                }
                sort_by_distance_descending(&mut stack[start..top]);
            }
            loop {
                if top == 0 {
                    return (best != u32::MAX).then_some((best, best_t));
                }
                top -= 1;
                let (popped, t_popped) = stack[top];
                if t_popped < best_t {
                    node = popped;
                    break;
                }
            }
        }
    }
}

/// Insertion sort, farthest first: at most four entries.
#[inline(always)]
fn sort_by_distance_descending(entries: &mut [(u32, f64)]) {
    for i in 1..entries.len() {
        let mut j = i;
        while j > 0 && entries[j - 1].1 < entries[j].1 {
            entries.swap(j - 1, j);
            j -= 1;
        }
    }
}

/// What a node of parry's tree links to, in [`read_pairs`]'s numbering.
#[derive(Clone, Copy, Debug)]
enum Link {
    /// A leaf: the index of its box in `Bvh::from_leaves`.
    Leaf(u32),
    /// An inner node: the index of the pair of its children.
    Inner(usize),
}

/// parry's tree (of at least two leaves) as pairs of siblings: pair 0 holds
/// the root's children, and an inner node links to the pair of its own.
fn read_pairs(bvh: &Bvh) -> Vec<[(Aabb, Link); 2]> {
    let unset = (Aabb::new(Vector::ZERO, Vector::ZERO), Link::Leaf(0));
    let mut pairs = vec![[unset; 2]];
    // (parry's wide-node index, our pair index)
    let mut todo = vec![(0u32, 0usize)];
    while let Some((wide, ours)) = todo.pop() {
        for k in 0..2 {
            let (aabb, link) = match inspect(bvh, BvhNodeIndex::new(wide, k == 1)) {
                (aabb, ParryLink::Leaf(piece)) => (aabb, Link::Leaf(piece)),
                (aabb, ParryLink::Inner(children)) => {
                    pairs.push([unset; 2]);
                    todo.push((children, pairs.len() - 1));
                    (aabb, Link::Inner(pairs.len() - 1))
                }
            };
            pairs[ours][k] = (aabb, link);
        }
    }
    pairs
}

/// The four-wide copy of a binary tree given as [`read_pairs`] gives it:
/// nodes, their links, and the number of levels.
fn collapse(pairs: &[[(Aabb, Link); 2]]) -> (Vec<Node>, Vec<Links>, usize) {
    let (mut nodes, mut links) = (vec![Node::empty()], vec![[LEAF; 4]]);
    let mut levels = 0;
    // (pair index, our node index, level)
    let mut todo = vec![(0usize, 0usize, 1usize)];
    while let Some((pair, ours, level)) = todo.pop() {
        levels = levels.max(level);
        // A child that is a leaf stays; an inner child gives its two children.
        let mut lanes = Vec::with_capacity(4);
        for &(aabb, link) in &pairs[pair] {
            match link {
                Link::Leaf(_) => lanes.push((aabb, link)),
                Link::Inner(below) => lanes.extend(pairs[below]),
            }
        }
        for (k, (aabb, link)) in lanes.into_iter().enumerate() {
            nodes[ours].set_box(k, &aabb);
            links[ours][k] = match link {
                Link::Leaf(piece) => LEAF | piece,
                Link::Inner(below) => {
                    nodes.push(Node::empty());
                    links.push([LEAF; 4]);
                    todo.push((below, nodes.len() - 1, level + 1));
                    (nodes.len() - 1) as u32
                }
            };
        }
    }
    (nodes, links.into_iter().map(Links::new).collect(), levels)
}

/// What a node of parry's tree links to, in parry's numbering.
enum ParryLink {
    /// A leaf: the index of its box in `Bvh::from_leaves`.
    Leaf(u32),
    /// An inner node: the wide-node index of its two children.
    Inner(u32),
}

/// A node's box and link, read through parry's public traversal: starting at
/// the node, the next node visited is one of its children, whose index names
/// the pair of both.
fn inspect(bvh: &Bvh, index: BvhNodeIndex) -> (Aabb, ParryLink) {
    let mut seen: Option<(Aabb, Option<u32>)> = None;
    let mut children = None;
    bvh.traverse_indexed(Some(index), |node, at| match seen {
        None => {
            seen = Some((node.aabb(), node.leaf_data()));
            TraversalAction::Continue
        }
        Some(_) => {
            children = Some(at.decompose().0 as u32);
            TraversalAction::EarlyExit
        }
    });
    match (seen, children) {
        (Some((aabb, Some(piece))), _) => (aabb, ParryLink::Leaf(piece)),
        (Some((aabb, None)), Some(children)) => (aabb, ParryLink::Inner(children)),
        // parry visits the node it starts from, and then a child of an
        // inner node: not an input error but a broken assumption about parry.
        _ => unreachable!("parry's traversal skipped a node"),
    }
}

/// Where a ray enters the boxes of a node, and which boxes it enters (before
/// a given distance).
struct Slabs {
    /// Lane `k`: the distance at which the ray enters box `k`, if it does.
    t_in: [f64; 4],
    /// Bit `k` set: the ray enters box `k`.
    entered: u32,
}

/// The slab test for rays off the axes, the sides picked by the ray's
/// direction, all four lanes at once; boxes entered at `best_t` or later do
/// not count.
///
/// Which boxes the ray enters comes out as bits, computed without a branch on
/// each (a coin flip to the branch predictor).
#[inline(always)]
fn enter(node: &Node, ray: &Ray, best_t: f64) -> Slabs {
    let (nx, ny) = (ray.near[0] & 1, ray.near[1] & 1);
    let slab = |side: [f64; 4], axis| {
        (f64x4::from(side) - f64x4::splat(ray.o[axis])) * f64x4::splat(ray.inv[axis])
    };
    let (x_in, x_out) = (slab(node.x[nx], 0), slab(node.x[nx ^ 1], 0));
    let (y_in, y_out) = (slab(node.y[ny], 1), slab(node.y[ny ^ 1], 1));
    // `fast_max(b)` is `if a > b { a } else { b }`, lane by lane (no NaN here).
    let t_in = x_in.fast_max(y_in).fast_max(f64x4::ZERO);
    let t_out = x_out.fast_min(y_out);
    let entered = t_in.simd_le(t_out) & t_in.simd_lt(f64x4::splat(best_t));
    Slabs {
        t_in: t_in.to_array(),
        entered: entered.to_bitmask(),
    }
}

/// [`enter`] for rays parallel to an axis (the origin may lie on a box's face,
/// where `0 * inf` would be NaN).
#[inline(always)]
fn enter_careful(node: &Node, ray: &Ray, best_t: f64) -> Slabs {
    let slab = |axis: usize, [lo, hi]: [f64; 2]| -> (f64, f64) {
        let o = ray.o[axis];
        if ray.d[axis] == 0.0 {
            if lo <= o && o <= hi {
                (f64::NEG_INFINITY, f64::INFINITY)
            } else {
                (f64::INFINITY, f64::NEG_INFINITY)
            }
        } else {
            let (a, b) = ((lo - o) * ray.inv[axis], (hi - o) * ray.inv[axis]);
            (min(a, b), max(a, b))
        }
    };
    let mut slabs = Slabs {
        t_in: [0.0; 4],
        entered: 0,
    };
    for k in 0..4 {
        let (x_in, x_out) = slab(0, [node.x[0][k], node.x[1][k]]);
        let (y_in, y_out) = slab(1, [node.y[0][k], node.y[1][k]]);
        let (t_in, t_out) = (max(max(x_in, y_in), 0.0), min(x_out, y_out));
        slabs.t_in[k] = t_in;
        slabs.entered |= u32::from(t_in <= t_out && t_in < best_t) << k;
    }
    slabs
}

/// The smaller of two numbers that are not NaN, as one comparison
/// (`f64::min` pays for NaN handling).
#[inline(always)]
fn min(a: f64, b: f64) -> f64 {
    if a < b { a } else { b }
}

/// The larger of two numbers that are not NaN.
#[inline(always)]
fn max(a: f64, b: f64) -> f64 {
    if a > b { a } else { b }
}

/// The distance at which `ray` crosses the piece, if in `[0, best_t)`.
#[inline(always)]
fn hit_piece(p: &Line, ray: &Ray, best_t: f64) -> Option<f64> {
    let (o, d) = (ray.o, ray.d);
    let denom = d[0] * p.e[1] - d[1] * p.e[0];
    if denom == 0.0 {
        return None; // parallel: grazing, the neighbours decide
    }
    let w = [p.a[0] - o[0], p.a[1] - o[1]];
    let inv_denom = 1.0 / denom;
    let t = (w[0] * p.e[1] - w[1] * p.e[0]) * inv_denom;
    let u = (w[0] * d[1] - w[1] * d[0]) * inv_denom;
    (t >= 0.0 && t < best_t && (0.0..=1.0).contains(&u)).then_some(t)
}

#[cfg(test)]
mod tests;
