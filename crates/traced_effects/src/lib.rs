#![doc = include_str!("../README.md")]
//!
//! ## Contents
//!
//! Ray-traced reflections and refractions for a rasteriser (Serenity thesis, chapter 6): the
//! rays a G-buffer pass wants traced (its ray casting buffer, 6.2.6) go through a SAH kd-tree
//! over the whole scene on the CPU ([`kdtree_tracer`]), and each hit is shaded with the
//! deferred pass's light model (6.2.8, 6.3), or handed back as a traced G-buffer record for
//! the GPU to light (6.2.7, 6.3); the traced radiance is then added to the lit view with
//! Fresnel weights through a depth-aware gather (6.3.4-6.3.5). The sun mirrored by planar
//! reflectors lights the hits as further suns ([`mirrored_sun`]), light the thesis's engine
//! never had.
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

pub mod combine;
mod error;
#[cfg(feature = "gpu")]
pub mod gpu;
pub mod mirrored_sun;
pub mod ray_casting;
pub mod screen;
pub mod trace;

pub use error::TraceError;
