//! Ray-traced reflections and refractions for a rasteriser (Serenity thesis, chapter 6): the
//! rays a G-buffer pass wants traced (its ray casting buffer, 6.2.6) go through a SAH kd-tree
//! over the whole scene on the CPU ([`kdtree_tracer`]), and each hit is shaded with the
//! deferred pass's light model (6.2.8, 6.3), or handed back as a traced G-buffer record for
//! the GPU to light (6.3). The sun mirrored by planar reflectors lights the hits as further
//! suns ([`mirrored_sun`]), light the thesis's engine never had.
//!
//! - [`trace`]: the scene prepared for tracing ([`trace::TraceScene`]), [`trace::trace_rays`]
//!   (radiance along each ray) and [`trace::trace_surfaces`] (each ray's first surface for
//!   GPU lighting).
//! - [`mirrored_sun`]: the planar reflectors of a scene and the sun each mirrors.
//!
//! ```
//! use glam::Vec3;
//! use traced_effects::trace::{TraceLighting, TraceRay, TraceScene, TraceSettings, trace_rays};
//! let scene = scene::Generated::PlaneBox.build(1);
//! let traced = TraceScene::new(&scene).expect("a valid scene");
//! let sky = |_d: Vec3| Vec3::splat(0.5);
//! let ambient = |_p: Vec3, _n: Vec3| Vec3::ZERO;
//! let lighting = TraceLighting {
//!     sun: Some((Vec3::new(0.3, 1.0, 0.2).normalize(), Vec3::splat(3.0))),
//!     point_lights: &[],
//!     sky: &sky,
//!     ambient: &ambient,
//!     reflectors: &[],
//! };
//! let rays = [TraceRay { origin: Vec3::new(0.0, 5.0, 0.0), dir: Vec3::NEG_Y }];
//! let radiance = trace_rays(&traced, &lighting, &rays, &TraceSettings::default());
//! assert!(radiance[0].is_finite() && radiance[0].min_element() >= 0.0);
//! ```

mod error;
pub mod mirrored_sun;
pub mod trace;

pub use error::TraceError;
