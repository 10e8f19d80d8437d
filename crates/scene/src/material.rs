//! A surface material: glTF 2.0's metallic-roughness parameters (base colour, metallic,
//! roughness: the model of [`crate::brdf`]) beside the thesis's Phong parameters of its
//! G-buffer (Table 3.1: albedo, glossiness, Phong power) that the renderers not yet moved to
//! [`crate::brdf`] still read, plus what the ray tracer needs (mirror reflectivity,
//! transparency with an index of refraction), a tangent-space normal map, an alpha-test mask,
//! and emission.
//!
//! The two sets describe one surface: the constructors ([`Material::diffuse`],
//! [`Material::glossy`], [`Material::mirror`], [`Material::glass`]) take the thesis's
//! parameters and derive the metallic-roughness ones by
//! [`crate::PhongParams::to_metallic_roughness`]; a caller that edits the Phong fields calls
//! [`Material::with_phong_converted`] to derive them again, and a loader of glTF sets both
//! (the glTF parameters read directly).

use crate::{SceneError, TextureId};
use glam::Vec3;

/// The specular lobe of the model, energy-normalised Phong: `(n + 2) / (2 pi) cos^n` at
/// the cosine `cos_r` between the mirror direction and the light, zero behind (a material's
/// specular BRDF is its glossiness times this). The renderers not yet moved to
/// [`crate::brdf`] evaluate it here; the WGSL twin is `base_brdf_cos` in
/// `shaders/engine/lighting.wgsl`.
pub fn phong_lobe(power: f32, cos_r: f32) -> f32 {
    if cos_r > 0.0 { (power + 2.0) / (2.0 * std::f32::consts::PI) * cos_r.powf(power) } else { 0.0 }
}

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
    /// Diffuse reflectivity of the thesis's Phong model, linear RGB in [0, 1].
    pub albedo: Vec3,
    /// Multiplies `albedo` (linear RGB after sRGB decoding).
    pub albedo_texture: Option<TextureId>,
    /// Specular intensity in [0, 1] (G-buffer alpha of the colour target).
    pub glossiness: f32,
    /// Phong exponent, >= 1.
    pub specular_power: f32,
    /// Tangent-space normal map (stored linear, `rgb * 2 - 1`).
    pub normal_texture: Option<TextureId>,
    /// Fraction of light reflected as a sharp mirror reflection, [0, 1] (ray traced).
    pub reflectivity: f32,
    /// Fraction of light transmitted (refracted), [0, 1] (ray traced).
    pub transparency: f32,
    /// Index of refraction of the transmitting medium, >= 1.
    pub ior: f32,
    pub alpha_mask: Option<AlphaMask>,
    /// Emitted radiance, linear RGB, >= 0.
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
    /// A matte material.
    pub fn diffuse(name: impl Into<String>, albedo: Vec3) -> Self {
        Self {
            name: name.into(),
            base_color: albedo,
            metallic: 0.0,
            roughness: 1.0,
            albedo,
            albedo_texture: None,
            glossiness: 0.0,
            specular_power: 1.0,
            normal_texture: None,
            reflectivity: 0.0,
            transparency: 0.0,
            ior: 1.5,
            alpha_mask: None,
            emission: Vec3::ZERO,
            double_sided: false,
        }
    }

    /// A glossy material with a Phong lobe.
    pub fn glossy(name: impl Into<String>, albedo: Vec3, glossiness: f32, power: f32) -> Self {
        Self { glossiness, specular_power: power, ..Self::diffuse(name, albedo) }
            .with_phong_converted()
    }

    /// A mirror with the given reflectivity.
    pub fn mirror(name: impl Into<String>, reflectivity: f32) -> Self {
        Self {
            reflectivity,
            glossiness: 1.0,
            specular_power: 2048.0,
            ..Self::diffuse(name, Vec3::splat(0.02))
        }
        .with_phong_converted()
    }

    /// Clear glass: mostly transmitted, some reflected.
    pub fn glass(name: impl Into<String>, transparency: f32, ior: f32) -> Self {
        Self {
            transparency,
            ior,
            reflectivity: 0.08,
            glossiness: 1.0,
            specular_power: 1024.0,
            double_sided: true,
            ..Self::diffuse(name, Vec3::splat(0.02))
        }
        .with_phong_converted()
    }

    /// A pure emitter that also reflects diffusely.
    pub fn emissive(name: impl Into<String>, albedo: Vec3, emission: Vec3) -> Self {
        Self { emission, ..Self::diffuse(name, albedo) }
    }

    /// A material of glTF's metallic-roughness model. The Phong fields that the renderers not
    /// yet moved to [`crate::brdf`] read are derived as follows (`c` base colour, `m`
    /// metallic, `r` roughness, `a = r^2`, `t` the metal's [`rough_share`]): albedo =
    /// `c (1 - m) + c m t`; glossiness = `mix(0.04, max(c), m (1 - t))`; specular power =
    /// `2 / a^2 - 2` (the Blinn-Phong <-> GGX correspondence) clamped to [1, 8192]; mirror
    /// reflectivity = `m max(c) max(0, 1 - r / TRACED_ROUGHNESS)`: only smooth metals are
    /// traced mirrors, fading out by [`crate::TRACED_ROUGHNESS`].
    ///
    /// The Phong model's specular term has no colour, so a metal's colour can only live in
    /// the albedo: the rough share `t` of a metal's reflectance is moved there (its lobe is
    /// broad enough that a diffuse lobe of its colour is the closer of the two Phong
    /// stand-ins), and the rest stays a colourless highlight. Without it, glTF's default
    /// material (metallic 1, roughness 1, so every file that leaves `metallicFactor` out)
    /// rendered black apart from a grey highlight, its base colour and texture unseen.
    pub fn metallic_roughness(
        name: impl Into<String>,
        base_color: Vec3,
        metallic: f32,
        roughness: f32,
    ) -> Self {
        let brdf = crate::Brdf::new(base_color, metallic, roughness);
        let alpha = brdf.alpha();
        let reflectivity = metallic
            * base_color.max_element()
            * (1.0 - roughness / crate::TRACED_ROUGHNESS).max(0.0);
        let rough_metal = metallic * rough_share(roughness);
        let highlight = crate::Brdf::new(base_color, metallic - rough_metal, roughness);
        Self {
            base_color,
            metallic,
            roughness,
            glossiness: highlight.f0().max_element(),
            specular_power: (2.0 / (alpha * alpha) - 2.0).clamp(1.0, 8192.0),
            reflectivity,
            ..Self::diffuse(name, brdf.diffuse_color() + base_color * rough_metal)
        }
    }

    /// The BRDF of this material (before textures).
    pub fn brdf(&self) -> crate::Brdf {
        crate::Brdf::new(self.base_color, self.metallic, self.roughness)
    }

    /// The thesis's Phong parameters of this material.
    pub fn phong(&self) -> crate::PhongParams {
        crate::PhongParams {
            albedo: self.albedo,
            glossiness: self.glossiness,
            specular_power: self.specular_power,
            reflectivity: self.reflectivity,
            transparency: self.transparency,
        }
    }

    /// The same material with `base_color`, `metallic` and `roughness` derived again from
    /// its Phong fields ([`crate::PhongParams::to_metallic_roughness`]), after editing them.
    pub fn with_phong_converted(self) -> Self {
        let (base_color, metallic, roughness) = self.phong().to_metallic_roughness();
        Self { base_color, metallic, roughness, ..self }
    }

    pub fn is_mirror(&self) -> bool {
        self.reflectivity > RAY_TRACE_THRESHOLD
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
        if !self.albedo.is_finite()
            || self.albedo.min_element() < 0.0
            || self.albedo.max_element() > 1.0
        {
            return Err(SceneError::invalid(
                el(),
                format!("albedo {} outside [0, 1]", self.albedo),
            ));
        }
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
        unit(self.glossiness, "glossiness")?;
        unit(self.reflectivity, "reflectivity")?;
        unit(self.transparency, "transparency")?;
        if self.reflectivity + self.transparency > 1.0 + 1e-5 {
            return Err(SceneError::invalid(el(), "reflectivity + transparency exceeds 1"));
        }
        if !(self.specular_power >= 1.0 && self.specular_power.is_finite()) {
            return Err(SceneError::invalid(
                el(),
                format!("specular power {}", self.specular_power),
            ));
        }
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
        if let Some(m) = self.alpha_mask {
            tex(Some(m.texture), "alpha mask")?;
            if !(m.cutoff > 0.0 && m.cutoff <= 1.0) {
                return Err(SceneError::invalid(el(), format!("alpha cutoff {}", m.cutoff)));
            }
        }
        Ok(())
    }
}

