//! Packets: up to [`PACKET`] rays (a block of neighbouring pixels) traced down the kd-tree
//! together, after I. Wald's packet traversal (PhD thesis 2004, 7.1) with per-ray active masks
//! and per-ray intervals.
//!
//! Every ray of a packet gets exactly the answer [`KdTree::intersect`] gives it alone (bit for
//! bit: the same `t`, triangle and barycentrics, also when several triangles tie at the same
//! `t`). That holds because each ray sees the same leaves in the same order, with the same
//! best hit, as it would alone:
//!
//! - at an interior node each active ray makes the single-ray decision (which children, in
//!   which order, with which intervals) from its own interval; the packet visits a child with
//!   the mask of the rays that want it;
//! - when the rays that visit both children disagree on the order, the packet visits the left
//!   child twice: first with the left-first rays and the rays that want only the left, then
//!   the right child with every ray that wants it, then the left again with the right-first
//!   rays (each ray's own order is kept; the subtree is walked twice);
//! - a popped node keeps the rays whose interval starts before their own best hit (the single
//!   ray's test at the same point of its own walk, so with the same best hit);
//! - a leaf runs the single ray's own leaf test ([`KdTree::leaf`]) for each active ray;
//! - a node reached with one active ray is finished by that ray's single-ray walk
//!   ([`KdTree::walk`]), which tests the leaves of the subtree in the order a whole-tree
//!   traversal does, so sparse packets cost no more than single rays.
//!
//! Rays the single-ray path rescales (tiny directions) or rejects are answered one by one.

use crate::node::Node;
use crate::ray::{Hit, Ray, Rescaled};
use crate::settings::MAX_DEPTH_LIMIT;
use crate::traverse::{self, Best, WIDEN, clip_box, max, min};
use crate::tree::KdTree;
use crate::triangle::PreparedRay;

/// Rays per packet (a 4x4 pixel block in [`crate::trace_tiles`]).
pub const PACKET: usize = 16;

/// Each level pushes at most two entries (the order-conflict case): the stack's capacity.
pub(crate) const STACK: usize = 2 * MAX_DEPTH_LIMIT as usize + 8;

/// The stacks of packet traversals, made once for many packets: the packet's own and the one
/// its single-ray walks use.
pub(crate) struct Scratch {
    packet: Vec<Entry>,
    single: traverse::Stack,
}

impl Scratch {
    pub(crate) fn new() -> Self {
        Self { packet: Vec::with_capacity(STACK), single: traverse::new_stack() }
    }
}

/// A pending node with the rays that visit it and their intervals.
#[derive(Clone, Copy)]
pub(crate) struct Entry {
    node: u32,
    mask: u32,
    t0: [f32; PACKET],
    t1: [f32; PACKET],
}

/// The packet's rays in structure-of-arrays form for the plane decisions (index `[axis][lane]`,
/// arrays of 4 axes so that `axis & 3` needs no bounds check).
struct Lanes {
    o: [[f32; PACKET]; 4],
    d: [[f32; PACKET]; 4],
    inv: [[f32; PACKET]; 4],
    eps: [f32; PACKET],
    t_min: [f32; PACKET],
    r: [PreparedRay; PACKET],
}

impl KdTree {
    /// Closest hits of up to [`PACKET`] rays at once (`out[i]` for `rays[i]`; `None` rays get
    /// `None`): the same answers as [`KdTree::intersect`] on each ray, bit for bit, traced
    /// together while the rays take the same way down the tree (see [`crate::trace_tiles`],
    /// which hands it blocks of neighbouring pixels).
    ///
    /// # Panics
    /// When `rays.len() > PACKET` or `out.len() != rays.len()`.
    pub fn intersect_packet(&self, rays: &[Option<Ray>], t_max: f32, out: &mut [Option<Hit>]) {
        self.packet(rays, t_max, out, &mut Scratch::new());
    }

    /// [`Self::intersect_packet`] with stacks the caller keeps (made once for many packets:
    /// zeroing fixed stacks per packet cost more than the traversal).
    pub(crate) fn packet(
        &self,
        rays: &[Option<Ray>],
        t_max: f32,
        out: &mut [Option<Hit>],
        scratch: &mut Scratch,
    ) {
        self.packet_with(rays, t_max, out, scratch, crate::leaf::avx());
    }

