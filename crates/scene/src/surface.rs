//! A material at a surface point: what its textures say there (base colour, metallic,
//! roughness, and the normal map's normal), for the renderers that shade on the CPU (the
//! traced hits, the reference). The G-buffer shader (`shaders/scene/gbuffer.wgsl`) reads the
//! same textures the same way, and the normal map's decoding has a WGSL twin
//! (`material_perturbed_normal` in `shaders/scene/material.inc.wgsl`, parity-tested).
//!
//! Normal maps are tangent-space maps as glTF defines them: a texel `rgb` holds the normal
//! `2 rgb - 1` in the frame (T, B, N) of the surface's unit tangent `T` (along +U, the
//! file's `TANGENT` or MikkTSpace's), its bitangent `B = w N x T` and its interpolated
//! normal `N`; `normal_scale` multiplies x and y (Mikkelsen, "Simulation of Wrinkled
//! Surfaces Revisited", 2008).

use crate::{Material, Texture, TextureId};
use glam::{Vec2, Vec3, Vec4};

/// Where a material's textures are read: the texture coordinates and the footprint's width
/// in texture-coordinate units (each texture's level of detail is `log2` of it in that
/// texture's texels; 0 reads the full-resolution level, bilinear), and the unit shading
/// normal and tangent frame the normal map perturbs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TextureLookup {
    pub uv: Vec2,
    pub footprint: f32,
    /// Unit interpolated shading normal.
    pub normal: Vec3,
    /// Unit tangent along +U, bitangent sign in `w`.
    pub tangent: Vec4,
}

/// A material's surface parameters at a point, its textures applied.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfacePoint {
    /// Base colour times the base-colour texture, in `[0, 1]`.
    pub base_color: Vec3,
    pub metallic: f32,
    pub roughness: f32,
    /// The unit shading normal, the normal map applied.
    pub normal: Vec3,
}

/// The shading normal `n` perturbed by a normal map's texel `texel` (stored `rgb`, so
/// `2 rgb - 1`, x and y times `scale`) in the frame of `tangent` (see the module doc); `n`
/// itself when the frame or the texel degenerates.
pub fn perturbed_normal(n: Vec3, tangent: Vec4, texel: Vec3, scale: f32) -> Vec3 {
    let m = texel * 2.0 - Vec3::ONE;
    let t = tangent.truncate();
    let b = tangent.w * n.cross(t);
    let p = t * (m.x * scale) + b * (m.y * scale) + n * m.z;
    p.try_normalize().filter(|p| p.is_finite()).unwrap_or(n)
}

