//! Percentage-closer filtering and percentage-closer soft shadows (Fernando 2005) on the CPU
//! over a [`DepthMap`]; the WGSL twin is `shaders/shadows/pcss.inc.wgsl` (same arithmetic, same
//! tap tables, kept equal by a parity test).
//!
//! All lengths are in texels, all depths in the map's stored units. PCSS:
//! 1. blocker search: average the depths closer than the (biased) receiver inside a search
//!    disk; none means fully lit;
//! 2. penumbra estimate `w = (d_r - d_b) * light_size / d_b` (perspective, Fernando), or
//!    `w = (d_r - d_b) * light_size` for a directional light (`light_size` then being
//!    texels of penumbra radius per unit of stored depth, `tan(angular radius) * depth range
//!    / texel size`: the `d_b -> infinity` limit of the same similar triangles);
//! 3. PCF over a disk of radius `w`.
//!
//! The blocker depths are summed in four partial sums (tap `i` into sum `i mod 4`, total
//! `(s0 + s1) + (s2 + s3)`) on every path, CPU and WGSL: the CPU evaluates four taps per step
//! (`pcss_kernel`).
//!
//! Biases: a constant, a slope-scaled term `slope * |dz/dtexel|` (covers the nearest-texel
//! quantisation of a tilted receiver), and optionally the receiver-plane depth bias, which
//! compares every tap against the receiver's plane evaluated at the sampled texel's centre.

use crate::depth_map::DepthMap;
use crate::error::ShadowError;
use crate::light_space::ShadowView;
use crate::pcss_kernel::{self as kernel, Disk, Plane, TapLanes};
use crate::taps::{TapPattern, taps};
use glam::{Vec2, Vec3, Vec4};

/// Tap counts, pattern and biases (the user-facing knobs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PcssSettings {
    pub blocker_taps: u32,
    pub pcf_taps: u32,
    pub pattern: TapPattern,
    /// Depth bias in stored units.
    pub constant_bias: f32,
    /// Multiplies `|dz/dtexel|` (0.71 covers half a texel diagonal).
    pub slope_bias: f32,
    /// Compare taps against the receiver's plane instead of its centre depth.
    pub receiver_plane: bool,
    /// Smallest PCF radius in texels (keeps a texel-wide filter on contact shadows).
    pub min_filter_texels: f32,
    /// Largest search / PCF radius in texels.
    pub max_filter_texels: f32,
}

impl PcssSettings {
    pub const fn low() -> Self {
        Self { blocker_taps: 8, pcf_taps: 8, ..Self::DEFAULT }
    }
    /// 16 + 16 Poisson taps, receiver-plane bias.
    pub const DEFAULT: Self = Self {
        blocker_taps: 16,
        pcf_taps: 16,
        pattern: TapPattern::Poisson,
        constant_bias: 2e-5,
        slope_bias: 0.75,
        receiver_plane: true,
        min_filter_texels: 0.5,
        max_filter_texels: 64.0,
    };
    pub const fn high() -> Self {
        Self { blocker_taps: 32, pcf_taps: 32, ..Self::DEFAULT }
    }
    pub const fn reference() -> Self {
        Self { blocker_taps: 64, pcf_taps: 64, ..Self::DEFAULT }
    }

    pub fn validate(&self) -> Result<(), ShadowError> {
        let bad = |name, reason: String| Err(ShadowError::InvalidParameter { name, reason });
        if !(1..=256).contains(&self.blocker_taps) || !(1..=256).contains(&self.pcf_taps) {
            return bad(
                "taps",
                format!("must be in 1..=256, got {}+{}", self.blocker_taps, self.pcf_taps),
            );
        }
        for (name, v) in [
            ("constant_bias", self.constant_bias),
            ("slope_bias", self.slope_bias),
            ("min_filter_texels", self.min_filter_texels),
        ] {
            if !(v.is_finite() && v >= 0.0) {
                return bad(name, format!("must be finite and >= 0, got {v}"));
            }
        }
        if !(self.max_filter_texels.is_finite() && self.max_filter_texels >= self.min_filter_texels)
        {
            return bad(
                "max_filter_texels",
                format!("must be >= min_filter_texels, got {}", self.max_filter_texels),
            );
        }
        Ok(())
    }
}