    /// [`Self::packet`] with the AVX paths (`wide`, only where the CPU has AVX) or the SSE
    /// and scalar ones.
    fn packet_with(
        &self,
        rays: &[Option<Ray>],
        t_max: f32,
        out: &mut [Option<Hit>],
        scratch: &mut Scratch,
        wide: bool,
    ) {
        assert!(rays.len() <= PACKET && out.len() == rays.len(), "packet of {} rays", rays.len());
        #[cfg(not(target_arch = "x86_64"))]
        let _ = wide;
        let dummy = PreparedRay::new(&Ray::new(glam::Vec3::ZERO, glam::Vec3::X));
        let mut l = Lanes {
            o: [[0.0; PACKET]; 4],
            d: [[0.0; PACKET]; 4],
            inv: [[0.0; PACKET]; 4],
            eps: [0.0; PACKET],
            t_min: [0.0; PACKET],
            r: [dummy; PACKET],
        };
        let mut t0 = [0.0f32; PACKET];
        let mut t1 = [0.0f32; PACKET];
        #[cfg(target_arch = "x86_64")]
        let mask = if wide {
            // SAFETY: `wide`: the CPU has AVX.
            unsafe { self.setup_avx(rays, t_max, out, &mut l, &mut t0, &mut t1) }
        } else {
            self.setup(rays, t_max, out, &mut l, &mut t0, &mut t1)
        };
        #[cfg(not(target_arch = "x86_64"))]
        let mask = self.setup(rays, t_max, out, &mut l, &mut t0, &mut t1);
        let mut best_t = [t_max; PACKET];
        let mut best: [Best; PACKET] = [None; PACKET];
        if mask != 0 {
            scratch.packet.clear();
            #[cfg(target_arch = "x86_64")]
            if wide {
                // SAFETY: `wide` is true only where the CPU has AVX (`leaf::avx`).
                unsafe { self.walk_packet_avx(&l, mask, t0, t1, &mut best_t, &mut best, scratch) };
            } else {
                self.walk_packet::<false>(&l, mask, t0, t1, &mut best_t, &mut best, scratch);
            }
            #[cfg(not(target_arch = "x86_64"))]
            self.walk_packet::<false>(&l, mask, t0, t1, &mut best_t, &mut best, scratch);
        }
        for i in 0..rays.len() {
            if mask >> i & 1 == 1 {
                out[i] = self.hit(best[i], best_t[i]);
            }
        }
    }

    /// Each ray's single-ray setup (validity, rescaling, [`PreparedRay`], the box): fills the
    /// lanes of the rays to trace and returns their mask; the others' answers are written.
    fn setup(
        &self,
        rays: &[Option<Ray>],
        t_max: f32,
        out: &mut [Option<Hit>],
        l: &mut Lanes,
        t0: &mut [f32; PACKET],
        t1: &mut [f32; PACKET],
    ) -> u32 {
        let mut mask = 0u32;
        for (i, (ray, o)) in rays.iter().zip(out.iter_mut()).enumerate() {
            *o = None;
            let Some(ray) = ray else { continue };
            let t_min = ray.t_min.max(0.0);
            if !ray.is_valid() || !(t_min <= t_max) || self.bounds.is_empty() {
                continue;
            }
            if Rescaled::of(ray, t_min, t_max).is_some() {
                *o = self.intersect(ray, t_max);
                continue;
            }
            let r = PreparedRay::new(ray);
            let eps = self.ray_eps(ray);
            let Some((a, b)) = clip_box(self, &r, t_min, t_max, eps) else { continue };
            for axis in 0..3 {
                l.o[axis][i] = r.o[axis];
                l.d[axis][i] = r.d[axis];
                l.inv[axis][i] = r.inv[axis];
            }
            l.eps[i] = eps;
            l.t_min[i] = t_min;
            l.r[i] = r;
            (t0[i], t1[i]) = (a, b);
            mask |= 1 << i;
        }
        mask
    }