/// The share of a metal's reflectance that [`Material::metallic_roughness`] gives the Phong
/// fields as diffuse albedo (with the metal's colour): 0 up to [`crate::TRACED_ROUGHNESS`]
/// (smooth metals stay traced mirrors and highlights), rising linearly to 1 at roughness 1.
pub fn rough_share(roughness: f32) -> f32 {
    ((roughness - crate::TRACED_ROUGHNESS) / (1.0 - crate::TRACED_ROUGHNESS)).clamp(0.0, 1.0)
}

#[cfg(test)]
mod tests {
    use super::{Material, phong_lobe, rough_share};
    use glam::Vec3;

    /// glTF's default material is a rough metal: its colour must reach the Phong albedo (it
    /// rendered black before), smooth metals stay colourless traced mirrors, and no derived
    /// material reflects more than its base colour plus the dielectric coating.
    #[test]
    fn metals_keep_their_colour_in_the_phong_fields() {
        let red = Vec3::new(0.8, 0.0, 0.0);
        let rough = Material::metallic_roughness("box", red, 1.0, 1.0);
        assert_eq!(rough.albedo, red);
        assert!((rough.glossiness - 0.04).abs() < 1e-6 && rough.reflectivity == 0.0);
        let smooth = Material::metallic_roughness("chrome", red, 1.0, 0.1);
        assert_eq!(smooth.albedo, Vec3::ZERO);
        assert!((smooth.glossiness - 0.8).abs() < 1e-6 && smooth.reflectivity > 0.3);
        let mid = Material::metallic_roughness("brushed", red, 1.0, 0.6);
        let t = rough_share(0.6);
        assert!(t > 0.4 && t < 0.6, "{t}");
        assert!((mid.albedo - red * t).length() < 1e-6);
        // A dielectric is what it was: base colour times (1 - m), the coating's 0.04.
        let plastic = Material::metallic_roughness("plastic", red, 0.0, 1.0);
        assert_eq!(plastic.albedo, red);
        assert!((plastic.glossiness - 0.04).abs() < 1e-6);
        for (m, r) in [(0.0f32, 0.0f32), (0.5, 0.3), (1.0, 0.5), (0.3, 1.0), (1.0, 1.0)] {
            let w = Material::metallic_roughness("w", Vec3::ONE, m, r);
            assert!(w.albedo.max_element() + w.glossiness <= 1.04 + 1e-6, "{m} {r}");
        }
        assert_eq!((rough_share(0.0), rough_share(0.2), rough_share(1.0)), (0.0, 0.0, 1.0));
    }

    /// At normal incidence the lobe times the cosine integrates to 1 over the hemisphere
    /// (midpoint rule in the polar angle), for any power; nothing comes from behind.
    #[test]
    fn the_phong_lobe_is_energy_normalised() {
        for power in [1.0f32, 8.0, 64.0, 512.0] {
            let n = 20_000;
            let d = std::f64::consts::FRAC_PI_2 / n as f64;
            let integral: f64 = (0..n)
                .map(|i| {
                    let th = (i as f64 + 0.5) * d;
                    let c = th.cos() as f32;
                    f64::from(phong_lobe(power, c))
                        * th.cos()
                        * th.sin()
                        * 2.0
                        * std::f64::consts::PI
                        * d
                })
                .sum();
            assert!((integral - 1.0).abs() < 1e-3, "power {power}: {integral}");
            assert_eq!(phong_lobe(power, -0.5), 0.0);
            assert_eq!(phong_lobe(power, 0.0), 0.0);
        }
    }
}