impl Default for PcssSettings {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// The light model of the map: what `light_size` means.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LightModel {
    /// Orthographic map of a distant light (the sun). `light_size`: texels of penumbra
    /// radius per unit of stored depth.
    Directional { light_size: f32 },
    /// Perspective map with linear depth (Fernando 2005). `light_size`: light radius in
    /// texels at the near plane `near` (stored-depth units).
    Perspective { light_size: f32, near: f32 },
}

/// The flat parameter block shared with WGSL (`PcssParams` in `pcss.inc.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Default)]
#[cfg_attr(feature = "gpu", derive(bytemuck::Pod, bytemuck::Zeroable))]
pub struct PcssParams {
    pub light_size: f32,
    pub near: f32,
    /// 1: perspective model, 0: directional.
    pub perspective: u32,
    pub blocker_taps: u32,
    pub pcf_taps: u32,
    pub constant_bias: f32,
    pub slope_bias: f32,
    pub receiver_plane: u32,
    pub min_filter: f32,
    pub max_filter: f32,
    pub width: u32,
    pub height: u32,
}

const _: () = assert!(std::mem::size_of::<PcssParams>() == 48);

/// A ready-to-evaluate filter: parameters and tap tables (blocker taps first, then PCF taps,
/// the layout the GPU buffer uses).
#[derive(Clone, Debug, PartialEq)]
pub struct Pcss {
    params: PcssParams,
    taps: Vec<Vec2>,
    /// The blocker and PCF taps as lanes of four (the CPU fast path).
    blocker_lanes: TapLanes,
    pcf_lanes: TapLanes,
    /// `width * height <= 2^24`: texel indices can be formed exactly in `f32`.
    float_index: bool,
}

/// One receiver: map coordinates (texels), stored depth, and the receiver plane's depth
/// gradient per texel (`dz/dx, dz/dy`; zero when unknown). Shared with WGSL (20 bytes).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Default)]
#[cfg_attr(feature = "gpu", derive(bytemuck::Pod, bytemuck::Zeroable))]
pub struct Receiver {
    pub x: f32,
    pub y: f32,
    pub depth: f32,
    pub gradient: Vec2,
}

const _: () = assert!(std::mem::size_of::<Receiver>() == 20);

impl Receiver {
    /// The depth gradient per texel of a plane with unit normal `n_light` (light space:
    /// x right, y up, z towards the light) in an orthographic map, for a map whose texel is
    /// `texel_size` metres and whose stored depth spans `depth_range` metres. Map y grows
    /// downwards. Normals almost perpendicular to the light are clamped to `|n.z| >= 1e-4`.
    pub fn ortho_gradient(n_light: Vec3, texel_size: f32, depth_range: f32) -> Vec2 {
        let nz = if n_light.z.abs() < 1e-4 { 1e-4f32.copysign(n_light.z) } else { n_light.z };
        // Plane: z_light = z0 - (nx dx + ny dy) / nz; depth = (z_near - z_light)/range.
        let s = texel_size / depth_range / nz;
        Vec2::new(n_light.x * s, -n_light.y * s)
    }
}