    /// [`Self::setup`] eight rays at a time with AVX: the same divisions, comparisons and
    /// selects in the same order, so the same bits (tested against it).
    ///
    /// # Safety
    /// The CPU must have AVX.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx")]
    unsafe fn setup_avx(
        &self,
        rays: &[Option<Ray>],
        t_max: f32,
        out: &mut [Option<Hit>],
        l: &mut Lanes,
        t0: &mut [f32; PACKET],
        t1: &mut [f32; PACKET],
    ) -> u32 {
        // The rays to trace, in structure-of-arrays form (others answered here).
        let mut todo = 0u32;
        for (i, (ray, o)) in rays.iter().zip(out.iter_mut()).enumerate() {
            *o = None;
            let Some(ray) = ray else { continue };
            let t_min = ray.t_min.max(0.0);
            if !ray.is_valid() || !(t_min <= t_max) || self.bounds.is_empty() {
                continue;
            }
            if Rescaled::of(ray, t_min, t_max).is_some() {
                *o = self.intersect(ray, t_max);
                continue;
            }
            for axis in 0..3 {
                l.o[axis][i] = ray.origin[axis];
                l.d[axis][i] = ray.dir[axis];
            }
            l.t_min[i] = t_min;
            todo |= 1 << i;
        }
        let (mut kz, mut sx, mut sy, mut sz) =
            ([0.0f32; PACKET], [0.0; PACKET], [0.0; PACKET], [0.0; PACKET]);
        let mut alive = 0u32;
        // SAFETY: AVX is available (the caller's contract); every load and store reads or
        // writes eight f32 at offset k < PACKET, a multiple of 8, of an array of PACKET (only
        // AVX intrinsics: no AVX2 integer operations).
        unsafe {
            use std::arch::x86_64::*;
            let sel = |m: __m256, x: __m256, y: __m256| _mm256_blendv_ps(y, x, m);
            let sign = _mm256_set1_ps(-0.0);
            let abs = |a: __m256| _mm256_andnot_ps(sign, a);
            let (one, inf, widen) =
                (_mm256_set1_ps(1.0), _mm256_set1_ps(f32::INFINITY), _mm256_set1_ps(WIDEN));
            for k in (0..PACKET).step_by(8) {
                let ld = |a: &[f32; PACKET]| _mm256_loadu_ps(a.as_ptr().add(k));
                let o = [ld(&l.o[0]), ld(&l.o[1]), ld(&l.o[2])];
                let d = [ld(&l.d[0]), ld(&l.d[1]), ld(&l.d[2])];
                let inv = d.map(|d| _mm256_div_ps(one, d));
                // `Vec3::max_position` of |d|: the first largest.
                let (ax, ay, az) = (abs(d[0]), abs(d[1]), abs(d[2]));
                let y_first = _mm256_cmp_ps::<_CMP_GT_OQ>(ay, ax);
                let z_first = _mm256_cmp_ps::<_CMP_GT_OQ>(az, sel(y_first, ay, ax));
                let is1 = _mm256_andnot_ps(z_first, y_first);
                let dkz = sel(z_first, d[2], sel(is1, d[1], d[0]));
                let dkx = sel(z_first, d[0], sel(is1, d[2], d[1]));
                let dky = sel(z_first, d[1], sel(is1, d[0], d[2]));
                let st = |dst: &mut [f32; PACKET], v: __m256| {
                    _mm256_storeu_ps(dst.as_mut_ptr().add(k), v)
                };
                st(&mut sx, _mm256_div_ps(dkx, dkz));
                st(&mut sy, _mm256_div_ps(dky, dkz));
                st(&mut sz, _mm256_div_ps(one, dkz));
                let two = _mm256_set1_ps(2.0);
                st(&mut kz, sel(z_first, two, _mm256_and_ps(is1, one)));
                // `KdTree::ray_eps`: `Vec3::max_element` is `a > b ? a : b`, as `maxps`.
                let max3 = |x: __m256, y: __m256, z: __m256| _mm256_max_ps(x, _mm256_max_ps(y, z));
                let mo = max3(abs(o[0]), abs(o[1]), abs(o[2]));
                let md = max3(ax, ay, az);
                let scale = _mm256_set1_ps(self.scale);
                let eps = _mm256_div_ps(
                    _mm256_mul_ps(_mm256_set1_ps(2e-6), _mm256_add_ps(scale, mo)),
                    md,
                );
                st(&mut l.eps, eps);
                // `clip_box`.
                let mut a = ld(&l.t_min);
                let mut b = _mm256_set1_ps(t_max);
                let mut inside = _mm256_cmp_ps::<_CMP_EQ_OQ>(one, one);
                let bounds = &self.bounds;
                for axis in 0..3 {
                    let (lo, hi) =
                        (_mm256_set1_ps(bounds.min[axis]), _mm256_set1_ps(bounds.max[axis]));
                    let parallel = _mm256_cmp_ps::<_CMP_EQ_OQ>(abs(inv[axis]), inf);
                    let out_slab = _mm256_or_ps(
                        _mm256_cmp_ps::<_CMP_LT_OQ>(o[axis], lo),
                        _mm256_cmp_ps::<_CMP_GT_OQ>(o[axis], hi),
                    );
                    inside = _mm256_andnot_ps(_mm256_and_ps(parallel, out_slab), inside);
                    let n = _mm256_mul_ps(_mm256_sub_ps(lo, o[axis]), inv[axis]);
                    let f = _mm256_mul_ps(_mm256_sub_ps(hi, o[axis]), inv[axis]);
                    let swap = _mm256_cmp_ps::<_CMP_GT_OQ>(n, f);
                    let (n, f) = (sel(swap, f, n), sel(swap, n, f));
                    let na = _mm256_max_ps(
                        a,
                        _mm256_sub_ps(_mm256_sub_ps(n, _mm256_mul_ps(abs(n), widen)), eps),
                    );
                    let fb = _mm256_min_ps(
                        b,
                        _mm256_add_ps(_mm256_add_ps(f, _mm256_mul_ps(abs(f), widen)), eps),
                    );
                    a = sel(parallel, a, na);
                    b = sel(parallel, b, fb);
                }
                st(t0, a);
                st(t1, b);
                for (axis, v) in inv.into_iter().enumerate() {
                    st(&mut l.inv[axis], v);
                }
                let ok = _mm256_and_ps(inside, _mm256_cmp_ps::<_CMP_LE_OQ>(a, b));
                alive |= (_mm256_movemask_ps(ok) as u32) << k;
            }
        }
        let mask = todo & alive;
        let mut m = mask;
        while m != 0 {
            let i = m.trailing_zeros() as usize;
            m &= m - 1;
            let v = |a: &[[f32; PACKET]; 4]| [a[0][i], a[1][i], a[2][i], 0.0];
            l.r[i] = PreparedRay {
                o: v(&l.o),
                d: v(&l.d),
                inv: v(&l.inv),
                kz: kz[i] as usize,
                sx: sx[i],
                sy: sy[i],
                sz: sz[i],
                wide: true,
            };
        }
        mask
    }

