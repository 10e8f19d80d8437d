//! Sun shadow maps (thesis 4.2): stabilised cascades fitted by `shadows` to the camera each
//! frame and rendered by its resident pass over the scene's own buffers; the lighting pass
//! reads them through `shaders/shadows/csm.inc.wgsl`.

use crate::gpu::{Gpu, SceneBuffers};
use crate::{EngineError, Settings};
use glam::Vec3;
use shadows::gpu::{CascadeMaps, CascadeShadows};
use shadows::{CascadedShadowMap, CsmCascade, CsmSettings, Pcss, PcssSettings, ShadowView};

/// Cascades beyond this view distance are not shadowed (metres).
pub const SHADOW_DISTANCE: f32 = 300.0;

/// What the last render left for the lighting pass: the number of cascades written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ShadowMaps {
    pub count: u32,
}

pub struct ShadowPass {
    maps: CascadeShadows,
}

fn tech(e: shadows::ShadowError) -> EngineError {
    EngineError::technique("shadows", e)
}

impl ShadowPass {
    pub fn new(device: &wgpu::Device, settings: &Settings) -> Result<Self, EngineError> {
        let maps = CascadeShadows::new(
            device,
            SceneBuffers::SHADOW_LAYOUT,
            settings.csm_resolution,
            settings.csm_cascades,
        )
        .map_err(tech)?;
        Ok(Self { maps })
    }

    /// The lighting pass's bindings for `maps` (none: zero cascades).
    pub fn bindings(&self, maps: Option<&ShadowMaps>) -> CascadeMaps<'_> {
        self.maps.maps(maps.map_or(0, |m| m.count))
    }

    /// Fits the cascades to `camera` for a sun towards `sun_dir`, with PCSS filters for a sun
    /// disk of `angular_radius` (hard shadows when the preset has no PCF taps), and renders
    /// them.
    pub fn render(
        &self,
        gpu: &Gpu,
        scene: &SceneBuffers,
        camera: &scene::Camera,
        sun_dir: Vec3,
        angular_radius: f32,
        settings: &Settings,
    ) -> Result<ShadowMaps, EngineError> {
        let cam = shadows::Camera::look_to(
            camera.position.as_dvec3(),
            camera.forward,
            camera.up,
            camera.fov_y_deg.to_radians(),
            camera.aspect,
            camera.near,
            camera.far.min(SHADOW_DISTANCE).max(camera.near * 2.0),
        )
        .map_err(tech)?;
        let csm_settings = CsmSettings {
            cascades: settings.csm_cascades,
            resolution: self.maps.resolution(),
            ..CsmSettings::DEFAULT
        };
        let csm = CascadedShadowMap::fit(&cam, -sun_dir, &csm_settings).map_err(tech)?;
        let views = csm.cascades.iter().map(|c| (&c.view, c.split_far as f32));
        let count = render_sun_maps(&self.maps, gpu, scene, views, angular_radius, settings)?;
        Ok(ShadowMaps { count })
    }
}

/// Renders sun shadow maps of `views` (each with the view depth its cascade ends at) into
/// `maps`, their lookup blocks filtered by PCSS for a sun disk of `angular_radius` (hard
/// shadows when the preset has no PCF taps); returns how many were rendered. The view's
/// cascades and the traced G-buffer's overlapped maps both render through it.
pub fn render_sun_maps<'a>(
    maps: &CascadeShadows,
    gpu: &Gpu,
    scene: &SceneBuffers,
    views: impl Iterator<Item = (&'a ShadowView, f32)>,
    angular_radius: f32,
    settings: &Settings,
) -> Result<u32, EngineError> {
    let pcss_settings = PcssSettings {
        blocker_taps: settings.pcss_blocker_taps.max(1),
        pcf_taps: settings.pcss_pcf_taps.max(1),
        ..PcssSettings::DEFAULT
    };
    let radius = if settings.pcss_pcf_taps == 0 { 0.0 } else { angular_radius };
    let mut taps = Vec::new();
    let mut blocks = Vec::new();
    for (view, split_far) in views {
        let pcss = Pcss::directional(view, radius, &pcss_settings).map_err(tech)?;
        taps = pcss.taps().to_vec();
        blocks.push(CsmCascade::of_view(view, split_far, &pcss));
    }
    let mut enc = gpu.device.create_command_encoder(&Default::default());
    let geometry = scene.shadow_geometry(false);
    let rendered = maps.record(&gpu.queue, &mut enc, &geometry, &blocks, &taps).map_err(tech)?;
    gpu.queue.submit([enc.finish()]);
    Ok(rendered.count)
}
