#![doc = include_str!("../README.md")]
//!
//! ## Contents
//!
//! Each technique lives in its crate, each pass is a plain function over typed inputs
//! ([`passes`]), and [`graph`] declares them to `frame_scheduler`, which runs only what the
//! scene calls for and reports why. [`docs/ARCHITECTURE.md`](../../docs/ARCHITECTURE.md) at
//! the workspace root has the pass graph.
//!
//! ### One frame
//! | pass | what | thesis | crate |
//! |---|---|---|---|
//! | `sky map` | paraboloid sky map, rebuilt only when the sun moved | 3.6.2 | `atmosphere` |
//! | `sky volume` | sky-light irradiance volume, a few layers per frame | 5.3 (5.3.5) | `sky_volume` |
//! | `shadow maps` | stabilised cascades fitted to the camera, PCSS parameters (resident pass; only the cascades whose texel-snapped view moved) | 4.3.1, 4.4 | `shadows` |
//! | `point shadows` | one depth cube array for the shadow-casting point lights (resident pass) | 4.2 | `shadows` |
//! | `g-buffer` | albedo + gloss, normal + power (specular anti-aliasing), geometry normal + material, depth; a depth pre-pass shades each pixel once (resident pass) | 3.3.2, Table 3.1 | `scene` |
//! | `lpv` | indirect `lpv`: its own sun RSM (and with `Settings::sky_bounce` the G-buffer's sky-bounce VPLs, `passes::sky_bounce`) → injection (from their textures on a GPU) + propagation in 3 cascades | 5.2, 5.3.7 | `shadows`, `lpv`, `sky_volume` |
//! | `rsm (gather)` | indirect `rsm`: the sun RSM, kept on the GPU for the lighting pass's interleaved gather | Hahn 2012 (seed) | `shadows`, `rsm_gi` |
//! | `rsm + radiance cache` | indirect `cache`: the sun RSM's VPLs light the caches the view needs, on the CPU with shadow rays, over `Settings::cache_frames` frames; with many bounces (`radiance_cache::Bounces::Many`) the caches' rays also gather the sky, the point lights and the caches' own light their hits reflect (`passes::cache_bounce`) | Reich 2015 (seed) | `shadows`, `radiance_cache`, `kdtree_tracer` |
//! | `ray casting buffer` | quarter-res origins + reflection/refraction rays; the texels with rays listed and read back (resident pass) | 6.2.4, 6.2.6, Table 6.1 | `traced_effects` |
//! | `ray tracing` | CPU kd-tree tracing and shading of those rays, on a worker thread | 6.2.1-6.2.8, 6.3 | `traced_effects`, `kdtree_tracer` |
//! | `lighting` | sun (glTF metallic-roughness BRDF, `scene::brdf`; PCSS), point lights, sky volume + the one-bounce lookup (LPV, radiance cache) or the RSM gather, SSAO (the crates' WGSL snippets) | 4.2, 5.3.6-5.3.8 | `shadows`, `ssao`, `sky_volume`, `lpv`, `rsm_gi`, `radiance_cache` |
//! | `overlapped shadow maps` | with `TracedShading::Gpu`: the sun's maps around the camera for what reflections see (resident pass) | 6.3.1 | `shadows` |
//! | `traced g-buffer lighting` | with `TracedShading::Gpu`: the traced hits uploaded and lit with the deferred pass's BRDF, the maps above, the sky volume's and the LPV's lookups | 6.2.7 (Table 6.2), 6.3 | `shadows`, `sky_volume`, `lpv` |
//! | `traced upload + combine` | traced radiance added with Fresnel weights, depth-aware 3x3 gather, drawn over the mirror and glass draws alone (resident pass) | 6.3.4-6.3.5 | `traced_effects` |
//! | `still-view accumulation` | a still view's jittered frames averaged, up to `Settings::still_samples` | - | `post` |
//! | `tone mapping` | on the GPU, every frame: log-average luminance, eye adaptation, Reinhard, sRGB | 3.4.2-3.4.3, 3.5.1 | `post` |
//!
//! Nothing is read back for the frame but the ray-casting buffer's texels that have rays
//! (and, when traced rays read the LPV on a GPU, its volumes), and nothing uploaded but their
//! traced radiance and the uniforms: [`Renderer::advance_frame`] renders,
//! [`Renderer::read_frame`] reads the HDR and display images when a caller wants them, and
//! [`Renderer::render_frame`] does both; [`Frame::report`] counts the bytes each frame moved.
//! The ray tracing runs on a rayon worker while the main thread submits the GPU lighting
//! (`frame_scheduler`'s overlapped mode, thesis 6.3.6, Fig. 6.14). [`components`] splits a
//! frame into the lighting terms the reference computes one by one. This library depends on
//! no command-line, progress-bar or reference crate.
//!
//! What differs from the thesis (still-view anti-aliasing, the RSM gather as the presets'
//! one bounce, the traced hits shaded on the CPU, the LPV's lookup offset, the thesis's LPV
//! extras as settings, glass through the combine pass), with the figures that decided each:
//! `docs/differences.md`.

pub mod components;
mod effects;
pub mod error;
mod frame;
mod gpu;
pub mod graph;
pub mod passes;
mod renderer;
pub mod settings;
pub mod shaders;
mod state;
pub mod views;

pub use components::Component;
pub use effects::{Effect, Effects};
pub use error::{EngineError, error_chain};
pub use gpu::{TransferCounts, check_capabilities};
pub use graph::pass;
pub use radiance_cache::{Bounces, CacheSummary, Settings as CacheSettings};
pub use renderer::{Frame, FrameStats, HdrFrame, Renderer};
pub use settings::{Indirect, Preset, Settings, TracedShading};
/// The ray casting buffer's rays, their CPU tracing and the mirrored sun live in
/// `traced_effects`.
pub use traced_effects::{mirrored_sun, ray_casting, trace};
pub use views::{Channel, View};
