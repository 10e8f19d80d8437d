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

use std::mem::MaybeUninit;

use crate::leaf::{self, ROWS};
use crate::node::Node;
use crate::packet::{self, PACKET};
use crate::ray::{Hit, Ray, RayQuery, Rescaled};
use crate::settings::MAX_DEPTH_LIMIT;
use crate::tree::KdTree;
use crate::triangle::PreparedRay;

/// Relative widening of plane distances (a few ulps of f32, with margin).
pub(crate) const WIDEN: f32 = 1e-6;
pub(crate) const STACK: usize = MAX_DEPTH_LIMIT as usize + 8;

/// The best hit so far: where its ids are ([`leaf::id_place`]) and its barycentrics.
pub(crate) type Best = Option<(u32, u32, f32, f32)>;

/// A pending node of the single-ray walk.
#[derive(Clone, Copy)]
pub(crate) struct Entry {
    node: u32,
    t0: f32,
    t1: f32,
}

/// The single-ray walk's stack: left uninitialised (zeroing its 768 bytes per ray cost more
/// than a short walk); [`KdTree::walk`] reads only the entries below its own stack pointer,
/// which it wrote.
pub(crate) type Stack = [MaybeUninit<Entry>; STACK];

/// A stack for [`KdTree::walk`] (nothing written).
#[inline(always)]
pub(crate) fn new_stack() -> Stack {
    [const { MaybeUninit::uninit() }; STACK]
}

/// The larger of two numbers that are not NaN (one `maxss`: `f32::max` also handles NaN;
/// of `0.0` and `-0.0` either may come back, which no later comparison tells apart).
#[inline(always)]
pub(crate) fn max(a: f32, b: f32) -> f32 {
    if a > b { a } else { b }
}

/// The smaller of two numbers that are not NaN (see [`max`]).
#[inline(always)]
pub(crate) fn min(a: f32, b: f32) -> f32 {
    if a < b { a } else { b }
}