    /// One ray's single-ray walk of the subtree at `node`.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn walk_one<const AVX: bool>(
        &self,
        l: &Lanes,
        i: usize,
        node: u32,
        t0: f32,
        t1: f32,
        bt: &mut f32,
        b: &mut Best,
        stack: &mut traverse::Stack,
    ) {
        let r = &l.r[i];
        let (eps, t_min) = (l.eps[i], l.t_min[i]);
        match r.kz {
            0 => self.walk::<false, 0, AVX>(r, eps, t_min, node, t0, t1, bt, b, stack),
            1 => self.walk::<false, 1, AVX>(r, eps, t_min, node, t0, t1, bt, b, stack),
            _ => self.walk::<false, 2, AVX>(r, eps, t_min, node, t0, t1, bt, b, stack),
        }
    }

    /// [`Self::walk_packet`] compiled with AVX (the 8-wide leaf test inlined).
    ///
    /// # Safety
    /// The CPU must have AVX.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx")]
    #[allow(clippy::too_many_arguments)]
    unsafe fn walk_packet_avx(
        &self,
        l: &Lanes,
        mask: u32,
        t0: [f32; PACKET],
        t1: [f32; PACKET],
        best_t: &mut [f32; PACKET],
        best: &mut [Best; PACKET],
        scratch: &mut Scratch,
    ) {
        self.walk_packet::<true>(l, mask, t0, t1, best_t, best, scratch);
    }

    /// The packet traversal from the root (see the module doc).
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn walk_packet<const AVX: bool>(
        &self,
        l: &Lanes,
        mut mask: u32,
        mut t0: [f32; PACKET],
        mut t1: [f32; PACKET],
        best_t: &mut [f32; PACKET],
        best: &mut [Best; PACKET],
        scratch: &mut Scratch,
    ) {
        let Scratch { packet: stack, single } = scratch;
        let nodes: &[Node] = &self.nodes;
        let mut index = 0u32;
        loop {
            let node = nodes[index as usize];
            if mask & (mask - 1) == 0 {
                // One ray left: its own walk finishes this subtree.
                let i = mask.trailing_zeros() as usize;
                self.walk_one::<AVX>(
                    l,
                    i,
                    index,
                    t0[i],
                    t1[i],
                    &mut best_t[i],
                    &mut best[i],
                    single,
                );
            } else if node.is_leaf() {
                let mut m = mask;
                while m != 0 {
                    let i = m.trailing_zeros() as usize;
                    m &= m - 1;
                    let r = &l.r[i];
                    let (bt, b) = (&mut best_t[i], &mut best[i]);
                    match r.kz {
                        0 => self.leaf::<0, AVX>(r, node, l.t_min[i], bt, b),
                        1 => self.leaf::<1, AVX>(r, node, l.t_min[i], bt, b),
                        _ => self.leaf::<2, AVX>(r, node, l.t_min[i], bt, b),
                    };
                }
            } else {
                let axis = node.axis() & 3;
                let first = node.first_child();
                let Decision { lm, rm, rl, lt0, lt1, rt0, rt1 } =
                    decide::<AVX>(l, axis, node.split(), mask, &t0, &t1);
                let (left, right) = (first, first + 1);
                let lr = lm & rm & !rl;
                let mut push = |node: u32, mask: u32, a: [f32; PACKET], b: [f32; PACKET]| {
                    if mask != 0 {
                        stack.push(Entry { node, mask, t0: a, t1: b });
                    }
                };
                if rl == 0 {
                    // Left, then right.
                    if lm != 0 {
                        push(right, rm, rt0, rt1);
                        (index, mask, t0, t1) = (left, lm, lt0, lt1);
                    } else {
                        (index, mask, t0, t1) = (right, rm, rt0, rt1);
                    }
                } else if lr == 0 {
                    // Right, then left.
                    if rm != 0 {
                        push(left, lm, lt0, lt1);
                        (index, mask, t0, t1) = (right, rm, rt0, rt1);
                    } else {
                        (index, mask, t0, t1) = (left, lm, lt0, lt1);
                    }
                } else {
                    // Both orders: left for the left-first rays (and the left-only ones),
                    // right for all, left again for the right-first rays.
                    push(left, rl, lt0, lt1);
                    push(right, rm, rt0, rt1);
                    (index, mask, t0, t1) = (left, lm & !rl, lt0, lt1);
                }
                continue;
            }
            // Pop the next node some ray still needs: its interval starts before the ray's
            // best hit (each ray's single-ray test).
            loop {
                let Some(e) = stack.pop() else { return };
                let m = e.mask & starts_before::<AVX>(l, &e.t0, best_t);
                if m != 0 {
                    (index, mask, t0, t1) = (e.node, m, e.t0, e.t1);
                    break;
                }
            }
        }
    }
}

/// The rays' single-ray decisions at one split: which rays visit the left and the right
/// child (`lm`, `rm`), which of those visiting both go right first (`rl`), and each ray's
/// interval in each child.
struct Decision {
    lm: u32,
    rm: u32,
    rl: u32,
    lt0: [f32; PACKET],
    lt1: [f32; PACKET],
    rt0: [f32; PACKET],
    rt1: [f32; PACKET],
}

/// [`Decision`] for the rays of `mask` at the plane `split` on `axis` (`AVX`: eight rays at a
/// time; only inlined into a function compiled with AVX).
#[inline(always)]
fn decide<const AVX: bool>(
    l: &Lanes,
    axis: usize,
    split: f32,
    mask: u32,
    t0: &[f32; PACKET],
    t1: &[f32; PACKET],
) -> Decision {
    #[cfg(target_arch = "x86_64")]
    {
        if AVX {
            // SAFETY: `AVX` is true only where the CPU has AVX.
            return unsafe { decide_avx(l, axis, split, mask, t0, t1) };
        }
        decide_sse(l, axis, split, mask, t0, t1)
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        decide_scalar(l, axis, split, mask, t0, t1)
    }
}

