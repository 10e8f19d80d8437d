//! The renderer's GPU and technique state that the pass bodies share, and the per-frame
//! context the scheduler evaluates conditions and keys on.

use crate::gpu::{GBufferTargets, Gpu, SceneBuffers, storage_buffer, uniform_buffer};
use crate::passes::{
    display::{accumulate_pass, tone_map_pass},
    lighting::LightingPass,
    lpv::LpvState,
    point_shadows::{PointShadowPass, gpu_lights, scene_lights},
    radiance_cache::CacheState,
    rsm_gather::RsmGatherState,
    shadow::ShadowPass,
    sky::SkySetup,
    sky_bounce::SkyBounceInputs,
};
use crate::trace::TraceScene;
use crate::{EngineError, Settings};
use traced_effects::gpu::{Combine, RayCasting};

/// What every frame is rendered with, built once per scene and settings and never changed
/// by a pass: the device, the scene's buffers and the passes' pipelines and targets. What
/// passes make and change (shadow maps, the sky, the one-bounce techniques' volumes) are
/// the frame graph's typed resources (`crate::graph`), made on first use.
pub struct State {
    pub gpu: Gpu,
    pub settings: Settings,
    pub scene: SceneBuffers,
    /// The scene's bounds (where the one-bounce techniques place their maps and caches).
    pub bounds: scene::Aabb,
    pub targets: GBufferTargets,
    /// The G-buffer pass (`scene::gpu`).
    pub gbuffer: scene::gpu::GBufferPass,
    pub shadow: ShadowPass,
    pub lighting: LightingPass,
    /// The ray casting buffer and the combination of the traced rays (`traced_effects`).
    pub raycast: RayCasting,
    pub combine: Combine,
    pub accumulate: post::gpu::AccumulatePass,
    pub display: post::gpu::ToneMapPass,
    /// The atmosphere and where the sky volume goes; `None` when the scene shows no sky.
    pub sky: Option<SkySetup>,
    pub trace: TraceScene,
    pub frame: wgpu::Buffer,
    pub lights: wgpu::Buffer,
    pub point_shadow: PointShadowPass,
    /// The scene's point and spot lights, then the stand-ins for its emissive surfaces
    /// (`Settings::emitter_lights`).
    pub point_lights: Vec<scene::PointLight>,
    /// The share of the emissive surfaces' power no stand-in carries (over budget).
    pub emitter_power_left_out: f32,
    /// The scene's planar reflectors (`crate::mirrored_sun`), for the traced rays' shading.
    pub reflectors: Vec<crate::mirrored_sun::Reflector>,
}

/// What one frame is rendered from.
pub struct FrameCtx {
    pub state: std::sync::Arc<State>,
    pub camera: scene::Camera,
    pub needs: scene::SceneNeeds,
    /// The sun the passes light with (`None`: the scene has none).
    pub sun: Option<vocab::Sun>,
    pub frame: u64,
    /// Which lighting component the frame shows (`crate::components::code`; 0 the full frame).
    pub component: u32,
    /// Seconds of eye adaptation this frame, and whether exposure adapts at once instead.
    pub dt: f32,
    pub reset_exposure: bool,
    /// The application's switches (already applied to `needs`).
    pub effects: crate::effects::Effects,
    /// The one-bounce technique of this frame.
    pub indirect: crate::settings::Indirect,
    /// The still view's sample this frame renders (`post`; 0: a first frame, unjittered).
    pub still_sample: u32,
}

/// The specular widening of each of `n` jittered samples averaged into one pixel:
/// `min(1, 16 / n³)`. The average of the samples is itself the pixel's box filter, so the
/// widening only has to cover what `n` samples leave aliased, and the widening, estimated
/// from the normal's screen derivatives, is biased against the truth (the city's direct sun
/// 4x4 supersampled with a whole sub-pixel's widening each: 0.069 against 64 spp, where 64
/// jittered samples without widening give 0.044). Fitted on the city's direct sun against 64
/// spp (320x180, `serein-render --components`), rel RMS by widening per sample:
///
/// | `n` | 1/2 | 1/4 | 1/16 | 1/64 | 1/256 | none |
/// |---|---|---|---|---|---|---|
/// | 4 (low) | 0.352 | **0.324** | 0.374 | - | - | 0.439 |
/// | 16 (default) | - | 0.246 | 0.152 | - | **0.123** | 0.121 |
/// | 64 (high) | - | - | - | 0.056 | - | **0.044** (16/n³) |
///
/// `1 / n` (what each sample's share of the pixel would suggest) was best at 4 samples only.
/// The table was measured while the view's first frame, widened by the whole pixel's
/// variance, was one of the `n` samples; since it is shown alone and left out of the average
/// (`post`) the same rule gives 0.344 / 0.099 / 0.035 (low / default / high; at low a
/// widening of 1/2 gives 0.342, 1/8 0.420).
/// Checked at other sizes (default preset, 16 samples, `16 / n³` against `1 / n`): 640x360
/// 0.073 against 0.078, but 160x90, where the statue is a few pixels across, 0.231 against
/// 0.220. `plane_box` and `cornell_window`, with no curved glossy surfaces, do not move
/// (direct sun 0.035 and 0.178 at 320x180 with either rule). `app/tests/specular_aa.rs`
/// holds the 320x180 figure.
pub fn jittered_footprint(n: u32) -> f32 {
    let n = n.max(1) as f32;
    (16.0 / (n * n * n)).min(1.0)
}

