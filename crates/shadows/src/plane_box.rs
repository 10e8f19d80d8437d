//! The `plane_box` test configuration and its sun-disk soft-shadow truth.
//!
//! A box standing on a ground plane under a sun of angular radius 0.004675 rad (Bruneton 2017 and
//! Hillaire 2020). The truth is the visible fraction of the sun disk from each receiver on
//! the plane, estimated by Monte Carlo over the disk against the box with an analytic ray-box
//! test ([`PlaneBox::reference_visibility`]). It stands behind one function boundary
//! ([`PlaneBox::reference_image`]) so that the workspace's `reference` renderer's component
//! render can later replace it.

use crate::depth_map::DepthMap;
use crate::error::ShadowError;
use crate::light_space::{LightBasis, ShadowView};
use crate::pcss::Receiver;
use crate::raster::rasterize;
use crate::taps::{TapPattern, taps};
use glam::{DVec3, Vec3};
use rayon::prelude::*;

/// Sun angular radius in radians (Bruneton 2017, Hillaire 2020).
pub const SUN_ANGULAR_RADIUS: f32 = 0.004675;

/// A box on a plane lit by the sun; the receivers are a square grid on the plane around the
/// box and its shadow.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlaneBox {
    /// The ground is the square `[-plane_half, plane_half]^2` at `y = 0`.
    pub plane_half: f32,
    pub box_min: Vec3,
    pub box_max: Vec3,
    /// Unit direction towards the sun.
    pub to_sun: Vec3,
    pub sun_angular_radius: f32,
    /// Receiver region on the plane: `[min.x, max.x] x [min.y, max.y]` in world (x, z).
    pub region_min: glam::Vec2,
    pub region_max: glam::Vec2,
}

impl PlaneBox {
    /// Checks the configuration: finite fields, a non-zero sun direction, a non-empty box
    /// and region, a non-negative sun radius. The other methods assume a valid
    /// configuration and panic (with this check's message) on an invalid one.
    pub fn validate(&self) -> Result<(), ShadowError> {
        let finite = self.plane_half.is_finite()
            && self.box_min.is_finite()
            && self.box_max.is_finite()
            && self.to_sun.is_finite()
            && self.sun_angular_radius.is_finite()
            && self.region_min.is_finite()
            && self.region_max.is_finite();
        if !finite {
            return Err(ShadowError::NonFinite("plane_box configuration"));
        }
        LightBasis::new(self.to_sun)?;
        if self.box_min.cmpge(self.box_max).any()
            || self.region_min.cmpge(self.region_max).any()
            || self.sun_angular_radius < 0.0
            || self.plane_half <= 0.0
        {
            return Err(ShadowError::Invariant(
                "plane_box: empty box/region or negative sizes".into(),
            ));
        }
        Ok(())
    }

    fn checked(&self) -> &Self {
        if let Err(e) = self.validate() {
            panic!("invalid PlaneBox: {e}");
        }
        self
    }

    /// A 1 x 3 x 1 m box on a 40 x 40 m plane, sun 35 degrees high; the 7 x 7 m receiver
    /// region holds the whole shadow (about 4.3 m long).
    pub const DEFAULT: Self = Self {
        plane_half: 20.0,
        box_min: Vec3::new(-0.5, 0.0, -0.5),
        box_max: Vec3::new(0.5, 3.0, 0.5),
        // elevation 35 deg, azimuth 200 deg: to_sun = (cos e cos a, sin e, cos e sin a).
        to_sun: Vec3::new(-0.769_751_4, 0.573_576_4, -0.280_166_3),
        sun_angular_radius: SUN_ANGULAR_RADIUS,
        region_min: glam::Vec2::new(-1.5, -2.5),
        region_max: glam::Vec2::new(5.5, 4.5),
    };

    /// Plane (2 triangles) then box (12 triangles; its bottom face lies on the plane).
    pub fn triangles(&self) -> Vec<[Vec3; 3]> {
        let h = self.plane_half;
        let p = [
            Vec3::new(-h, 0.0, -h),
            Vec3::new(h, 0.0, -h),
            Vec3::new(h, 0.0, h),
            Vec3::new(-h, 0.0, h),
        ];
        let mut t = vec![[p[0], p[1], p[2]], [p[0], p[2], p[3]]];
        let (a, b) = (self.box_min, self.box_max);
        let c = |i: usize| {
            Vec3::new(
                if i & 1 == 0 { a.x } else { b.x },
                if i & 2 == 0 { a.y } else { b.y },
                if i & 4 == 0 { a.z } else { b.z },
            )
        };
        for q in
            [[0, 1, 3, 2], [4, 6, 7, 5], [0, 4, 5, 1], [2, 3, 7, 6], [0, 2, 6, 4], [1, 5, 7, 3]]
        {
            t.push([c(q[0]), c(q[1]), c(q[2])]);
            t.push([c(q[0]), c(q[2]), c(q[3])]);
        }
        t
    }