/// [`decide`] one ray at a time, with the single-ray traversal's own branches (the portable
/// path, and the reference the SSE path is tested against).
#[cfg_attr(target_arch = "x86_64", allow(dead_code))]
fn decide_scalar(
    l: &Lanes,
    axis: usize,
    split: f32,
    mask: u32,
    t0: &[f32; PACKET],
    t1: &[f32; PACKET],
) -> Decision {
    let mut r = Decision { lm: 0, rm: 0, rl: 0, lt0: *t0, lt1: *t1, rt0: *t0, rt1: *t1 };
    for i in 0..PACKET {
        let (o, d) = (l.o[axis][i], l.d[axis][i]);
        let ts = (split - o) * l.inv[axis][i];
        let (a, b) = (t0[i], t1[i]);
        let e = l.eps[i] + ts.abs() * WIDEN;
        // (near?, far?, near's end, far's start and end); near starts at `a`.
        let (nv, fv, n1, f0, f1) = if ts.is_nan() {
            (true, true, b, a, b)
        } else if ts.is_infinite() {
            (true, false, b, a, b)
        } else if ts < 0.0 {
            (true, ts >= -e && a <= e, b, a, min(b, max(e, a)))
        } else if ts - e > b {
            (true, false, b, a, b)
        } else if ts + e < a {
            (false, true, b, a, b)
        } else {
            let c = min(max(ts, a), b);
            (true, true, c, c, b)
        };
        let bit = mask & (1 << i);
        let (nb, fb) = (if nv { bit } else { 0 }, if fv { bit } else { 0 });
        if o < split || (o == split && d > 0.0) {
            r.lm |= nb;
            r.rm |= fb;
            (r.lt1[i], r.rt0[i], r.rt1[i]) = (n1, f0, f1);
        } else {
            r.rm |= nb;
            r.lm |= fb;
            r.rl |= nb & fb;
            (r.rt1[i], r.lt0[i], r.lt1[i]) = (n1, f0, f1);
        }
    }
    r
}

/// [`decide_scalar`] four rays at a time with SSE: the same comparisons and arithmetic as
/// selects (the intervals can differ from the scalar path's only in the sign of a zero, which
/// no later comparison sees).
#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn decide_sse(
    l: &Lanes,
    axis: usize,
    split: f32,
    mask: u32,
    t0: &[f32; PACKET],
    t1: &[f32; PACKET],
) -> Decision {
    let mut r = Decision {
        lm: 0,
        rm: 0,
        rl: 0,
        lt0: [0.0; PACKET],
        lt1: [0.0; PACKET],
        rt0: [0.0; PACKET],
        rt1: [0.0; PACKET],
    };
    // SAFETY: SSE and SSE2 are part of the x86-64 baseline; every load and store reads or
    // writes four f32 inside an array of PACKET (a multiple of 4) at offset 0 or 4.
    unsafe {
        use std::arch::x86_64::*;
        let sel =
            |m: __m128, x: __m128, y: __m128| _mm_or_ps(_mm_and_ps(m, x), _mm_andnot_ps(m, y));
        let (zero, sp) = (_mm_setzero_ps(), _mm_set1_ps(split));
        let (inf, widen) = (_mm_set1_ps(f32::INFINITY), _mm_set1_ps(WIDEN));
        let sign = _mm_set1_ps(-0.0);
        let ones = _mm_cmpeq_ps(zero, zero);
        for h in 0..PACKET / 4 {
            let k = 4 * h;
            let ld = |a: &[f32; PACKET]| _mm_loadu_ps(a.as_ptr().add(k));
            let (o, d, inv) = (ld(&l.o[axis]), ld(&l.d[axis]), ld(&l.inv[axis]));
            let (a, b, eps) = (ld(t0), ld(t1), ld(&l.eps));
            let ts = _mm_mul_ps(_mm_sub_ps(sp, o), inv);
            let abs = _mm_andnot_ps(sign, ts);
            let e = _mm_add_ps(eps, _mm_mul_ps(abs, widen));
            let nan = _mm_cmpunord_ps(ts, ts);
            // Finite: neither NaN nor infinite.
            let regular = _mm_cmplt_ps(abs, inf);
            let neg = _mm_and_ps(regular, _mm_cmplt_ps(ts, zero));
            let pos = _mm_andnot_ps(_mm_cmplt_ps(ts, zero), regular);
            let beyond = _mm_cmpgt_ps(_mm_sub_ps(ts, e), b);
            let before = _mm_cmplt_ps(_mm_add_ps(ts, e), a);
            // Finite, not behind, not beyond the interval: "before" or straddling.
            let reach = _mm_andnot_ps(beyond, pos);
            let mid = _mm_andnot_ps(before, reach);
            let nv = _mm_xor_ps(_mm_and_ps(reach, before), ones);
            let grazing = _mm_and_ps(_mm_cmpge_ps(ts, _mm_xor_ps(e, sign)), _mm_cmple_ps(a, e));
            let fv = _mm_or_ps(_mm_or_ps(nan, _mm_and_ps(neg, grazing)), reach);
            let c = _mm_min_ps(_mm_max_ps(ts, a), b);
            let n1 = sel(mid, c, b);
            let f0 = sel(mid, c, a);
            let f1 = sel(neg, _mm_min_ps(b, _mm_max_ps(e, a)), b);
            let bf = _mm_or_ps(
                _mm_cmplt_ps(o, sp),
                _mm_and_ps(_mm_cmpeq_ps(o, sp), _mm_cmpgt_ps(d, zero)),
            );
            let bits = |m: __m128| (_mm_movemask_ps(m) as u32) << k;
            r.lm |= bits(sel(bf, nv, fv));
            r.rm |= bits(sel(bf, fv, nv));
            r.rl |= bits(_mm_andnot_ps(bf, _mm_and_ps(nv, fv)));
            let st = |dst: &mut [f32; PACKET], v: __m128| _mm_storeu_ps(dst.as_mut_ptr().add(k), v);
            st(&mut r.lt0, sel(bf, a, f0));
            st(&mut r.lt1, sel(bf, n1, f1));
            st(&mut r.rt0, sel(bf, f0, a));
            st(&mut r.rt1, sel(bf, f1, n1));
        }
    }
    r.lm &= mask;
    r.rm &= mask;
    r.rl &= mask;
    r
}

