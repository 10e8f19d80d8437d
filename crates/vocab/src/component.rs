//! The lighting terms a frame splits into: what a real-time engine shows one by one and what
//! a reference renderer computes as the truth for each.

/// A lighting term of a frame (or of the irradiance at a point). Each is the truth for one
/// real-time technique: a renderer shows it on its own, a reference renderer computes it, and
/// a comparison puts the two side by side by this one name.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Component {
    /// Direct sunlight through the disk (area-light shadows with true penumbrae): the truth
    /// for shadow maps (CSM, PCSS). Images: reflected radiance; points: irradiance.
    SunDirect,
    /// Sunlight after exactly one diffuse bounce: the truth for light propagation volumes,
    /// reflective-shadow-map gathers and radiance caches. Images: reflected (diffuse)
    /// radiance; points: irradiance.
    SunIndirectDiffuse,
    /// Sky light with occlusion: the truth for the sky volume. Images and points:
    /// irradiance `E = int L_sky V cos` (images at the first visible surface).
    SkyIrradiance,
    /// Light reaching the eye through the first surface's mirror/glass part, with full
    /// global illumination after it: the truth for ray-traced reflections and refractions.
    Reflections,
    /// Everything: emission, sun, point lights and sky, all bounces. Points: irradiance.
    Full,
    /// Direct light of the point lights, shadowed: the truth for point lights with cube
    /// shadow maps. Images: reflected radiance; points: irradiance.
    PointLights,
    /// Emission seen directly (no bounce). Images: the first surface's emitted radiance;
    /// points: irradiance from emitters.
    Emission,
    /// Sky light reflected diffusely at the first surface: `rho_d / pi` times the occluded
    /// sky irradiance (what a real-time engine makes of its sky volume's lookup). Images:
    /// reflected radiance; points: the occluded sky irradiance, as [`Self::SkyIrradiance`].
    SkyDiffuse,
    /// Direct light of emissive surfaces (area lights), shadowed: the truth for emitters
    /// lighting a real-time frame. Images: reflected radiance; points: irradiance.
    AreaLights,
}

impl Component {
    /// Every component.
    pub const ALL: [Self; 9] = [
        Self::SunDirect,
        Self::SunIndirectDiffuse,
        Self::SkyIrradiance,
        Self::Reflections,
        Self::Full,
        Self::PointLights,
        Self::Emission,
        Self::SkyDiffuse,
        Self::AreaLights,
    ];

    /// The components a one-bounce engine computes, in radiance: their sum over the pixels
    /// where a surface is seen is [`Self::Full`] less the light of more than one bounce (sky
    /// light bouncing, sunlight bouncing twice or more, glossy indirect light, sunlight
    /// through mirrors onto diffuse surfaces, light of emitters and point lights after a
    /// bounce). Every path through the first surface's mirror or glass part is in
    /// [`Self::Reflections`].
    pub const ONE_BOUNCE: [Self; 7] = [
        Self::SunDirect,
        Self::SunIndirectDiffuse,
        Self::SkyDiffuse,
        Self::Reflections,
        Self::PointLights,
        Self::AreaLights,
        Self::Emission,
    ];

    /// The component's name (`snake_case`), the same on every side of a comparison.
    pub fn name(self) -> &'static str {
        match self {
            Self::SunDirect => "sun_direct",
            Self::SunIndirectDiffuse => "sun_indirect_diffuse",
            Self::SkyIrradiance => "sky_irradiance",
            Self::Reflections => "reflections",
            Self::Full => "full",
            Self::PointLights => "point_lights",
            Self::Emission => "emission",
            Self::SkyDiffuse => "sky_diffuse",
            Self::AreaLights => "area_lights",
        }
    }

    /// The component of a [`Component::name`].
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|c| c.name() == name)
    }
}

impl std::fmt::Display for Component {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}
