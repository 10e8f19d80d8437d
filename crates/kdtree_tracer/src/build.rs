//! SAH kd-tree construction in O(N log N) after Wald & Havran 2006, "On building fast kd-trees
//! for ray tracing, and on doing that in O(N log N)".
//!
//! Each node carries, per axis, the list of its triangles' box events (start, end, or planar
//! when the box is flat on that axis) sorted once at the root by (position, type). The best
//! plane of an axis is found by one sweep over its list; splitting classifies triangles as
//! left / right / both from the chosen axis's list and then *filters* the three sorted lists
//! into the children (order is preserved, nothing is re-sorted). Only the straddling
//! triangles get new events (from their boxes clipped to each child, or from the triangle
//! itself clipped to the child with perfect splits); those few are sorted and merged in.
//! Subtrees above a size threshold are built in parallel with `rayon::join` and spliced
//! together; the result does not depend on the number of threads.

use std::cmp::Ordering;

use glam::Vec3;

use crate::aabb::Aabb;
use crate::node::Node;
use crate::settings::Settings;
use crate::triangle::clip_bounds;

const END: u32 = 0;
const PLANAR: u32 = 1;
const START: u32 = 2;
const TRI_MASK: u32 = (1 << 30) - 1;

/// Subtrees with at least this many triangles are built in parallel.
const PAR_BUILD: usize = 4096;
/// Nodes with at least this many triangles sweep their three axes in parallel.
const PAR_SWEEP: usize = 65_536;

#[derive(Clone, Copy, Debug)]
struct Event {
    pos: f32,
    /// `kind << 30 | local triangle id`: sorting by key sorts by (kind, triangle).
    key: u32,
}

impl Event {
    #[inline]
    fn new(pos: f32, kind: u32, tri: u32) -> Self {
        Self { pos: pos + 0.0, key: (kind << 30) | tri }
    }
    #[inline]
    fn kind(self) -> u32 {
        self.key >> 30
    }
    #[inline]
    fn tri(self) -> usize {
        (self.key & TRI_MASK) as usize
    }
    #[inline]
    fn with_tri(self, tri: u32) -> Self {
        Self { pos: self.pos, key: (self.key & !TRI_MASK) | tri }
    }
}

#[inline]
fn cmp_events(a: &Event, b: &Event) -> Ordering {
    a.pos.total_cmp(&b.pos).then(a.key.cmp(&b.key))
}

fn push_events(out: &mut Vec<Event>, b: &Aabb, axis: usize, tri: u32) {
    let (lo, hi) = (b.min[axis], b.max[axis]);
    if lo == hi {
        out.push(Event::new(lo, PLANAR, tri));
    } else {
        out.push(Event::new(lo, START, tri));
        out.push(Event::new(hi, END, tri));
    }
}

/// Everything a node needs to be split: triangles (local id -> global id), their clipped
/// boxes, and the three sorted event lists over local ids.
struct NodeInput {
    bounds: Aabb,
    tris: Vec<u32>,
    boxes: Vec<Aabb>,
    events: [Vec<Event>; 3],
    depth: u32,
}

#[derive(Clone, Copy, Debug)]
struct Split {
    axis: usize,
    pos: f32,
    planar_left: bool,
    cost: f32,
}

struct Ctx<'a> {
    corners: &'a [[Vec3; 3]],
    settings: Settings,
    max_depth: u32,
}

/// Nodes (root first, siblings adjacent) and the triangle references of the leaves.
#[derive(Default)]
pub(crate) struct Built {
    pub nodes: Vec<Node>,
    pub refs: Vec<u32>,
}

