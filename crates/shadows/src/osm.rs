//! Overlapped shadow maps (thesis 6.3.1): a few maps centred on the camera with growing
//! extents, covering every direction (also points seen only in reflections and refractions,
//! which the view-fitted cascades miss). Each map is snapped like a stabilised cascade.

use crate::error::{ShadowError, positive};
use crate::light_space::{LightBasis, ShadowView};
use glam::{DVec3, Vec3};

/// Number, size and growth of the overlapped maps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OsmSettings {
    /// Number of maps (1..=8); the thesis uses 3.
    pub maps: u32,
    /// Texels per side; the thesis uses 512.
    pub resolution: u32,
    /// Radius in metres covered by the smallest map.
    pub base_radius: f32,
    /// Each map covers `growth` times the radius of the previous one.
    pub growth: f32,
    /// Metres added towards the light for casters outside the covered sphere.
    pub caster_extension: f32,
}

impl OsmSettings {
    /// The thesis's setting: 3 maps of 512x512.
    pub const DEFAULT: Self =
        Self { maps: 3, resolution: 512, base_radius: 32.0, growth: 4.0, caster_extension: 200.0 };
    pub const fn low() -> Self {
        Self { maps: 2, resolution: 512, base_radius: 32.0, growth: 6.0, caster_extension: 200.0 }
    }
    pub const fn high() -> Self {
        Self { maps: 3, resolution: 1024, base_radius: 32.0, growth: 4.0, caster_extension: 400.0 }
    }
    pub const fn reference() -> Self {
        Self { maps: 4, resolution: 2048, base_radius: 16.0, growth: 4.0, caster_extension: 1000.0 }
    }

    pub fn validate(&self) -> Result<(), ShadowError> {
        if !(1..=8).contains(&self.maps) {
            return Err(ShadowError::InvalidParameter {
                name: "maps",
                reason: format!("must be in 1..=8, got {}", self.maps),
            });
        }
        if !(2..=16384).contains(&self.resolution) {
            return Err(ShadowError::InvalidParameter {
                name: "resolution",
                reason: format!("must be in 2..=16384, got {}", self.resolution),
            });
        }
        positive(self.base_radius, "base_radius")?;
        if !(self.growth.is_finite() && self.growth >= 1.0) {
            return Err(ShadowError::InvalidParameter {
                name: "growth",
                reason: format!("must be >= 1, got {}", self.growth),
            });
        }
        if !(self.caster_extension.is_finite() && self.caster_extension >= 0.0) {
            return Err(ShadowError::InvalidParameter {
                name: "caster_extension",
                reason: format!("must be >= 0, got {}", self.caster_extension),
            });
        }
        Ok(())
    }
}

impl Default for OsmSettings {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// The overlapped maps of one frame, smallest first.
#[derive(Clone, Debug, PartialEq)]
pub struct OverlappedShadowMaps {
    pub settings: OsmSettings,
    pub center: DVec3,
    pub maps: Vec<ShadowView>,
}

impl OverlappedShadowMaps {
    /// Centres the maps on `camera_position` (snapped to whole texels per map), for a sun in
    /// the direction `to_sun` (towards it, a `vocab::Sun`'s `direction`).
    pub fn fit(
        camera_position: DVec3,
        to_sun: Vec3,
        settings: &OsmSettings,
    ) -> Result<Self, ShadowError> {
        settings.validate()?;
        if !camera_position.is_finite() {
            return Err(ShadowError::NonFinite("camera position"));
        }
        let basis = LightBasis::new(to_sun)?;
        let maps = (0..settings.maps)
            .map(|i| {
                let r = settings.base_radius as f64 * (settings.growth as f64).powi(i as i32);
                ShadowView::fit_sphere(
                    basis,
                    camera_position,
                    r,
                    settings.resolution,
                    settings.caster_extension as f64,
                    true,
                )
            })
            .collect();
        Ok(Self { settings: *settings, center: camera_position, maps })
    }

    /// The selection rule: the smallest (sharpest) map that contains the world point with
    /// `margin_texels` to spare for the filter footprint; `None` outside every map.
    pub fn select(&self, p: DVec3, margin_texels: f64) -> Option<usize> {
        self.maps.iter().position(|m| m.contains(p, margin_texels))
    }

    /// Every map is centred within half a texel of the camera and larger than the previous.
    pub fn validate(&self) -> Result<(), ShadowError> {
        let mut prev = 0.0;
        for (i, m) in self.maps.iter().enumerate() {
            if m.half_extent <= prev {
                return Err(ShadowError::Invariant(format!(
                    "map {i} is not larger than map {}",
                    i.max(1) - 1
                )));
            }
            prev = m.half_extent;
            let c = m.world_to_map(self.center);
            let mid = m.resolution as f64 * 0.5;
            if (c.x - mid).abs() > 0.5 + 1e-6 || (c.y - mid).abs() > 0.5 + 1e-6 {
                return Err(ShadowError::Invariant(format!(
                    "map {i} is not centred on the camera"
                )));
            }
        }
        Ok(())
    }
}
