//! The frame graph: every pass of the pipeline declared once with the condition under which
//! it runs (from `scene::SceneNeeds`), the inputs and keys whose change makes it run again,
//! and a body that calls the pass's plain function. `frame_scheduler` decides, runs (the CPU
//! ray tracing on a worker thread while the GPU lights the view) and reports.

use crate::effects::Effect;
use crate::frame::{
    FLAG_BLINN, FLAG_INDIRECT, FLAG_LPV_GLOSSY, FLAG_REFLECTIONS, FLAG_REFRACTIONS, FLAG_SHADOWS,
    FLAG_SKY, FLAG_SKY_VOLUME, FLAG_SUN_GLINTS, FrameUniform,
};
use crate::passes::display::{Exposure, Shown};
use crate::passes::lighting::{IndirectSource, LightingInputs};
use crate::passes::raycast::RayBatch;
use crate::settings::{Indirect, Specular};
use crate::state::{FrameCtx, poisoned};
use crate::trace::{TraceLighting, TraceSettings, trace_rays};
use frame_scheduler::{Budget, FrameGraph, PassBuilder, PassId, PassResult, Res, quantise_dir};
use glam::Vec3;
use std::sync::atomic::Ordering;

/// Traced radiance per ray of the batch.
pub struct Traced(pub Vec<Vec3>);

/// Handles to the graph's resources the renderer reads.
pub struct Outputs {
    /// Which HDR target the display image of the frame was made from.
    pub shown: Res<Shown>,
    pub sky_volume: PassId,
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

/// Writes the frame uniform for this frame's camera, sun and enabled techniques.
fn write_frame_uniform(c: &FrameCtx) {
    let s = &c.state;
    let set = &s.settings;
    let mut u = FrameUniform::new(&c.camera, set.width, set.height);
    if let Some(sun) = c.sun.filter(|_| c.needs.sun_lighting.needed) {
        u.sun_dir = sun.dir.extend(1.0).to_array();
        u.sun_irradiance = sun.irradiance.extend(sun.angular_radius).to_array();
    }
    let mut flags = 0;
    if s.sky.is_some() && c.needs.sky_lighting.needed {
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
    let maps = s.shadow_maps.lock().ok().and_then(|m| *m);
    let cubes = s.point_shadows_ready.load(Ordering::Acquire);
    u.csm[2] = if cubes { set.point_shadow_resolution } else { 0 };
    if let Some(m) = maps.filter(|m| m.count > 0 && c.needs.sun_shadows.needed) {
        flags |= FLAG_SHADOWS;
        u.csm[0] = m.count;
        u.csm[1] = set.csm_resolution;
    }
    let sky_size = s.sky.as_ref().and_then(|k| k.read().ok()).map_or(0, |k| k.map_size());
    u.size = [set.width, set.height, s.scene_lights(), flags];
    let ao = if c.effects.is_on(Effect::AmbientOcclusion) { set.ssao_samples } else { 0 };
    u.params = [set.ssao_radius, ao as f32, sky_size as f32, c.frame as f32];
    u.csm[3] = c.component;
    s.gpu.write(&s.frame, 0, bytemuck::bytes_of(&u));
}

/// The graph's resources: what each pass writes and the passes after it read.
#[derive(Clone, Copy)]
struct Resources {
    sky_map: Res<u64>,
    sky_vol: Res<u64>,
    shadow: Res<u64>,
    gbuf: Res<u64>,
    cubes: Res<u64>,
    lpv: Res<u64>,
    sun_rsm: Res<u64>,
    cache: Res<u64>,
    batch: Res<RayBatch>,
    traced: Res<Traced>,
    lit: Res<u64>,
    combined: Res<u64>,
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
    lighting_pass(&mut g, r);
    combine_pass(&mut g, r);
    tone_mapping_pass(&mut g, r);
    (g, Outputs { shown: r.shown, sky_volume })
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
            let dir = c.sun.map_or(Vec3::Y, |s| s.dir);
            if let Some(sky) = &c.state.sky {
                sky.write().map_err(poisoned)?.build_map(&c.state.gpu, dir)?;
            }
            io.ctx().state.gpu.take_error()?;
            io.put(r.sky_map, c.frame)?;
            Ok(())
        });

    g.gpu_pass(pass::SKY_VOLUME)
        .reads(r.sky_map)
        .writes(r.sky_vol)
        .switched(Effect::SkyLighting)
        .run_if(SKY_NEEDED, sky_needed)
        .cached()
        .amortised(sky_layers, Budget::Units(layers_per_frame))
        .run(move |io| -> PassResult {
            let c = io.ctx();
            let layer = io.unit().map_or(0, |u| u.index);
            if let Some(sky) = &c.state.sky {
                sky.write().map_err(poisoned)?.fill_layers(&c.state.gpu, layer..layer + 1)?;
            }
            io.ctx().state.gpu.take_error()?;
            io.put(r.sky_vol, c.frame)?;
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
            let s = &c.state;
            let sun = c.sun.ok_or_else(|| crate::EngineError::Settings("no sun".into()))?;
            let maps = s.shadow.render(
                &s.gpu,
                &s.scene,
                &c.camera,
                sun.dir,
                sun.angular_radius,
                &s.settings,
            )?;
            *s.shadow_maps.lock().map_err(poisoned)? = Some(maps);
            io.ctx().state.gpu.take_error()?;
            io.put(r.shadow, c.frame)?;
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
            let c = io.ctx();
            let s = &c.state;
            s.point_shadow.render(&s.gpu, &s.scene)?;
            s.point_shadows_ready.store(true, Ordering::Release);
            io.ctx().state.gpu.take_error()?;
            io.put(r.cubes, c.frame)?;
            Ok(())
        });
}

