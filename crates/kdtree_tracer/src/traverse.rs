//! Front-to-back kd-tree traversal with a small fixed stack (no allocation per ray).
//!
//! Robustness rules (all tested in `tests/hard_cases.rs`):
//! - intervals are closed, and every decision against a plane's `t` is widened by
//!   `eps = eps_ray + |t| * WIDEN`, where `eps_ray = 2e-6 (|scene| + |origin|) / |dir|` bounds
//!   the error of the ray/triangle test's `t` (its vertices are taken relative to the origin
//!   in f32). So rounding never skips a node at a shared corner or edge, a triangle the test
//!   reports at exactly `t_max` is found, and a pending node is dropped only when it starts
//!   `eps` after the best hit (a closer hit in it is then impossible);
//! - a ray lying *in* a split plane (direction component zero, origin on the plane: `t` is
//!   `0 * inf = NaN`) visits both children with the full interval, because triangles touching
//!   the plane from either side may be hit;
//! - a ray starting on a plane is "near" on the side it leaves (so the far child gets the whole
//!   rest of the interval), and a zero or negative-zero direction component is handled by the
//!   IEEE infinities of `1/d` (`+-inf` never lies inside the interval).

use crate::leaf4::Tri4;
use crate::node::Node;
use crate::ray::{Hit, Ray, RayQuery, Rescaled};
use crate::settings::MAX_DEPTH_LIMIT;
use crate::tree::KdTree;
use crate::triangle::PreparedRay;

/// Relative widening of plane distances (a few ulps of f32, with margin).
const WIDEN: f32 = 1e-6;
const STACK: usize = MAX_DEPTH_LIMIT as usize + 8;

#[derive(Clone, Copy, Default)]
struct Entry {
    node: u32,
    t0: f32,
    t1: f32,
}

/// Clips `[t0, t1]` to the box (widened by `eps`); `None` when the ray misses it.
#[inline(always)]
fn clip_box(
    tree: &KdTree,
    r: &PreparedRay,
    mut t0: f32,
    mut t1: f32,
    eps: f32,
) -> Option<(f32, f32)> {
    let b = &tree.bounds;
    for a in 0..3 {
        let (lo, hi) = (b.min[a], b.max[a]);
        let inv = r.inv[a];
        if inv.is_infinite() {
            // Parallel to the slab (d = +-0 or denormal): inside or never.
            if r.o[a] < lo || r.o[a] > hi {
                return None;
            }
            continue;
        }
        let (mut n, mut f) = ((lo - r.o[a]) * inv, (hi - r.o[a]) * inv);
        if n > f {
            std::mem::swap(&mut n, &mut f);
        }
        t0 = t0.max(n - n.abs() * WIDEN - eps);
        t1 = t1.min(f + f.abs() * WIDEN + eps);
    }
    (t0 <= t1).then_some((t0, t1))
}

impl KdTree {
    /// Closest hit with `t` in `[max(ray.t_min, 0), t_max]`.
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<Hit> {
        self.traverse::<false>(ray, t_max)
    }

    /// True when anything is hit with `t` in `[max(ray.t_min, 0), t_max]`.
    #[inline]
    pub fn occluded(&self, ray: &Ray, t_max: f32) -> bool {
        self.any_hit(ray, t_max).is_some()
    }

    /// Some hit with `t` in `[max(ray.t_min, 0), t_max]`, not necessarily the closest: the
    /// first one the traversal meets (the early out of [`KdTree::occluded`], with the hit).
    /// A caller that filters hits (alpha-tested holes) can accept it when it passes and fall
    /// back to [`KdTree::intersect`] when it does not.
    #[inline]
    pub fn any_hit(&self, ray: &Ray, t_max: f32) -> Option<Hit> {
        self.traverse::<true>(ray, t_max)
    }

    #[inline(always)]
    fn traverse<const ANY: bool>(&self, ray: &Ray, t_max: f32) -> Option<Hit> {
        let t_min = ray.t_min.max(0.0);
        if !ray.is_valid() || !(t_min <= t_max) || self.bounds.is_empty() {
            return None;
        }
        if let Some(s) = Rescaled::of(ray, t_min, t_max) {
            return self.traverse_prepared::<ANY>(&s.ray, s.t_min, s.t_max).map(|h| s.unscale(h));
        }
        self.traverse_prepared::<ANY>(ray, t_min, t_max)
    }

