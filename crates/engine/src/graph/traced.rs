//! The passes of the traced rays: the ray-casting buffer read back, the CPU tracing, the
//! traced G-buffer lit on the GPU (`TracedShading::Gpu`) and the combination with the view
//! (the first and the last `traced_effects::gpu`'s passes).

use super::*;
use traced_effects::gpu::{CombineInputs, TracedView};
use traced_effects::ray_casting::RayKinds;
use traced_effects::screen::ScreenView;

/// `traced_effects`' uniform for this frame's view (jittered as the G-buffer), the kinds of
/// rays the scene calls for, and whether the view shown takes the traced radiance (the full
/// frame and the reflections component).
fn traced_view(c: &FrameCtx) -> TracedView {
    let set = &c.state.settings;
    let (eye, forward) = (c.camera.position, c.camera.forward);
    let view = ScreenView::new(c.view_projection(), eye, forward, (set.width, set.height));
    let kinds = RayKinds {
        reflections: c.needs.reflections.needed,
        refractions: c.needs.refractions.needed,
    };
    let shown = [None, Some(crate::Component::Reflections)].map(crate::components::code);
    TracedView::new(&view, kinds, shown.contains(&c.component))
}

/// The ray-casting buffer read back and traced on a CPU worker.
pub(super) fn trace_passes(g: &mut FrameGraph<FrameCtx>, r: Resources) {
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
            let (s, gpu) = (&c.state, &c.state.gpu);
            let gbuffer = s.targets.traced_gbuffer();
            let (device, queue, materials) = (&gpu.device, &gpu.queue, &s.scene.materials);
            let listed = s.raycast.run(device, queue, &traced_view(c), &gbuffer, materials)?;
            gpu.transfers.traced(listed.transferred);
            gpu.take_error()?;
            io.put(r.batch, listed.batch)?;
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
            let bounce = c.needs.indirect.needed;
            let lpv = io.try_read(r.lpv).filter(|_| bounce && c.indirect == Indirect::Lpv);
            let cache = io.try_read(r.cache).filter(|_| bounce && c.indirect == Indirect::Cache);
            let sky_fn = |d: Vec3| sky.map_or(Vec3::ZERO, |k| k.radiance(d));
            let ambient = |p: Vec3, n: Vec3| {
                sky.map_or(Vec3::ZERO, |k| k.irradiance(p, n))
                    + lpv.map_or(Vec3::ZERO, |l| l.lpv().irradiance(p, n))
                    + cache.map_or(Vec3::ZERO, |k| k.cache.irradiance(p, n))
            };
            let lighting = TraceLighting {
                sun: c.sun.filter(|_| c.needs.sun_lighting.needed),
                point_lights: &s.point_lights,
                sky: &sky_fn,
                ambient: &ambient,
                reflectors: if s.settings.mirrored_sun { &s.reflectors } else { &[] },
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

const GPU_SHADING: &str = "the traced G-buffer is lit on the GPU";

fn gpu_shading(c: &FrameCtx) -> bool {
    c.state.settings.traced_shading == TracedShading::Gpu
}

/// The traced G-buffer lit on the GPU (`TracedShading::Gpu`): the sun's overlapped shadow
/// maps around the camera, and the lighting of the traced surfaces into the combine pass's
/// traced radiance.
pub(super) fn traced_gbuffer_passes(g: &mut FrameGraph<FrameCtx>, r: Resources) {
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
            let bounce = c.needs.indirect.needed && c.indirect == Indirect::Lpv;
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
                reflectors: &s.scene.reflectors,
                specular_albedo: &s.scene.gpu.specular_albedo,
            };
            pass.run(&s.gpu, io.read(r.batch)?, hits, &inputs)?;
            s.gpu.take_error()?;
            io.put(r.traced_lit, pass)?;
            Ok(())
        });
}

/// The traced radiance (uploaded from the CPU, or lit on the GPU) combined with the lit view.
pub(super) fn combine_pass(g: &mut FrameGraph<FrameCtx>, r: Resources) {
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
            let (s, gpu, t) = (&c.state, &c.state.gpu, &c.state.targets);
            let mut enc = gpu.device.create_command_encoder(&Default::default());
            if let Traced::Radiance(radiance) = io.read(r.traced)? {
                let batch = io.read(r.batch)?;
                gpu.transfers.traced(s.combine.upload(&gpu.queue, &mut enc, batch, radiance));
            }
            let inputs = CombineInputs {
                gbuffer: t.traced_gbuffer(),
                lit: (&t.lit_texture, &t.lit),
                output: (&t.combined_texture, &t.combined),
                zbuffer: &t.zbuffer,
                scene: &s.scene.gpu,
                rays: &s.raycast,
            };
            let view = traced_view(c);
            let written = s.combine.record(&gpu.device, &gpu.queue, &mut enc, &view, &inputs)?;
            gpu.transfers.traced(written);
            gpu.queue.submit([enc.finish()]);
            gpu.take_error()?;
            io.put(r.combined, CombinedView(c.component))?;
            Ok(())
        });
}
