//! A material at a surface point: what its textures and the vertex colour say there (base
//! colour, metallic, roughness, the normal map's normal, the occlusion and the emission), for
//! the renderers that shade on the CPU (the traced hits, the reference). The G-buffer shader
//! (`shaders/scene/gbuffer.wgsl`) reads the same textures the same way; the normal map's
//! decoding and the factors' products ([`surface_factors`]) have WGSL twins
//! (`material_perturbed_normal` and `material_surface_factors` in
//! `shaders/scene/material.inc.wgsl`, parity-tested).
//!
//! The products, each texel clamped to `[0, 1]` (a missing texture reads as white):
//! base colour `= factor x vertex colour x base-colour texture (rgb)`; metallic and
//! roughness `= factor x` the metallic-roughness texture's blue and green; occlusion
//! `= 1 + strength (ao - 1)` with `ao` the occlusion texture's red; emission `= factor x`
//! the emissive texture's rgb (see [`crate::material`] for what the occlusion scales).
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
    /// The interpolated vertex colour (linear RGB; white for a mesh without colours).
    pub color: Vec3,
}

/// A material's surface parameters at a point, its textures applied.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfacePoint {
    /// Base colour times the vertex colour times the base-colour texture, in `[0, 1]`.
    pub base_color: Vec3,
    pub metallic: f32,
    pub roughness: f32,
    /// The unit shading normal, the normal map applied.
    pub normal: Vec3,
    /// The share of the ambient light (sky, indirect) the point receives, in `[0, 1]`:
    /// `1 + strength (ao - 1)` (1 without an occlusion texture).
    pub occlusion: f32,
    /// Emitted radiance: the material's emission times its emissive texture.
    pub emission: Vec3,
}

/// What the factors of a material become at a point ([`surface_factors`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceFactors {
    pub base_color: Vec3,
    pub metallic: f32,
    pub roughness: f32,
    pub occlusion: f32,
    pub emission: Vec3,
}

