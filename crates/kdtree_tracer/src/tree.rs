//! The kd-tree: build entry point, statistics and `validate()`.

use glam::{DVec3, Vec3};
use rayon::prelude::*;

use crate::aabb::Aabb;
use crate::build;
use crate::error::Error;
use crate::layout;
use crate::leaf::{self, Quad, ROWS};
use crate::mesh::Mesh;
use crate::node::{MAX_FIELD, Node, Nodes};
use crate::settings::{MAX_DEPTH_LIMIT, Settings};
use crate::triangle::{LeafTri, is_degenerate};

/// Most triangles a [`Mesh`] (and so a tree) may hold: the 30-bit fields of the compact node.
pub const MAX_TRIANGLES: usize = MAX_FIELD as usize;

/// A static SAH kd-tree over a [`Mesh`].
///
/// Nodes are 8 bytes ([`TreeStats::bytes`] reports the total); each leaf's triangles are
/// stored contiguously in one structure-of-arrays block (corners and ids in rows of a multiple
/// of four lanes, 44 bytes a lane, tested eight or four lanes at a time), so a leaf is one
/// linear read. Queries are [`KdTree::intersect`] (closest hit) and [`KdTree::occluded`] (any hit).
#[derive(Clone, Debug, PartialEq)]
pub struct KdTree {
    /// Root first, in cache lines of subtrees (`crate::layout`).
    pub(crate) nodes: Nodes,
    /// Each leaf's block of triangles with their ids (`crate::leaf`); a leaf node's offset is
    /// its first quad here.
    pub(crate) packs: Vec<Quad>,
    pub(crate) bounds: Aabb,
    /// Largest absolute coordinate of `bounds` (scales the traversal's epsilon).
    pub(crate) scale: f32,
    settings: Settings,
    triangle_count: usize,
    indexed_count: usize,
}

/// Size and shape of a built tree.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TreeStats {
    /// Triangles of the mesh.
    pub triangles: usize,
    /// Triangles in the tree (degenerate ones are left out).
    pub indexed_triangles: usize,
    pub nodes: usize,
    pub leaves: usize,
    pub empty_leaves: usize,
    /// Triangle records in leaves (a triangle straddling planes is stored in several).
    pub references: usize,
    pub max_depth: u32,
    /// Bytes of nodes + leaf records.
    pub bytes: usize,
    /// `bytes / triangles` (0 for an empty mesh).
    pub bytes_per_triangle: f64,
}

impl KdTree {
    /// Builds the tree with the SAH costs of `settings` (see [`Settings`]).
    ///
    /// Errors: invalid settings. (Non-finite vertices are rejected when they enter the
    /// [`Mesh`].) Degenerate triangles are left out: they can never be hit.
    pub fn build(mesh: &Mesh, settings: &Settings) -> Result<Self, Error> {
        settings.validate()?;
        let n = mesh.triangle_count();
        if n > MAX_TRIANGLES {
            return Err(Error::TooManyTriangles(n));
        }
        if let Some(p) = mesh.positions().iter().position(|p| !p.is_finite()) {
            let v = mesh.positions()[p];
            return Err(Error::NonFiniteVertex {
                mesh: 0,
                vertex: p as u32,
                x: v.x,
                y: v.y,
                z: v.z,
            });
        }
        let corners: Vec<[Vec3; 3]> =
            (0..n as u32).into_par_iter().map(|t| mesh.triangle(t)).collect();
        let ids: Vec<u32> = (0..n as u32)
            .filter(|&t| {
                let [a, b, c] = corners[t as usize];
                !is_degenerate(a, b, c)
            })
            .collect();
        let indexed_count = ids.len();
        let (built, bounds) = build::build(&corners, ids, settings);
        if built.nodes.len() > MAX_FIELD as usize || built.refs.len() > u32::MAX as usize {
            return Err(Error::TooManyTriangles(built.refs.len()));
        }
        let mut nodes = built.nodes;
        let packs = pack_leaves(&mut nodes, &built.refs, |g| {
            LeafTri::new(corners[g as usize], g, mesh.mesh_of(g))
        });
        if packs.len() > u32::MAX as usize {
            return Err(Error::TooManyTriangles(built.refs.len()));
        }
        let nodes = layout::treelets(&nodes);
        if nodes.len() > MAX_FIELD as usize {
            return Err(Error::TooManyTriangles(built.refs.len()));
        }
        Ok(Self {
            nodes: Nodes::from_slice(&nodes),
            packs,
            bounds,
            scale: if bounds.is_empty() {
                0.0
            } else {
                bounds.min.abs().max(bounds.max.abs()).max_element()
            },
            settings: *settings,
            triangle_count: n,
            indexed_count,
        })
    }

