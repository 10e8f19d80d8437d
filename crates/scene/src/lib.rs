#![doc = include_str!("../README.md")]
//!
//! ## Contents
//!
//! The scene description every renderer of the workspace reads: triangle meshes with
//! tangent frames, mip-mapped linear textures, one surface model for every renderer (glTF 2.0's
//! metallic-roughness, [`brdf`], in place of the Phong model of the Serenity engine's G-buffer:
//! the Serenity master's thesis, a hybrid GPU rasterization + CPU ray tracing real-time GI
//! engine, 3.3.2 and Table 3.1, whose parameters the constructors convert; smooth surfaces'
//! reflections traced as the thesis's were; see [`Material`]) with transmission, normal maps
//! and alpha testing, the sun (a direction, or a date, time and place through
//! [`atmosphere::solar_position`]), point and spot lights (and emissive surfaces as a few
//! point lights for renderers that light with them, [`emitter_lights`]), occlusion quads (thesis 5.3.3, with the
//! opacity and tint its future work proposes; derived from the geometry for scenes that
//! author none, [`Scene::sky_occluders`]), and where the sky volume and LPV cascades go.
//!
//! It loads glTF 2.0 ([`load_gltf`]; the metallic-roughness mapping is documented there), OBJ
//! with MTL ([`load_obj`]) and a TOML scene file ([`load_scene_file`]); textures are decoded from
//! sRGB to linear at load and mip-mapped (thesis 3.5 and 6.2.3). It generates seven test scenes
//! from a seed ([`Generated`]: the reference `city`, `cornell_window`, `two_rooms`,
//! `plane_box`, `furnace`, `cornell_area`, a Cornell box lit only by a one-sided ceiling
//! light, and `pbr_gallery`, spheres of the metallic-roughness model from smooth to rough
//! with a normal-mapped wall, a spot light and an emissive panel), and answers the engine's per-frame question of which effects the
//! scene calls for, and why ([`SceneNeeds`]), and what changed since the last frame
//! ([`SceneChange`]).
//!
//! With the cargo feature `gpu`, `scene::gpu` uploads a scene for a wgpu rasterizer (vertex
//! and index buffers, a draw per material, the material table and its WGSL struct, textures
//! with a bind group per material) and draws it into that G-buffer (`scene::gpu::GBufferPass`,
//! a resident pass: base colour + metallic, shading normal + roughness widened for specular
//! anti-aliasing, geometry normal + material id, linear depth; a depth pre-pass shades each
//! pixel once).
//!
//! World frame: +Y up, +X east, -Z north, metres.
//!
//! References: the master's thesis describing the Serenity engine (3.5 linear-space lighting,
//! 5.3.3 occlusion quads, 6.2.3 textures for the ray tracer, Chapter 7 reference scene);
//! IEC 61966-2-1 (sRGB transfer function); Khronos glTF 2.0 specification; Lengyel,
//! "Computing tangent space basis vectors for an arbitrary mesh" (2001); Gribb & Hartmann,
//! "Fast extraction of viewing frustum planes" (2001).

mod bounds;
pub mod brdf;
mod camera;
mod change;
mod defaults;
mod emitters;
mod error;
#[cfg(feature = "generate")]
mod generate;
#[cfg(feature = "gpu")]
pub mod gpu;
mod light;
#[cfg(feature = "load")]
mod load;
mod material;
mod mesh;
mod needs;
mod occluders;
mod scene;
pub mod surface;
mod texture;
mod volumes;
mod warning;

pub use atmosphere::CivilDate;
pub use bounds::Aabb;
pub use brdf::{Brdf, BrdfSample, PhongParams, TRACED_ROUGHNESS};
pub use camera::{Camera, DEFAULT_ASPECT, DEFAULT_FOV_Y_DEG, FRAMING_ELEVATION_DEG, Frustum};
pub use change::{SceneChange, SceneState};
pub use defaults::{
    DEFAULT_SUN_DATE, DEFAULT_SUN_LATITUDE_DEG, DEFAULT_SUN_LONGITUDE_DEG, DEFAULT_SUN_UTC_HOURS,
    default_sun, sun_time_phrase,
};
pub use emitters::{EmitterLights, SPLIT_FRACTION, emitter_lights};
pub use error::{Cause, LoadError, LoadErrorKind, SceneError};
#[cfg(feature = "generate")]
pub use generate::{
    FURNACE_ALBEDO, FURNACE_EMISSION, Generated, PBR_GALLERY_PANEL_EMISSION, PBR_GALLERY_ROUGHNESS,
    PBR_GALLERY_ROWS, PBR_GALLERY_SPHERE_RADIUS, PBR_GALLERY_SPOT_CONE_DEG,
    PBR_GALLERY_SPOT_POSITION, PBR_GALLERY_SPOT_TARGET, PBR_GALLERY_SUN_ELEVATION_DEG,
    PBR_GALLERY_SUN_GRAZE_DEG, city, cornell_window, furnace, furnace_radiance, pbr_gallery,
    pbr_gallery_sphere_center, plane_box, two_rooms,
};
pub use light::{
    EmitterShape, PointLight, SOLAR_ILLUMINANCE_LUX, SUN_ANGULAR_RADIUS, SpotCone, Sun,
    SunPosition, from_photometric,
};
#[cfg(feature = "load")]
pub use load::gltf::{load_gltf, load_gltf_slice};
#[cfg(feature = "load")]
pub use load::obj::{load_obj, load_obj_slice};
#[cfg(feature = "load")]
pub use load::scene_file::{load_scene_file, load_scene_str};
#[cfg(feature = "load")]
pub use load::{LoadOptions, load, load_with};
pub use material::{AlphaMask, Material, MaterialId, RAY_TRACE_THRESHOLD};
pub use mesh::{Cleanup, Mesh, MeshData, orthonormal_tangent};
pub use needs::{Need, SKY_DARK_ELEVATION_DEG, SceneNeeds};
pub use occluders::{DeriveSettings, derive_occlusion_quads};
pub use scene::{Scene, SceneStats, SceneTriangles};
pub use surface::{SurfaceFactors, SurfacePoint, TextureLookup, perturbed_normal, surface_factors};
pub use texture::{
    ColorSpace, Filter, MAX_TEXTURE_SIZE, Texture, TextureId, TextureLevel, Wrap, linear_to_srgb,
    srgb_to_linear,
};
pub use vocab::OcclusionQuad;
pub use volumes::{LpvPlacement, SkyVolumePlacement};
pub use warning::{LoadWarning, LoadWarningKind, STAND_IN_COLORS, STAND_IN_TEXTURE};
