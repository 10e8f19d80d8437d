//! The plain-slice inputs (an RSM and a G-buffer) and the counters of what was skipped.

use crate::error::RsmGiError;
use glam::{Mat4, Vec2, Vec3};

const MAX_SIDE: u32 = 16_384;

fn check_size(what: &'static str, width: u32, height: u32) -> Result<(), RsmGiError> {
    if width == 0 || height == 0 || width > MAX_SIDE || height > MAX_SIDE {
        return Err(RsmGiError::BadSize { what, width, height });
    }
    Ok(())
}

fn check_len(what: &'static str, got: usize, width: u32, height: u32) -> Result<(), RsmGiError> {
    if got != width as usize * height as usize {
        return Err(RsmGiError::SizeMismatch { what, got, width, height });
    }
    Ok(())
}

/// Where a world point lands in the RSM: `world_to_texel.project_point3(p)` gives x, y in
/// texels from the map's top-left corner (texel `i` covers `[i, i + 1)`); z is unused.
/// For `shadows::ShadowView` it is the texel scale-and-flip times `view_proj`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RsmProjection {
    pub world_to_texel: Mat4,
}

impl RsmProjection {
    /// From a light's clip-space `view_proj` (x, y in -1..1, y up) and the map's size.
    pub fn from_view_proj(view_proj: Mat4, width: u32, height: u32) -> Self {
        let (w, h) = (width as f32, height as f32);
        let to_texel = Mat4::from_cols_array(&[
            0.5 * w,
            0.0,
            0.0,
            0.0, //
            0.0,
            -0.5 * h,
            0.0,
            0.0, //
            0.0,
            0.0,
            1.0,
            0.0, //
            0.5 * w,
            0.5 * h,
            0.0,
            1.0,
        ]);
        Self { world_to_texel: to_texel * view_proj }
    }

    /// Texel coordinates of a world point.
    #[inline]
    pub fn texel(&self, p: Vec3) -> Vec2 {
        self.world_to_texel.project_point3(p).truncate()
    }

    /// For an orthographic map (a sun's): the world area one texel covers on a plane facing
    /// the light, and the unit direction along which the map looks (either sign). From the
    /// rows of `world_to_texel` that give the texel's x and y: their cross product's length is
    /// texels per square metre. A degenerate projection gives `(0, 0)`.
    pub fn texel_footprint(&self) -> (f32, Vec3) {
        let m = self.world_to_texel;
        let rx = Vec3::new(m.x_axis.x, m.y_axis.x, m.z_axis.x);
        let ry = Vec3::new(m.x_axis.y, m.y_axis.y, m.z_axis.y);
        let c = rx.cross(ry);
        let len = c.length();
        if !(len > 0.0 && len.is_finite()) {
            return (0.0, Vec3::ZERO);
        }
        (1.0 / len, c / len)
    }
}

/// A reflective shadow map as three row-major planes of `width * height` texels (row 0 at
/// the top), as `shadows::Rsm` holds them: the flux each texel's surface reflects
/// (`light colour * albedo * texel cross-section`), its unit normal (facing the light) and
/// its world position. Texels no surface covers have a zero normal (or zero flux).
#[derive(Clone, Copy, Debug)]
pub struct RsmInput<'a> {
    pub width: u32,
    pub height: u32,
    pub flux: &'a [Vec3],
    pub normal: &'a [Vec3],
    pub position: &'a [Vec3],
    pub projection: RsmProjection,
}

impl RsmInput<'_> {
    /// Sizes and the projection checked (texel values are checked as they are read).
    pub fn validate(&self) -> Result<(), RsmGiError> {
        check_size("RSM", self.width, self.height)?;
        check_len("RSM flux", self.flux.len(), self.width, self.height)?;
        check_len("RSM normal", self.normal.len(), self.width, self.height)?;
        check_len("RSM position", self.position.len(), self.width, self.height)?;
        if !self.projection.world_to_texel.is_finite() {
            return Err(RsmGiError::NonFiniteMatrix("RSM projection"));
        }
        Ok(())
    }
}

/// The view's G-buffer: world position and normal per pixel (row-major, row 0 at the top),
/// and the camera's `view_proj` (world to clip, x right and y up in -1..1, w = view depth)
/// that made it. Pixels with a zero normal are background (not shaded, not counted as
/// bad).
#[derive(Clone, Copy, Debug)]
pub struct GBuffer<'a> {
    pub width: u32,
    pub height: u32,
    pub position: &'a [Vec3],
    pub normal: &'a [Vec3],
    pub view_proj: Mat4,
}

impl GBuffer<'_> {
    pub fn validate(&self) -> Result<(), RsmGiError> {
        check_size("G-buffer", self.width, self.height)?;
        check_len("G-buffer position", self.position.len(), self.width, self.height)?;
        check_len("G-buffer normal", self.normal.len(), self.width, self.height)?;
        if !self.view_proj.is_finite() {
            return Err(RsmGiError::NonFiniteMatrix("G-buffer view_proj"));
        }
        Ok(())
    }
}

