//! The renderer's GPU and technique state that the pass bodies share, and the per-frame
//! context the scheduler evaluates conditions and keys on.

use crate::gpu::{GBufferTargets, Gpu, SceneBuffers, storage, uniform};
use crate::passes::{
    combine::CombinePass,
    display::DisplayPass,
    gbuffer::GBufferPass,
    lighting::LightingPass,
    lpv::LpvState,
    point_shadows::{PointShadowPass, gpu_lights},
    radiance_cache::CacheState,
    raycast::RayCastPass,
    rsm_gather::RsmGatherState,
    shadow::ShadowMaps,
    shadow::ShadowPass,
    sky::SkyState,
    sky_bounce::SkyBounceInputs,
};
use crate::trace::TraceScene;
use crate::{EngineError, Settings};
use glam::Vec3;
use std::sync::atomic::AtomicBool;
use std::sync::{Mutex, RwLock};

/// Everything the passes read and write, built once per scene and settings.
pub struct State {
    pub gpu: Gpu,
    pub settings: Settings,
    pub scene: SceneBuffers,
    pub targets: GBufferTargets,
    pub gbuffer: GBufferPass,
    pub shadow: ShadowPass,
    pub lighting: LightingPass,
    pub raycast: RayCastPass,
    pub combine: CombinePass,
    pub display: DisplayPass,
    pub sky: Option<RwLock<SkyState>>,
    pub lpv: RwLock<LpvState>,
    pub rsm_gather: RwLock<RsmGatherState>,
    pub cache: RwLock<CacheState>,
    pub trace: TraceScene,
    pub frame: wgpu::Buffer,
    pub lights: wgpu::Buffer,
    pub shadow_maps: Mutex<Option<ShadowMaps>>,
    pub point_shadow: PointShadowPass,
    /// Whether the point lights' cubes have been rendered.
    pub point_shadows_ready: AtomicBool,
    pub point_lights: Vec<scene::PointLight>,
}

/// The sun as the passes light with it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SunLight {
    /// Unit direction towards the sun.
    pub dir: Vec3,
    /// Irradiance at the ground (RGB).
    pub irradiance: Vec3,
    pub angular_radius: f32,
}

/// What one frame is rendered from.
pub struct FrameCtx {
    pub state: std::sync::Arc<State>,
    pub camera: scene::Camera,
    pub needs: scene::SceneNeeds,
    pub sun: Option<SunLight>,
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
}

impl State {
    pub fn new(scene: &scene::Scene, settings: Settings, gpu: Gpu) -> Result<Self, EngineError> {
        settings.validate()?;
        scene.validate()?;
        let device = &gpu.device;
        let buffers = SceneBuffers::new(device, &gpu.queue, scene);
        let targets = GBufferTargets::new(device, settings.width, settings.height);
        let sky = if scene.sky {
            Some(RwLock::new(SkyState::new(&gpu, scene, &settings)?))
        } else {
            None
        };
        let cube_size = settings.point_shadow_resolution;
        let mut lights = gpu_lights(&scene.point_lights, cube_size);
        if lights.is_empty() {
            // Bindings need one element; the frame uniform's light count stays 0.
            lights.push(bytemuck::Zeroable::zeroed());
        }
        let frame =
            uniform(device, "frame", &[0u8; std::mem::size_of::<crate::frame::FrameUniform>()]);
        let view =
            SkyBounceInputs { targets: &targets, frame: &frame, materials: &buffers.materials };
        let lpv = LpvState::new(&gpu, &buffers, &settings, &view)?;
        let state = Self {
            gbuffer: GBufferPass::new(device, &buffers)?,
            shadow: ShadowPass::new(device, &settings)?,
            lighting: LightingPass::new(device, &targets)?,
            raycast: RayCastPass::new(device, &targets)?,
            combine: CombinePass::new(device, &targets)?,
            display: DisplayPass::new(device, &targets)?,
            lpv: RwLock::new(lpv),
            rsm_gather: RwLock::new(RsmGatherState::new(
                &gpu, scene, &buffers, &targets, &settings,
            )?),
            cache: RwLock::new(CacheState::new(&gpu, scene, &buffers, &settings)?),
            trace: TraceScene::new(scene)?,
            frame,
            lights: storage(device, "point lights", bytemuck::cast_slice(&lights)),
            shadow_maps: Mutex::new(None),
            point_shadow: PointShadowPass::new(device, &scene.point_lights, cube_size)?,
            point_shadows_ready: AtomicBool::new(false),
            sky,
            point_lights: scene.point_lights.clone(),
            scene: buffers,
            targets,
            settings,
            gpu,
        };
        state.gpu.take_error()?;
        Ok(state)
    }
}

impl State {
    /// Number of point lights the lighting pass loops over.
    pub fn scene_lights(&self) -> u32 {
        self.point_lights.len() as u32
    }
}

/// Poisoned locks become errors, not panics.
pub(crate) fn poisoned<T>(_: T) -> EngineError {
    EngineError::Gpu("a pass panicked while holding shared state".into())
}