/// [`decide_sse`] eight rays at a time with AVX.
///
/// # Safety
/// The CPU must have AVX.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
#[inline]
unsafe fn decide_avx(
    l: &Lanes,
    axis: usize,
    split: f32,
    mask: u32,
    t0: &[f32; PACKET],
    t1: &[f32; PACKET],
) -> Decision {
    let mut r = Decision {
        lm: 0,
        rm: 0,
        rl: 0,
        lt0: [0.0; PACKET],
        lt1: [0.0; PACKET],
        rt0: [0.0; PACKET],
        rt1: [0.0; PACKET],
    };
    // SAFETY: AVX is available (the caller's contract); every load and store reads or writes
    // eight f32 at offset k < PACKET (a multiple of 8) of an array of PACKET.
    unsafe {
        use std::arch::x86_64::*;
        let sel = |m: __m256, x: __m256, y: __m256| _mm256_blendv_ps(y, x, m);
        let (zero, sp) = (_mm256_setzero_ps(), _mm256_set1_ps(split));
        let (inf, widen) = (_mm256_set1_ps(f32::INFINITY), _mm256_set1_ps(WIDEN));
        let sign = _mm256_set1_ps(-0.0);
        for k in (0..PACKET).step_by(8) {
            let ld = |a: &[f32; PACKET]| _mm256_loadu_ps(a.as_ptr().add(k));
            let (o, d, inv) = (ld(&l.o[axis]), ld(&l.d[axis]), ld(&l.inv[axis]));
            let (a, b, eps) = (ld(t0), ld(t1), ld(&l.eps));
            let ts = _mm256_mul_ps(_mm256_sub_ps(sp, o), inv);
            let abs = _mm256_andnot_ps(sign, ts);
            let e = _mm256_add_ps(eps, _mm256_mul_ps(abs, widen));
            let nan = _mm256_cmp_ps::<_CMP_UNORD_Q>(ts, ts);
            let regular = _mm256_cmp_ps::<_CMP_LT_OQ>(abs, inf);
            let below = _mm256_cmp_ps::<_CMP_LT_OQ>(ts, zero);
            let neg = _mm256_and_ps(regular, below);
            let pos = _mm256_andnot_ps(below, regular);
            let beyond = _mm256_cmp_ps::<_CMP_GT_OQ>(_mm256_sub_ps(ts, e), b);
            let before = _mm256_cmp_ps::<_CMP_LT_OQ>(_mm256_add_ps(ts, e), a);
            let reach = _mm256_andnot_ps(beyond, pos);
            let mid = _mm256_andnot_ps(before, reach);
            // Not near only when finite, ahead, within reach and before the interval.
            let far_only = _mm256_and_ps(reach, before);
            let grazing = _mm256_and_ps(
                _mm256_cmp_ps::<_CMP_GE_OQ>(ts, _mm256_xor_ps(e, sign)),
                _mm256_cmp_ps::<_CMP_LE_OQ>(a, e),
            );
            let fv = _mm256_or_ps(_mm256_or_ps(nan, _mm256_and_ps(neg, grazing)), reach);
            let c = _mm256_min_ps(_mm256_max_ps(ts, a), b);
            let n1 = sel(mid, c, b);
            let f0 = sel(mid, c, a);
            let f1 = sel(neg, _mm256_min_ps(b, _mm256_max_ps(e, a)), b);
            let bf = _mm256_or_ps(
                _mm256_cmp_ps::<_CMP_LT_OQ>(o, sp),
                _mm256_and_ps(
                    _mm256_cmp_ps::<_CMP_EQ_OQ>(o, sp),
                    _mm256_cmp_ps::<_CMP_GT_OQ>(d, zero),
                ),
            );
            let bits = |m: __m256| (_mm256_movemask_ps(m) as u32) << k;
            let (near, far, first) = (!bits(far_only), bits(fv), bits(bf));
            let lanes = 0xffu32 << k;
            let (near, far) = (near & lanes, far & lanes);
            r.lm |= (near & first) | (far & !first);
            r.rm |= (far & first) | (near & !first);
            r.rl |= near & far & !first;
            let st =
                |dst: &mut [f32; PACKET], v: __m256| _mm256_storeu_ps(dst.as_mut_ptr().add(k), v);
            st(&mut r.lt0, sel(bf, a, f0));
            st(&mut r.lt1, sel(bf, n1, f1));
            st(&mut r.rt0, sel(bf, f0, a));
            st(&mut r.rt1, sel(bf, f1, n1));
        }
    }
    r.lm &= mask;
    r.rm &= mask;
    r.rl &= mask;
    r
}

/// The rays whose pending interval starting at `t0` may still hold a hit no farther than their
/// best (the single-ray pop test; `AVX`: eight at once).
#[inline(always)]
fn starts_before<const AVX: bool>(l: &Lanes, t0: &[f32; PACKET], best_t: &[f32; PACKET]) -> u32 {
    #[cfg(target_arch = "x86_64")]
    if AVX {
        // SAFETY: `AVX` is true only where the CPU has AVX.
        return unsafe { starts_before_avx(l, t0, best_t) };
    }
    let mut m = 0u32;
    for i in 0..PACKET {
        let s = t0[i];
        if s - l.eps[i] - s.abs() * WIDEN <= best_t[i] {
            m |= 1 << i;
        }
    }
    m
}