/// What a pass did with its inputs. Non-finite values are skipped and counted here, never
/// propagated into the image.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Stats {
    /// Pixels shaded (finite position, non-zero finite normal, in front of the camera).
    pub shaded: u64,
    /// Background pixels (zero normal).
    pub background: u64,
    /// Pixels skipped for a non-finite position or normal (output zero).
    pub non_finite_pixels: u64,
    /// RSM texels skipped for a non-finite flux, normal or position.
    pub non_finite_texels: u64,
    /// VPLs the splat used (0 for the gather).
    pub vpls: u64,
    /// Low-resolution pixels no coarse neighbour could fill, evaluated at full resolution.
    pub fallback_pixels: u64,
}

/// A G-buffer pixel after the checks: world position, unit normal, view depth.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Pixel {
    pub position: Vec3,
    pub normal: Vec3,
    pub depth: f32,
}

/// The pixel's checked form, or why it is skipped.
pub(crate) enum PixelKind {
    Shaded(Pixel),
    Background,
    NonFinite,
}

pub(crate) fn classify(g: &GBuffer, i: usize) -> PixelKind {
    let (p, n) = (g.position[i], g.normal[i]);
    if !(p.is_finite() && n.is_finite()) {
        return PixelKind::NonFinite;
    }
    let Some(n) = n.try_normalize() else { return PixelKind::Background };
    let depth = (g.view_proj * p.extend(1.0)).w;
    if !(depth.is_finite() && depth > 0.0) {
        return PixelKind::Background;
    }
    PixelKind::Shaded(Pixel { position: p, normal: n, depth })
}

/// An RSM texel after the checks, the VPL already moved against its normal.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Texel {
    pub position: Vec3,
    pub normal: Vec3,
    pub flux: Vec3,
}

/// Every texel checked once: emitting texels moved by `offset` against their normal;
/// non-emitting or non-finite ones zero (a zero normal emits nothing). Returns the count of
/// non-finite texels.
pub(crate) fn prepare_texels(rsm: &RsmInput, offset: f32) -> (Vec<Texel>, u64) {
    let mut bad = 0;
    let texels = (0..rsm.flux.len())
        .map(|i| {
            let (p, n, f) = (rsm.position[i], rsm.normal[i], rsm.flux[i]);
            if !(p.is_finite() && n.is_finite() && f.is_finite()) {
                bad += 1;
                return Texel::default();
            }
            let f = f.max(Vec3::ZERO);
            match n.try_normalize() {
                Some(n) if f != Vec3::ZERO => {
                    Texel { position: p - n * offset, normal: n, flux: f }
                }
                _ => Texel::default(),
            }
        })
        .collect();
    (texels, bad)
}

/// Irradiance at `(x, n)` from a VPL (the point-to-point form factor of Dachsbacher &
/// Stamminger 2005, eq. 1, with radiant intensity `flux / pi cos`):
/// `flux max(0, n_p . (x - x_p)) max(0, n . (x_p - x)) / (pi |x - x_p|^4)`.
#[inline]
pub fn vpl_irradiance(x: Vec3, n: Vec3, vpl_position: Vec3, vpl_normal: Vec3, flux: Vec3) -> Vec3 {
    vpl_irradiance_area(x, n, vpl_position, vpl_normal, flux, 0.0)
}

/// [`vpl_irradiance`] from a VPL that is a disc of `area` (an RSM texel's surface): the
/// disc's form factor `area cos cos / (pi d² + area)` (exact on the disc's axis) instead of
/// the point's `area cos cos / (pi d²)`. Far away the two agree; near the disc the point's
/// grows without bound while the disc's stays below the texel's radiosity `flux / area`,
/// which is what keeps a wall next to a sunlit floor from gathering many times the light
/// the floor reflects. `area` 0 is the point.
#[inline]
pub fn vpl_irradiance_area(
    x: Vec3,
    n: Vec3,
    vpl_position: Vec3,
    vpl_normal: Vec3,
    flux: Vec3,
    area: f32,
) -> Vec3 {
    let d = x - vpl_position;
    let r2 = d.length_squared();
    let c = vpl_normal.dot(d).max(0.0) * n.dot(-d).max(0.0);
    if r2 <= 1e-12 || c <= 0.0 {
        return Vec3::ZERO;
    }
    flux * (c / (r2 * (std::f32::consts::PI * r2 + area.max(0.0))))
}

/// The surface area an RSM texel with unit normal `n` covers: the texel's footprint on a
/// plane facing the light over `|n . light|`, at most [`MAX_TEXEL_STRETCH`] footprints.
#[inline]
pub fn texel_area(footprint: f32, light: Vec3, n: Vec3) -> f32 {
    footprint / n.dot(light).abs().max(1.0 / MAX_TEXEL_STRETCH)
}

/// The most a grazing surface stretches an RSM texel's area (1 / the smallest cosine).
pub const MAX_TEXEL_STRETCH: f32 = 10.0;