    /// The settings the tree was built with.
    pub fn settings(&self) -> &Settings {
        &self.settings
    }

    /// Bounds `(min, max)` of the indexed triangles, `None` when there are none.
    pub fn bounds(&self) -> Option<(Vec3, Vec3)> {
        (!self.bounds.is_empty()).then_some((self.bounds.min, self.bounds.max))
    }

    /// Node count, leaf count, references, depth and memory.
    pub fn stats(&self) -> TreeStats {
        let (mut leaves, mut empty, mut max_depth, mut refs) = (0, 0, 0, 0);
        let mut stack = vec![(0u32, 0u32)];
        while let Some((i, d)) = stack.pop() {
            let n = self.nodes[i as usize];
            max_depth = max_depth.max(d);
            if n.is_leaf() {
                leaves += 1;
                empty += usize::from(n.count() == 0);
                refs += n.count() as usize;
            } else {
                stack.push((n.first_child(), d + 1));
                stack.push((n.first_child() + 1, d + 1));
            }
        }
        let bytes = self.nodes.len() * std::mem::size_of::<Node>()
            + self.packs.len() * std::mem::size_of::<Quad>();
        TreeStats {
            triangles: self.triangle_count,
            indexed_triangles: self.indexed_count,
            nodes: self.nodes.iter().filter(|n| !n.is_pad()).count(),
            leaves,
            empty_leaves: empty,
            references: refs,
            max_depth,
            bytes,
            bytes_per_triangle: if self.triangle_count == 0 {
                0.0
            } else {
                bytes as f64 / self.triangle_count as f64
            },
        }
    }

    /// Checks every invariant of the tree built from `mesh`: node indices in range and each
    /// node reached exactly once; split planes strictly inside their node's box (so child boxes
    /// nest); no interior node with an empty subtree; depth within the limit; leaf records equal
    /// to the mesh's triangles; every non-degenerate triangle in at least one leaf, and in
    /// *every* leaf whose open box its clipped triangle overlaps.
    pub fn validate(&self, mesh: &Mesh) -> Result<(), Error> {
        let bad = |s: String| Err(Error::Invalid(s));
        if mesh.triangle_count() != self.triangle_count {
            return bad(format!(
                "tree has {} triangles, mesh {}",
                self.triangle_count,
                mesh.triangle_count()
            ));
        }
        if self.nodes.is_empty() {
            return bad("no root node".into());
        }
        for (i, n) in self.nodes.iter().enumerate().filter(|(_, n)| n.is_leaf() && n.count() > 0) {
            let (o, m) = (n.offset() as usize, leaf::lanes(n.count() as usize));
            let Some(block) = self.packs.get(o..o + ROWS * m / 4) else {
                return bad(format!("leaf {i} block {o}+{m} lanes out of range"));
            };
            for lane in 0..m {
                let (t, id_mesh) = leaf::ids(block, m, lane);
                if t as usize >= self.triangle_count {
                    return bad(format!("leaf {i} lane {lane} names triangle {t}"));
                }
                if leaf::corners(block, m, lane) != mesh.triangle(t) || id_mesh != mesh.mesh_of(t) {
                    return bad(format!("leaf {i} lane {lane} does not match triangle {t}"));
                }
                if mesh.is_degenerate(t) {
                    return bad(format!("degenerate triangle {t} is in a leaf"));
                }
            }
        }
        let mut seen = vec![false; self.nodes.len()];
        let mut present = vec![false; self.triangle_count];
        let all: Vec<u32> = (0..self.triangle_count as u32)
            .filter(|&t| !mesh.is_degenerate(t))
            .filter(|&t| overlaps_open(mesh.triangle(t), &self.bounds))
            .collect();
        self.check_node(mesh, 0, self.bounds, 0, all, &mut seen, &mut present)?;
        if let Some(i) = (0..seen.len()).find(|&i| !seen[i] && !self.nodes[i].is_pad()) {
            return bad(format!("node {i} is unreachable"));
        }
        if let Some(t) = (0..self.triangle_count as u32)
            .find(|&t| !present[t as usize] && !mesh.is_degenerate(t))
        {
            return bad(format!("triangle {t} is in no leaf"));
        }
        Ok(())
    }

