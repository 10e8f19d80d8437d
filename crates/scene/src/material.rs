//! A surface material in glTF 2.0's metallic-roughness model ([`crate::brdf`]: base colour,
//! metallic, roughness), with what the ray tracer needs beyond it (transmission with an index
//! of refraction), its textures (base colour, metallic-roughness, a tangent-space normal map,
//! occlusion, emission; read at a surface point by [`crate::surface`]), an alpha-test mask
//! and emission.
//!
//! # Occlusion
//!
//! glTF's occlusion texture marks "areas that receive less indirect lighting": every
//! renderer scales the *ambient* light a surface point receives (the sky's light and the
//! indirect bounces, where screen-space ambient occlusion applies too) by
//! `1 + strength (ao - 1)` ([`crate::SurfacePoint::occlusion`]), never the direct light of
//! the sun, the point and spot lights or the emitters, nor the surface's own emission. The
//! reference's reading of it, for every vertex of a path, is in the `reference` crate's doc.
//!
//! # One surface model for every renderer
//!
//! A material reflects the share `1 - t` of the light (`t` its [`Material::transparency`])
//! by its [`crate::Brdf`] and transmits the share `t` through a smooth Fresnel dielectric
//! (reflected with the dielectric's Fresnel factor at [`Material::ior`], refracted
//! otherwise). The deferred lighting, the traced hits, the caches and the reference all
//! follow this split:
//!
//! - a **rough** surface (roughness at least [`crate::TRACED_ROUGHNESS`]) is lit through
//!   the whole BRDF ([`crate::Brdf::eval`]);
//! - a **smooth** one ([`crate::Brdf::is_smooth`]) is lit through its diffuse lobe
//!   ([`crate::Brdf::eval_diffuse`]) and its specular lobe is a traced mirror ray of RGB
//!   weight `(1 - t) F(n.v)` ([`Material::mirror_weight`]): the thesis's split between
//!   analytic lighting and the ray tracer;
//! - techniques that carry only diffuse light (reflective shadow maps, light propagation
//!   volumes, radiance caches) carry [`Material::diffuse_albedo`].
//!
//! The constructors [`Material::diffuse`], [`Material::glossy`], [`Material::mirror`] and
//! [`Material::glass`] take the thesis's Phong parameters (Table 3.1) and convert them once
//! ([`crate::PhongParams::to_metallic_roughness`]); [`Material::metallic_roughness`] takes
//! glTF's directly.

use crate::{PhongParams, SceneError, TextureId};
use glam::Vec3;

/// Index of a material in [`crate::Scene::materials`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct MaterialId(pub u32);

impl MaterialId {
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// Alpha testing: texels whose alpha is below `cutoff` are cut away (leaves, fences).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AlphaMask {
    /// The texture whose alpha channel is tested (usually the albedo texture).
    pub texture: TextureId,
    /// In (0, 1].
    pub cutoff: f32,
}

/// A surface material.
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    pub name: String,
    /// glTF's base colour, linear RGB in [0, 1] ([`crate::brdf`]): the diffuse colour of a
    /// dielectric and the specular colour of a metal. Multiplied by `albedo_texture`.
    pub base_color: Vec3,
    /// glTF's metallic factor in [0, 1].
    pub metallic: f32,
    /// glTF's perceptual roughness in [0, 1] (`alpha = roughness^2`); below
    /// [`crate::TRACED_ROUGHNESS`] the specular reflection is ray traced.
    pub roughness: f32,
    /// glTF's base-colour texture: multiplies `base_color` (linear RGB after sRGB decoding).
    pub albedo_texture: Option<TextureId>,
    /// glTF's metallic-roughness texture (linear): its green channel multiplies `roughness`,
    /// its blue channel `metallic`.
    pub metallic_roughness_texture: Option<TextureId>,
    /// Tangent-space normal map (stored linear, `rgb * 2 - 1`), in the mesh's MikkTSpace
    /// tangent frame ([`crate::perturbed_normal`]).
    pub normal_texture: Option<TextureId>,
    /// glTF's `normalTexture.scale`: multiplies the normal map's x and y (1: as stored).
    pub normal_scale: f32,
    /// glTF's occlusion texture (linear): its red channel `ao` scales the ambient light the
    /// surface receives by `1 + occlusion_strength (ao - 1)` (module doc).
    pub occlusion_texture: Option<TextureId>,
    /// glTF's `occlusionTexture.strength` in `[0, 1]` (1: as stored, 0: no occlusion).
    pub occlusion_strength: f32,
    /// glTF's emissive texture (sRGB, decoded to linear): multiplies `emission`.
    pub emissive_texture: Option<TextureId>,
    /// Share of light transmitted through a smooth dielectric, [0, 1] (ray traced).
    pub transparency: f32,
    /// Index of refraction of the transmitting medium, >= 1.
    pub ior: f32,
    pub alpha_mask: Option<AlphaMask>,
    /// Emitted radiance, linear RGB, >= 0 (glTF's emissive factor times its strength);
    /// multiplied by `emissive_texture` where there is one, so it bounds the emission of
    /// every point of the surface.
    pub emission: Vec3,
    /// Rendered from both sides (tree cards, thin panes).
    pub double_sided: bool,
}

