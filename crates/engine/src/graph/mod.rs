//! The frame graph: every pass of the pipeline declared once with the condition under which
//! it runs (from `scene::SceneNeeds`), the inputs and keys whose change makes it run again,
//! and a body that calls the pass's plain function. `frame_scheduler` decides, runs (the CPU
//! ray tracing on a worker thread while the GPU lights the view) and reports.

use crate::EngineError;
use crate::effects::Effect;
use crate::frame::{
    FLAG_INDIRECT, FLAG_LPV_GLOSSY, FLAG_MIRRORED_SUN, FLAG_SHADOWS, FLAG_SKY, FLAG_SKY_VOLUME,
    FLAG_SUN_GLINTS, FLAG_VOLUME_QUERIES, FrameUniform,
};
use crate::mirrored_sun::ReflectorSet;
use crate::passes::display::Shown;
use crate::passes::lighting::{IndirectSource, LightingInputs};
use crate::passes::lpv::LpvState;
use crate::passes::radiance_cache::CacheState;
use crate::passes::rsm_gather::RsmGatherState;
use crate::passes::shadow::{ShadowMaps, SunMapsPlan};
use crate::passes::sky::{SkyLight, SkyMapState, SkyVolumeState};
use crate::passes::traced_lighting::{OsmPass, TracedInputs, TracedLightingPass};
use crate::settings::Indirect;
use crate::settings::TracedShading;
use crate::state::FrameCtx;
use crate::trace::{TraceLighting, TraceSettings, TracedHit, trace_rays, trace_surfaces};
use frame_scheduler::{
    Budget, FrameGraph, PassBuilder, PassId, PassIo, PassResult, Res, quantise_dir,
};
use glam::Vec3;
use std::any::Any;
use traced_effects::ray_casting::RayBatch;

mod light;
mod traced;

use light::{
    accumulate_pass, bounce_passes, cache_pass, gbuffer_pass, lighting_pass, shadow_passes,
    sky_passes, tone_mapping_pass,
};
use traced::{combine_pass, trace_passes, traced_gbuffer_passes};

/// What the ray tracing job made of the batch's rays.
pub enum Traced {
    /// Each ray's radiance, shaded on the CPU (`TracedShading::Cpu`).
    Radiance(Vec<Vec3>),
    /// Each ray's first surface, for the GPU to light (`TracedShading::Gpu`).
    Surfaces(Vec<TracedHit>),
}

/// The G-buffer targets (in `State`) hold the view of this camera.
pub struct GBufferView(pub scene::Camera);

/// The point lights' depth cubes (in `State`) are rendered.
pub struct CubeShadows;

/// The lit (combined) HDR target holds the view of this lighting component code.
pub struct LitView(pub u32);
pub struct CombinedView(pub u32);

/// The accumulated HDR target holds the mean of this many still-view samples (1: the first
/// frame alone, or the first sample).
pub struct Accumulated(pub u32);

/// Handles to the graph's resources the renderer reads.
pub struct Outputs {
    /// Which HDR target the display image of the frame was made from.
    pub shown: Res<Shown>,
    pub sky_volume: PassId,
    pub cache: Res<CacheState>,
}

/// Stable pass names (the report and the tests use them).
pub mod pass {
    pub const SKY_MAP: &str = "sky map";
    pub const SKY_VOLUME: &str = "sky volume";
    pub const SHADOW_MAPS: &str = "shadow maps";
    pub const POINT_SHADOWS: &str = "point shadows";
    pub const GBUFFER: &str = "g-buffer";
    pub const LPV: &str = "lpv";
    pub const SUN_RSM: &str = "rsm (gather)";
    pub const RADIANCE_CACHE: &str = "rsm + radiance cache";
    pub const RAY_CASTING: &str = "ray casting buffer";
    pub const RAY_TRACING: &str = "ray tracing";
    pub const LIGHTING: &str = "lighting";
    pub const OSM: &str = "overlapped shadow maps";
    pub const TRACED_LIGHTING: &str = "traced g-buffer lighting";
    pub const COMBINE: &str = "traced upload + combine";
    pub const ACCUMULATE: &str = "still-view accumulation";
    pub const TONE_MAPPING: &str = "tone mapping";
}

