//! The PCSS filter as it was before the speed work (commit eb66cf9), frozen so the sweep can
//! race the current filter against it in one process (`gi_report::interleaved`). Same
//! arithmetic and tap tables as then; built from a current [`Pcss`]'s parameters and taps.

#![allow(dead_code)]

use glam::{IVec4, Vec2, Vec4};
use shadows::{DepthMap, Pcss, PcssParams, Receiver};

pub struct PcssV0 {
    params: PcssParams,
    taps: Vec<Vec2>,
}

impl PcssV0 {
    pub fn from_current(p: &Pcss) -> Self {
        Self { params: *p.params(), taps: p.taps().to_vec() }
    }

    #[inline(always)]
    fn bias(&self, r: &Receiver) -> f32 {
        self.params.constant_bias + self.params.slope_bias * r.gradient.length()
    }

    /// The reference depth of texel `(tx, ty)` is `c0 + gx * tx + gy * ty`: the receiver
    /// plane evaluated at the texel's centre (receiver-plane bias), or the receiver's own
    /// depth (`gx = gy = 0`); the bias is folded into `c0`.
    #[inline(always)]
    fn plane(&self, r: &Receiver) -> (f32, f32, f32) {
        let b = self.bias(r);
        if self.params.receiver_plane != 0 {
            let (gx, gy) = (r.gradient.x, r.gradient.y);
            (r.depth - b + gx * (0.5 - r.x) + gy * (0.5 - r.y), gx, gy)
        } else {
            (r.depth - b, 0.0, 0.0)
        }
    }

    #[inline(always)]
    fn texel(&self, x: f32, y: f32) -> (i32, i32) {
        let tx = (x.floor() as i32).clamp(0, self.params.width as i32 - 1);
        let ty = (y.floor() as i32).clamp(0, self.params.height as i32 - 1);
        (tx, ty)
    }

    /// True when a disk of `radius` texels around the receiver lies inside the map, so taps
    /// need neither `floor` (truncation equals it for non-negative values) nor clamping.
    #[inline(always)]
    fn inside(&self, r: &Receiver, radius: f32) -> bool {
        let radius = radius.abs();
        r.x - radius >= 0.0
            && r.y - radius >= 0.0
            && r.x + radius < self.params.width as f32 - 1.0
            && r.y + radius < self.params.height as f32 - 1.0
    }

    /// Fetches the stored depth and the reference depth of the texel under `(x, y)`.
    #[inline(always)]
    fn fetch<const FAST: bool>(
        &self,
        depth: &[f32],
        x: f32,
        y: f32,
        plane: (f32, f32, f32),
    ) -> (f32, f32) {
        let (tx, ty) = if FAST { (x as i32, y as i32) } else { self.texel(x, y) };
        let z = depth[ty as usize * self.params.width as usize + tx as usize];
        (z, plane.0 + plane.1 * tx as f32 + plane.2 * ty as f32)
    }

    /// The plain shadow test: 1 lit, 0 shadowed.
    pub fn hard(&self, map: &DepthMap, r: &Receiver) -> f32 {
        if !self.matches(map) {
            return 1.0;
        }
        let (z, zr) = self.fetch::<false>(map.as_slice(), r.x, r.y, self.plane(r));
        if z >= zr { 1.0 } else { 0.0 }
    }

    /// The map has the size the parameters were built for (otherwise everything is lit:
    /// a mismatched map is a caller error, never an out-of-bounds read).
    #[inline(always)]
    fn matches(&self, map: &DepthMap) -> bool {
        map.width() == self.params.width && map.height() == self.params.height
    }

    /// Four taps at once (the in-bounds fast path): the same operations in the same order
    /// as the scalar loop, so results are bit-identical to it. Returns, per lane, the
    /// stored and the reference depth.
    #[inline(always)]
    fn fetch4(
        &self,
        depth: &[f32],
        o: &[Vec2],
        r: &Receiver,
        radius: f32,
        plane: (f32, f32, f32),
    ) -> (Vec4, Vec4) {
        let ox = Vec4::new(o[0].x, o[1].x, o[2].x, o[3].x);
        let oy = Vec4::new(o[0].y, o[1].y, o[2].y, o[3].y);
        let x = Vec4::splat(r.x) + ox * radius;
        let y = Vec4::splat(r.y) + oy * radius;
        let (tx, ty) = (x.as_ivec4(), y.as_ivec4());
        let idx = ty * IVec4::splat(self.params.width as i32) + tx;
        let z = Vec4::new(
            depth[idx.x as usize],
            depth[idx.y as usize],
            depth[idx.z as usize],
            depth[idx.w as usize],
        );
        let zr = Vec4::splat(plane.0)
            + Vec4::splat(plane.1) * tx.as_vec4()
            + Vec4::splat(plane.2) * ty.as_vec4();
        (z, zr)
    }

