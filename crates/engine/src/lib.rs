//! # engine
//!
//! The hybrid real-time global-illumination renderer of the Serenity master's thesis
//! (chapters 3-7; [`docs/ARCHITECTURE.md`](../../docs/ARCHITECTURE.md) has the pass graph), composed from the workspace's technique
//! crates on wgpu. The engine only wires: each technique lives in its crate, each pass is a
//! plain function over typed inputs ([`passes`]), and [`graph`] declares them to
//! `frame_scheduler`, which runs only what the scene calls for and reports why.
//!
//! ## One frame
//! | pass | what | thesis | crate |
//! |---|---|---|---|
//! | `sky map` | paraboloid sky map, rebuilt only when the sun moved | 4.3 | `atmosphere` |
//! | `sky volume` | sky-light irradiance volume, a few layers per frame | 5.3 | `sky_volume` |
//! | `shadow maps` | stabilised cascades fitted to the camera, PCSS parameters (resident pass; only the cascades whose texel-snapped view moved) | 4.2 | `shadows` |
//! | `point shadows` | one depth cube array for the shadow-casting point lights (resident pass) | 4.2 | `shadows` |
//! | `g-buffer` | albedo + gloss, normal + power (specular anti-aliasing), geometry normal + material, depth; a depth pre-pass shades each pixel once (resident pass) | Table 3.1 | `scene` |
//! | `rsm + lpv` | sun RSM (and with `Settings::sky_bounce` the G-buffer's sky-bounce VPLs, `passes::sky_bounce`) → injection (from their textures on a GPU) + propagation in 3 cascades (indirect `lpv`) | 5.2, 5.3.7 | `shadows`, `lpv`, `sky_volume` |
//! | `rsm (gather)` | the same sun RSM, kept on the GPU for the lighting pass's interleaved gather (indirect `rsm`) | seed 2 | `shadows`, `rsm_gi` |
//! | `ray casting buffer` | quarter-res origins + reflection/refraction rays; the texels with rays listed and read back (resident pass) | 6.2.1 | `traced_effects` |
//! | `ray tracing` | CPU kd-tree tracing and shading of those rays, on a worker thread | 6.2-6.3 | `traced_effects`, `kdtree_tracer` |
//! | `lighting` | sun (Phong/Blinn-Phong, PCSS), point lights, sky volume + LPV lookups or the RSM gather, SSAO (the crates' WGSL snippets) | 3.3, 5.3.6-5.3.8 | `shadows`, `ssao`, `sky_volume`, `lpv`, `rsm_gi` |
//! | `overlapped shadow maps` | with `TracedShading::Gpu`: the sun's maps around the camera for what reflections see (resident pass) | 6.3.1 | `shadows` |
//! | `traced g-buffer lighting` | with `TracedShading::Gpu`: the traced hits uploaded and lit with the deferred pass's BRDF, the maps above, the sky volume's and the LPV's lookups | 6.3 | `shadows`, `sky_volume`, `lpv` |
//! | `traced upload + combine` | traced radiance added with Fresnel weights, depth-aware 3x3 gather, drawn over the mirror and glass draws alone (resident pass) | 6.3.4-6.3.5 | `traced_effects` |
//! | `still-view accumulation` | a still view's jittered frames averaged, up to `Settings::still_samples` | - | `post` |
//! | `tone mapping` | on the GPU, every frame: log-average luminance, eye adaptation, Reinhard, sRGB | 3.7 | `post` |
//!
//! Nothing is read back for the frame itself but the ray-casting buffer's texels that have
//! rays (with the LPV as the one-bounce technique also its volumes for the traced rays on a
//! GPU, the RSM on the CPU path), and nothing uploaded but their traced radiance, one entry
//! per ray, and the uniforms: [`Renderer::advance_frame`] renders, [`Renderer::read_frame`]
//! reads the HDR and display images when a caller wants them, and [`Renderer::render_frame`]
//! does both. The report counts the bytes each frame moved (the city at 1600x900: 4.8 MiB
//! read back and 2.0 MiB uploaded, where the whole buffer and a slot per texel were 16.5 and
//! 11.0 MiB).
//!
//! The ray tracing runs on a rayon worker while the main thread submits the GPU lighting
//! (`frame_scheduler`'s overlapped mode, thesis Fig. 6.14). Every pass's outcome (ran,
//! reused, skipped, amortised), its reason, CPU ms and GPU ms (wgpu timestamp queries) are in
//! [`Frame::report`]; `app::report::write_report` writes it as markdown, JSON and an SVG
//! timeline beside the thesis's Table 7.1.
//!
//! ## Use
//! ```no_run
//! use engine::{Preset, Renderer, Settings};
//! let scene = scene::Generated::City.build(1);
//! let mut renderer = Renderer::new(scene, Settings::preset(Preset::Default, 1600, 900))?;
//! // The sky volume fills over the first frames; then a still view averages its jittered
//! // samples (`Settings::still_samples`). `settle` renders until both are done.
//! renderer.settle()?;
//! let frame = renderer.render_frame()?;
//! frame.write_png("city.png")?;
//! println!("{}", frame.report.to_markdown());
//! # Ok::<(), engine::EngineError>(())
//! ```
//! `cargo xtask render` (binary `serein-render` of the `app` crate) is the same from the
//! command line, and measures a frame against the `reference` path tracer; [`components`]
//! splits a frame into the lighting terms the reference computes one by one. This library
//! depends on no command-line, progress-bar or reference crate.
//!
//! ## What differs from the thesis
//! - A still view is anti-aliased by averaging jittered frames (`post`; the
//!   thesis shades one point per pixel): on the city's ledger the whole frame's rel RMS goes
//!   0.43 -> 0.27 against the reference, the direct sun's 0.48 -> 0.20
//!   (`app::ledger` has the table). A moving camera gets no anti-aliasing.
//! - The presets gather the sun's bounce from its reflective shadow map (`rsm_gi`, the second
//!   seed's technique) instead of the LPV: on the component ledger it halves to thirds the
//!   bounce's error at the same or less time ([`Indirect`] has the figures);
//!   `Settings::indirect` (`--indirect lpv`) brings back the thesis's LPV, and
//!   [`Renderer::set_indirect`] switches between them per frame.
//! - The presets shade the traced hits on the CPU with the same BRDF as the deferred pass
//!   (the sun with shadow rays instead of overlapped shadow maps, so glass lets it through;
//!   sky volume + LPV or radiance-cache irradiance). The thesis's traced G-buffer, uploaded
//!   and lit on the GPU with overlapped shadow maps, is `Settings::traced_shading =
//!   TracedShading::Gpu`; the bench's `engine/traced_shading_*` entries compare the two.
//! - The LPV is looked up 1.5 cells along the normal at the default and high presets (half a
//!   cell in the thesis and the `lpv` crate): a surface sees less of its own injected bounce
//!   ([`settings::ENGINE_LPV_LOOKUP_OFFSET`] has the ledger's figures).
//! - The thesis's two extras of the LPV are settings, off in the presets because the ledger
//!   shows them buying little: the sky-bounce VPLs from the G-buffer (`Settings::sky_bounce`,
//!   thesis 5.3.7) and the glossy lookup (`Settings::lpv_glossy`, 5.2.7); the settings' docs
//!   have the figures. On a hardware adapter the LPV is injected from the RSMs' textures and
//!   propagated on the GPU (resident), on a software adapter by the crate's CPU path (faster
//!   there).
//! - Glass is handled by the combine pass (reflection + refraction rays weighted by Fresnel),
//!   not by a forward pass for transparent surfaces; normal maps are not applied.

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
pub use radiance_cache::CacheSummary;
pub use renderer::{Frame, FrameStats, HdrFrame, Renderer};
pub use settings::{Indirect, Preset, Settings, Specular, TracedShading};
/// The ray casting buffer's rays, their CPU tracing and the mirrored sun live in
/// `traced_effects`.
pub use traced_effects::{mirrored_sun, ray_casting, trace};
pub use views::{Channel, View};