fn camera_key(c: &FrameCtx) -> [i64; 6] {
    let p = quantise_dir(c.camera.position.to_array(), 1e-3);
    let f = quantise_dir(c.camera.forward.to_array(), 1e-5);
    [p[0], p[1], p[2], f[0], f[1], f[2]]
}

fn sun_key(c: &FrameCtx) -> Option<[i64; 3]> {
    c.sun.map(|s| quantise_dir(s.direction.to_array(), 1e-3))
}

/// What the lighting pass binds besides the G-buffer, as the frame uniform reports it to the
/// shaders (the passes before it write the camera part, which is all they read).
#[derive(Clone, Copy, Default)]
struct Bound {
    shadows: Option<ShadowMaps>,
    cubes: bool,
    sky_map_size: u32,
}

/// Writes the frame uniform for this frame's camera, sun and enabled techniques.
fn write_frame_uniform(c: &FrameCtx, bound: Bound) {
    let s = &c.state;
    let set = &s.settings;
    let mut u = FrameUniform::new(&c.camera, c.view_projection(), set.width, set.height);
    if let Some(sun) = c.sun.filter(|_| c.needs.sun_lighting.needed) {
        u.sun_dir = sun.direction.extend(1.0).to_array();
        u.sun_irradiance = sun.irradiance.extend(sun.angular_radius).to_array();
    }
    let mut flags = 0;
    if sky_needed(c) {
        flags |= FLAG_SKY | FLAG_SKY_VOLUME;
    }
    if c.needs.indirect.needed && c.indirect != Indirect::None {
        flags |= FLAG_INDIRECT;
        if matches!(c.indirect, Indirect::Lpv | Indirect::Cache) {
            flags |= FLAG_VOLUME_QUERIES;
        }
    }
    if set.sun_glints {
        flags |= FLAG_SUN_GLINTS;
    }
    if set.lpv_glossy > 0 && c.needs.indirect.needed && c.indirect == Indirect::Lpv {
        flags |= FLAG_LPV_GLOSSY;
    }
    if set.mirrored_sun {
        flags |= FLAG_MIRRORED_SUN;
    }
    u.csm[2] = if bound.cubes { set.point_shadow_resolution } else { 0 };
    if let Some(m) = bound.shadows.filter(|m| m.count > 0) {
        flags |= FLAG_SHADOWS;
        u.csm[0] = m.count;
        u.csm[1] = set.csm_resolution;
    }
    u.size = [set.width, set.height, s.scene_lights(), flags];
    let ao = if c.effects.is_on(Effect::AmbientOcclusion) { set.ssao_samples } else { 0 };
    u.params = [set.ssao_radius, ao as f32, bound.sky_map_size as f32, c.footprint()];
    u.csm[3] = c.component;
    s.gpu.write(&s.frame, 0, bytemuck::bytes_of(&u));
}

/// The output's value from the pass's last run, or, on its first, a new one from `make`:
/// a technique's state is built when a frame first needs it, not with the renderer.
fn previous_or<T: Any + Send + Sync>(
    io: &mut PassIo<'_, FrameCtx>,
    res: Res<T>,
    make: impl FnOnce(&FrameCtx) -> Result<T, EngineError>,
) -> Result<T, Box<dyn std::error::Error + Send + Sync>> {
    match io.take_previous(res)? {
        Some(v) => Ok(v),
        None => Ok(make(io.ctx())?),
    }
}

/// The sky of this frame, when both its passes have run (the map and the volume lit from it).
fn sky_light<'a>(io: &'a PassIo<'_, FrameCtx>, r: Resources) -> Option<SkyLight<'a>> {
    Some(SkyLight { map: io.try_read(r.sky_map)?, volume: io.try_read(r.sky_vol)? })
}

fn sky_setup(c: &FrameCtx) -> Result<&crate::passes::sky::SkySetup, EngineError> {
    c.state.sky.as_ref().ok_or_else(|| EngineError::Settings("the scene has no sky".into()))
}