/// Builds the tree over triangles `ids` (global ids indexing `corners`); returns the nodes,
/// leaf references and the root box.
pub(crate) fn build(corners: &[[Vec3; 3]], ids: Vec<u32>, settings: &Settings) -> (Built, Aabb) {
    use rayon::prelude::*;
    let boxes: Vec<Aabb> =
        ids.par_iter().map(|&i| Aabb::from_points(&corners[i as usize])).collect();
    let bounds = boxes.iter().fold(Aabb::EMPTY, |a, b| a.union(b));
    if ids.is_empty() {
        return (Built { nodes: vec![Node::EMPTY_LEAF], refs: Vec::new() }, bounds);
    }
    let mk = |axis: usize| {
        let mut ev = Vec::with_capacity(2 * boxes.len());
        for (t, b) in boxes.iter().enumerate() {
            push_events(&mut ev, b, axis, t as u32);
        }
        ev.par_sort_unstable_by(cmp_events);
        ev
    };
    let (ex, (ey, ez)) = rayon::join(|| mk(0), || rayon::join(|| mk(1), || mk(2)));
    let ctx = Ctx { corners, settings: *settings, max_depth: settings.depth_limit(ids.len()) };
    let input = NodeInput { bounds, tris: ids, boxes, events: [ex, ey, ez], depth: 0 };
    (build_par(&ctx, input), bounds)
}

fn build_par(ctx: &Ctx, input: NodeInput) -> Built {
    if input.tris.len() < PAR_BUILD {
        let mut w = Built { nodes: vec![Node::EMPTY_LEAF], refs: Vec::new() };
        build_seq(ctx, &mut w, 0, input);
        return w;
    }
    let Some(split) = find_split(ctx, &input) else {
        let n = input.tris.len() as u32;
        return Built { nodes: vec![Node::leaf(n, 0)], refs: input.tris };
    };
    let (l, r) = split_node(ctx, input, &split);
    let (wl, wr) = rayon::join(|| build_par(ctx, l), || build_par(ctx, r));
    let ll = wl.nodes.len() as u32;
    let lrefs = wl.refs.len() as u32;
    let mut nodes = Vec::with_capacity(1 + wl.nodes.len() + wr.nodes.len());
    nodes.push(Node::inner(split.axis, split.pos, 1));
    // Left subtree: its root moves to 1 and node j >= 1 to j + 2; right subtree: root to 2
    // and node j >= 1 to j + ll + 1. Child indices always point at j >= 1, so one shift each.
    nodes.push(wl.nodes[0].shifted(2, 0));
    nodes.push(wr.nodes[0].shifted(ll + 1, lrefs));
    nodes.extend(wl.nodes[1..].iter().map(|n| n.shifted(2, 0)));
    nodes.extend(wr.nodes[1..].iter().map(|n| n.shifted(ll + 1, lrefs)));
    let mut refs = wl.refs;
    refs.extend_from_slice(&wr.refs);
    Built { nodes, refs }
}

fn build_seq(ctx: &Ctx, w: &mut Built, slot: usize, input: NodeInput) {
    match find_split(ctx, &input) {
        None => {
            w.nodes[slot] = Node::leaf(input.tris.len() as u32, w.refs.len() as u32);
            w.refs.extend_from_slice(&input.tris);
        }
        Some(split) => {
            let first = w.nodes.len();
            w.nodes.push(Node::EMPTY_LEAF);
            w.nodes.push(Node::EMPTY_LEAF);
            w.nodes[slot] = Node::inner(split.axis, split.pos, first as u32);
            let (l, r) = split_node(ctx, input, &split);
            build_seq(ctx, w, first, l);
            build_seq(ctx, w, first + 1, r);
        }
    }
}

/// The cheapest SAH split, or `None` when a leaf is cheaper (or a limit is reached).
fn find_split(ctx: &Ctx, input: &NodeInput) -> Option<Split> {
    let n = input.tris.len();
    let s = &ctx.settings;
    if n == 0 || n <= s.leaf_size as usize || input.depth >= ctx.max_depth {
        return None;
    }
    // Every split costs at least `traversal_cost * (1 - empty_bonus)` (rounding is monotone),
    // so when the leaf is no dearer no sweep can find a cheaper split: skip the sweeps (most
    // nodes are this small; the tree is the same).
    if s.intersection_cost * blocks(n) <= s.traversal_cost * (1.0 - s.empty_bonus) {
        return None;
    }
    let sweep = |axis: usize| sweep_axis(s, input, axis);
    let per_axis: [Option<Split>; 3] = if n >= PAR_SWEEP {
        let (a, (b, c)) = rayon::join(|| sweep(0), || rayon::join(|| sweep(1), || sweep(2)));
        [a, b, c]
    } else {
        [sweep(0), sweep(1), sweep(2)]
    };
    let best = per_axis.into_iter().flatten().fold(None::<Split>, |best, c| match best {
        Some(b) if b.cost <= c.cost => Some(b),
        _ => Some(c),
    })?;
    (best.cost < s.intersection_cost * blocks(n)).then_some(best)
}