    fn pcf_loop<const FAST: bool>(&self, depth: &[f32], r: &Receiver, radius: f32) -> f32 {
        let plane = self.plane(r);
        let start = self.params.blocker_taps as usize;
        let taps = &self.taps[start..start + self.params.pcf_taps as usize];
        let mut lit = 0u32;
        let mut taps = taps;
        if FAST {
            let mut chunks = taps.chunks_exact(4);
            for c in &mut chunks {
                let (z, zr) = self.fetch4(depth, c, r, radius, plane);
                lit += z.cmpge(zr).bitmask().count_ones();
            }
            taps = chunks.remainder();
        }
        for o in taps {
            let (z, zr) = self.fetch::<FAST>(depth, r.x + o.x * radius, r.y + o.y * radius, plane);
            lit += (z >= zr) as u32;
        }
        lit as f32 / self.params.pcf_taps as f32
    }

    /// PCF over the PCF taps scaled to `radius` texels: the lit fraction in `[0, 1]`.
    pub fn pcf(&self, map: &DepthMap, r: &Receiver, radius: f32) -> f32 {
        if !self.matches(map) {
            return 1.0;
        }
        if self.inside(r, radius) {
            self.pcf_loop::<true>(map.as_slice(), r, radius)
        } else {
            self.pcf_loop::<false>(map.as_slice(), r, radius)
        }
    }

    fn blocker_loop<const FAST: bool>(
        &self,
        depth: &[f32],
        r: &Receiver,
        radius: f32,
    ) -> (f32, u32) {
        let plane = self.plane(r);
        let mut sum = 0.0f32;
        let mut count = 0u32;
        let mut taps = &self.taps[..self.params.blocker_taps as usize];
        if FAST {
            let mut chunks = taps.chunks_exact(4);
            for c in &mut chunks {
                let (z, zr) = self.fetch4(depth, c, r, radius, plane);
                let closer = z.cmplt(zr);
                let m = closer.bitmask();
                // Sequential sum, as the scalar loop (adding 0.0 leaves a sum unchanged).
                let zs = Vec4::select(closer, z, Vec4::ZERO);
                sum += zs.x;
                sum += zs.y;
                sum += zs.z;
                sum += zs.w;
                count += m.count_ones();
            }
            taps = chunks.remainder();
        }
        for o in taps {
            let (z, zr) = self.fetch::<FAST>(depth, r.x + o.x * radius, r.y + o.y * radius, plane);
            let blocker = z < zr;
            sum += if blocker { z } else { 0.0 };
            count += blocker as u32;
        }
        (sum, count)
    }

    /// The blocker search radius in texels for a receiver at depth `z_r`.
    #[inline(always)]
    fn search_radius(&self, z_r: f32) -> f32 {
        let p = &self.params;
        let s = if p.perspective != 0 {
            if z_r > 0.0 { p.light_size * (z_r - p.near).max(0.0) / z_r } else { 0.0 }
        } else {
            p.light_size * z_r.max(0.0)
        };
        s.clamp(p.min_filter, p.max_filter)
    }

    /// Penumbra radius in texels from receiver and average blocker depth (never divides by
    /// zero: a blocker at the receiver gives zero).
    #[inline(always)]
    pub fn penumbra(&self, z_r: f32, z_b: f32) -> f32 {
        let p = &self.params;
        let dz = (z_r - z_b).max(0.0);
        let w = if p.perspective != 0 {
            if z_b > 0.0 && z_r > 0.0 { dz * p.light_size * p.near / (z_b * z_r) } else { 0.0 }
        } else {
            dz * p.light_size
        };
        w.clamp(p.min_filter, p.max_filter)
    }

    /// Percentage-closer soft shadow: the lit fraction in `[0, 1]`. A zero light size is
    /// exactly the plain shadow test.
    pub fn pcss(&self, map: &DepthMap, r: &Receiver) -> f32 {
        if self.params.light_size.is_nan() || self.params.light_size <= 0.0 {
            return self.hard(map, r);
        }
        if !self.matches(map) {
            return 1.0;
        }
        let radius = self.search_radius(r.depth);
        let depth = map.as_slice();
        let (sum, count) = if self.inside(r, radius) {
            self.blocker_loop::<true>(depth, r, radius)
        } else {
            self.blocker_loop::<false>(depth, r, radius)
        };
        if count == 0 {
            return 1.0;
        }
        let w = self.penumbra(r.depth, sum / count as f32);
        self.pcf(map, r, w)
    }
}