/// The G-buffer of the camera.
fn gbuffer_pass(g: &mut FrameGraph<FrameCtx>, r: Resources) {
    g.gpu_pass(pass::GBUFFER).writes(r.gbuf).key("camera", camera_key).run(
        move |io| -> PassResult {
            let c = io.ctx();
            let s = &c.state;
            write_frame_uniform(c);
            let mut enc = s.gpu.device.create_command_encoder(&Default::default());
            s.gbuffer.record(&s.gpu.device, &mut enc, &s.targets, &s.frame, &s.scene);
            s.gpu.queue.submit([enc.finish()]);
            io.ctx().state.gpu.take_error()?;
            io.put(r.gbuf, c.frame)?;
            Ok(())
        },
    );
}

/// One bounce of sunlight: the LPV, or the RSM the lighting pass gathers from.
fn bounce_passes(g: &mut FrameGraph<FrameCtx>, r: Resources, sky_bounce: bool) {
    let mut lpv = g
        .gpu_pass(pass::LPV)
        .writes(r.lpv)
        .switched(Effect::IndirectLight)
        .run_if(BOUNCE_NEEDED, bounce_needed)
        .run_if("the indirect technique is the LPV", |c: &FrameCtx| c.indirect == Indirect::Lpv)
        .key("camera cell (1 m)", |c: &FrameCtx| quantise_dir(c.camera.position.to_array(), 1.0))
        .key("sun direction", sun_key);
    if sky_bounce {
        // The sky-bounce VPLs are the view's surfaces lit by the sky volume.
        lpv = lpv.reads(r.gbuf).reads(r.sky_vol);
    }
    lpv.run(move |io| -> PassResult {
        let c = io.ctx();
        let s = &c.state;
        let sun = c.sun.ok_or_else(|| crate::EngineError::Settings("no sun".into()))?;
        let sky = match &s.sky {
            Some(k) if c.needs.sky_lighting.needed => Some(k.read().map_err(poisoned)?),
            _ => None,
        };
        let mut l = s.lpv.write().map_err(poisoned)?;
        l.update(&s.gpu, &s.scene, &c.camera, &sun, sky.as_deref())?;
        s.gpu.take_error()?;
        io.put(r.lpv, c.frame)?;
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
            let c = io.ctx();
            let sun = c.sun.ok_or_else(|| crate::EngineError::Settings("no sun".into()))?;
            let mut gather = c.state.rsm_gather.write().map_err(poisoned)?;
            let (eye, s) = (c.camera.position, &c.state);
            gather.update(&s.gpu, &s.scene, eye, &sun)?;
            io.ctx().state.gpu.take_error()?;
            io.put(r.sun_rsm, c.frame)?;
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
            let c = io.ctx();
            let s = &c.state;
            let sun = c.sun.ok_or_else(|| crate::EngineError::Settings("no sun".into()))?;
            let mut cache = s.cache.write().map_err(poisoned)?;
            let lookup = s.lighting.lookup_io();
            cache.update(&s.gpu, &s.scene, &s.trace, &c.camera, &sun, lookup)?;
            io.ctx().state.gpu.take_error()?;
            io.put(r.cache, c.frame)?;
            Ok(())
        });
}