/// Ray/triangle tests a leaf of `n` triangles costs: its packs of four
/// (`crate::leaf4::Tri4`), tested together.
#[inline]
fn blocks(n: usize) -> f32 {
    n.div_ceil(4) as f32
}

/// One sweep over an axis's sorted events (Wald & Havran, Algorithm 4).
fn sweep_axis(s: &Settings, input: &NodeInput, axis: usize) -> Option<Split> {
    let b = &input.bounds;
    let (lo, hi) = (b.min[axis], b.max[axis]);
    if !(hi > lo) {
        return None;
    }
    let area = b.area();
    if !(area > 0.0) {
        return None;
    }
    let d = b.max - b.min;
    let (e1, e2) = (d[(axis + 1) % 3], d[(axis + 2) % 3]);
    let cap = e1 * e2;
    let ring = e1 + e2;
    let inv_area = 1.0 / area;
    let (kt, ki, keep) = (s.traversal_cost, s.intersection_cost, 1.0 - s.empty_bonus);
    let cost = |pl: f32, pr: f32, nl: usize, nr: usize| {
        let c = kt + ki * (pl * blocks(nl) + pr * blocks(nr));
        if nl == 0 || nr == 0 { c * keep } else { c }
    };
    let ev = &input.events[axis];
    let (mut nl, mut nr) = (0usize, input.tris.len());
    let mut best: Option<Split> = None;
    let mut i = 0;
    while i < ev.len() {
        let p = ev[i].pos;
        let (mut ends, mut planars, mut starts) = (0usize, 0usize, 0usize);
        while i < ev.len() && ev[i].pos == p && ev[i].kind() == END {
            ends += 1;
            i += 1;
        }
        while i < ev.len() && ev[i].pos == p && ev[i].kind() == PLANAR {
            planars += 1;
            i += 1;
        }
        while i < ev.len() && ev[i].pos == p && ev[i].kind() == START {
            starts += 1;
            i += 1;
        }
        nr -= planars + ends;
        if p > lo && p < hi {
            let pl = 2.0 * (cap + (p - lo) * ring) * inv_area;
            let pr = 2.0 * (cap + (hi - p) * ring) * inv_area;
            let c_left = cost(pl, pr, nl + planars, nr);
            let c_right = cost(pl, pr, nl, nr + planars);
            let (c, planar_left) =
                if c_left <= c_right { (c_left, true) } else { (c_right, false) };
            if best.is_none_or(|b| c < b.cost) {
                best = Some(Split { axis, pos: p, planar_left, cost: c });
            }
        }
        nl += starts + planars;
    }
    best
}

const LEFT: u8 = 1;
const RIGHT: u8 = 2;
const BOTH: u8 = 3;