/// Clips `[t0, t1]` to the box (widened by `eps`); `None` when the ray misses it.
#[inline(always)]
pub(crate) fn clip_box(
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
        t0 = max(t0, n - n.abs() * WIDEN - eps);
        t1 = min(t1, f + f.abs() * WIDEN + eps);
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
        #[cfg(target_arch = "x86_64")]
        if r.wide {
            // SAFETY: `wide` is true only where the CPU has AVX (`leaf::avx`).
            return unsafe { self.traverse_avx::<ANY>(ray, &r, t_min, t_max) };
        }
        match r.kz {
            0 => self.traverse_k::<ANY, 0, false>(ray, &r, t_min, t_max),
            1 => self.traverse_k::<ANY, 1, false>(ray, &r, t_min, t_max),
            _ => self.traverse_k::<ANY, 2, false>(ray, &r, t_min, t_max),
        }
    }

    /// The whole traversal compiled with AVX, so that the 8-wide leaf test is inlined into it.
    ///
    /// # Safety
    /// The CPU must have AVX.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx")]
    unsafe fn traverse_avx<const ANY: bool>(
        &self,
        ray: &Ray,
        r: &PreparedRay,
        t_min: f32,
        t_max: f32,
    ) -> Option<Hit> {
        match r.kz {
            0 => self.traverse_k::<ANY, 0, true>(ray, r, t_min, t_max),
            1 => self.traverse_k::<ANY, 1, true>(ray, r, t_min, t_max),
            _ => self.traverse_k::<ANY, 2, true>(ray, r, t_min, t_max),
        }
    }

    /// The traversal for rays whose major axis is `KZ` (`AVX`: with the 8-wide leaf test,
    /// only inside [`Self::traverse_avx`] or another function compiled with AVX).
    #[inline(always)]
    fn traverse_k<const ANY: bool, const KZ: usize, const AVX: bool>(
        &self,
        ray: &Ray,
        r: &PreparedRay,
        t_min: f32,
        t_max: f32,
    ) -> Option<Hit> {
        let eps = self.ray_eps(ray);
        let (t0, t1) = clip_box(self, r, t_min, t_max, eps)?;
        let mut best_t = t_max;
        let mut best = None;
        let mut stack = new_stack();
        self.walk::<ANY, KZ, AVX>(r, eps, t_min, 0, t0, t1, &mut best_t, &mut best, &mut stack);
        self.hit(best, best_t)
    }

    /// The widening of every plane decision for `ray` (see the module doc).
    #[inline(always)]
    pub(crate) fn ray_eps(&self, ray: &Ray) -> f32 {
        2e-6 * (self.scale + ray.origin.abs().max_element()) / ray.dir.abs().max_element()
    }

    /// Front-to-back traversal of the subtree at node `root`, entered with the interval
    /// `[t0, t1]`, updating the best hit `best_t`, `best` (pack, lane, u, v); with `ANY`, it
    /// returns at the first hit. Every node pushed here is popped here, so the leaves it
    /// tests, in order, are those the whole-tree traversal tests when it enters `root` with
    /// the same interval and best hit (the packets rely on this).
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    pub(crate) fn walk<const ANY: bool, const KZ: usize, const AVX: bool>(
        &self,
        r: &PreparedRay,
        eps: f32,
        t_min: f32,
        root: u32,
        mut t0: f32,
        mut t1: f32,
        best_t: &mut f32,
        best: &mut Best,
        stack: &mut Stack,
    ) {
        let nodes: &[Node] = &self.nodes;
        let mut sp = 0usize;
        let mut node = nodes[root as usize];
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
                        stack[sp] = MaybeUninit::new(Entry { node: far, t0, t1 });
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
                            push = Some((t0, min(t1, max(e, t0))));
                        }
                        node = nodes[near as usize];
                    } else if ts - e > t1 {
                        node = nodes[near as usize];
                    } else if ts + e < t0 {
                        node = nodes[far as usize];
                    } else {
                        let c = min(max(ts, t0), t1);
                        push = Some((c, t1));
                        t1 = c;
                        node = nodes[near as usize];
                    }
                    if let Some((a, b)) = push
                        && sp < STACK
                    {
                        stack[sp] = MaybeUninit::new(Entry { node: far, t0: a, t1: b });
                        sp += 1;
                    }
                }
                continue;
            }
            if self.leaf::<KZ, AVX>(r, node, t_min, best_t, best) && ANY {
                return;
            }
            // Pop the next node whose interval still starts before the best hit. (No separate
            // early exit: after a ray-in-plane split both children share an interval, so only
            // this test is valid in every case; in front-to-back order it ends the search
            // as soon as the best hit precedes every pending node.)
            loop {
                if sp == 0 {
                    return;
                }
                sp -= 1;
                // SAFETY: every entry below `sp` was written by this walk (pushes write
                // `stack[sp]` before incrementing `sp`).
                let e = unsafe { stack[sp].assume_init() };
                if e.t0 - eps - e.t0.abs() * WIDEN <= *best_t {
                    node = nodes[e.node as usize];
                    t0 = e.t0;
                    t1 = e.t1;
                    break;
                }
            }
        }
    }

    /// Tests the triangles of leaf `node` against `[t_min, best_t]`, updating the best hit
    /// (`best`: where the hit lane's ids are, [`leaf::id_place`], and its barycentrics); true
    /// when one was found here.
    #[inline(always)]
    pub(crate) fn leaf<const KZ: usize, const AVX: bool>(
        &self,
        r: &PreparedRay,
        node: Node,
        t_min: f32,
        best_t: &mut f32,
        best: &mut Best,
    ) -> bool {
        let start = node.offset() as usize;
        let m = leaf::lanes(node.count() as usize);
        let block = &self.packs[start..start + ROWS * m / 4];
        match r.intersect_leaf::<KZ, AVX>(block, m, t_min, *best_t) {
            Some((t, u, v, lane)) => {
                let (q, l) = leaf::id_place(start, m, lane);
                *best_t = t;
                *best = Some((q, l, u, v));
                true
            }
            None => false,
        }
    }

    /// The hit recorded in `best` at distance `t`.
    #[inline]
    pub(crate) fn hit(&self, best: Best, t: f32) -> Option<Hit> {
        best.map(|(q, l, u, v)| {
            let (triangle, mesh) = leaf::ids_at(&self.packs, (q, l));
            Hit { t, triangle, mesh, barycentrics: glam::Vec2::new(u, v) }
        })
    }
}

impl RayQuery for KdTree {
    fn intersect(&self, ray: &Ray, t_max: f32) -> Option<Hit> {
        KdTree::intersect(self, ray, t_max)
    }
    fn occluded(&self, ray: &Ray, t_max: f32) -> bool {
        KdTree::occluded(self, ray, t_max)
    }
    fn intersect_many(&self, rays: &[Option<Ray>], t_max: f32, out: &mut [Option<Hit>]) {
        assert_eq!(rays.len(), out.len(), "one output per ray");
        let mut scratch = packet::Scratch::new();
        for (r, o) in rays.chunks(PACKET).zip(out.chunks_mut(PACKET)) {
            self.packet(r, t_max, o, &mut scratch);
        }
    }
}
