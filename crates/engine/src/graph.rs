//! The frame graph: every pass of the pipeline declared once with the condition under which
//! it runs (from `scene::SceneNeeds`), the inputs and keys whose change makes it run again,
//! and a body that calls the pass's plain function. `frame_scheduler` decides, runs (the CPU
//! ray tracing on a worker thread while the GPU lights the view) and reports.

use crate::EngineError;
use crate::effects::Effect;
use crate::frame::{
    FLAG_BLINN, FLAG_INDIRECT, FLAG_LPV_GLOSSY, FLAG_REFLECTIONS, FLAG_REFRACTIONS, FLAG_SHADOWS,
    FLAG_SKY, FLAG_SKY_VOLUME, FLAG_SUN_GLINTS, FrameUniform,
};
use crate::passes::display::{Exposure, Shown};
use crate::passes::lighting::{IndirectSource, LightingInputs};
use crate::passes::lpv::LpvState;
use crate::passes::radiance_cache::CacheState;
use crate::passes::raycast::RayBatch;
use crate::passes::rsm_gather::RsmGatherState;
use crate::passes::shadow::ShadowMaps;
use crate::passes::sky::{SkyLight, SkyMapState, SkyVolumeState};
use crate::passes::traced_lighting::{OsmPass, TracedInputs, TracedLightingPass};
use crate::settings::TracedShading;
use crate::settings::{Indirect, Specular};
use crate::state::FrameCtx;
use crate::state::SunLight;
use crate::trace::{TraceLighting, TraceSettings, TracedHit, trace_rays, trace_surfaces};
use frame_scheduler::{
    Budget, FrameGraph, PassBuilder, PassId, PassIo, PassResult, Res, quantise_dir,
};
use glam::Vec3;
use std::any::Any;

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
    pub const LPV: &str = "rsm + lpv";
    pub const SUN_RSM: &str = "rsm (gather)";
    pub const RADIANCE_CACHE: &str = "rsm + radiance cache";
    pub const RAY_CASTING: &str = "ray casting buffer";
    pub const RAY_TRACING: &str = "ray tracing";
    pub const LIGHTING: &str = "lighting";
    pub const OSM: &str = "overlapped shadow maps";
    pub const TRACED_LIGHTING: &str = "traced g-buffer lighting";
    pub const COMBINE: &str = "traced upload + combine";
    pub const TONE_MAPPING: &str = "tone mapping";
}

fn camera_key(c: &FrameCtx) -> [i64; 6] {
    let p = quantise_dir(c.camera.position.to_array(), 1e-3);
    let f = quantise_dir(c.camera.forward.to_array(), 1e-5);
    [p[0], p[1], p[2], f[0], f[1], f[2]]
}

