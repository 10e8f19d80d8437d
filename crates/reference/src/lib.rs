#![doc = include_str!("../README.md")]
//!
//! ## Contents
//!
//! The ground truth every real-time approximation of the workspace is measured against: a
//! CPU Monte Carlo path tracer (J. Kajiya, "The Rendering Equation", SIGGRAPH 1986) over
//! [`kdtree_tracer`], with
//!
//! - **next-event estimation** towards the sun's disk (uniform cone sampling over its
//!   angular radius 0.004675 rad, so shadows get true penumbrae), point lights and
//!   **emissive triangles** (one chosen by power from a Walker alias table, a point on it
//!   uniform in area), the latter combined with BRDF sampling by multiple importance
//!   sampling (balance heuristic; [`PathSettings::emitter_sampling`] turns it off);
//! - **emission as the scene says**: from the wound front side only, unless the material
//!   is double-sided ([`Material::double_sided`]); an emissive texture makes it vary over a
//!   triangle (the emission seen and each emitter sample are read at their point, while
//!   the emitter is chosen by its material's bound, [`Material::emission`]: every point that
//!   emits keeps a positive density, so light sampling stays unbiased);
//! - **the occlusion texture** (glTF's `occlusionTexture`, "areas that receive less
//!   indirect lighting"), read as part of the material: at every surface vertex of a path,
//!   what the path gathers after a non-delta bounce there (the sky, light bounced by other
//!   surfaces, sunlight through mirrors and glass) is scaled by the vertex's
//!   [`Material::occlusion`], `1 + strength (ao - 1)`; its next-event estimates (the sun,
//!   point and spot lights, the emitters) and the emitters' light its bounce finds (the
//!   other half of the emitters' multiple importance sampling) are not, nor is its own
//!   emission or a mirror's or glass's delta bounce. The components follow: `SkyIrradiance`,
//!   `SkyDiffuse` and `SunIndirectDiffuse` are scaled by the first surface's occlusion,
//!   `SunDirect`, `PointLights`, `Emission` and `Reflections` are not. The engine scales
//!   the same terms at the surfaces it sees and at its traced hits (its sky, bounce and
//!   glossy lookups); the light its techniques bounce off further surfaces (reflective
//!   shadow maps, the sky's VPLs) is not scaled, where the reference scales the sky light
//!   those surfaces reflect: a difference of the second bounce;
//! - **sky light** from any radiance function (`atmosphere`'s sky map, a constant),
//!   importance-sampled with the BRDF (its visible-normal GGX sampling or the cosine);
//! - **multiple importance sampling** of the BRDF's sampling (the GGX lobe's visible
//!   normals, E. Heitz, JCGT 2018, mixed with cosine sampling; `scene::Brdf::sample`)
//!   against the emitters' (balance heuristic, E. Veach and L. Guibas, SIGGRAPH 1995);
//! - **sun caustics by progressive photon mapping** ([`PathSettings::caustic_photons`], off
//!   by default): sunlight reaching a surface through mirrors, glass and sharp GGX lobes
//!   (paths `sun (S)+ D`) is a density estimate of photons shot from the sun's disk at the
//!   specular surfaces, one photon map per sample index with the radius shrinking by
//!   C. Knaus and M. Zwicker's schedule ("Progressive photon mapping: a probabilistic
//!   approach", ACM TOG 2011; after T. Hachisuka, S. Ogaki and H. W. Jensen, "Progressive
//!   photon mapping", SIGGRAPH Asia 2008, and T. Hachisuka and H. W. Jensen, "Stochastic
//!   progressive photon mapping", SIGGRAPH Asia 2009), so the estimate is consistent; the
//!   path tracer then leaves exactly those paths out (each light path is counted once),
//!   which removes the fireflies of the sun found by chance through a chain of specular
//!   bounces (see the `caustics` module for the partition of paths);
//! - **refinement where the image is noisiest** ([`Renderer::refine`], [`Refinement`]): a
//!   second stage of fresh samples, which replace the first stage's, for the pixels whose
//!   standard error is above a share of their 8 x 8 block's light and for the pixels a
//!   deterministic probe ([`glint_pixels`]) finds the sun's disk in a mirror reflection of
//!   (a smooth mirror's glint of the sun is a dot far smaller than a pixel that a plain
//!   render finds a few times in a thousand samples); each chosen pixel's sample count is
//!   fixed before its samples are drawn, so its estimate stays unbiased;
//! - **Russian roulette** on the path throughput;
//! - **materials**: glTF's metallic-roughness BRDF, the workspace's one copy of it
//!   (`scene::Brdf`: GGX with height-correlated Smith masking and Schlick Fresnel, plus a
//!   coated Lambertian lobe), whose smooth surfaces (roughness below
//!   `scene::TRACED_ROUGHNESS`) reflect a traced mirror ray of weight `F(n.v)` as the
//!   engine's do; smooth glass with Fresnel over a transparency share; emission; alpha test
//!   ([`Material`]);
//! - **components** that match one technique each ([`Component`]): direct sun with area
//!   shadows (CSM/PCSS), one-bounce diffuse from the sun (LPV), occluded sky irradiance
//!   (sky volume), mirror reflections and refractions (ray-traced reflections), shadowed
//!   point lights, direct light of emissive surfaces (area lights, by emitter samples alone),
//!   emission seen directly, full image;
//! - **point queries** ([`irradiance`], [`radiance`]): positions and normals (or rays) in,
//!   an [`Estimate`] with its standard error out;
//! - **progressive images** ([`Renderer`]): 16x16 tiles on rayon, one seeded random stream
//!   per (pixel, sample), so results are identical bit for bit whatever the thread count;
//!   EXR output of the mean and standard error, tone-mapped PNG; progress reported to a
//!   callback ([`Renderer::with_progress`], [`Progress`]);
//! - **an honest standard error**: each pixel's samples fall into [`BATCHES`] independent
//!   batches, each its own stratified sequence over the pixel, and the error is the spread
//!   of the batch means ([`BatchMoments`]), which stays right on pixels an edge crosses,
//!   where the spread of stratified samples overstates it several-fold;
//! - **partial renders that merge** ([`Partial`]): renders of other seeds or other pixels
//!   ([`Renderer::with_pixels`]) add up to the estimate one render of all their samples
//!   would state, so a large reference spreads over machines;
//! - **difference images** ([`difference_image`], [`error_in_std_errors`]); the scalar
//!   error metrics over whole images are `gi_report`'s (`gi_report::image_errors`).
//!
//! With the `scene` crate's scenes: [`world_from_scene`] and [`camera_from_scene`].
//!
//! Where the time goes (a profile): `docs/profile.md`.

