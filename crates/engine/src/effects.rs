//! Effects an application switches on and off (a viewer's toggles). A switched-off effect is
//! not needed whatever the scene says, and every pass that serves only it is skipped with the
//! switch as the reason in the frame report.

use scene::{Need, SceneNeeds};

/// An effect with a switch.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Effect {
    /// Direct sunlight.
    SunLighting,
    /// Sun shadow maps.
    SunShadows,
    /// The sky map and sky-light volume.
    SkyLighting,
    /// One bounce of sunlight (the LPV, the RSM gather or the radiance cache,
    /// `Settings::indirect`).
    IndirectLight,
    /// Traced mirror reflections (and the reflected part of glass).
    Reflections,
    /// Traced glass refractions (one ray-casting pass serves both kinds of rays).
    Refractions,
    /// Point-light cube shadows.
    PointLightShadows,
    /// Screen-space ambient occlusion.
    AmbientOcclusion,
}

impl Effect {
    pub const ALL: [Self; 8] = [
        Self::SunLighting,
        Self::SunShadows,
        Self::SkyLighting,
        Self::IndirectLight,
        Self::Reflections,
        Self::Refractions,
        Self::PointLightShadows,
        Self::AmbientOcclusion,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Self::SunLighting => "sun lighting",
            Self::SunShadows => "sun shadows",
            Self::SkyLighting => "sky lighting",
            Self::IndirectLight => "indirect light",
            Self::Reflections => "reflections",
            Self::Refractions => "refractions",
            Self::PointLightShadows => "point-light shadows",
            Self::AmbientOcclusion => "ambient occlusion",
        }
    }

    /// The condition a pass serving this effect runs under, as the frame report names it.
    pub fn switch_label(self) -> String {
        format!("{} switched on", self.name())
    }

    fn needs(self, needs: &mut SceneNeeds) -> Vec<&mut Need> {
        match self {
            Self::SunLighting => vec![&mut needs.sun_lighting],
            Self::SunShadows => vec![&mut needs.sun_shadows],
            Self::SkyLighting => vec![&mut needs.sky_lighting],
            Self::IndirectLight => vec![&mut needs.indirect],
            Self::Reflections => vec![&mut needs.reflections],
            Self::Refractions => vec![&mut needs.refractions],
            Self::PointLightShadows => vec![&mut needs.point_light_shadows],
            Self::AmbientOcclusion => Vec::new(),
        }
    }
}

/// Which effects are switched on (all, by default).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Effects {
    off: u16,
}

impl Effects {
    pub fn is_on(self, e: Effect) -> bool {
        self.off & (1 << e as u16) == 0
    }

    pub fn set(&mut self, e: Effect, on: bool) {
        if on {
            self.off &= !(1 << e as u16);
        } else {
            self.off |= 1 << e as u16;
        }
    }

    /// `needs` with every switched-off effect not needed, the switch as its reason.
    pub fn apply(self, needs: &mut SceneNeeds) {
        for e in Effect::ALL.into_iter().filter(|&e| !self.is_on(e)) {
            for n in e.needs(needs) {
                *n = Need { needed: false, reason: format!("{} switched off", e.name()) };
            }
        }
    }
}