    /// Returns the number of references in the subtree.
    #[allow(clippy::too_many_arguments)]
    fn check_node(
        &self,
        mesh: &Mesh,
        i: u32,
        b: Aabb,
        depth: u32,
        cand: Vec<u32>,
        seen: &mut [bool],
        present: &mut [bool],
    ) -> Result<usize, Error> {
        let bad = |s: String| Err(Error::Invalid(s));
        let Some(s) = seen.get_mut(i as usize) else {
            return bad(format!("child index {i} out of range"));
        };
        if *s {
            return bad(format!("node {i} reached twice"));
        }
        *s = true;
        if depth > MAX_DEPTH_LIMIT {
            return bad(format!("node {i} at depth {depth} > {MAX_DEPTH_LIMIT}"));
        }
        let n = self.nodes[i as usize];
        if n.is_leaf() {
            let (o, c) = (n.offset() as usize, n.count() as usize);
            let m = leaf::lanes(c);
            let Some(block) = self.packs.get(o..o + ROWS * m / 4) else {
                return bad(format!("leaf {i} block {o}+{m} lanes out of range"));
            };
            let mut ids: Vec<u32> = (0..c).map(|k| leaf::ids(block, m, k).0).collect();
            ids.sort_unstable();
            for &t in &ids {
                present[t as usize] = true;
            }
            if let Some(t) = cand.iter().find(|t| ids.binary_search(t).is_err()) {
                return bad(format!("triangle {t} overlaps leaf {i} but is not in it"));
            }
            return Ok(c);
        }
        let (axis, p) = (n.axis(), n.split());
        if !(p > b.min[axis] && p < b.max[axis]) {
            return bad(format!(
                "node {i}: split {p} on axis {axis} not inside ({}, {})",
                b.min[axis], b.max[axis]
            ));
        }
        let (mut lb, mut rb) = (b, b);
        lb.max[axis] = p;
        rb.min[axis] = p;
        let lc: Vec<u32> =
            cand.iter().copied().filter(|&t| overlaps_open(mesh.triangle(t), &lb)).collect();
        let rc: Vec<u32> =
            cand.iter().copied().filter(|&t| overlaps_open(mesh.triangle(t), &rb)).collect();
        drop(cand);
        let first = n.first_child();
        let l = self.check_node(mesh, first, lb, depth + 1, lc, seen, present)?;
        let r = self.check_node(mesh, first + 1, rb, depth + 1, rc, seen, present)?;
        if l + r == 0 {
            return bad(format!("interior node {i} has an empty subtree"));
        }
        Ok(l + r)
    }
}

/// Stores each leaf's triangles (`offset`, `count` into `refs`, global ids made into records by
/// `record`) as one block (`crate::leaf`), and points the leaf at its first quad instead.
fn pack_leaves(nodes: &mut [Node], refs: &[u32], record: impl Fn(u32) -> LeafTri) -> Vec<Quad> {
    let mut quads = Vec::with_capacity(refs.len() * ROWS / 3 + 1);
    let mut recs = Vec::new();
    for n in nodes.iter_mut().filter(|n| n.is_leaf()) {
        let (o, c) = (n.offset() as usize, n.count() as usize);
        let first = quads.len() as u32;
        if c > 0 {
            recs.clear();
            recs.extend(refs[o..o + c].iter().map(|&g| record(g)));
            leaf::push_leaf(&mut quads, &recs);
        }
        *n = Node::leaf(c as u32, first);
    }
    quads
}

/// True when the triangle reaches into the box's interior (the box shrunk by a relative 1e-6
/// on each axis with extent, in f64 so the margin is never lost to rounding; flat axes stay
/// closed), i.e. it does more than touch the boundary.
fn overlaps_open(p: [Vec3; 3], b: &Aabb) -> bool {
    let (lo, hi) = (b.min.as_dvec3(), b.max.as_dvec3());
    let margin = (hi - lo) * 1e-6;
    let (lo, hi) = (lo + margin, hi - margin);
    let mut poly: Vec<DVec3> = p.iter().map(|v| v.as_dvec3()).collect();
    for axis in 0..3 {
        for (plane, above) in [(lo[axis], true), (hi[axis], false)] {
            let inside = |q: DVec3| if above { q[axis] >= plane } else { q[axis] <= plane };
            let mut out = Vec::with_capacity(poly.len() + 1);
            for i in 0..poly.len() {
                let (a, c) = (poly[i], poly[(i + 1) % poly.len()]);
                if inside(a) {
                    out.push(a);
                }
                if inside(a) != inside(c) {
                    let s = (plane - a[axis]) / (c[axis] - a[axis]);
                    let mut q = a + (c - a) * s;
                    q[axis] = plane;
                    out.push(q);
                }
            }
            if out.is_empty() {
                return false;
            }
            poly = out;
        }
    }
    true
}
