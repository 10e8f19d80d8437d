//! traced_effects' accuracy-vs-time sweep for `cargo xtask bench`.
//!
//! The rays are what the engine's ray casting buffer asks for on the city's view: the mirror
//! reflections of the camera rays whose first surface has a mirror or glass part (`support/
//! city.rs`; 160x90 quick, 320x180 full). The truth is the reference path tracer's radiance
//! along the same rays (`reference::query::radiance`, `Component::Full`, 64 samples quick, 256
//! full). Error: relative RMS over the rays' RGB; time: median ms of `trace_rays` over all
//! of them on every thread.
//!
//! Headlines:
//! - `traced_effects/city_mirror_rays_depth_<d>` for `d` in 1 (the thesis: hits shaded by the
//!   deferred pass's model only), 2, 4 and 8 (mirrors and glass followed): what recursion
//!   buys.
//! - `traced_effects/city_mirror_rays_surfaces`: `trace_surfaces`, the traced G-buffer for
//!   the GPU to light (time only: its light is the GPU's).
//!
//! The tracer gets the reference world's sun, point lights and sky and no ambient light (the
//! engine passes its sky volume and one bounce): the error floor at every depth is the light
//! the hits receive from other surfaces and the sky's occlusion-free ambient, which the
//! reference has and these rays' shading does not.

#[path = "../support/city.rs"]
mod city;

use gi_report::{Entry, Sweep, rel_rms, time_ms};
use reference::{Component, QuerySettings};
use traced_effects::trace::{TraceSettings, trace_rays, trace_surfaces};

fn rgb(v: &[glam::Vec3]) -> Vec<f64> {
    v.iter().flat_map(|c| [c.x as f64, c.y as f64, c.z as f64]).collect()
}

fn main() {
    let mut sweep = Sweep::from_env("traced_effects");
    let (w, h, samples) = if sweep.quick() { (160, 90, 64) } else { (320, 180, 256) };
    let threads = rayon::current_num_threads();
    let city = city::City::new();
    let camera = scene::Camera { aspect: w as f32 / h as f32, ..city.scene.camera };
    let primary = city::camera_rays(&camera, w, h);
    let rays = city.with_lighting(|l| city::mirror_rays(&city.traced, l, &primary));
    sweep.stage(&format!("reference radiance along {} mirror rays, {samples} samples", rays.len()));
    let settings = QuerySettings { samples, ..QuerySettings::DEFAULT };
    let pairs: Vec<(glam::Vec3, glam::Vec3)> = rays.iter().map(|r| (r.origin, r.dir)).collect();
    let truth = reference::radiance(&city.world, Component::Full, &pairs, &settings)
        .expect("reference radiance");
    let truth_rgb = rgb(&truth.iter().map(|e| e.mean).collect::<Vec<_>>());
    let noise = rgb(&truth.iter().map(|e| e.std_error).collect::<Vec<_>>());
    // The reference's own noise, in the error's units.
    let noise = (noise.iter().map(|s| s * s).sum::<f64>()
        / truth_rgb.iter().map(|t| t * t).sum::<f64>())
    .sqrt();
    let reps = sweep.reps(7);
    for depth in [1, 2, 4, 8] {
        sweep.stage(&format!("depth {depth}"));
        let s = TraceSettings { max_depth: depth, alpha_test: true };
        let (ms, radiance) =
            city.with_lighting(|l| time_ms(reps, || trace_rays(&city.traced, l, &rays, &s)));
        sweep.entry(
            Entry::new(format!("traced_effects/city_mirror_rays_depth_{depth}"), "trace_rays", ms)
                .setting("max_depth", depth)
                .setting("rays", rays.len())
                .setting("view", format!("{w}x{h}"))
                .setting("reference_samples", samples)
                .setting("reference_rel_std_error", noise)
                .setting("ambient", "none")
                .error("rel_rms", rel_rms(&rgb(&radiance), &truth_rgb), "reference::query::radiance (Full)")
                .threads(threads)
                .note("the city's mirror-reflection rays, shaded with the sun, the point lights and the sky; the floor is the light from other surfaces the rays' hits do not get"),
        );
    }
    sweep.stage("surfaces");
    let s = TraceSettings::default();
    let (ms, _) =
        city.with_lighting(|l| time_ms(reps, || trace_surfaces(&city.traced, l, &rays, &s)));
    sweep.entry(
        Entry::new("traced_effects/city_mirror_rays_surfaces", "trace_surfaces", ms)
            .setting("rays", rays.len())
            .setting("view", format!("{w}x{h}"))
            .threads(threads)
            .note("each ray's first surface as a traced G-buffer record for the GPU to light (thesis 6.3)"),
    );
    sweep.finish().expect("write the report part");
}