fn sun_key(c: &FrameCtx) -> Option<[i64; 3]> {
    c.sun.map(|s| quantise_dir(s.dir.to_array(), 1e-3))
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
    let mut u = FrameUniform::new(&c.camera, set.width, set.height);
    if let Some(sun) = c.sun.filter(|_| c.needs.sun_lighting.needed) {
        u.sun_dir = sun.dir.extend(1.0).to_array();
        u.sun_irradiance = sun.irradiance.extend(sun.angular_radius).to_array();
    }
    let mut flags = 0;
    if sky_needed(c) {
        flags |= FLAG_SKY | FLAG_SKY_VOLUME;
    }
    if c.needs.indirect_lpv.needed && c.indirect != Indirect::None {
        flags |= FLAG_INDIRECT;
    }
    if c.needs.reflections.needed {
        flags |= FLAG_REFLECTIONS;
    }
    if c.needs.refractions.needed {
        flags |= FLAG_REFRACTIONS;
    }
    if set.specular == Specular::BlinnPhong {
        flags |= FLAG_BLINN;
    }
    if set.sun_glints {
        flags |= FLAG_SUN_GLINTS;
    }
    if set.lpv_glossy > 0 && c.needs.indirect_lpv.needed && c.indirect == Indirect::Lpv {
        flags |= FLAG_LPV_GLOSSY;
    }
    u.csm[2] = if bound.cubes { set.point_shadow_resolution } else { 0 };
    if let Some(m) = bound.shadows.filter(|m| m.count > 0) {
        flags |= FLAG_SHADOWS;
        u.csm[0] = m.count;
        u.csm[1] = set.csm_resolution;
    }
    u.size = [set.width, set.height, s.scene_lights(), flags];
    let ao = if c.effects.is_on(Effect::AmbientOcclusion) { set.ssao_samples } else { 0 };
    u.params = [set.ssao_radius, ao as f32, bound.sky_map_size as f32, c.frame as f32];
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

fn sun_of(c: &FrameCtx) -> Result<SunLight, EngineError> {
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
    c.needs.indirect_lpv.needed && c.sun.is_some()
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
    cache_pass(&mut g, r, set.cache_frames);
    trace_passes(&mut g, r);
    traced_gbuffer_passes(&mut g, r);
    lighting_pass(&mut g, r);
    combine_pass(&mut g, r);
    tone_mapping_pass(&mut g, r);
    (g, Outputs { shown: r.shown, sky_volume, cache: r.cache })
}

/// The sky map (when the sun moved) and the sky volume filled over frames.
fn sky_passes(
    g: &mut FrameGraph<FrameCtx>,
    r: Resources,
    sky_layers: u32,
    layers_per_frame: u32,
) -> PassId {
    g.sync_point(pass::SKY_MAP)
        .writes(r.sky_map)
        .switched(Effect::SkyLighting)
        .run_if(SKY_NEEDED, sky_needed)
        .key("sun direction (0.06 deg)", sun_key)
        .run(move |io| -> PassResult {
            let c = io.ctx();
            let (s, dir) = (&c.state, c.sun.map_or(Vec3::Y, |s| s.dir));
            let previous = io.take_previous(r.sky_map)?;
            let map = SkyMapState::build(&s.gpu, sky_setup(c)?, &s.settings, dir, previous)?;
            s.gpu.take_error()?;
            io.put(r.sky_map, map)?;
            Ok(())
        });

    g.sync_point(pass::SKY_VOLUME)
        .reads(r.sky_map)
        .writes(r.sky_vol)
        .switched(Effect::SkyLighting)
        .run_if(SKY_NEEDED, sky_needed)
        .cached()
        .amortised(sky_layers, Budget::Units(layers_per_frame))
        .run(move |io| -> PassResult {
            let layer = io.unit().map_or(0, |u| u.index);
            let mut volume = previous_or(io, r.sky_vol, |c| {
                let s = &c.state;
                SkyVolumeState::new(&s.gpu, sky_setup(c)?, &s.settings, s.lighting.sky_io())
            })?;
            let s = &io.ctx().state;
            volume.fill_layer(&s.gpu, io.read(r.sky_map)?, layer)?;
            s.gpu.take_error()?;
            io.put(r.sky_vol, volume)?;
            Ok(())
        })
}

/// The sun's cascades and the point lights' cube maps.
fn shadow_passes(g: &mut FrameGraph<FrameCtx>, r: Resources) {
    g.gpu_pass(pass::SHADOW_MAPS)
        .writes(r.shadow)
        .switched(Effect::SunShadows)
        .run_if("the sun casts shadows in view", |c: &FrameCtx| {
            c.needs.sun_shadows.needed && c.sun.is_some()
        })
        .key("camera", camera_key)
        .key("sun direction", sun_key)
        .run(move |io| -> PassResult {
            let c = io.ctx();
            let (s, sun) = (&c.state, sun_of(c)?);
            let (dir, radius) = (sun.dir, sun.angular_radius);
            let maps = s.shadow.render(&s.gpu, &s.scene, &c.camera, dir, radius, &s.settings)?;
            s.gpu.take_error()?;
            io.put(r.shadow, maps)?;
            Ok(())
        });

    g.gpu_pass(pass::POINT_SHADOWS)
        .writes(r.cubes)
        .switched(Effect::PointLightShadows)
        .run_if("a shadow-casting point light reaches geometry in view", |c: &FrameCtx| {
            c.needs.point_light_shadows.needed
        })
        .cached()
        .run(move |io| -> PassResult {
            let s = &io.ctx().state;
            s.point_shadow.render(&s.gpu, &s.scene)?;
            s.gpu.take_error()?;
            io.put(r.cubes, CubeShadows)?;
            Ok(())
        });
}

/// The G-buffer of the camera.
fn gbuffer_pass(g: &mut FrameGraph<FrameCtx>, r: Resources) {
    g.gpu_pass(pass::GBUFFER).writes(r.gbuf).key("camera", camera_key).run(
        move |io| -> PassResult {
            let c = io.ctx();
            let s = &c.state;
            write_frame_uniform(c, Bound::default());
            let mut enc = s.gpu.device.create_command_encoder(&Default::default());
            s.gbuffer.record(&s.gpu.device, &mut enc, &s.targets, &s.frame, &s.scene);
            s.gpu.queue.submit([enc.finish()]);
            s.gpu.take_error()?;
            io.put(r.gbuf, GBufferView(c.camera))?;
            Ok(())
        },
    );
}

/// Whether traced rays read the one-bounce technique on the CPU this frame.
fn rays_traced(c: &FrameCtx) -> bool {
    rays_switched(c) && c.needs.ray_tracing()
}

/// One bounce of sunlight: the LPV, or the RSM the lighting pass gathers from.
fn bounce_passes(g: &mut FrameGraph<FrameCtx>, r: Resources, sky_bounce: bool) {
    let mut lpv = g
        .sync_point(pass::LPV)
        .writes(r.lpv)
        .switched(Effect::IndirectLight)
        .run_if(BOUNCE_NEEDED, bounce_needed)
        .run_if("the indirect technique is the LPV", |c: &FrameCtx| c.indirect == Indirect::Lpv)
        .key("camera cell (1 m)", |c: &FrameCtx| quantise_dir(c.camera.position.to_array(), 1.0))
        .key("sun direction", sun_key)
        .key("traced rays read the volumes", rays_traced);
    if sky_bounce {
        // The sky-bounce VPLs are the view's surfaces lit by the sky volume.
        lpv = lpv.reads(r.gbuf).reads(r.sky_map).reads(r.sky_vol);
    }
    lpv.run(move |io| -> PassResult {
        let mut l = previous_or(io, r.lpv, |c| c.state.new_lpv())?;
        let c = io.ctx();
        let (s, sun) = (&c.state, sun_of(c)?);
        let sky = sky_light(io, r).filter(|_| sky_needed(c));
        l.update(&s.gpu, &s.scene, &c.camera, &sun, sky)?;
        if rays_traced(c) {
            // The traced hits look the LPV up on the CPU.
            l.sync_cpu(&s.gpu)?;
        }
        s.gpu.take_error()?;
        io.put(r.lpv, l)?;
        Ok(())
    });

    g.gpu_pass(pass::SUN_RSM)
        .writes(r.sun_rsm)
        .switched(Effect::IndirectLight)
        .run_if(BOUNCE_NEEDED, bounce_needed)
        .run_if("the indirect technique is the RSM gather", |c: &FrameCtx| {
            c.indirect == Indirect::Rsm
        })
        .key("camera cell (1 m)", |c: &FrameCtx| quantise_dir(c.camera.position.to_array(), 1.0))
        .key("sun direction", sun_key)
        .run(move |io| -> PassResult {
            let mut gather = previous_or(io, r.sun_rsm, |c| c.state.new_rsm_gather())?;
            let c = io.ctx();
            let (s, sun) = (&c.state, sun_of(c)?);
            gather.update(&s.gpu, &s.scene, c.camera.position, &sun)?;
            s.gpu.take_error()?;
            io.put(r.sun_rsm, gather)?;
            Ok(())
        });
}

/// The radiance cache: allocated from the view, lit on the CPU, written to its GPU copy;
/// `cache_frames` frames after each camera or sun move (one unit per frame), then reused.
fn cache_pass(g: &mut FrameGraph<FrameCtx>, r: Resources, cache_frames: u32) {
    g.sync_point(pass::RADIANCE_CACHE)
        .writes(r.cache)
        .switched(Effect::IndirectLight)
        .run_if(BOUNCE_NEEDED, bounce_needed)
        .run_if("the indirect technique is the radiance cache", |c: &FrameCtx| {
            c.indirect == Indirect::Cache
        })
        .key("camera", camera_key)
        .key("sun direction", sun_key)
        .amortised(cache_frames, Budget::Units(1))
        .run(move |io| -> PassResult {
            let mut cache = previous_or(io, r.cache, |c| c.state.new_cache())?;
            let c = io.ctx();
            let (s, sun) = (&c.state, sun_of(c)?);
            let lookup = s.lighting.lookup_io();
            cache.update(&s.gpu, &s.scene, &s.trace, &c.camera, &sun, lookup)?;
            s.gpu.take_error()?;
            io.put(r.cache, cache)?;
            Ok(())
        });
}

/// The ray-casting buffer read back and traced on a CPU worker.
fn trace_passes(g: &mut FrameGraph<FrameCtx>, r: Resources) {
    g.sync_point(pass::RAY_CASTING)
        .reads(r.gbuf)
        .writes(r.batch)
        .run_if(RAYS_SWITCHED, rays_switched)
        .run_if(RAYS_NEEDED, |c: &FrameCtx| c.needs.ray_tracing())
        .cached()
        .key("kinds of rays (reflection, refraction)", |c: &FrameCtx| {
            (c.needs.reflections.needed, c.needs.refractions.needed)
        })
        .run(move |io| -> PassResult {
            let c = io.ctx();
            let s = &c.state;
            write_frame_uniform(c, Bound::default());
            let b = s.raycast.run(&s.gpu, &s.targets, &s.frame, &s.scene.materials)?;
            s.gpu.take_error()?;
            io.put(r.batch, b)?;
            Ok(())
        });

    g.cpu_job(pass::RAY_TRACING)
        .reads(r.batch)
        .reads(r.sky_map)
        .reads(r.sky_vol)
        .reads(r.lpv)
        .reads(r.cache)
        .writes(r.traced)
        .run_if(RAYS_SWITCHED, rays_switched)
        .run_if(RAYS_NEEDED, |c: &FrameCtx| c.needs.ray_tracing())
        .cached()
        .run(move |io| -> PassResult {
            let c = io.ctx();
            let s = &c.state;
            let b = io.read(r.batch)?;
            let sky = sky_light(io, r).filter(|_| c.needs.sky_lighting.needed);
            // The RSM gather is per pixel of the view: traced hits get no bounce from it.
            let bounce = c.needs.indirect_lpv.needed;
            let lpv = io.try_read(r.lpv).filter(|_| bounce && c.indirect == Indirect::Lpv);
            let cache = io.try_read(r.cache).filter(|_| bounce && c.indirect == Indirect::Cache);
            let sky_fn = |d: Vec3| sky.map_or(Vec3::ZERO, |k| k.radiance(d));
            let ambient = |p: Vec3, n: Vec3| {
                sky.map_or(Vec3::ZERO, |k| k.irradiance(p, n))
                    + lpv.map_or(Vec3::ZERO, |l| l.lpv.irradiance(p, n))
                    + cache.map_or(Vec3::ZERO, |k| k.cache.irradiance(p, n))
            };
            let lighting = TraceLighting {
                sun: c.sun.filter(|_| c.needs.sun_lighting.needed).map(|s| (s.dir, s.irradiance)),
                point_lights: &s.point_lights,
                sky: &sky_fn,
                ambient: &ambient,
            };
            let settings = TraceSettings { max_depth: s.settings.trace_depth, alpha_test: true };
            let traced = match s.settings.traced_shading {
                TracedShading::Cpu => {
                    Traced::Radiance(trace_rays(&s.trace, &lighting, &b.rays, &settings))
                }
                TracedShading::Gpu => {
                    Traced::Surfaces(trace_surfaces(&s.trace, &lighting, &b.rays, &settings))
                }
            };
            io.put(r.traced, traced)?;
            Ok(())
        });
}

/// The one-bounce source the lighting pass binds this frame.
fn indirect_source<'a>(io: &'a PassIo<'_, FrameCtx>, r: Resources) -> IndirectSource<'a> {
    let c = io.ctx();
    if !c.needs.indirect_lpv.needed {
        return IndirectSource::None;
    }
    let source = match c.indirect {
        Indirect::Lpv => io.try_read(r.lpv).map(IndirectSource::Lpv),
        Indirect::Rsm => io
            .try_read(r.sun_rsm)
            .filter(|g| g.ready)
            .map(|g| IndirectSource::Rsm(g, c.camera.view_projection())),
        Indirect::Cache => io.try_read(r.cache).filter(|k| k.ready()).map(IndirectSource::Cache),
        Indirect::None => None,
    };
    source.unwrap_or(IndirectSource::None)
}

/// The deferred lighting of the view.
fn lighting_pass(g: &mut FrameGraph<FrameCtx>, r: Resources) {
    g.gpu_pass(pass::LIGHTING)
        .reads(r.gbuf)
        .reads(r.shadow)
        .reads(r.cubes)
        .reads(r.sky_map)
        .reads(r.sky_vol)
        .reads(r.lpv)
        .reads(r.sun_rsm)
        .reads(r.cache)
        .writes(r.lit)
        .cached()
        .key("view shown", |c: &FrameCtx| c.component)
        .run(move |io| -> PassResult {
            let c = io.ctx();
            let s = &c.state;
            let shadows = io.try_read(r.shadow).copied().filter(|_| c.needs.sun_shadows.needed);
            let sky = sky_light(io, r);
            let cubes = io.try_read(r.cubes).is_some();
            let sky_map_size = sky.map_or(0, |k| k.map.size());
            write_frame_uniform(c, Bound { shadows, cubes, sky_map_size });
            let inputs = LightingInputs {
                frame: &s.frame,
                shadows: s.shadow.bindings(shadows.as_ref()),
                sky,
                sky_volume: c.needs.sky_lighting.needed && sky.is_some(),
                indirect: indirect_source(io, r),
                materials: &s.scene.materials,
                lights: &s.lights,
                cubes: s.point_shadow.bindings(),
            };
            let mut enc = s.gpu.device.create_command_encoder(&Default::default());
            s.lighting.record(&s.gpu, &mut enc, &s.targets, &inputs)?;
            s.gpu.queue.submit([enc.finish()]);
            s.gpu.take_error()?;
            io.put(r.lit, LitView(c.component))?;
            Ok(())
        });
}

const GPU_SHADING: &str = "the traced G-buffer is lit on the GPU";
fn gpu_shading(c: &FrameCtx) -> bool {
    c.state.settings.traced_shading == TracedShading::Gpu
}

/// The traced G-buffer lit on the GPU (`TracedShading::Gpu`): the sun's overlapped shadow
/// maps around the camera, and the lighting of the traced surfaces into the combine pass's
/// traced radiance.
fn traced_gbuffer_passes(g: &mut FrameGraph<FrameCtx>, r: Resources) {
    g.gpu_pass(pass::OSM)
        .writes(r.osm)
        .switched(Effect::SunShadows)
        .run_if(GPU_SHADING, gpu_shading)
        .run_if(RAYS_SWITCHED, rays_switched)
        .run_if(RAYS_NEEDED, |c: &FrameCtx| c.needs.ray_tracing())
        .run_if("the sun casts shadows", |c: &FrameCtx| {
            c.needs.sun_shadows.needed && c.sun.is_some()
        })
        .key("camera cell (1 m)", |c: &FrameCtx| quantise_dir(c.camera.position.to_array(), 1.0))
        .key("sun direction", sun_key)
        .run(move |io| -> PassResult {
            let mut osm =
                previous_or(io, r.osm, |c| OsmPass::new(&c.state.gpu.device, &c.state.settings))?;
            let c = io.ctx();
            let (s, sun) = (&c.state, sun_of(c)?);
            osm.render(&s.gpu, &s.scene, c.camera.position, &sun)?;
            s.gpu.take_error()?;
            io.put(r.osm, osm)?;
            Ok(())
        });

    g.sync_point(pass::TRACED_LIGHTING)
        .reads(r.batch)
        .reads(r.traced)
        .reads(r.osm)
        .reads(r.cubes)
        .reads(r.sky_map)
        .reads(r.sky_vol)
        .reads(r.lpv)
        .writes(r.traced_lit)
        .run_if(GPU_SHADING, gpu_shading)
        .run_if(RAYS_SWITCHED, rays_switched)
        .run_if(RAYS_NEEDED, |c: &FrameCtx| c.needs.ray_tracing())
        .cached()
        .run(move |io| -> PassResult {
            let mut pass =
                previous_or(io, r.traced_lit, |c| TracedLightingPass::new(&c.state.gpu.device))?;
            let c = io.ctx();
            let s = &c.state;
            let Traced::Surfaces(hits) = io.read(r.traced)? else {
                return Err(
                    EngineError::Settings("the ray tracing job shaded on the CPU".into()).into()
                );
            };
            let osm = io.try_read(r.osm).filter(|_| c.needs.sun_shadows.needed);
            let bounce = c.needs.indirect_lpv.needed && c.indirect == Indirect::Lpv;
            let sky = sky_light(io, r).filter(|_| c.needs.sky_lighting.needed);
            let cubes = io.try_read(r.cubes).is_some();
            write_frame_uniform(c, Bound { shadows: None, cubes, sky_map_size: 0 });
            let inputs = TracedInputs {
                frame: &s.frame,
                osm: osm.map_or_else(|| s.shadow.bindings(None), OsmPass::bindings),
                sky,
                lpv: io.try_read(r.lpv).filter(|_| bounce),
                lights: &s.lights,
                cubes: s.point_shadow.bindings(),
                out: s.combine.traced(),
            };
            pass.run(&s.gpu, io.read(r.batch)?, hits, &inputs)?;
            s.gpu.take_error()?;
            io.put(r.traced_lit, pass)?;
            Ok(())
        });
}

/// The traced radiance (uploaded from the CPU, or lit on the GPU) combined with the lit view.
fn combine_pass(g: &mut FrameGraph<FrameCtx>, r: Resources) {
    g.sync_point(pass::COMBINE)
        .reads(r.lit)
        .reads(r.batch)
        .reads(r.traced)
        .reads(r.traced_lit)
        .writes(r.combined)
        .run_if(RAYS_SWITCHED, rays_switched)
        .run_if(RAYS_NEEDED, |c: &FrameCtx| c.needs.ray_tracing())
        .cached()
        .key("view shown", |c: &FrameCtx| c.component)
        .run(move |io| -> PassResult {
            let c = io.ctx();
            let s = &c.state;
            if let Traced::Radiance(radiance) = io.read(r.traced)? {
                s.combine.upload(&s.gpu, io.read(r.batch)?, radiance);
            }
            let mut enc = s.gpu.device.create_command_encoder(&Default::default());
            let (device, targets, frame) = (&s.gpu.device, &s.targets, &s.frame);
            s.combine.record(device, &mut enc, targets, frame, &s.scene.materials, &s.raycast);
            s.gpu.queue.submit([enc.finish()]);
            s.gpu.take_error()?;
            io.put(r.combined, CombinedView(c.component))?;
            Ok(())
        });
}

/// Tone mapping and eye adaptation, every frame.
fn tone_mapping_pass(g: &mut FrameGraph<FrameCtx>, r: Resources) {
    // Every frame: eye adaptation moves on even when the view is unchanged.
    g.gpu_pass(pass::TONE_MAPPING).reads(r.lit).reads(r.combined).writes(r.shown).run(
        move |io| -> PassResult {
            let c = io.ctx();
            let s = &c.state;
            let combined = io.try_read(r.combined).is_some() && c.needs.ray_tracing();
            let which = if combined { Shown::Combined } else { Shown::Lit };
            let set = &s.settings;
            let mut enc = s.gpu.device.create_command_encoder(&Default::default());
            let exposure = Exposure {
                dt: c.dt,
                rate: set.adaptation_per_s,
                key: set.key,
                reset: c.reset_exposure,
                raw: crate::views::View::of_code(c.component).is_some_and(|v| v.is_raw()),
            };
            s.display.record(&s.gpu, &mut enc, which, exposure);
            s.gpu.queue.submit([enc.finish()]);
            s.gpu.take_error()?;
            io.put(r.shown, which)?;
            Ok(())
        },
    );
}