    /// `n x n` receivers at the cell centres of the region, row-major (row 0 at min z).
    pub fn receivers(&self, n: u32) -> Vec<Vec3> {
        let (lo, hi) = (self.region_min, self.region_max);
        (0..n * n)
            .map(|i| {
                let (x, z) = ((i % n) as f32 + 0.5, (i / n) as f32 + 0.5);
                Vec3::new(
                    lo.x + (hi.x - lo.x) * x / n as f32,
                    0.0,
                    lo.y + (hi.y - lo.y) * z / n as f32,
                )
            })
            .collect()
    }

    /// A snapped orthographic view of `resolution` texels covering the region and the box.
    ///
    /// # Panics
    /// On an invalid configuration (see [`PlaneBox::validate`]).
    pub fn shadow_view(&self, resolution: u32) -> ShadowView {
        let basis = LightBasis::new(self.checked().to_sun).expect("validated");
        let lo = Vec3::new(self.region_min.x, 0.0, self.region_min.y).min(self.box_min);
        let hi = Vec3::new(self.region_max.x, 0.0, self.region_max.y).max(self.box_max);
        let c = ((lo + hi) * 0.5).as_dvec3();
        let r = ((hi - lo) * 0.5).length() as f64;
        ShadowView::fit_sphere(basis, c, r, resolution, 10.0, true)
    }

    /// Renders the depth map of the scene for `view` on the CPU.
    ///
    /// # Panics
    /// On an invalid configuration (see [`PlaneBox::validate`]) or a non-finite view.
    pub fn depth_map(&self, view: &ShadowView) -> DepthMap {
        self.checked();
        let mut map = DepthMap::new(view.resolution, view.resolution)
            .expect("a shadow view has a valid resolution");
        rasterize(&mut map, None, &view.view_proj_f64(), &self.triangles())
            .expect("finite matrix and sizes");
        map
    }

    /// The PCSS/PCF receivers of points on the plane for `view` (plane normal +Y).
    pub fn map_receivers(&self, view: &ShadowView, points: &[Vec3]) -> Vec<Receiver> {
        let n_light = (view.basis.world_to_light * DVec3::Y).as_vec3();
        let g =
            Receiver::ortho_gradient(n_light, view.texel_size as f32, view.depth_range() as f32);
        points
            .iter()
            .map(|p| {
                let m = view.world_to_map(p.as_dvec3());
                Receiver { x: m.x as f32, y: m.y as f32, depth: m.z as f32, gradient: g }
            })
            .collect()
    }

    /// Fraction of the sun disk visible from `p`: `samples` directions spread over the disk
    /// (golden-angle spiral, uniform in area) traced against the box (slab test).
    ///
    /// # Panics
    /// On an invalid configuration (see [`PlaneBox::validate`]).
    pub fn reference_visibility(&self, p: Vec3, samples: usize) -> f32 {
        let s = self.checked().to_sun.as_dvec3().normalize();
        let basis = LightBasis::new(self.to_sun).expect("validated");
        let m = basis.world_to_light.transpose();
        let (e1, e2) = (m.x_axis, m.y_axis);
        let tan_r = (self.sun_angular_radius as f64).tan();
        let disk = taps(TapPattern::Spiral, samples);
        let o = p.as_dvec3();
        let visible = disk
            .iter()
            .filter(|d| {
                let dir = (s + (e1 * d.x as f64 + e2 * d.y as f64) * tan_r).normalize();
                !ray_hits_box(o, dir, self.box_min.as_dvec3(), self.box_max.as_dvec3())
            })
            .count();
        visible as f32 / samples.max(1) as f32
    }

    /// The reference image over `n x n` receivers (row-major), in parallel, deterministic.
    /// Name it in reports as [`PlaneBox::reference_name`].
    pub fn reference_image(&self, n: u32, samples: usize) -> Vec<f32> {
        self.checked();
        self.receivers(n).par_iter().map(|&p| self.reference_visibility(p, samples)).collect()
    }

    /// `sun_disk_mc_ray_box_<samples>`.
    pub fn reference_name(samples: usize) -> String {
        format!("sun_disk_mc_ray_box_{samples}")
    }
}

/// Slab test: does the ray `o + t d`, `t > 1e-6`, hit the closed box?
pub fn ray_hits_box(o: DVec3, d: DVec3, lo: DVec3, hi: DVec3) -> bool {
    let inv = d.recip();
    let t0 = (lo - o) * inv;
    let t1 = (hi - o) * inv;
    // NaN (0 * inf) on an axis-parallel ray through a slab face is treated as inside.
    let tmin = t0.min(t1);
    let tmax = t0.max(t1);
    let near = [tmin.x, tmin.y, tmin.z].into_iter().filter(|v| !v.is_nan()).fold(1e-6, f64::max);
    let far =
        [tmax.x, tmax.y, tmax.z].into_iter().filter(|v| !v.is_nan()).fold(f64::INFINITY, f64::min);
    near <= far
}
