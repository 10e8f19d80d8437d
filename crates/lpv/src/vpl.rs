//! The plain inputs: virtual point lights (from an RSM or a sky-lit G-buffer) and surfels
//! (for the geometry volume), and the sky-bounce VPL footprint compensation.

use glam::Vec3;

/// A virtual point light: a small diffuse (hemispherical) emitter.
///
/// `flux` is the RGB flux it reflects (W, or any consistent unit): for an RSM texel, the
/// texel's reflected flux `albedo * E_sun * texel_area`. It emits `flux / pi * max(0, n.w)`
/// per steradian, above its surface only. The `shadows` crate's RSM extraction produces the
/// same three fields.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Vpl {
    pub position: Vec3,
    /// Surface normal; need not be unit (it is normalised); a zero normal emits nothing.
    pub normal: Vec3,
    pub flux: Vec3,
}

impl Vpl {
    pub const fn new(position: Vec3, normal: Vec3, flux: Vec3) -> Self {
        Self { position, normal, flux }
    }

    /// The unit normal and the flux with negative components clamped to zero, or `None`
    /// when this VPL emits nothing or is not finite (such VPLs are skipped).
    pub fn sanitized(&self) -> Option<(Vec3, Vec3)> {
        if !(self.position.is_finite() && self.normal.is_finite() && self.flux.is_finite()) {
            return None;
        }
        let n = sh_math::normalize_dir(self.normal)?;
        let flux = self.flux.max(Vec3::ZERO);
        (flux != Vec3::ZERO).then_some((n, flux))
    }
}

/// A small piece of surface for the geometry volume: it blocks light that travels into its
/// front side. From an RSM texel (area = the texel's world-space area) or a G-buffer pixel
/// (area from [`pixel_footprint_area`]).
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Surfel {
    pub position: Vec3,
    pub normal: Vec3,
    /// World-space area (>= 0).
    pub area: f32,
}

impl Surfel {
    pub const fn new(position: Vec3, normal: Vec3, area: f32) -> Self {
        Self { position, normal, area }
    }
}

/// World-space area seen by one pixel of a perspective G-buffer at linear view depth
/// `depth`, for a vertical field of view `fov_y` (radians) over `height_px` pixel rows
/// (square pixels), on a surface whose normal makes cosine `n_dot_v` with the view ray.
///
/// This is the thesis's compensation for sky-bounce VPLs (Fig. 5.17): a VPL taken from a
/// G-buffer pixel stands for this much surface, so its flux is `radiosity * area`; without
/// it, near surfaces (many pixels) would bounce more light than far ones. `n_dot_v` is
/// clamped to at least 0.1 so grazing pixels do not explode. Returns 0 for non-finite or
/// non-positive depth, field of view or height.
pub fn pixel_footprint_area(depth: f32, fov_y: f32, height_px: u32, n_dot_v: f32) -> f32 {
    let ok = depth.is_finite()
        && depth > 0.0
        && fov_y.is_finite()
        && fov_y > 0.0
        && fov_y < std::f32::consts::PI
        && height_px > 0;
    if !ok {
        return 0.0;
    }
    let side = 2.0 * depth * (0.5 * fov_y).tan() / height_px as f32;
    let cos = if n_dot_v.is_finite() { n_dot_v.abs().clamp(0.1, 1.0) } else { 1.0 };
    side * side / cos
}

/// A sky-bounce VPL from a G-buffer pixel: position and normal of the pixel, flux =
/// `albedo * sky_irradiance * pixel_footprint_area(..)` (the irradiance from the sky volume
/// at that pixel; thesis 5.3.7).
#[allow(clippy::too_many_arguments)]
pub fn sky_bounce_vpl(
    position: Vec3,
    normal: Vec3,
    albedo: Vec3,
    sky_irradiance: Vec3,
    depth: f32,
    fov_y: f32,
    height_px: u32,
    n_dot_v: f32,
) -> Vpl {
    let area = pixel_footprint_area(depth, fov_y, height_px, n_dot_v);
    Vpl { position, normal, flux: albedo * sky_irradiance * area }
}