/// The ray-casting buffer read back and traced on a CPU worker.
fn trace_passes(g: &mut FrameGraph<FrameCtx>, r: Resources) {
    g.sync_point(pass::RAY_CASTING)
        .reads(r.gbuf)
        .reads(r.sky_vol)
        .reads(r.lpv)
        .reads(r.cache)
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
            write_frame_uniform(c);
            if c.needs.indirect_lpv.needed && c.indirect == Indirect::Lpv {
                // The traced hits look the LPV up on the CPU.
                s.lpv.write().map_err(poisoned)?.sync_cpu(&s.gpu)?;
            }
            let b = s.raycast.run(&s.gpu, &s.targets, &s.frame, &s.scene.materials)?;
            io.ctx().state.gpu.take_error()?;
            io.put(r.batch, b)?;
            Ok(())
        });

    g.cpu_job(pass::RAY_TRACING)
        .reads(r.batch)
        .writes(r.traced)
        .run_if(RAYS_SWITCHED, rays_switched)
        .run_if(RAYS_NEEDED, |c: &FrameCtx| c.needs.ray_tracing())
        .cached()
        .run(move |io| -> PassResult {
            let c = io.ctx();
            let s = &c.state;
            let b = io.read(r.batch)?;
            let sky_guard = match &s.sky {
                Some(k) => Some(k.read().map_err(poisoned)?),
                None => None,
            };
            let lpv_guard = s.lpv.read().map_err(poisoned)?;
            let cache_guard = s.cache.read().map_err(poisoned)?;
            // The RSM gather is per pixel of the view: traced hits get no bounce from it.
            let bounce = c.needs.indirect_lpv.needed;
            let use_lpv = bounce && c.indirect == Indirect::Lpv;
            let use_cache = bounce && c.indirect == Indirect::Cache;
            let use_sky = c.needs.sky_lighting.needed;
            let sky_fn = |d: Vec3| {
                sky_guard.as_ref().filter(|_| use_sky).map_or(Vec3::ZERO, |k| k.radiance(d))
            };
            let ambient = |p: Vec3, n: Vec3| {
                let mut e = Vec3::ZERO;
                if let Some(k) = sky_guard.as_ref().filter(|_| use_sky) {
                    e += k.volume.irradiance(p, n);
                }
                if use_lpv {
                    e += lpv_guard.lpv.irradiance(p, n);
                }
                if use_cache {
                    e += cache_guard.cache.irradiance(p, n);
                }
                e
            };
            let lighting = TraceLighting {
                sun: c.sun.filter(|_| c.needs.sun_lighting.needed).map(|s| (s.dir, s.irradiance)),
                point_lights: &s.point_lights,
                sky: &sky_fn,
                ambient: &ambient,
            };
            let settings = TraceSettings { max_depth: s.settings.trace_depth, alpha_test: true };
            let radiance = trace_rays(&s.trace, &lighting, &b.rays, &settings);
            io.put(r.traced, Traced(radiance))?;
            Ok(())
        });
}

/// The deferred lighting of the view.
fn lighting_pass(g: &mut FrameGraph<FrameCtx>, r: Resources) {
    g.gpu_pass(pass::LIGHTING)
        .reads(r.gbuf)
        .reads(r.shadow)
        .reads(r.cubes)
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
            write_frame_uniform(c);
            let maps = *s.shadow_maps.lock().map_err(poisoned)?;
            let sky = match &s.sky {
                Some(k) => Some(k.read().map_err(poisoned)?),
                None => None,
            };
            let lpv_state = s.lpv.read().map_err(poisoned)?;
            let rsm_state = s.rsm_gather.read().map_err(poisoned)?;
            let cache_state = s.cache.read().map_err(poisoned)?;
            let indirect = match c.indirect {
                _ if !c.needs.indirect_lpv.needed => IndirectSource::None,
                Indirect::Lpv => IndirectSource::Lpv(&lpv_state),
                Indirect::Rsm if rsm_state.ready => {
                    IndirectSource::Rsm(&rsm_state, c.camera.view_projection())
                }
                Indirect::Cache if cache_state.ready() => IndirectSource::Cache(&cache_state),
                Indirect::Rsm | Indirect::Cache | Indirect::None => IndirectSource::None,
            };
            let inputs = LightingInputs {
                frame: &s.frame,
                shadows: s.shadow.bindings(maps.as_ref().filter(|_| c.needs.sun_shadows.needed)),
                sky: sky.as_deref(),
                sky_volume: c.needs.sky_lighting.needed && sky.is_some(),
                indirect,
                materials: &s.scene.materials,
                lights: &s.lights,
                cubes: s.point_shadow.bindings(),
            };
            let mut enc = s.gpu.device.create_command_encoder(&Default::default());
            s.lighting.record(&s.gpu, &mut enc, &s.targets, &inputs)?;
            s.gpu.queue.submit([enc.finish()]);
            io.ctx().state.gpu.take_error()?;
            io.put(r.lit, c.frame)?;
            Ok(())
        });
}

/// The traced radiance uploaded and combined with the lit view.
fn combine_pass(g: &mut FrameGraph<FrameCtx>, r: Resources) {
    g.sync_point(pass::COMBINE)
        .reads(r.lit)
        .reads(r.batch)
        .reads(r.traced)
        .writes(r.combined)
        .run_if(RAYS_SWITCHED, rays_switched)
        .run_if(RAYS_NEEDED, |c: &FrameCtx| c.needs.ray_tracing())
        .cached()
        .key("view shown", |c: &FrameCtx| c.component)
        .run(move |io| -> PassResult {
            let c = io.ctx();
            let s = &c.state;
            let (b, t) = (io.read(r.batch)?, io.read(r.traced)?);
            s.combine.upload(&s.gpu, b, &t.0);
            let mut enc = s.gpu.device.create_command_encoder(&Default::default());
            s.combine.record(
                &s.gpu.device,
                &mut enc,
                &s.targets,
                &s.frame,
                &s.scene.materials,
                &s.raycast,
            );
            s.gpu.queue.submit([enc.finish()]);
            io.ctx().state.gpu.take_error()?;
            io.put(r.combined, c.frame)?;
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