/// [`starts_before`] with AVX.
///
/// # Safety
/// The CPU must have AVX.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
#[inline]
unsafe fn starts_before_avx(l: &Lanes, t0: &[f32; PACKET], best_t: &[f32; PACKET]) -> u32 {
    // SAFETY: AVX is available; each load reads eight f32 at offset k < PACKET (a multiple
    // of 8) of an array of PACKET.
    unsafe {
        use std::arch::x86_64::*;
        let mut m = 0u32;
        for k in (0..PACKET).step_by(8) {
            let s = _mm256_loadu_ps(t0.as_ptr().add(k));
            let abs = _mm256_andnot_ps(_mm256_set1_ps(-0.0), s);
            let lo = _mm256_sub_ps(
                _mm256_sub_ps(s, _mm256_loadu_ps(l.eps.as_ptr().add(k))),
                _mm256_mul_ps(abs, _mm256_set1_ps(WIDEN)),
            );
            let ok = _mm256_cmp_ps::<_CMP_LE_OQ>(lo, _mm256_loadu_ps(best_t.as_ptr().add(k)));
            m |= (_mm256_movemask_ps(ok) as u32) << k;
        }
        m
    }
}

#[cfg(all(test, target_arch = "x86_64"))]
mod tests {
    use proptest::prelude::*;

    use super::*;

    /// A plane-distance component: ordinary, on a grid (ties with the split), or special.
    fn value() -> impl Strategy<Value = f32> {
        prop_oneof![
            4 => -3.0f32..3.0,
            2 => (-3i32..=3).prop_map(|k| k as f32 * 0.5),
            1 => prop_oneof![
                Just(0.0f32),
                Just(-0.0),
                Just(f32::INFINITY),
                Just(f32::NEG_INFINITY),
                Just(1e-30),
            ],
        ]
    }

    fn component() -> impl Strategy<Value = f32> {
        prop_oneof![
            2 => -3.0f32..3.0,
            1 => prop_oneof![Just(0.0f32), Just(-0.0), Just(1e-30), Just(-2.5), Just(2.5)],
        ]
    }