// `!(a > b)` is used on purpose: it is also true when either side is NaN.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod analytic;
mod camera;
mod caustics;
mod compare;
mod error;
mod from_scene;
mod image;
mod integrator;
mod lights;
mod material;
mod partial;
mod progress;
mod query;
mod refine;
mod render;
mod rng;
mod sampling;
mod stats;
mod world;

pub use camera::Camera;
pub use compare::{difference_image, error_in_std_errors};
pub use error::Error;
pub use from_scene::{SceneLighting, camera_from_scene, world_from_scene};
pub use image::Image;
pub use integrator::{Component, PathSettings};
pub use material::{AlphaTest, CoverageFn, Material, Sample, SurfaceTextures, TextureFn};
pub use partial::{Part, Partial};
pub use progress::{Progress, ProgressFn, Stage};
pub use query::{QueryPoint, QuerySettings, ambient_occlusion, irradiance, radiance};
pub use refine::{GLINT_BOUNCES, Refinement, glint_pixels};
pub use render::{CAUSTIC_BATCH, RenderSettings, Renderer, TILE, render};
pub use rng::Rng;
pub use sampling::luminance;
pub use stats::{BATCHES, BatchMoments, Estimate, Moments, PixelSums};
pub use world::{PointLight, SkyFn, Sun, SurfaceHit, World, WorldBuilder};