impl FrameCtx {
    /// The share of a pixel's normal variance this frame's G-buffer widens specular lobes by
    /// (its specular anti-aliasing): 1 for a first sample (it is shown alone), and for the
    /// jittered samples of a still view averaging `n` (`post`) [`jittered_footprint`]`(n)`.
    pub fn footprint(&self) -> f32 {
        match self.still_sample {
            0 => 1.0,
            _ => jittered_footprint(self.state.settings.still_samples),
        }
    }

    /// The bias of the G-buffer's texture levels of detail this frame: 0 for a first sample,
    /// and for the `n` jittered samples of a still view `-0.5 log2 n`, each reading the
    /// level of its share of the pixel (`scene::gpu::GBufferCamera::with_texture_bias`), so
    /// that their average integrates the textures over the pixel, normal maps included (the
    /// reference integrates each pixel over the full-resolution maps).
    pub fn texture_bias(&self) -> f32 {
        match self.still_sample {
            0 => 0.0,
            _ => -0.5 * (self.state.settings.still_samples.max(1) as f32).log2(),
        }
    }

    /// The camera the G-buffer is drawn from: the jittered view-projection, the camera's
    /// position and forward axis (as the frame uniform has them) and [`FrameCtx::footprint`].
    pub fn gbuffer_camera(&self) -> scene::gpu::GBufferCamera {
        let (camera, vp) = (&self.camera, self.view_projection());
        scene::gpu::GBufferCamera::new(vp, camera.position, camera.forward, self.footprint())
            .with_texture_bias(self.texture_bias())
    }

    /// The camera's view-projection moved by this frame's sub-pixel jitter: what the
    /// G-buffer is rasterised with and every pass that projects into the view uses.
    pub fn view_projection(&self) -> glam::Mat4 {
        let j = post::frame_jitter(self.still_sample);
        let set = &self.state.settings;
        // Clip-space x + 2 j.x / W w: the image moves by j pixels (y up in clip space).
        let ndc =
            glam::Vec3::new(2.0 * j.x / set.width as f32, -2.0 * j.y / set.height as f32, 0.0);
        glam::Mat4::from_translation(ndc) * self.camera.view_projection()
    }
}

impl State {
    pub fn new(scene: &scene::Scene, settings: Settings, gpu: Gpu) -> Result<Self, EngineError> {
        settings.validate()?;
        scene.validate()?;
        let device = &gpu.device;
        let reflectors = crate::mirrored_sun::planar_reflectors(scene);
        let buffers = SceneBuffers::new(device, &gpu.queue, scene, &reflectors);
        let targets = GBufferTargets::new(device, settings.width, settings.height);
        let sky = if scene.sky { Some(SkySetup::new(scene)?) } else { None };
        let cube_size = settings.point_shadow_resolution;
        let (point_lights, emitter_power_left_out) = scene_lights(scene, settings.emitter_lights);
        let mut lights = gpu_lights(&point_lights, cube_size);
        if lights.is_empty() {
            // Bindings need one element; the frame uniform's light count stays 0.
            lights.push(bytemuck::Zeroable::zeroed());
        }
        let frame = uniform_buffer(
            device,
            "frame",
            &[0u8; std::mem::size_of::<crate::frame::FrameUniform>()],
        );
        let state = Self {
            gbuffer: scene::gpu::GBufferPass::new(device, &buffers)
                .map_err(|e| crate::gpu::shader_error("gbuffer", e))?,
            shadow: ShadowPass::new(device, &settings)?,
            lighting: LightingPass::new(device, &targets)?,
            raycast: RayCasting::new(device, targets.size())?,
            combine: Combine::new(device, targets.size(), crate::gpu::HDR_FORMAT)?,
            accumulate: accumulate_pass(device, &targets)?,
            display: tone_map_pass(device, &targets)?,
            trace: TraceScene::new(scene)?,
            frame,
            lights: storage_buffer(device, "point lights", bytemuck::cast_slice(&lights)),
            point_shadow: PointShadowPass::new(device, &point_lights, cube_size)?,
            sky,
            bounds: scene.bounds(),
            point_lights,
            emitter_power_left_out,
            reflectors,
            scene: buffers,
            targets,
            settings,
            gpu,
        };
        state.gpu.take_error()?;
        Ok(state)
    }

    /// Number of point lights the lighting pass loops over.
    pub fn scene_lights(&self) -> u32 {
        self.point_lights.len() as u32
    }

    /// The LPV (its RSM, the sky-bounce VPLs' targets, the resident volume), for the LPV
    /// pass's first update.
    pub fn new_lpv(&self) -> Result<LpvState, EngineError> {
        let view = SkyBounceInputs {
            targets: &self.targets,
            frame: &self.frame,
            materials: &self.scene.materials,
        };
        LpvState::new(&self.gpu, &self.scene, &self.settings, &view)
    }

    /// The sun RSM and its gather, bound to the view's targets.
    pub fn new_rsm_gather(&self) -> Result<RsmGatherState, EngineError> {
        RsmGatherState::new(&self.gpu, &self.bounds, &self.scene, &self.targets, &self.settings)
    }

    /// The radiance cache, its RSM and its resident copy.
    pub fn new_cache(&self) -> Result<CacheState, EngineError> {
        CacheState::new(&self.gpu, &self.bounds, &self.scene, &self.settings)
    }
}
