//! The passes that light the view: the sky map and volume, the shadow maps, the G-buffer,
//! the one-bounce techniques, the deferred lighting and the tone mapping.

use super::*;
use crate::passes::cache_bounce::SceneHitShading;
use crate::passes::display::post_err;

/// The sky map (when the sun moved) and the sky volume filled over frames.
pub(super) fn sky_passes(
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
            let (s, dir) = (&c.state, c.sun.map_or(Vec3::Y, |s| s.direction));
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
                SkyVolumeState::new(&s.gpu, sky_setup(c)?, &s.settings)
            })?;
            let s = &io.ctx().state;
            volume.fill_layer(&s.gpu, io.read(r.sky_map)?, layer)?;
            s.gpu.take_error()?;
            io.put(r.sky_vol, volume)?;
            Ok(())
        })
}

/// The sun's cascades and the point lights' cube maps.
pub(super) fn shadow_passes(g: &mut FrameGraph<FrameCtx>, r: Resources) {
    g.gpu_pass(pass::SHADOW_MAPS)
        .writes(r.shadow)
        .switched(Effect::SunShadows)
        .run_if("the sun casts shadows in view", |c: &FrameCtx| {
            c.needs.sun_shadows.needed && c.sun.is_some()
        })
        // Equal plans render equal maps: the stabilised cascades keep their views while the
        // camera moves by less than their texels; of a changed plan, only the maps whose view
        // moved are rendered.
        .key("cascade views (texel-snapped)", |c: &FrameCtx| sun_maps_plan(c).ok())
        .run(move |io| -> PassResult {
            let s = &io.ctx().state;
            let maps = s.shadow.render(&s.gpu, &s.scene, &sun_maps_plan(io.ctx())?)?;
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

/// The sun cascades the frame's camera and sun call for.
fn sun_maps_plan(c: &FrameCtx) -> Result<SunMapsPlan, EngineError> {
    let (s, sun) = (&c.state, sun_of(c)?);
    s.shadow.plan(&c.camera, &sun, &s.settings)
}

/// The G-buffer of the camera.
pub(super) fn gbuffer_pass(g: &mut FrameGraph<FrameCtx>, r: Resources) {
    let gbuffer = g.gpu_pass(pass::GBUFFER).writes(r.gbuf).key("camera", camera_key);
    gbuffer.key("still-view sample (sub-pixel jitter)", |c: &FrameCtx| c.still_sample).run(
        move |io| -> PassResult {
            let c = io.ctx();
            let s = &c.state;
            write_frame_uniform(c, Bound::default());
            let camera = c.gbuffer_camera();
            let mut enc = s.gpu.device.create_command_encoder(&Default::default());
            let bytes = s.gbuffer.record(&s.gpu.queue, &mut enc, &s.targets, &s.scene, &camera);
            s.gpu.transfers.uploaded(bytes);
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
pub(super) fn bounce_passes(g: &mut FrameGraph<FrameCtx>, r: Resources, sky_bounce: bool) {
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
/// With `many_bounces` (`radiance_cache::Bounces::Many`) its rays' hits are shaded with the
/// sky volume's light too ([`SceneHitShading`]), so the pass also reads the sky and starts
/// again when the sky volume changed (while it fills, and after the sun moved).
pub(super) fn cache_pass(
    g: &mut FrameGraph<FrameCtx>,
    r: Resources,
    cache_frames: u32,
    many_bounces: bool,
) {
    let p = g
        .sync_point(pass::RADIANCE_CACHE)
        .writes(r.cache)
        .switched(Effect::IndirectLight)
        .run_if(BOUNCE_NEEDED, bounce_needed)
        .run_if("the indirect technique is the radiance cache", |c: &FrameCtx| {
            c.indirect == Indirect::Cache
        })
        .key("camera", camera_key)
        .key("sun direction", sun_key);
    let p = if many_bounces {
        let sky_needed = |c: &FrameCtx| c.needs.sky_lighting.needed;
        p.reads(r.sky_map).reads(r.sky_vol).key("sky lighting", sky_needed)
    } else {
        p
    };
    p.amortised(cache_frames, Budget::Units(1)).run(move |io| -> PassResult {
        let mut cache = previous_or(io, r.cache, |c| c.state.new_cache())?;
        let c = io.ctx();
        let (s, sun) = (&c.state, sun_of(c)?);
        let lookup = s.lighting.lookup_io();
        let shading = many_bounces.then(|| SceneHitShading {
            trace: &s.trace,
            albedo: &s.scene.diffuse_albedo,
            sky: sky_light(io, r).filter(|_| c.needs.sky_lighting.needed),
            point_lights: &s.point_lights,
        });
        cache.update(&s.gpu, &s.scene, &s.trace, &c.camera, &sun, lookup, shading.as_ref())?;
        s.gpu.take_error()?;
        io.put(r.cache, cache)?;
        Ok(())
    });
}

/// The one-bounce source the lighting pass binds this frame.
pub(super) fn indirect_source<'a>(
    io: &'a PassIo<'_, FrameCtx>,
    r: Resources,
) -> IndirectSource<'a> {
    let c = io.ctx();
    if !c.needs.indirect.needed {
        return IndirectSource::None;
    }
    let source = match c.indirect {
        Indirect::Lpv => io.try_read(r.lpv).map(IndirectSource::Lpv),
        Indirect::Rsm => io
            .try_read(r.sun_rsm)
            .filter(|g| g.ready)
            .map(|g| IndirectSource::Rsm(g, c.view_projection())),
        Indirect::Cache => io.try_read(r.cache).filter(|k| k.ready()).map(IndirectSource::Cache),
        Indirect::None => None,
    };
    source.unwrap_or(IndirectSource::None)
}

/// The deferred lighting of the view.
pub(super) fn lighting_pass(g: &mut FrameGraph<FrameCtx>, r: Resources) {
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
            let reflectors = match c.sun {
                Some(sun) => ReflectorSet::in_view(
                    &s.reflectors,
                    sun.direction,
                    &s.bounds,
                    &c.camera.frustum(),
                ),
                None => ReflectorSet::new(&[]),
            };
            let inputs = LightingInputs {
                frame: &s.frame,
                shadows: s.shadow.bindings(shadows.as_ref()),
                sky,
                sky_volume: c.needs.sky_lighting.needed && sky.is_some(),
                indirect: indirect_source(io, r),
                materials: &s.scene.materials,
                specular_albedo: &s.scene.gpu.specular_albedo,
                reflectors: &reflectors,
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

/// The frame's HDR image before anti-aliasing: the combined view when traced rays were
/// combined with it, else the lit view.
fn frame_image(io: &PassIo<'_, FrameCtx>, r: Resources) -> Shown {
    let combined = io.try_read(r.combined).is_some() && io.ctx().needs.ray_tracing();
    if combined { Shown::Combined } else { Shown::Lit }
}

/// Why a view's first frame (still sample 0, every frame of a moving camera) is not
/// accumulated: it is shown alone, so tone mapping reads the lit image itself rather than a
/// copy of it, and the first sample of the average clears the accumulated image anyway.
const FIRST_FRAME_SHOWN_AS_LIT: &str =
    "a still view's sample (a view's first frame is shown as it was lit, not copied)";

/// The still view's anti-aliasing: the frame's image averaged with the still view's earlier
/// samples (`post::gpu::AccumulatePass`).
pub(super) fn accumulate_pass(g: &mut FrameGraph<FrameCtx>, r: Resources) {
    g.gpu_pass(pass::ACCUMULATE)
        .reads(r.lit)
        .reads(r.combined)
        .writes(r.accumulated)
        .run_if("still views are anti-aliased (more than one still sample)", |c: &FrameCtx| {
            c.state.settings.still_samples > 1
        })
        .run_if(FIRST_FRAME_SHOWN_AS_LIT, |c: &FrameCtx| c.still_sample > 0)
        .cached()
        .key("still-view sample", |c: &FrameCtx| c.still_sample)
        .run(move |io| -> PassResult {
            let c = io.ctx();
            let s = &c.state;
            let mut enc = s.gpu.device.create_command_encoder(&Default::default());
            let source = frame_image(io, r).index();
            s.accumulate.record(&mut enc, source, c.still_sample).map_err(post_err)?;
            s.gpu.queue.submit([enc.finish()]);
            s.gpu.take_error()?;
            io.put(r.accumulated, super::Accumulated(c.still_sample.max(1)))?;
            Ok(())
        });
}

/// Tone mapping and eye adaptation, every frame.
pub(super) fn tone_mapping_pass(g: &mut FrameGraph<FrameCtx>, r: Resources) {
    // Every frame: eye adaptation moves on even when the view is unchanged.
    let reads = g.gpu_pass(pass::TONE_MAPPING).reads(r.lit).reads(r.combined);
    reads.reads(r.accumulated).writes(r.shown).run(move |io| -> PassResult {
        let c = io.ctx();
        let s = &c.state;
        let which = match io.try_read(r.accumulated) {
            Some(_) => Shown::Accumulated,
            None => frame_image(io, r),
        };
        let set = &s.settings;
        let mut enc = s.gpu.device.create_command_encoder(&Default::default());
        let exposure = post::Exposure {
            dt: c.dt,
            rate: set.adaptation_per_s,
            key: set.key,
            reset: c.reset_exposure,
            raw: crate::views::View::of_code(c.component).is_some_and(|v| v.is_raw()),
        };
        s.display.record(&s.gpu.queue, &mut enc, which.index(), exposure).map_err(post_err)?;
        s.gpu.transfers.uploaded(post::gpu::ToneMapPass::UPLOAD_BYTES);
        s.gpu.queue.submit([enc.finish()]);
        s.gpu.take_error()?;
        io.put(r.shown, which)?;
        Ok(())
    });
}