    fn lanes() -> Lanes {
        let dummy = PreparedRay::new(&Ray::new(glam::Vec3::ZERO, glam::Vec3::X));
        Lanes {
            o: [[0.0; PACKET]; 4],
            d: [[0.0; PACKET]; 4],
            inv: [[0.0; PACKET]; 4],
            eps: [0.0; PACKET],
            t_min: [0.0; PACKET],
            r: [dummy; PACKET],
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 500, ..ProptestConfig::default() })]
        /// The AVX setup of a packet gives the scalar setup's lanes bit for bit: rays with
        /// zero, negative-zero and tiny direction components, origins on and off the box.
        #[test]
        fn vector_setup_matches_the_scalar_one(
            rays in proptest::collection::vec(proptest::option::of((
                (component(), component(), component()),
                (component(), component(), component()),
                prop_oneof![Just(0.0f32), 0.0f32..2.0],
            )), 0..=PACKET),
            t_max in prop_oneof![Just(f32::INFINITY), 0.0f32..5.0],
        ) {
            prop_assume!(crate::leaf::avx());
            let mesh = crate::test_util::city_block(1, 200);
            let tree = KdTree::build(&mesh, &crate::Settings::DEFAULT).unwrap();
            let (lo, hi) = tree.bounds().unwrap();
            let rays: Vec<Option<Ray>> = rays
                .into_iter()
                .map(|r| r.map(|((ox, oy, oz), (dx, dy, dz), t)| {
                    let o = lo + (hi - lo) * glam::Vec3::new(ox, oy, oz) / 3.0;
                    Ray::new(o, glam::Vec3::new(dx, dy, dz)).with_t_min(t)
                }))
                .collect();
            let (mut la, mut lb) = (lanes(), lanes());
            let (mut a0, mut a1, mut b0, mut b1) = ([0.0; PACKET], [0.0; PACKET], [0.0; PACKET], [0.0; PACKET]);
            let (mut oa, mut ob) = (vec![None; rays.len()], vec![None; rays.len()]);
            let ma = tree.setup(&rays, t_max, &mut oa, &mut la, &mut a0, &mut a1);
            // SAFETY: the CPU has AVX (assumed above).
            let mb = unsafe { tree.setup_avx(&rays, t_max, &mut ob, &mut lb, &mut b0, &mut b1) };
            prop_assert_eq!(ma, mb);
            prop_assert_eq!(oa, ob);
            let bits = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            for i in (0..PACKET).filter(|i| ma >> i & 1 == 1) {
                let (ra, rb) = (&la.r[i], &lb.r[i]);
                prop_assert_eq!(bits(&ra.o), bits(&rb.o));
                prop_assert_eq!(bits(&ra.d), bits(&rb.d));
                prop_assert_eq!(bits(&ra.inv), bits(&rb.inv));
                prop_assert_eq!(ra.kz, rb.kz);
                prop_assert_eq!(bits(&[ra.sx, ra.sy, ra.sz]), bits(&[rb.sx, rb.sy, rb.sz]));
                prop_assert_eq!(bits(&[la.eps[i], la.t_min[i], a0[i], a1[i]]), bits(&[lb.eps[i], lb.t_min[i], b0[i], b1[i]]));
                for axis in 0..3 {
                    prop_assert_eq!(
                        bits(&[la.o[axis][i], la.d[axis][i], la.inv[axis][i]]),
                        bits(&[lb.o[axis][i], lb.d[axis][i], lb.inv[axis][i]])
                    );
                }
            }
        }
    }

    /// The SSE packet path (every AVX step has an SSE twin) against single rays, bit for bit:
    /// the packet proptest exercises only the path of the CPU it runs on.
    #[test]
    fn sse_packets_agree_with_single_rays() {
        let mesh = crate::test_util::city_block(4, 1500);
        let tree = KdTree::build(&mesh, &crate::Settings::DEFAULT).unwrap();
        let cam = crate::test_util::Camera::over_city(&mesh);
        let mirror = crate::test_util::screen_mirror_rays(&tree, &mesh, &cam, 64, 48);
        let hemi = crate::test_util::screen_incoherent_rays(&tree, &mesh, &cam, 64, 48, 9);
        let mut scratch = Scratch::new();
        let bits = |h: Option<Hit>| {
            h.map(|h| (h.t.to_bits(), h.triangle, h.barycentrics.to_array().map(f32::to_bits)))
        };
        let mut checked = 0;
        for rays in [&mirror, &hemi] {
            for chunk in rays.chunks(PACKET) {
                let mut out = [None; PACKET];
                tree.packet_with(
                    chunk,
                    f32::INFINITY,
                    &mut out[..chunk.len()],
                    &mut scratch,
                    false,
                );
                for (r, h) in chunk.iter().zip(out) {
                    assert_eq!(
                        bits(h),
                        bits(r.and_then(|r| tree.intersect(&r, f32::INFINITY))),
                        "{r:?}"
                    );
                    checked += usize::from(h.is_some());
                }
            }
        }
        assert!(checked > 2000, "{checked} hits");
    }

    fn same(a: f32, b: f32) -> bool {
        a == b || (a.is_nan() && b.is_nan())
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 3000, ..ProptestConfig::default() })]
        /// The SSE and AVX decisions are the scalar one: the same masks, and for every ray
        /// in a child the same interval (up to the sign of a zero); and the pop test agrees.
        #[test]
        fn vector_decisions_match_the_scalar_one(
            o in proptest::collection::vec(value(), PACKET),
            d in proptest::collection::vec(value(), PACKET),
            ab in proptest::collection::vec((0.0f32..4.0, 0.0f32..4.0), PACKET),
            eps in 1e-7f32..1e-2,
            split in prop_oneof![Just(0.0f32), Just(0.5), -2.0f32..2.0],
            mask in any::<u32>(),
            best in proptest::collection::vec(0.0f32..4.0, PACKET),
            ties in proptest::collection::vec(0u32..5, PACKET),
        ) {
            let dummy = PreparedRay::new(&Ray::new(glam::Vec3::ZERO, glam::Vec3::X));
            let mut l = Lanes {
                o: [[0.0; PACKET]; 4],
                d: [[0.0; PACKET]; 4],
                inv: [[0.0; PACKET]; 4],
                eps: [eps; PACKET],
                t_min: [0.0; PACKET],
                r: [dummy; PACKET],
            };
            let (mut t0, mut t1) = ([0.0; PACKET], [0.0; PACKET]);
            for i in 0..PACKET {
                l.o[1][i] = o[i];
                l.d[1][i] = if d[i] == 0.0 || !d[i].is_finite() { d[i].signum() * 0.0 } else { d[i] };
                l.inv[1][i] = 1.0 / l.d[1][i];
                (t0[i], t1[i]) = (ab[i].0.min(ab[i].1), ab[i].0.max(ab[i].1));
                // Intervals ending exactly on a decision's threshold.
                let ts = (split - l.o[1][i]) * l.inv[1][i];
                let e = eps + ts.abs() * WIDEN;
                match ties[i] {
                    1 => t0[i] = e,
                    2 => t1[i] = ts - e,
                    3 => t0[i] = ts + e,
                    4 => t0[i] = -ts,
                    _ => {}
                }
                if !(t0[i] <= t1[i]) || !t0[i].is_finite() || !t1[i].is_finite() {
                    (t0[i], t1[i]) = (ab[i].0.min(ab[i].1), ab[i].0.max(ab[i].1));
                }
            }
            let mask = mask & ((1u64 << PACKET) - 1) as u32;
            let want = decide_scalar(&l, 1, split, mask, &t0, &t1);
            let best: [f32; PACKET] = std::array::from_fn(|i| best[i]);
            let want_pop = (0..PACKET)
                .filter(|&i| t0[i] - l.eps[i] - t0[i].abs() * WIDEN <= best[i])
                .fold(0u32, |m, i| m | 1 << i);
            let mut got = vec![(decide_sse(&l, 1, split, mask, &t0, &t1), starts_before::<false>(&l, &t0, &best))];
            if crate::leaf::avx() {
                // SAFETY: the CPU has AVX.
                got.push(unsafe { (decide_avx(&l, 1, split, mask, &t0, &t1), starts_before_avx(&l, &t0, &best)) });
            }
            for (g, pop) in got {
                prop_assert_eq!((g.lm, g.rm, g.rl), (want.lm, want.rm, want.rl));
                prop_assert_eq!(pop, want_pop);
                for i in 0..PACKET {
                    if g.lm >> i & 1 == 1 {
                        prop_assert!(same(g.lt0[i], want.lt0[i]) && same(g.lt1[i], want.lt1[i]), "left {}", i);
                    }
                    if g.rm >> i & 1 == 1 {
                        prop_assert!(same(g.rt0[i], want.rt0[i]) && same(g.rt1[i], want.rt1[i]), "right {}", i);
                    }
                }
            }
        }
    }
}