impl Pcss {
    pub fn new(
        model: LightModel,
        settings: &PcssSettings,
        width: u32,
        height: u32,
    ) -> Result<Self, ShadowError> {
        settings.validate()?;
        let (light_size, near, perspective) = match model {
            LightModel::Directional { light_size } => (light_size, 0.0, 0),
            LightModel::Perspective { light_size, near } => (light_size, near, 1),
        };
        if !(light_size.is_finite() && light_size >= 0.0 && near.is_finite() && near >= 0.0) {
            return Err(ShadowError::InvalidParameter {
                name: "light model",
                reason: format!(
                    "light_size and near must be finite and >= 0, got {light_size}, {near}"
                ),
            });
        }
        let mut t = taps(settings.pattern, settings.blocker_taps as usize);
        let pcf = taps(settings.pattern, settings.pcf_taps as usize);
        let (blocker_lanes, pcf_lanes) = (TapLanes::new(&t), TapLanes::new(&pcf));
        t.extend(pcf);
        Ok(Self {
            blocker_lanes,
            pcf_lanes,
            float_index: width as u64 * height as u64 <= 1 << 24,
            params: PcssParams {
                light_size,
                near,
                perspective,
                blocker_taps: settings.blocker_taps,
                pcf_taps: settings.pcf_taps,
                constant_bias: settings.constant_bias,
                slope_bias: settings.slope_bias,
                receiver_plane: settings.receiver_plane as u32,
                min_filter: settings.min_filter_texels,
                max_filter: settings.max_filter_texels,
                width,
                height,
            },
            taps: t,
        })
    }

    /// The parameter block to upload as the `PcssParams` uniform.
    pub fn params(&self) -> &PcssParams {
        &self.params
    }

    /// The tap table to upload (`array<vec2<f32>>`): blocker taps, then PCF taps.
    pub fn taps(&self) -> &[Vec2] {
        &self.taps
    }

    /// PCSS for a sun of angular radius `angular_radius` (radians) over an orthographic
    /// shadow view.
    pub fn directional(
        view: &ShadowView,
        angular_radius: f32,
        settings: &PcssSettings,
    ) -> Result<Self, ShadowError> {
        if !(angular_radius.is_finite() && angular_radius >= 0.0) {
            return Err(ShadowError::InvalidParameter {
                name: "angular_radius",
                reason: format!("must be finite and >= 0, got {angular_radius}"),
            });
        }
        let light_size = (angular_radius as f64).tan() * view.depth_range() / view.texel_size;
        Self::new(
            LightModel::Directional { light_size: light_size as f32 },
            settings,
            view.resolution,
            view.resolution,
        )
    }

    #[inline(always)]
    fn bias(&self, r: &Receiver) -> f32 {
        self.params.constant_bias + self.params.slope_bias * r.gradient.length()
    }

    /// The reference depth of texel `(tx, ty)` is `c0 + gx * tx + gy * ty`: the receiver
    /// plane evaluated at the texel's centre (receiver-plane bias), or the receiver's own
    /// depth (`gx = gy = 0`); the bias is folded into `c0`.
    #[inline(always)]
    fn plane(&self, r: &Receiver) -> Plane {
        let b = self.bias(r);
        if self.params.receiver_plane != 0 {
            let (gx, gy) = (r.gradient.x, r.gradient.y);
            Plane { c0: r.depth - b + gx * (0.5 - r.x) + gy * (0.5 - r.y), gx, gy }
        } else {
            Plane { c0: r.depth - b, gx: 0.0, gy: 0.0 }
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

    /// Fetches (clamped to the edge) the stored depth and the reference depth of the texel
    /// under `(x, y)`.
    #[inline(always)]
    fn fetch(&self, depth: &[f32], x: f32, y: f32, plane: Plane) -> (f32, f32) {
        let (tx, ty) = self.texel(x, y);
        let z = depth[ty as usize * self.params.width as usize + tx as usize];
        (z, plane.c0 + plane.gx * tx as f32 + plane.gy * ty as f32)
    }

    /// The plain shadow test: 1 lit, 0 shadowed.
    pub fn hard(&self, map: &DepthMap, r: &Receiver) -> f32 {
        if !self.matches(map) {
            return 1.0;
        }
        let (z, zr) = self.fetch(map.as_slice(), r.x, r.y, self.plane(r));
        if z >= zr { 1.0 } else { 0.0 }
    }

    /// The map has the size the parameters were built for (otherwise everything is lit:
    /// a mismatched map is a caller error, never an out-of-bounds read).
    #[inline(always)]
    fn matches(&self, map: &DepthMap) -> bool {
        map.width() == self.params.width && map.height() == self.params.height
    }

    /// The filter disk of a receiver (fast path inputs).
    #[inline(always)]
    fn disk<'a>(&self, depth: &'a [f32], r: &Receiver, radius: f32, plane: Plane) -> Disk<'a> {
        Disk { depth, width: self.params.width, x: r.x, y: r.y, radius, plane }
    }