fn sun_of(c: &FrameCtx) -> Result<vocab::Sun, EngineError> {
    c.sun.ok_or_else(|| EngineError::Settings("no sun".into()))
}

/// The graph's resources: what each pass writes and the passes after it read.
#[derive(Clone, Copy)]
struct Resources {
    sky_map: Res<SkyMapState>,
    sky_vol: Res<SkyVolumeState>,
    shadow: Res<ShadowMaps>,
    gbuf: Res<GBufferView>,
    cubes: Res<CubeShadows>,
    lpv: Res<LpvState>,
    sun_rsm: Res<RsmGatherState>,
    cache: Res<CacheState>,
    batch: Res<RayBatch>,
    traced: Res<Traced>,
    osm: Res<OsmPass>,
    traced_lit: Res<TracedLightingPass>,
    lit: Res<LitView>,
    combined: Res<CombinedView>,
    accumulated: Res<Accumulated>,
    shown: Res<Shown>,
}

impl Resources {
    fn declare(g: &mut FrameGraph<FrameCtx>) -> Self {
        Self {
            sky_map: g.resource("sky map"),
            sky_vol: g.resource("sky volume"),
            shadow: g.resource("sun shadow maps"),
            gbuf: g.resource("g-buffer"),
            cubes: g.resource("point-light cube maps"),
            lpv: g.resource("lpv"),
            sun_rsm: g.resource("sun rsm (gather)"),
            cache: g.resource("radiance cache"),
            batch: g.resource("ray batch"),
            traced: g.resource("traced radiance"),
            osm: g.resource("overlapped shadow maps"),
            traced_lit: g.resource("traced g-buffer, lit"),
            lit: g.resource("lit view"),
            combined: g.resource("combined view"),
            accumulated: g.resource("accumulated still view"),
            shown: g.resource("display image"),
        }
    }
}

/// A pass that an application switch turns off.
trait Switched {
    fn switched(self, effect: Effect) -> Self;
}

impl Switched for PassBuilder<'_, FrameCtx> {
    fn switched(self, effect: Effect) -> Self {
        self.run_if(effect.switch_label(), move |c: &FrameCtx| c.effects.is_on(effect))
    }
}

const SKY_NEEDED: &str = "the scene shows the sky and the sun is up";
fn sky_needed(c: &FrameCtx) -> bool {
    c.state.sky.is_some() && c.needs.sky_lighting.needed
}

const BOUNCE_NEEDED: &str = "the sun lights diffuse surfaces (one indirect bounce)";
fn bounce_needed(c: &FrameCtx) -> bool {
    c.needs.indirect.needed && c.sun.is_some()
}

const RAYS_NEEDED: &str = "a mirror or glass surface is in view";

const RAYS_SWITCHED: &str = "reflections or refractions switched on";
fn rays_switched(c: &FrameCtx) -> bool {
    c.effects.is_on(Effect::Reflections) || c.effects.is_on(Effect::Refractions)
}

/// Declares the pipeline for `set`, over a sky volume of `sky_layers` layers.
pub fn build(set: &crate::Settings, sky_layers: u32) -> (FrameGraph<FrameCtx>, Outputs) {
    let mut g = FrameGraph::<FrameCtx>::new();
    let r = Resources::declare(&mut g);
    g.output(r.shown);
    let sky_volume = sky_passes(&mut g, r, sky_layers, set.sky_layers_per_frame);
    shadow_passes(&mut g, r);
    gbuffer_pass(&mut g, r);
    bounce_passes(&mut g, r, set.sky_bounce > 0);
    let many_bounces = set.radiance_cache.bounces == radiance_cache::Bounces::Many;
    cache_pass(&mut g, r, set.cache_frames, many_bounces);
    trace_passes(&mut g, r);
    traced_gbuffer_passes(&mut g, r);
    lighting_pass(&mut g, r);
    combine_pass(&mut g, r);
    accumulate_pass(&mut g, r);
    tone_mapping_pass(&mut g, r);
    (g, Outputs { shown: r.shown, sky_volume, cache: r.cache })
}