impl Material {
    /// The material's surface at `at`, its textures read through `textures` (a texture id
    /// the closure does not resolve counts as absent): base colour times the base-colour
    /// texture, metallic and roughness times the metallic-roughness texture's blue and green
    /// channels, and the normal map's normal ([`perturbed_normal`]); trilinear at each
    /// texture's level of detail for `at.footprint`.
    pub fn at<'a>(
        &self,
        textures: impl Fn(TextureId) -> Option<&'a Texture>,
        at: &TextureLookup,
    ) -> SurfacePoint {
        let texel = |id: Option<TextureId>| {
            id.and_then(&textures).map(|t| {
                let texels = at.footprint * (t.width() as f32 * t.height() as f32).sqrt();
                t.sample_trilinear(at.uv, if texels > 0.0 { texels.log2() } else { 0.0 })
            })
        };
        let finite =
            |v: Vec4| if v.is_finite() { v.clamp(Vec4::ZERO, Vec4::ONE) } else { Vec4::ONE };
        let base = texel(self.albedo_texture).map_or(Vec4::ONE, finite);
        let mr = texel(self.metallic_roughness_texture).map_or(Vec4::ONE, finite);
        let normal = match texel(self.normal_texture) {
            Some(n) => perturbed_normal(at.normal, at.tangent, n.truncate(), self.normal_scale),
            None => at.normal,
        };
        SurfacePoint {
            base_color: (self.base_color * base.truncate()).clamp(Vec3::ZERO, Vec3::ONE),
            metallic: (self.metallic * mr.z).clamp(0.0, 1.0),
            roughness: (self.roughness * mr.y).clamp(0.0, 1.0),
            normal,
        }
    }

    /// Whether any texture changes the surface (base colour, metallic-roughness or normal
    /// map): renderers skip [`Material::at`] when none does.
    pub fn is_textured(&self) -> bool {
        self.albedo_texture.is_some()
            || self.metallic_roughness_texture.is_some()
            || self.normal_texture.is_some()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A flat texel (0.5, 0.5, 1) keeps the normal; a texel leaning along +x tilts it
    /// towards the tangent by the stored angle, towards the bitangent for +y, and the
    /// bitangent sign mirrors y.
    #[test]
    fn the_normal_map_tilts_the_normal_in_the_tangent_frame() {
        let (n, t) = (Vec3::Z, Vec4::new(1.0, 0.0, 0.0, 1.0));
        assert_eq!(perturbed_normal(n, t, Vec3::new(0.5, 0.5, 1.0), 1.0), n);
        // 45 degrees towards +x: (1, 0, 1)/sqrt2 stored as rgb = (m + 1) / 2.
        let s = std::f32::consts::FRAC_1_SQRT_2;
        let rgb = |m: Vec3| (m + Vec3::ONE) * 0.5;
        let p = perturbed_normal(n, t, rgb(Vec3::new(s, 0.0, s)), 1.0);
        assert!((p - Vec3::new(s, 0.0, s)).length() < 1e-6, "{p}");
        let p = perturbed_normal(n, t, rgb(Vec3::new(0.0, s, s)), 1.0);
        assert!((p - Vec3::new(0.0, s, s)).length() < 1e-6, "B = N x T = +y: {p}");
        let mirrored = perturbed_normal(n, t.with_w(-1.0), rgb(Vec3::new(0.0, s, s)), 1.0);
        assert!((mirrored - Vec3::new(0.0, -s, s)).length() < 1e-6, "w = -1: {mirrored}");
        // Scale 0 flattens the map; a zero texel ((0.5, 0.5, 0.5): m = 0) keeps n.
        assert!((perturbed_normal(n, t, rgb(Vec3::new(s, 0.0, s)), 0.0) - n).length() < 1e-6);
        assert_eq!(perturbed_normal(n, t, Vec3::splat(0.5), 1.0), n);
    }

    /// The textures multiply the factors channel by channel (base colour rgb, metallic by
    /// blue, roughness by green); an id the lookup does not resolve leaves the factor.
    #[test]
    fn textures_multiply_the_factors() {
        let one = |v: Vec4| Texture::from_linear("t", 1, 1, vec![v]).expect("a 1x1 texture");
        let textures = [one(Vec4::new(0.5, 0.25, 1.0, 1.0)), one(Vec4::new(0.0, 0.5, 0.25, 1.0))];
        let m = Material {
            albedo_texture: Some(TextureId(0)),
            metallic_roughness_texture: Some(TextureId(1)),
            ..Material::metallic_roughness("m", Vec3::new(0.8, 0.8, 0.4), 0.8, 0.6)
        };
        let at = TextureLookup {
            uv: Vec2::splat(0.5),
            footprint: 0.0,
            normal: Vec3::Y,
            tangent: Vec4::new(1.0, 0.0, 0.0, 1.0),
        };
        let p = m.at(|id| textures.get(id.index()), &at);
        assert!((p.base_color - Vec3::new(0.4, 0.2, 0.4)).length() < 1e-3, "{p:?}");
        assert!((p.metallic - 0.2).abs() < 1e-3 && (p.roughness - 0.3).abs() < 1e-3, "{p:?}");
        assert_eq!(p.normal, Vec3::Y);
        let untextured = m.at(|_| None, &at);
        assert_eq!((untextured.base_color, untextured.metallic), (m.base_color, m.metallic));
        assert!(m.is_textured() && !Material::default().is_textured());
    }
}