/// The material's factors times what its textures and the vertex colour say at a point (the
/// module doc's products): `base` (base colour, metallic), `roughness`, `occlusion_strength`
/// and `emission` are the material's; `color` the vertex colour; the texels are the
/// base-colour, metallic-roughness, occlusion and emissive textures' (white where absent),
/// each clamped to `[0, 1]` (a non-finite one reads as white). The WGSL twin is
/// `material_surface_factors`.
#[allow(clippy::too_many_arguments)] // the factors and the texels, spelled out as in WGSL
pub fn surface_factors(
    base: Vec4,
    roughness: f32,
    occlusion_strength: f32,
    emission: Vec3,
    color: Vec3,
    base_texel: Vec4,
    mr_texel: Vec4,
    occlusion_texel: Vec4,
    emissive_texel: Vec4,
) -> SurfaceFactors {
    let unit = |v: Vec4| if v.is_finite() { v.clamp(Vec4::ZERO, Vec4::ONE) } else { Vec4::ONE };
    let (b, mr, ao, e) =
        (unit(base_texel), unit(mr_texel), unit(occlusion_texel), unit(emissive_texel));
    let color = if color.is_finite() { color.clamp(Vec3::ZERO, Vec3::ONE) } else { Vec3::ONE };
    SurfaceFactors {
        base_color: (base.truncate() * color * b.truncate()).clamp(Vec3::ZERO, Vec3::ONE),
        metallic: (base.w * mr.z).clamp(0.0, 1.0),
        roughness: (roughness * mr.y).clamp(0.0, 1.0),
        occlusion: (1.0 + occlusion_strength * (ao.x - 1.0)).clamp(0.0, 1.0),
        emission: emission * e.truncate(),
    }
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
    /// the closure does not resolve counts as absent): the products of the module doc
    /// ([`surface_factors`]) and the normal map's normal ([`perturbed_normal`]); trilinear at
    /// each texture's level of detail for `at.footprint`.
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
        let read = |id: Option<TextureId>| texel(id).unwrap_or(Vec4::ONE);
        let normal = match texel(self.normal_texture) {
            Some(n) => perturbed_normal(at.normal, at.tangent, n.truncate(), self.normal_scale),
            None => at.normal,
        };
        let f = surface_factors(
            self.base_color.extend(self.metallic),
            self.roughness,
            self.occlusion_strength,
            self.emission,
            at.color,
            read(self.albedo_texture),
            read(self.metallic_roughness_texture),
            read(self.occlusion_texture),
            read(self.emissive_texture),
        );
        SurfacePoint {
            base_color: f.base_color,
            metallic: f.metallic,
            roughness: f.roughness,
            normal,
            occlusion: f.occlusion,
            emission: f.emission,
        }
    }

    /// The surface without textures or vertex colour: the factors, `normal`, no occlusion.
    pub fn untextured(&self, normal: Vec3) -> SurfacePoint {
        SurfacePoint {
            base_color: self.base_color,
            metallic: self.metallic,
            roughness: self.roughness,
            normal,
            occlusion: 1.0,
            emission: self.emission,
        }
    }

    /// Whether any texture changes the surface (base colour, metallic-roughness, normal
    /// map, occlusion or emission): renderers skip [`Material::at`] when none does and the
    /// vertex colour is white.
    pub fn is_textured(&self) -> bool {
        self.albedo_texture.is_some()
            || self.metallic_roughness_texture.is_some()
            || self.normal_texture.is_some()
            || self.occlusion_texture.is_some()
            || self.emissive_texture.is_some()
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
            color: Vec3::ONE,
        };
        let p = m.at(|id| textures.get(id.index()), &at);
        assert!((p.base_color - Vec3::new(0.4, 0.2, 0.4)).length() < 1e-3, "{p:?}");
        assert!((p.metallic - 0.2).abs() < 1e-3 && (p.roughness - 0.3).abs() < 1e-3, "{p:?}");
        assert_eq!(p.normal, Vec3::Y);
        let untextured = m.at(|_| None, &at);
        assert_eq!((untextured.base_color, untextured.metallic), (m.base_color, m.metallic));
        assert!(m.is_textured() && !Material::default().is_textured());
    }

    /// The vertex colour multiplies the base colour; the occlusion texture's red channel
    /// gives `1 + strength (ao - 1)`; the emissive texture multiplies the emission; without
    /// them the point keeps the factors (white colour, occlusion 1, the emission).
    #[test]
    fn vertex_colour_occlusion_and_emissive_texture_apply_as_the_module_says() {
        let one = |v: Vec4| Texture::from_linear("t", 1, 1, vec![v]).expect("a 1x1 texture");
        let textures = [one(Vec4::new(0.2, 0.9, 0.9, 1.0)), one(Vec4::new(0.5, 0.25, 0.0, 1.0))];
        let m = Material {
            occlusion_texture: Some(TextureId(0)),
            occlusion_strength: 0.5,
            emissive_texture: Some(TextureId(1)),
            emission: Vec3::new(4.0, 2.0, 1.0),
            ..Material::diffuse("m", Vec3::new(0.8, 0.6, 0.4))
        };
        let at = TextureLookup {
            uv: Vec2::splat(0.5),
            footprint: 0.0,
            normal: Vec3::Y,
            tangent: Vec4::new(1.0, 0.0, 0.0, 1.0),
            color: Vec3::new(1.0, 0.5, 0.0),
        };
        let p = m.at(|id| textures.get(id.index()), &at);
        assert!((p.base_color - Vec3::new(0.8, 0.3, 0.0)).length() < 1e-6, "{p:?}");
        assert!((p.occlusion - 0.6).abs() < 1e-6, "1 + 0.5 (0.2 - 1): {p:?}");
        assert!((p.emission - Vec3::new(2.0, 0.5, 0.0)).length() < 1e-6, "{p:?}");
        let plain = m.at(|_| None, &TextureLookup { color: Vec3::ONE, ..at });
        assert_eq!(plain, m.untextured(Vec3::Y));
        assert!((plain.occlusion - 1.0).abs() < 1e-9 && plain.emission == m.emission);
    }
}