    /// Lit PCF taps over a disk of `radius` texels.
    #[inline(always)]
    fn pcf_count(&self, depth: &[f32], r: &Receiver, radius: f32, plane: Plane) -> u32 {
        if self.float_index && self.inside(r, radius) {
            return kernel::lit::<true>(&self.disk(depth, r, radius, plane), &self.pcf_lanes);
        }
        self.pcf_count_cold(depth, r, radius, plane)
    }

    /// The paths off the hot one (kept out of line so the hot loop keeps its registers):
    /// maps over 2^24 texels, and disks that reach the edge (clamped scalar taps).
    #[cold]
    #[inline(never)]
    fn pcf_count_cold(&self, depth: &[f32], r: &Receiver, radius: f32, plane: Plane) -> u32 {
        if self.inside(r, radius) {
            return kernel::lit::<false>(&self.disk(depth, r, radius, plane), &self.pcf_lanes);
        }
        let start = self.params.blocker_taps as usize;
        let taps = &self.taps[start..start + self.params.pcf_taps as usize];
        let mut lit = 0u32;
        for o in taps {
            let (z, zr) = self.fetch(depth, r.x + o.x * radius, r.y + o.y * radius, plane);
            lit += (z >= zr) as u32;
        }
        lit
    }

    /// PCF over the PCF taps scaled to `radius` texels: the lit fraction in `[0, 1]`.
    pub fn pcf(&self, map: &DepthMap, r: &Receiver, radius: f32) -> f32 {
        if !self.matches(map) {
            return 1.0;
        }
        let lit = self.pcf_count(map.as_slice(), r, radius, self.plane(r));
        lit as f32 / self.params.pcf_taps as f32
    }

    /// Blocker search over a disk of `radius` texels: the blocker depth total (four partial
    /// sums, see `pcss_kernel`) and the blocker count.
    #[inline(always)]
    fn blockers(&self, depth: &[f32], r: &Receiver, radius: f32, plane: Plane) -> (f32, u32) {
        if self.float_index && self.inside(r, radius) {
            let d = self.disk(depth, r, radius, plane);
            let (sum, count) = kernel::blockers::<true>(&d, &self.blocker_lanes);
            return (kernel::total(sum), count);
        }
        self.blockers_cold(depth, r, radius, plane)
    }

    /// The blocker search off the hot path (see [`Pcss::pcf_count_cold`]).
    #[cold]
    #[inline(never)]
    fn blockers_cold(&self, depth: &[f32], r: &Receiver, radius: f32, plane: Plane) -> (f32, u32) {
        if self.inside(r, radius) {
            let d = self.disk(depth, r, radius, plane);
            let (sum, count) = kernel::blockers::<false>(&d, &self.blocker_lanes);
            return (kernel::total(sum), count);
        }
        let mut part = [0.0f32; 4];
        let mut count = 0u32;
        for (i, o) in self.taps[..self.params.blocker_taps as usize].iter().enumerate() {
            let (z, zr) = self.fetch(depth, r.x + o.x * radius, r.y + o.y * radius, plane);
            let blocker = z < zr;
            part[i & 3] += if blocker { z } else { 0.0 };
            count += blocker as u32;
        }
        (kernel::total(Vec4::from_array(part)), count)
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
        let depth = map.as_slice();
        let plane = self.plane(r);
        let (sum, count) = self.blockers(depth, r, self.search_radius(r.depth), plane);
        if count == 0 {
            return 1.0;
        }
        let w = self.penumbra(r.depth, sum / count as f32);
        self.pcf_count(depth, r, w, plane) as f32 / self.params.pcf_taps as f32
    }
}
