//! Ray-traced reflections and refractions for a rasteriser (Serenity thesis, chapter 6): the
//! rays a G-buffer pass wants traced (its ray casting buffer, 6.2.1) go through a SAH kd-tree
//! over the whole scene on the CPU ([`kdtree_tracer`]), and each hit is shaded with the
//! deferred pass's light model (6.2.8, 6.3), or handed back as a traced G-buffer record for
//! the GPU to light (6.3); the traced radiance is then added to the lit view with Fresnel
//! weights through a depth-aware gather (6.3.4-6.3.5). The sun mirrored by planar reflectors
//! lights the hits as further suns ([`mirrored_sun`]), light the thesis's engine never had.
//!
//! - [`ray_casting`]: the ray casting buffer (quarter resolution, one texel per 2x2 block:
//!   origin, reflection and refraction rays with their weights) computed from a G-buffer
//!   ([`ray_casting::cast_rays`]), and the rays to trace in texel order
//!   ([`ray_casting::batch`], [`ray_casting::RayBatch`]).
//! - [`trace`]: the scene prepared for tracing ([`trace::TraceScene`]), [`trace::trace_rays`]
//!   (radiance along each ray) and [`trace::trace_surfaces`] (each ray's first surface for
//!   GPU lighting).
//! - [`combine`]: what the traced radiance adds to a lit pixel
//!   ([`combine::traced_radiance`]).
//! - [`screen`]: the view and G-buffer the screen-space steps read ([`screen::ScreenView`]
//!   reconstructs a pixel's world position from its linear depth).
//! - [`mirrored_sun`]: the planar reflectors of a scene and the sun each mirrors.
//! - `gpu` (feature `gpu`): the ray casting buffer and the combination as resident wgpu
//!   passes (`gpu::RayCasting`, `gpu::Combine`) over a renderer's G-buffer textures and the
//!   `scene` crate's GPU material table and draws, and the WGSL snippets (Fresnel, position
//!   reconstruction) a renderer's lighting shares with them. A renderer then writes only the
//!   wiring: fill `gpu::TracedView` from its camera, run the ray casting, trace the batch,
//!   upload the radiance and record the combination.
//!
//! One frame on the CPU, from a G-buffer to the radiance each mirror pixel gains:
//! ```
//! use glam::{UVec2, Vec3};
//! use traced_effects::combine::traced_radiance;
//! use traced_effects::ray_casting::{RayKinds, batch, cast_rays, ListedRay};
//! use traced_effects::screen::{ScreenGBuffer, ScreenView};
//! use traced_effects::trace::{TraceLighting, TraceScene, TraceSettings, trace_rays};
//!
//! let scene = scene::Generated::PlaneBox.build(1);
//! let traced = TraceScene::new(&scene).expect("a valid scene");
//! // A 4x4 G-buffer of a mirror seen head-on, 3 m in front of the camera.
//! let camera = scene::Camera::look_at(Vec3::new(0.0, 1.0, 5.0), Vec3::new(0.0, 1.0, 0.0), 60.0, 1.0);
//! let view = ScreenView::new(camera.view_projection(), camera.position, camera.forward, (4, 4));
//! let mut materials = scene.materials.clone();
//! materials.push(scene::Material { reflectivity: 1.0, ..Default::default() });
//! let mirror = materials.len() as u32 - 1;
//! let (normal, material, depth) = (vec![Vec3::Z; 16], vec![mirror; 16], vec![3.0; 16]);
//! let gbuffer = ScreenGBuffer { normal: &normal, material: &material, depth: &depth };
//! let rays = cast_rays(&view, &gbuffer, &materials, RayKinds::ALL).expect("fits the view");
//! // What a GPU lists and reads back: the texels with a ray.
//! let listed: Vec<ListedRay> = rays
//!     .iter()
//!     .enumerate()
//!     .map(|(i, &ray)| ListedRay { ray, texel: [i as u32, 0, 0, 0] })
//!     .collect();
//! let rays_to_trace = batch(rays.len(), &listed);
//! assert_eq!(rays_to_trace.rays.len(), 4); // one reflection ray per 2x2 block
//!
//! let sky = |_d: Vec3| Vec3::splat(0.5);
//! let ambient = |_p: Vec3, _n: Vec3| Vec3::ZERO;
//! let lighting = TraceLighting {
//!     sun: Some((Vec3::new(0.3, 1.0, 0.2).normalize(), Vec3::splat(3.0))),
//!     point_lights: &[],
//!     sky: &sky,
//!     ambient: &ambient,
//!     reflectors: &[],
//! };
//! let radiance = trace_rays(&traced, &lighting, &rays_to_trace.rays, &TraceSettings::default());
//! // Per texel, (reflected, refracted), placed at the rays' slots.
//! let mut per_texel = vec![[Vec3::ZERO; 2]; rays.len()];
//! for (&(texel, refract), r) in rays_to_trace.slots.iter().zip(&radiance) {
//!     per_texel[texel as usize][usize::from(refract)] = *r;
//! }
//! let added = traced_radiance(&view, &gbuffer, &materials, &rays, &per_texel, UVec2::new(1, 2));
//! assert!(added.expect("inside the view").is_finite());
//! ```

pub mod combine;
mod error;
#[cfg(feature = "gpu")]
pub mod gpu;
pub mod mirrored_sun;
pub mod ray_casting;
pub mod screen;
pub mod trace;

pub use error::TraceError;