impl Default for Material {
    fn default() -> Self {
        Self::diffuse("default", Vec3::splat(0.5))
    }
}

/// Reflectivity or transparency at or below this is treated as none when deciding what the
/// scene needs (a 1% mirror is not worth ray tracing).
pub const RAY_TRACE_THRESHOLD: f32 = 0.01;

impl Material {
    /// A matte material: a rough dielectric (roughness 1) of base colour `albedo`.
    pub fn diffuse(name: impl Into<String>, albedo: Vec3) -> Self {
        Self::metallic_roughness(name, albedo, 0.0, 1.0)
    }

    /// A material of the thesis's Phong model (albedo, glossiness `g`, Phong power, mirror
    /// reflectivity), converted once by [`PhongParams::to_metallic_roughness`].
    pub fn phong(name: impl Into<String>, phong: PhongParams) -> Self {
        let (base_color, metallic, roughness) = phong.to_metallic_roughness();
        Self {
            transparency: phong.transparency,
            ..Self::metallic_roughness(name, base_color, metallic, roughness)
        }
    }

    /// The thesis's glossy material: Lambert `(1 - g) albedo` plus a Phong lobe of weight
    /// `glossiness` and exponent `power`, converted to metallic-roughness.
    pub fn glossy(name: impl Into<String>, albedo: Vec3, glossiness: f32, power: f32) -> Self {
        Self::phong(
            name,
            PhongParams {
                albedo,
                glossiness,
                specular_power: power,
                reflectivity: 0.0,
                transparency: 0.0,
            },
        )
    }

    /// A mirror reflecting `reflectivity` of the light: a smooth grey metal.
    pub fn mirror(name: impl Into<String>, reflectivity: f32) -> Self {
        Self::metallic_roughness(name, Vec3::splat(reflectivity), 1.0, 0.0)
    }

    /// Clear glass: the share `transparency` transmitted (and reflected by the dielectric's
    /// Fresnel factor at `ior`), the rest a smooth dark dielectric.
    pub fn glass(name: impl Into<String>, transparency: f32, ior: f32) -> Self {
        Self {
            transparency,
            ior,
            double_sided: true,
            ..Self::metallic_roughness(name, Vec3::splat(0.02), 0.0, 0.0)
        }
    }

    /// A pure emitter that also reflects diffusely.
    pub fn emissive(name: impl Into<String>, albedo: Vec3, emission: Vec3) -> Self {
        Self { emission, ..Self::diffuse(name, albedo) }
    }

    /// A material of glTF's metallic-roughness model.
    pub fn metallic_roughness(
        name: impl Into<String>,
        base_color: Vec3,
        metallic: f32,
        roughness: f32,
    ) -> Self {
        Self {
            name: name.into(),
            base_color,
            metallic,
            roughness,
            albedo_texture: None,
            metallic_roughness_texture: None,
            normal_texture: None,
            normal_scale: 1.0,
            occlusion_texture: None,
            occlusion_strength: 1.0,
            emissive_texture: None,
            transparency: 0.0,
            ior: 1.5,
            alpha_mask: None,
            emission: Vec3::ZERO,
            double_sided: false,
        }
    }

    /// The BRDF of this material (before textures).
    pub fn brdf(&self) -> crate::Brdf {
        crate::Brdf::new(self.base_color, self.metallic, self.roughness)
    }

    /// The diffuse reflectance that techniques carrying only diffuse light use (reflective
    /// shadow maps, light propagation volumes, radiance caches): `(1 - t) c (1 - m)`, the
    /// BRDF's diffuse colour over the reflected share (before textures).
    pub fn diffuse_albedo(&self) -> Vec3 {
        self.brdf().diffuse_color() * (1.0 - self.transparency).max(0.0)
    }

    /// The RGB weight of the traced mirror ray at the cosine `n_dot_v` between the shading
    /// normal and the viewer: `(1 - t) F(n.v)` for a smooth surface, zero for a rough one
    /// (see the module doc).
    pub fn mirror_weight(&self, n_dot_v: f32) -> Vec3 {
        let b = self.brdf();
        if !b.is_smooth() {
            return Vec3::ZERO;
        }
        crate::brdf::specular_reflectance(b.f0(), n_dot_v) * (1.0 - self.transparency).max(0.0)
    }

