//! Sun shadow maps (thesis 4.3.1, 4.4): stabilised cascades fitted by `shadows` to the camera each
//! frame and rendered by its resident pass over the scene's own buffers; the lighting pass
//! reads them through `shaders/shadows/csm.inc.wgsl`. The cascades snap to their texels, so a
//! map whose view did not move is not rendered again (`CascadeShadows::record_moved`; the
//! scene's geometry is fixed for a renderer's life), and the frame graph reuses the pass while
//! no view moved ([`SunMapsPlan`] is its key).

use crate::gpu::{Gpu, SceneBuffers};
use crate::{EngineError, Settings};
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

    /// The cascades fitted to `camera` for `sun`, with PCSS filters for its disk (hard
    /// shadows when the preset has no PCF taps): what
    /// [`Self::render`] renders. Stabilised cascades snap to their texels, so the plan stays
    /// equal while the camera moves by less than a texel of every cascade.
    pub fn plan(
        &self,
        camera: &scene::Camera,
        sun: &vocab::Sun,
        settings: &Settings,
    ) -> Result<SunMapsPlan, EngineError> {
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
        let csm = CascadedShadowMap::fit(&cam, sun.direction, &csm_settings).map_err(tech)?;
        let views = csm.cascades.iter().map(|c| (&c.view, c.split_far as f32));
        SunMapsPlan::new(views, sun.angular_radius, settings)
    }

    /// Renders the maps of `plan` whose view changed since they were last rendered.
    pub fn render(
        &self,
        gpu: &Gpu,
        scene: &SceneBuffers,
        plan: &SunMapsPlan,
    ) -> Result<ShadowMaps, EngineError> {
        Ok(ShadowMaps { count: render_sun_maps(&self.maps, gpu, scene, plan)? })
    }
}

/// Sun shadow maps to render: each map's lookup block (view, split, PCSS filter) and the
/// shared PCSS taps. The view's cascades and the traced G-buffer's overlapped maps both
/// render through it.
#[derive(Clone, Debug, PartialEq)]
pub struct SunMapsPlan {
    blocks: Vec<CsmCascade>,
    taps: Vec<glam::Vec2>,
}

impl SunMapsPlan {
    /// The maps of `views` (each with the view depth its cascade ends at), filtered by PCSS
    /// for a sun disk of `angular_radius` (hard shadows when the preset has no PCF taps).
    pub fn new<'a>(
        views: impl Iterator<Item = (&'a ShadowView, f32)>,
        angular_radius: f32,
        settings: &Settings,
    ) -> Result<Self, EngineError> {
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
        Ok(Self { blocks, taps })
    }
}

/// Renders the maps of `plan` into `maps`, only those whose view changed since `maps` last
/// rendered them (the scene's geometry is fixed for the renderer's life); returns how many
/// maps the plan has.
pub fn render_sun_maps(
    maps: &CascadeShadows,
    gpu: &Gpu,
    scene: &SceneBuffers,
    plan: &SunMapsPlan,
) -> Result<u32, EngineError> {
    let mut enc = gpu.device.create_command_encoder(&Default::default());
    let geometry = scene.shadow_geometry(false);
    let recorded = maps
        .record_moved(&gpu.queue, &mut enc, &geometry, &plan.blocks, &plan.taps)
        .map_err(tech)?;
    gpu.queue.submit([enc.finish()]);
    Ok(recorded.maps.count)
}