/// Classifies, clips straddlers, and filters + merges the event lists into two children.
fn split_node(ctx: &Ctx, input: NodeInput, split: &Split) -> (NodeInput, NodeInput) {
    let n = input.tris.len();
    let (axis, p) = (split.axis, split.pos);
    let mut class = vec![BOTH; n];
    for e in &input.events[axis] {
        let t = e.tri();
        match e.kind() {
            END if e.pos <= p => class[t] = LEFT,
            START if e.pos >= p => class[t] = RIGHT,
            PLANAR => {
                class[t] = if e.pos < p || (e.pos == p && split.planar_left) { LEFT } else { RIGHT }
            }
            _ => {}
        }
    }
    let mut lb = input.bounds;
    lb.max[axis] = p;
    let mut rb = input.bounds;
    rb.min[axis] = p;

    // Each side's size up front (growing the large nodes' lists by doubling cost 5-8% of the
    // build on one thread).
    let count = |c: u8| class.iter().filter(|&&k| k == c).count();
    let (only_left, only_right) = (count(LEFT), count(RIGHT));
    let straddling = n - only_left - only_right;
    let mut left = Side::new(lb, input.depth + 1, only_left + straddling);
    let mut right = Side::new(rb, input.depth + 1, only_right + straddling);
    let mut ids = vec![[u32::MAX; 2]; n];
    let mut both = Vec::with_capacity(straddling);
    for t in 0..n {
        let (g, bx) = (input.tris[t], input.boxes[t]);
        match class[t] {
            LEFT => ids[t][0] = left.add(g, bx),
            RIGHT => ids[t][1] = right.add(g, bx),
            _ => {
                ids[t][0] = left.add(g, clip_to(ctx, g, &bx, &lb));
                ids[t][1] = right.add(g, clip_to(ctx, g, &bx, &rb));
                both.push(t);
            }
        }
    }
    let per_axis = |a: usize| {
        let src = &input.events[a];
        let mut lf = Vec::with_capacity(left.tris.len() * 2);
        let mut rf = Vec::with_capacity(right.tris.len() * 2);
        for &e in src {
            let t = e.tri();
            match class[t] {
                LEFT => lf.push(e.with_tri(ids[t][0])),
                RIGHT => rf.push(e.with_tri(ids[t][1])),
                _ => {}
            }
        }
        let (mut ln, mut rn) =
            (Vec::with_capacity(2 * both.len()), Vec::with_capacity(2 * both.len()));
        for &t in &both {
            let (il, ir) = (ids[t][0], ids[t][1]);
            push_events(&mut ln, &left.boxes[il as usize], a, il);
            push_events(&mut rn, &right.boxes[ir as usize], a, ir);
        }
        ln.sort_unstable_by(cmp_events);
        rn.sort_unstable_by(cmp_events);
        (merge(lf, ln), merge(rf, rn))
    };
    // Large nodes (the first levels, before subtrees run in parallel) filter their three
    // lists in parallel; the result is the same either way.
    let [x, y, z] = if n >= PAR_SWEEP {
        let (x, (y, z)) =
            rayon::join(|| per_axis(0), || rayon::join(|| per_axis(1), || per_axis(2)));
        [x, y, z]
    } else {
        [per_axis(0), per_axis(1), per_axis(2)]
    };
    for (a, (l, r)) in [x, y, z].into_iter().enumerate() {
        left.events[a] = l;
        right.events[a] = r;
    }
    drop(input);
    (left.into_input(), right.into_input())
}

/// The part of straddling triangle `g` (current box `bx`) inside `child`.
fn clip_to(ctx: &Ctx, g: u32, bx: &Aabb, child: &Aabb) -> Aabb {
    let coarse = bx.intersection(child);
    if !ctx.settings.perfect_splits {
        return coarse;
    }
    match clip_bounds(ctx.corners[g as usize], child.min, child.max) {
        Some((lo, hi)) => {
            let fine = Aabb { min: lo + Vec3::ZERO, max: hi + Vec3::ZERO }.intersection(&coarse);
            // Rounding can empty a piece that exists; fall back to the conservative box.
            if fine.is_empty() { coarse } else { fine }
        }
        None => coarse,
    }
}

fn merge(a: Vec<Event>, b: Vec<Event>) -> Vec<Event> {
    if b.is_empty() {
        return a;
    }
    let mut out = Vec::with_capacity(a.len() + b.len());
    let (mut i, mut j) = (0, 0);
    while i < a.len() && j < b.len() {
        if cmp_events(&a[i], &b[j]) != Ordering::Greater {
            out.push(a[i]);
            i += 1;
        } else {
            out.push(b[j]);
            j += 1;
        }
    }
    out.extend_from_slice(&a[i..]);
    out.extend_from_slice(&b[j..]);
    out
}

struct Side {
    bounds: Aabb,
    tris: Vec<u32>,
    boxes: Vec<Aabb>,
    events: [Vec<Event>; 3],
    depth: u32,
}

impl Side {
    fn new(bounds: Aabb, depth: u32, triangles: usize) -> Self {
        let (tris, boxes) = (Vec::with_capacity(triangles), Vec::with_capacity(triangles));
        Self { bounds, tris, boxes, events: Default::default(), depth }
    }
    fn add(&mut self, g: u32, b: Aabb) -> u32 {
        self.tris.push(g);
        self.boxes.push(b);
        (self.tris.len() - 1) as u32
    }
    fn into_input(self) -> NodeInput {
        NodeInput {
            bounds: self.bounds,
            tris: self.tris,
            boxes: self.boxes,
            events: self.events,
            depth: self.depth,
        }
    }
}