    /// True when the material's specular reflection is traced and worth tracing: smooth, with
    /// a normal-incidence mirror weight above [`RAY_TRACE_THRESHOLD`].
    pub fn is_mirror(&self) -> bool {
        self.mirror_weight(1.0).max_element() > RAY_TRACE_THRESHOLD
    }

    pub fn is_transparent(&self) -> bool {
        self.transparency > RAY_TRACE_THRESHOLD
    }

    pub fn is_emissive(&self) -> bool {
        self.emission.max_element() > 0.0
    }

    /// Checks ranges and texture references (`texture_count` textures exist).
    pub fn validate(&self, texture_count: usize) -> Result<(), SceneError> {
        let el = || format!("material \"{}\"", self.name);
        let unit = |v: f32, what: &str| {
            if (0.0..=1.0).contains(&v) {
                Ok(())
            } else {
                Err(SceneError::invalid(el(), format!("{what} {v} outside [0, 1]")))
            }
        };
        if !self.base_color.is_finite()
            || self.base_color.min_element() < 0.0
            || self.base_color.max_element() > 1.0
        {
            return Err(SceneError::invalid(
                el(),
                format!("base colour {} outside [0, 1]", self.base_color),
            ));
        }
        unit(self.metallic, "metallic")?;
        unit(self.roughness, "roughness")?;
        unit(self.transparency, "transparency")?;
        if !(self.ior >= 1.0 && self.ior.is_finite()) {
            return Err(SceneError::invalid(el(), format!("index of refraction {}", self.ior)));
        }
        if !self.emission.is_finite() || self.emission.min_element() < 0.0 {
            return Err(SceneError::invalid(el(), format!("emission {}", self.emission)));
        }
        let tex = |t: Option<TextureId>, what: &str| match t {
            Some(t) if t.index() >= texture_count => Err(SceneError::invalid(
                el(),
                format!("{what} texture {} does not exist ({texture_count} textures)", t.0),
            )),
            _ => Ok(()),
        };
        tex(self.albedo_texture, "albedo")?;
        tex(self.normal_texture, "normal")?;
        tex(self.metallic_roughness_texture, "metallic-roughness")?;
        tex(self.occlusion_texture, "occlusion")?;
        tex(self.emissive_texture, "emissive")?;
        unit(self.occlusion_strength, "occlusion strength")?;
        if !self.normal_scale.is_finite() {
            return Err(SceneError::invalid(el(), format!("normal scale {}", self.normal_scale)));
        }
        if let Some(m) = self.alpha_mask {
            tex(Some(m.texture), "alpha mask")?;
            if !(m.cutoff > 0.0 && m.cutoff <= 1.0) {
                return Err(SceneError::invalid(el(), format!("alpha cutoff {}", m.cutoff)));
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::Material;
    use glam::Vec3;

    /// The thesis's constructors keep what they reflect: a matte surface its albedo as the
    /// diffuse colour, a mirror its reflectivity as a traced mirror weight, glass its
    /// transmitted share; a rough metal is not traced, a smooth gold one traces gold.
    #[test]
    fn constructors_split_the_light_as_the_module_says() {
        let red = Vec3::new(0.8, 0.1, 0.05);
        let matte = Material::diffuse("matte", red);
        assert_eq!(matte.diffuse_albedo(), red);
        assert_eq!(matte.mirror_weight(1.0), Vec3::ZERO);
        assert!(!matte.is_mirror());
        let mirror = Material::mirror("mirror", 0.95);
        assert!(mirror.is_mirror());
        assert!((mirror.mirror_weight(1.0) - Vec3::splat(0.95)).abs().max_element() < 1e-6);
        assert_eq!(mirror.diffuse_albedo(), Vec3::ZERO);
        let glass = Material::glass("glass", 0.7, 1.5);
        assert!(glass.is_transparent());
        assert!((glass.mirror_weight(1.0) - Vec3::splat(0.3 * 0.04)).abs().max_element() < 1e-6);
        let gold = Vec3::new(1.0, 0.78, 0.34);
        assert_eq!(Material::metallic_roughness("gold", gold, 1.0, 0.1).mirror_weight(1.0), gold);
        assert_eq!(
            Material::metallic_roughness("rough", gold, 1.0, 0.5).mirror_weight(1.0),
            Vec3::ZERO
        );
        // Grazing: the mirror weight rises to 1 (Schlick).
        let w = Material::metallic_roughness("plastic", red, 0.0, 0.0).mirror_weight(0.0);
        assert!((w - Vec3::ONE).abs().max_element() < 1e-6, "{w}");
    }
}