    #[inline(always)]
    fn traverse_prepared<const ANY: bool>(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<Hit> {
        let r = PreparedRay::new(ray);
        match r.kz {
            0 => self.traverse_k::<ANY, 0>(ray, &r, t_min, t_max),
            1 => self.traverse_k::<ANY, 1>(ray, &r, t_min, t_max),
            _ => self.traverse_k::<ANY, 2>(ray, &r, t_min, t_max),
        }
    }

    /// The traversal for rays whose major axis is `KZ`.
    #[inline(always)]
    fn traverse_k<const ANY: bool, const KZ: usize>(
        &self,
        ray: &Ray,
        r: &PreparedRay,
        t_min: f32,
        t_max: f32,
    ) -> Option<Hit> {
        let eps =
            2e-6 * (self.scale + ray.origin.abs().max_element()) / ray.dir.abs().max_element();
        let (mut t0, mut t1) = clip_box(self, r, t_min, t_max, eps)?;
        let nodes: &[Node] = &self.nodes;
        let packs = &self.packs;
        let mut stack = [Entry::default(); STACK];
        let mut sp = 0usize;
        let mut node = nodes[0];
        let mut best_t = t_max;
        let mut best: Option<(u32, usize, f32, f32)> = None;
        loop {
            if !node.is_leaf() {
                let axis = node.axis() & 3;
                let split = node.split();
                let (o, d) = (r.o[axis], r.d[axis]);
                let ts = (split - o) * r.inv[axis];
                let first = node.first_child();
                // "Near" is the side the ray is on just before the plane.
                let below_first = o < split || (o == split && d > 0.0);
                let (near, far) = if below_first { (first, first + 1) } else { (first + 1, first) };
                if !(ts.abs() < f32::INFINITY) && ts.is_nan() {
                    // The ray lies in the plane: both sides, whole interval.
                    if sp < STACK {
                        stack[sp] = Entry { node: far, t0, t1 };
                        sp += 1;
                    }
                    node = nodes[near as usize];
                } else if ts.is_infinite() {
                    // Parallel to the plane (or crossing it only beyond f32 range).
                    node = nodes[near as usize];
                } else {
                    let e = eps + ts.abs() * WIDEN;
                    let mut push = None;
                    if ts < 0.0 {
                        // Plane behind the origin: the ray stays on the near side. Within `e`
                        // of the plane, the first `e` of the ray also sees the far side.
                        if ts >= -e && t0 <= e {
                            push = Some((t0, t1.min(e.max(t0))));
                        }
                        node = nodes[near as usize];
                    } else if ts - e > t1 {
                        node = nodes[near as usize];
                    } else if ts + e < t0 {
                        node = nodes[far as usize];
                    } else {
                        let c = ts.max(t0).min(t1);
                        push = Some((c, t1));
                        t1 = c;
                        node = nodes[near as usize];
                    }
                    if let Some((a, b)) = push
                        && sp < STACK
                    {
                        stack[sp] = Entry { node: far, t0: a, t1: b };
                        sp += 1;
                    }
                }
                continue;
            }
            let start = node.offset() as usize;
            let end = start + node.count().div_ceil(4) as usize;
            for (k, pack) in packs[start..end].iter().enumerate() {
                if let Some((t, u, v, lane)) = r.intersect4::<KZ>(pack, t_min, best_t) {
                    if ANY {
                        return Some(hit(pack, lane, t, u, v));
                    }
                    best_t = t;
                    best = Some(((start + k) as u32, lane, u, v));
                }
            }
            // Pop the next node whose interval still starts before the best hit. (No separate
            // early exit: after a ray-in-plane split both children share an interval, so only
            // this test is valid in every case; in front-to-back order it ends the search
            // as soon as the best hit precedes every pending node.)
            loop {
                if sp == 0 {
                    return best.map(|(i, lane, u, v)| hit(&packs[i as usize], lane, best_t, u, v));
                }
                sp -= 1;
                let e = stack[sp];
                if e.t0 - eps - e.t0.abs() * WIDEN <= best_t {
                    node = nodes[e.node as usize];
                    t0 = e.t0;
                    t1 = e.t1;
                    break;
                }
            }
        }
    }
}

#[inline]
fn hit(pack: &Tri4, lane: usize, t: f32, u: f32, v: f32) -> Hit {
    Hit { t, triangle: pack.tri[lane], mesh: pack.mesh[lane], barycentrics: glam::Vec2::new(u, v) }
}

impl RayQuery for KdTree {
    fn intersect(&self, ray: &Ray, t_max: f32) -> Option<Hit> {
        KdTree::intersect(self, ray, t_max)
    }
    fn occluded(&self, ray: &Ray, t_max: f32) -> bool {
        KdTree::occluded(self, ray, t_max)
    }
}
